// Solid casters drawn with their back faces culled (MeshData::solid, shadow_maps.cpp): every
// layer of every light type stores the depths it stores with every face drawn. The reference is
// the same scene with each mesh's `solid` flag cleared, which draws both sides.
#include <shadow/frame_runner.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/soft_test_support.h"

namespace shadow::solid_culling_test {
namespace {

constexpr int kMapSize = 256;

/// `mesh` as given, or a copy of it that draws both sides.
std::shared_ptr<const MeshData> sided(std::shared_ptr<MeshData> mesh, bool cull) {
    if (!cull) mesh->solid = false;
    return mesh;
}

/// A box mesh wound the other way: closed, not solid.
std::shared_ptr<MeshData> insideOutBox(const glm::vec3& halfExtents) {
    std::shared_ptr<MeshData> box = makeBoxMesh(halfExtents);
    for (std::size_t t = 0; t < box->indices.size(); t += 3) std::swap(box->indices[t + 1], box->indices[t + 2]);
    computeClosed(*box);
    return box;
}

Transform turned(const glm::dvec3& position, const glm::dvec3& axis, double angle, const glm::dvec3& scale) {
    Transform t = test::placed(position, scale);
    t.rotation = glm::angleAxis(angle, glm::normalize(axis));
    return t;
}

/// Solid casters of every kind the draw meets on a ground: a sphere, a turned box, a box
/// mirrored by its transform (a negative scale: its winding flips), a sphere squashed by a
/// non-uniform scale, and a box wound inside out (not solid: drawn with both sides), under one
/// light of `type`. `cull` false clears every mesh's `solid`.
Scene solids(LightType type, bool cull) {
    Scene scene;
    addMeshInstance(scene.world, "ground", sided(makePlaneMesh(6.0f, 4), cull), test::placed(glm::dvec3(0.0)));
    addMeshInstance(scene.world, "sphere", sided(makeSphereMesh(0.5f, 48, 24), cull), test::placed({-1.0, 0.8, 0.0}));
    addMeshInstance(scene.world, "turned", sided(makeBoxMesh(glm::vec3(0.4f, 0.3f, 0.5f)), cull),
                    turned({1.0, 0.7, 0.4}, {1.0, 2.0, 0.5}, 0.7, glm::dvec3(1.0)));
    addMeshInstance(scene.world, "mirrored", sided(makeBoxMesh(glm::vec3(0.5f, 0.2f, 0.3f)), cull),
                    turned({0.0, 0.6, -1.2}, {0.0, 1.0, 0.3}, 0.5, {-1.0, 1.0, 1.0}));
    addMeshInstance(scene.world, "squashed", sided(makeSphereMesh(0.4f, 32, 16), cull),
                    turned({0.3, 1.4, 1.0}, {1.0, 0.0, 0.0}, 0.3, {1.5, 0.5, 1.0}));
    addMeshInstance(scene.world, "inside-out", sided(insideOutBox(glm::vec3(0.3f)), cull),
                    test::placed({-0.9, 0.4, 1.4}));
    Light light = test::pointSizedLight(type, 1.0f);
    const glm::dvec3 position = type == LightType::Directional ? glm::dvec3(2.0, 6.0, 3.0) : glm::dvec3(0.5, 3.5, 0.8);
    addLight(
        scene, "light", light, test::hardShadow(kMapSize), position,
        type == LightType::Point ? glm::dvec3(0.0, -1.0, 0.0) : glm::normalize(-position + glm::dvec3(0.0, 0.5, 0.0)));
    addCamera(scene, "camera", Camera{}, {0.0, 4.0, 6.0}, {0.0, 0.5, 0.0});
    return scene;
}

/// A point light inside a solid box (its near planes cut through it), beside a sphere outside.
Scene lightInsideABox(bool cull) {
    Scene scene;
    addMeshInstance(scene.world, "ground", sided(makePlaneMesh(6.0f, 4), cull), test::placed(glm::dvec3(0.0)));
    addMeshInstance(scene.world, "room", sided(makeBoxMesh(glm::vec3(0.6f)), cull), test::placed({0.0, 2.0, 0.0}));
    addMeshInstance(scene.world, "sphere", sided(makeSphereMesh(0.4f, 32, 16), cull), test::placed({2.0, 0.5, 0.0}));
    addLight(scene, "light", test::pointSizedLight(LightType::Point), test::hardShadow(kMapSize), {0.0, 2.0, 0.0},
             {0.0, -1.0, 0.0});
    addCamera(scene, "camera", Camera{}, {0.0, 4.0, 6.0}, {0.0, 0.5, 0.0});
    return scene;
}

struct Layers {
    std::vector<std::vector<float>> depths;  ///< per layer, every texel (m)
    std::vector<float> far;                  ///< per layer, the depth of an empty texel (m)
    LightShadowStats stats;
};

Layers render(Scene scene) {
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, 64, 48);
    Layers out;
    out.stats = frame.stats.lights.at(0);
    for (int k = 0; k < out.stats.layers; ++k) {
        out.depths.push_back(runner.shadows().maps().readLayerDepth(0, k));
        out.far.push_back(runner.shadows().frame().lights.at(0).layers.at(static_cast<std::size_t>(k)).depthScale);
    }
    return out;
}

/// Texels of `a` and `b` that differ, over every layer.
struct Difference {
    long long texels = 0;
    long long differing = 0;
    long long caster = 0;  ///< texels nearer than the far depth in `b`
    double largest = 0.0;  ///< the largest difference (m)
};

Difference compare(const Layers& a, const Layers& b) {
    Difference d;
    EXPECT_EQ(a.depths.size(), b.depths.size());
    for (std::size_t k = 0; k < a.depths.size() && k < b.depths.size(); ++k) {
        EXPECT_EQ(a.depths[k].size(), b.depths[k].size());
        for (std::size_t i = 0; i < a.depths[k].size() && i < b.depths[k].size(); ++i) {
            ++d.texels;
            d.caster += b.depths[k][i] < b.far[k] ? 1 : 0;
            if (a.depths[k][i] != b.depths[k][i]) {
                ++d.differing;
                d.largest = std::max(d.largest, std::abs(static_cast<double>(a.depths[k][i]) - b.depths[k][i]));
            }
        }
    }
    return d;
}

class SolidCulling : public ::testing::TestWithParam<LightType> {};

TEST_P(SolidCulling, StoresTheDepthsOfBothSidesDrawn) {
    const LightType type = GetParam();
    const Layers culled = render(solids(type, true));
    const Layers both = render(solids(type, false));
    const Difference d = compare(culled, both);
    // A ray from outside meets a solid first on a front face, which the rasteriser covers the
    // texel with either way. Only where a silhouette's back face came out nearer by the
    // rasteriser's snapping of vertices to 1/256 texel may a texel differ: the point light's
    // layers had 1 of their 119 825 caster texels 0.1 mm off.
    EXPECT_LE(d.differing, d.caster / 10000) << "of " << d.texels << " texels (" << d.caster << " nearer than far)";
    EXPECT_LT(d.largest, 1e-3);
    EXPECT_GT(d.caster, d.texels / 20) << "the casters cover the layers";
    // Drawn with back faces culled: the four solids in each layer that holds them (the ground
    // is open, the inside-out box not solid), and nothing with every mesh's `solid` cleared.
    // The directional light and the spot hold every caster in their one layer.
    EXPECT_EQ(both.stats.castersCulled, 0);
    if (type == LightType::Point) {
        EXPECT_GE(culled.stats.castersCulled, 4);
    } else {
        EXPECT_EQ(culled.stats.layers, 1);
        EXPECT_EQ(culled.stats.castersDrawn, 6);
        EXPECT_EQ(culled.stats.castersCulled, 4);
    }
}

INSTANTIATE_TEST_SUITE_P(EveryLightType, SolidCulling,
                         ::testing::Values(LightType::Directional, LightType::Spot, LightType::Point),
                         [](const ::testing::TestParamInfo<LightType>& param) {
                             return std::string(lightTypeName(param.param));
                         });

TEST(SolidCullingInside, KeepsBothSidesOfASolidTheLightIsIn) {
    const Layers culled = render(lightInsideABox(true));
    const Layers both = render(lightInsideABox(false));
    const Difference d = compare(culled, both);
    EXPECT_LE(d.differing, d.caster / 10000);
    EXPECT_LT(d.largest, 1e-3);
    // The room's walls fill every face.
    EXPECT_EQ(d.caster, d.texels);
    // A culled room would show the ground or the far depth through its walls: it is drawn with
    // both sides in all six faces. The sphere outside it is culled, in the faces it falls in.
    EXPECT_GE(culled.stats.castersCulled, 1);
    EXPECT_LE(culled.stats.castersCulled, 3);
}

}  // namespace
}  // namespace shadow::solid_culling_test
