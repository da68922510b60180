// Light packing (engine/src/render/light_packing.cpp): which lights reach the lit passes, in which
// slots, with which compile-time configuration, and matrices that take camera-relative points.
#include <gtest/gtest.h>

#include "render/light_packing.h"

#include <glm/gtc/matrix_transform.hpp>

namespace shadow::render {
namespace {

ShadowLightPlan spotPlan(int index, bool withMap) {
    ShadowLightPlan p;
    p.sceneIndex = index;
    p.name = "spot" + std::to_string(index);
    p.shaded = true;
    p.light.type = LightType::Spot;
    p.light.intensity = 2.0f;
    p.light.color = {1.0f, 0.5f, 0.25f};
    p.light.radius = 0.2f;
    p.wsPosition = {1000.0 + index, 5.0, -2000.0};
    p.wsDirection = {0.0, -1.0, 0.0};
    p.settings.technique = withMap ? ShadowTechnique::Pcss : ShadowTechnique::None;
    p.settings.kernel = FilterKernel::Poisson;
    if (withMap) {
        p.mapSize = 512;
        ShadowLayerPlan layer;
        layer.lightFromWorld = glm::lookAt(p.wsPosition, p.wsPosition + p.wsDirection, glm::dvec3(0, 0, 1));
        layer.depthScale = 40.0f;
        p.layers.push_back(layer);
    }
    return p;
}

TEST(LightPacking, SkipsLightsThatCannotShadeAndFillsPassesInSceneOrder) {
    ShadowFrame frame;
    for (int i = 0; i < 12; ++i) frame.lights.push_back(spotPlan(i, i % 3 == 0));
    frame.lights[1].shaded = false;       // no Light, or a non-finite transform
    frame.lights[2].affectsView = false;  // its range misses the view
    const glm::dvec3 camera(1000.0, 2.0, -1990.0);
    std::vector<PassLights> passes;
    packLights(frame, camera, passes);

    ASSERT_EQ(passes.size(), 2u) << "10 lights shade the view: 8 + 2";
    EXPECT_EQ(passes[0].variant.lights, 8);
    EXPECT_EQ(passes[1].variant.lights, 2);
    const std::vector<int> expected = {0, 3, 4, 5, 6, 7, 8, 9};
    for (int s = 0; s < 8; ++s) EXPECT_EQ(passes[0].sceneLight[static_cast<std::size_t>(s)], expected[static_cast<std::size_t>(s)]);
    EXPECT_EQ(passes[1].sceneLight[0], 10);
    EXPECT_EQ(passes[1].sceneLight[1], 11);
    EXPECT_EQ(passes[1].sceneLight[2], -1) << "unused slots name no light";

    // Slot 1 of pass 0 is light 3 (shadowed); slot 2 is light 4 (no map).
    EXPECT_EQ(passes[0].variant.type[1], SG_LIGHT_SPOT);
    EXPECT_EQ(passes[0].variant.technique[1], SG_TECH_PCSS);
    EXPECT_EQ(passes[0].variant.kernel[1], SG_KERNEL_POISSON);
    EXPECT_EQ(passes[0].variant.technique[2], SG_TECH_NONE) << "a light without a map is drawn unshadowed";
    EXPECT_EQ(passes[0].lights[1].firstLayer, 1 * SG_MAX_LAYERS_PER_LIGHT);
    EXPECT_EQ(passes[0].lights[1].layerCount, 1);
}

TEST(LightPacking, RecordsAreCameraRelative) {
    ShadowFrame frame;
    frame.lights.push_back(spotPlan(0, true));
    const glm::dvec3 camera(1000.0, 2.0, -1990.0);
    std::vector<PassLights> passes;
    packLights(frame, camera, passes);
    ASSERT_EQ(passes.size(), 1u);
    const gpu::GpuLight& g = passes[0].lights[0];
    EXPECT_NEAR(g.csPosition.x, 0.0f, 1e-6f);
    EXPECT_NEAR(g.csPosition.y, 3.0f, 1e-6f);
    EXPECT_NEAR(g.csPosition.z, -10.0f, 1e-6f);
    EXPECT_NEAR(g.radiance.y, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(g.emitterSize, 0.2f);
    // A world point 0.5 m below the light, given camera-relative, lands on the light's axis.
    const glm::dvec3 wsPoint = frame.lights[0].wsPosition + glm::dvec3(0.0, -0.5, 0.0);
    const glm::vec4 ls = passes[0].layers[0].lightFromCs * glm::vec4(glm::vec3(wsPoint - camera), 1.0f);
    EXPECT_NEAR(ls.x, 0.0f, 1e-5f);
    EXPECT_NEAR(ls.y, 0.0f, 1e-5f);
    EXPECT_NEAR(ls.z, -0.5f, 1e-5f);
}

TEST(LightPacking, NoLightsStillMakeOnePassAndReusesStorage) {
    ShadowFrame frame;
    std::vector<PassLights> passes;
    packLights(frame, glm::dvec3(0.0), passes);
    ASSERT_EQ(passes.size(), 1u) << "the first pass writes the ambient term and the AOVs";
    EXPECT_EQ(passes[0].variant.lights, 0);

    for (int i = 0; i < 20; ++i) frame.lights.push_back(spotPlan(i, true));
    packLights(frame, glm::dvec3(0.0), passes);
    ASSERT_EQ(passes.size(), 3u);
    const PassLights* storage = passes.data();
    frame.lights.resize(9);
    packLights(frame, glm::dvec3(0.0), passes);
    EXPECT_EQ(passes.size(), 2u);
    packLights(frame, glm::dvec3(0.0), passes);
    EXPECT_EQ(passes.data(), storage) << "packing again must not reallocate";
}

}  // namespace
}  // namespace shadow::render
