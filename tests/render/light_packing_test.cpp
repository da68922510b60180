// Light packing (engine/src/render/light_packing.cpp): which lights reach the lit passes, in which
// slots, with which compile-time configuration, and matrices that take camera-relative points.
#include <gtest/gtest.h>

#include "render/light_packing.h"

#include <glm/gtc/matrix_transform.hpp>

namespace shadow::render {
namespace {

/// A view that sees every test light whole: no light has a range, so each covers the screen.
const ScreenView kView{glm::dmat4(1.0), 64, 48, {}};
std::vector<PackingEntry> scratch;

void pack(const ShadowFrame& frame, const glm::dvec3& camera, std::vector<PassLights>& passes) {
    packLights(frame, camera, kView, passes, scratch);
}

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

// Over several passes, wide lights alike (type, technique, kernel) share passes, in scene order
// among them: passes then share programs, each compiling a configuration once.
TEST(LightPacking, SkipsLightsThatCannotShadeAndFillsPassesWithLightsAlikeTogether) {
    ShadowFrame frame;
    for (int i = 0; i < 12; ++i) frame.lights.push_back(spotPlan(i, i % 3 == 0));
    frame.lights[1].shaded = false;       // no Light, or a non-finite transform
    frame.lights[2].affectsView = false;  // its range misses the view
    const glm::dvec3 camera(1000.0, 2.0, -1990.0);
    std::vector<PassLights> passes;
    pack(frame, camera, passes);

    ASSERT_EQ(passes.size(), 2u) << "10 lights shade the view: 8 + 2";
    EXPECT_EQ(passes[0].variant.lights, 8);
    EXPECT_EQ(passes[1].variant.lights, 2);
    // The unshadowed lights (technique None) first, then the PCSS ones (0, 3, 6, 9).
    const std::vector<int> expected = {4, 5, 7, 8, 10, 11, 0, 3};
    for (int s = 0; s < 8; ++s)
        EXPECT_EQ(passes[0].sceneLight[static_cast<std::size_t>(s)], expected[static_cast<std::size_t>(s)]);
    EXPECT_EQ(passes[1].sceneLight[0], 6);
    EXPECT_EQ(passes[1].sceneLight[1], 9);
    EXPECT_EQ(passes[1].sceneLight[2], -1) << "unused slots name no light";

    // Slot 7 of pass 0 is light 3 (shadowed); slot 2 is light 7 (no map).
    EXPECT_EQ(passes[0].variant.type[7], SG_LIGHT_SPOT);
    EXPECT_EQ(passes[0].variant.technique[7], SG_TECH_PCSS);
    EXPECT_EQ(passes[0].variant.kernel[7], SG_KERNEL_POISSON);
    EXPECT_EQ(passes[0].variant.technique[2], SG_TECH_NONE) << "a light without a map is drawn unshadowed";
    EXPECT_EQ(passes[0].lights[7].firstLayer, 7 * SG_MAX_LAYERS_PER_LIGHT);
    EXPECT_EQ(passes[0].lights[7].layerCount, 1);

    // Lights that fit in one pass keep the scene's order.
    frame.lights.resize(8);
    pack(frame, camera, passes);
    ASSERT_EQ(passes.size(), 1u);
    const std::vector<int> inOrder = {0, 3, 4, 5, 6, 7};
    for (int s = 0; s < 6; ++s)
        EXPECT_EQ(passes[0].sceneLight[static_cast<std::size_t>(s)], inOrder[static_cast<std::size_t>(s)]);
}

TEST(LightPacking, RecordsAreCameraRelative) {
    ShadowFrame frame;
    frame.lights.push_back(spotPlan(0, true));
    const glm::dvec3 camera(1000.0, 2.0, -1990.0);
    std::vector<PassLights> passes;
    pack(frame, camera, passes);
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
    pack(frame, glm::dvec3(0.0), passes);
    ASSERT_EQ(passes.size(), 1u) << "the first pass writes the ambient term and the AOVs";
    EXPECT_EQ(passes[0].variant.lights, 0);

    for (int i = 0; i < 20; ++i) frame.lights.push_back(spotPlan(i, true));
    pack(frame, glm::dvec3(0.0), passes);
    ASSERT_EQ(passes.size(), 3u);
    const PassLights* storage = passes.data();
    frame.lights.resize(9);
    pack(frame, glm::dvec3(0.0), passes);
    EXPECT_EQ(passes.size(), 2u);
    pack(frame, glm::dvec3(0.0), passes);
    EXPECT_EQ(passes.data(), storage) << "packing again must not reallocate";
}

/// Lights with a 1 m range on a grid seen from straight above: an orthographic view of 40 x 40 m.
TEST(LightPacking, ManyLocalLightsGetPassesBoundedByTheirReach) {
    ShadowFrame frame;
    ShadowLightPlan sun = spotPlan(0, true);
    sun.light.type = LightType::Directional;
    frame.lights.push_back(sun);
    for (int i = 1; i <= 12; ++i) {
        ShadowLightPlan p = spotPlan(i, false);
        p.light.type = LightType::Point;
        p.light.range = 1.0f;
        p.wsPosition = {-17.5 + 5.0 * (i % 8), 0.0, -17.5 + 5.0 * (i / 8)};
        frame.lights.push_back(p);
    }
    ScreenView view;
    view.width = 400;
    view.height = 400;
    // Looking down -Y: x to the right, -z up on screen; w = 1 everywhere (orthographic).
    view.clipFromWorld = glm::dmat4(glm::dvec4(0.05, 0, 0, 0), glm::dvec4(0, 0, -0.01, 0), glm::dvec4(0, -0.05, 0, 0),
                                    glm::dvec4(0, 0, 0.5, 1));
    const PixelRect one = screenBounds(frame.lights[1], view);
    EXPECT_NEAR(one.x1 - one.x0, 20, 1) << "a sphere of 1 m radius is 20 pixels wide at 10 pixels per metre";
    // Within the drawn geometry only: a floor 0.5 m thick that holds the sphere's centre row
    // keeps the width and cuts the height (screen y is world z here), one box beside it none.
    ScreenView floorView = view;
    floorView.wsGeometry.extend(glm::dvec3(-20.0, -0.25, -20.0));
    floorView.wsGeometry.extend(glm::dvec3(20.0, 0.25, frame.lights[1].wsPosition.z));
    const PixelRect clipped = screenBounds(frame.lights[1], floorView);
    EXPECT_EQ(clipped.x1 - clipped.x0, one.x1 - one.x0);
    EXPECT_NEAR(clipped.y1 - clipped.y0, 10, 1) << "half the sphere's depth lies beyond the geometry";
    ScreenView elsewhere = view;
    elsewhere.wsGeometry.extend(glm::dvec3(100.0));
    elsewhere.wsGeometry.extend(glm::dvec3(101.0));
    EXPECT_TRUE(screenBounds(frame.lights[1], elsewhere).empty()) << "no geometry within its range";
    std::vector<PassLights> passes;
    packLights(frame, glm::dvec3(0.0), view, passes, scratch);
    ASSERT_EQ(passes.size(), 13u) << "the sun's whole-screen pass, then one pass per local light";
    EXPECT_EQ(passes[0].bounds, (PixelRect{0, 0, 400, 400}));
    EXPECT_EQ(passes[0].variant.lights, 1);
    EXPECT_EQ(passes[0].sceneLight[0], 0);
    EXPECT_TRUE(passes[0].unbounded);
    long long covered = 0;
    for (std::size_t p = 1; p < passes.size(); ++p) {
        ASSERT_EQ(passes[p].variant.lights, 1);
        const ShadowLightPlan& light = frame.lights[static_cast<std::size_t>(passes[p].sceneLight[0])];
        EXPECT_EQ(passes[p].bounds, screenBounds(light, view));
        EXPECT_FALSE(passes[p].unbounded);
        EXPECT_EQ(passes[p].wsReach.min, light.wsPosition - glm::dvec3(1.0));
        EXPECT_EQ(passes[p].wsReach.max, light.wsPosition + glm::dvec3(1.0));
        covered += passes[p].bounds.area();
    }
    EXPECT_LE(covered, 12LL * 21 * 21) << "each local pass covers its light's sphere only";
}

TEST(LightPacking, SphereBehindTheEyeCoversTheScreenAndOffScreenLightsAreSkipped) {
    ScreenView view;
    view.width = 100;
    view.height = 100;
    view.clipFromWorld = glm::perspective(1.0, 1.0, 0.1, 100.0) *
                         glm::lookAt(glm::dvec3(0, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
    ShadowLightPlan around = spotPlan(0, false);
    around.light.type = LightType::Point;
    around.light.range = 2.0f;
    around.wsPosition = {0.0, 0.0, 0.5};  // the camera is inside its sphere
    EXPECT_EQ(screenBounds(around, view), (PixelRect{0, 0, 100, 100}));
    ShadowLightPlan aside = around;
    aside.sceneIndex = 1;
    aside.wsPosition = {-500.0, 0.0, -10.0};  // in front, far off to the side
    EXPECT_TRUE(screenBounds(aside, view).empty());
    ShadowFrame frame;
    frame.lights = {around, aside};
    std::vector<PassLights> passes;
    packLights(frame, glm::dvec3(0.0), view, passes, scratch);
    ASSERT_EQ(passes.size(), 1u);
    EXPECT_EQ(passes[0].variant.lights, 1) << "a light whose sphere is off screen shades nothing";
}

}  // namespace
}  // namespace shadow::render
