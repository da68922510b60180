// The min/max depth pyramid (engine/src/shadow/minmax_pyramid.cpp): every texel of every level
// holds exactly the least and greatest stored depth of its tile of the map, it exists only for
// the techniques that read it, and it follows the map when the map changes.
#include <shadow/shared_constants.h>

#include <gtest/gtest.h>

#include "gl/objects.h"
#include "render/render_test_support.h"

#include <algorithm>

namespace shadow {
namespace {

/// The box of the last scene made (one per test).
Entity& boxOf(Scene&) {
    static Entity box;
    return box;
}

/// A spot light over a ground with a box and a sphere, so the map holds several depths.
Scene tiltedScene(ShadowTechnique technique, int mapSize) {
    Scene scene;
    test::addGround(scene, 6.0f);
    boxOf(scene) = test::addBox(scene, "box", {0.5, 0.6, -0.3}, {0.4, 0.6, 0.5});
    Shadow shadow = test::hardShadow(mapSize);
    shadow.technique = technique;
    addLight(scene, "spot", test::pointSizedLight(LightType::Spot, 0.6f), shadow, {-3.0, 5.0, 2.0},
             glm::normalize(glm::dvec3(3.0, -5.0, -2.0)));
    addCamera(scene, "camera", Camera{}, {0.0, 6.0, 8.0}, {0.0, 0.0, 0.0});
    return scene;
}

/// Level `level` of layer `layer` of the pyramid `texture` (RG pairs, rows bottom first).
std::vector<float> readLevel(GLuint texture, int level, int layer, int size) {
    std::vector<float> data(static_cast<std::size_t>(size) * size * 2);
    gl.GetTextureSubImage(texture, level, 0, 0, layer, size, size, 1, GL_RG, GL_FLOAT,
                          static_cast<GLsizei>(data.size() * sizeof(float)), data.data());
    return data;
}

void expectPyramidMatchesMap(FrameRunner& runner, int mapSize, const std::string& what) {
    const ShadowSystem& shadows = runner.shadows();
    const GLuint pyramid = shadows.minMaxOf(0);
    ASSERT_NE(pyramid, 0u) << what;
    const float scale = shadows.frame().lights[0].layers[0].depthScale;
    std::vector<float> depth = shadows.readLayerDepth(0, 0);  // metres, rows bottom first
    for (float& d : depth) d /= scale;                        // back to stored units
    int size = 1;  // level 0: the power of two of at least mapSize / SG_MINMAX_TILE texels
    while (size * SG_MINMAX_TILE < mapSize) size *= 2;
    // Levels up to the first whose tiles span the widest region the lookup asks for.
    const float maxFilterTexels = shadows.frame().lights[0].settings.maxFilterTexels;
    int levels = 1;
    for (int tile = SG_MINMAX_TILE; tile < 2.0f * (maxFilterTexels + 1.5f) && (size >> levels) > 0; tile *= 2) ++levels;
    int checked = 0;
    for (int level = 0; level < levels; ++level, size = std::max(1, size / 2)) {
        const std::vector<float> got = readLevel(pyramid, level, 0, size);
        const int tile = SG_MINMAX_TILE << level;
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                float lo = 1.0f, hi = 0.0f;
                for (int ty = y * tile; ty < std::min((y + 1) * tile, mapSize); ++ty) {
                    for (int tx = x * tile; tx < std::min((x + 1) * tile, mapSize); ++tx) {
                        const float d = depth[static_cast<std::size_t>(ty) * mapSize + tx];
                        lo = std::min(lo, d);
                        hi = std::max(hi, d);
                    }
                }
                if (x * tile >= mapSize || y * tile >= mapSize) continue;  // past the map's edge
                const std::size_t i = 2 * (static_cast<std::size_t>(y) * size + x);
                ASSERT_FLOAT_EQ(got[i], lo) << what << ": level " << level << " texel " << x << "," << y;
                ASSERT_FLOAT_EQ(got[i + 1], hi) << what << ": level " << level << " texel " << x << "," << y;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 1000) << what;
}

TEST(MinMaxPyramid, EveryTexelHoldsTheRangeOfItsTile) {
    test::glContext();
    for (int mapSize : {256, 200}) {  // a power of two, and a size whose tiles overhang the map
        Scene scene = tiltedScene(ShadowTechnique::Pcss, mapSize);
        FrameRunner runner;
        (void)test::renderFrame(runner, scene, 64, 48);
        expectPyramidMatchesMap(runner, mapSize, "map " + std::to_string(mapSize));
    }
}

TEST(MinMaxPyramid, OnlyForTechniquesThatReadItAndRebuiltWhenTheMapChanges) {
    test::glContext();
    Scene scene = tiltedScene(ShadowTechnique::Hard, 256);
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, 64, 48);
    EXPECT_EQ(runner.shadows().minMaxOf(0), 0u) << "hard shadows read no pyramid";

    scene.world.get<Shadow>(scene.lights[0]).technique = ShadowTechnique::Pcf;
    (void)test::renderFrame(runner, scene, 64, 48);
    expectPyramidMatchesMap(runner, 256, "after switching to PCF");

    // Move the box: the layer is redrawn and its pyramid follows.
    scene.world.get<Transform>(boxOf(scene)).translation.x += 0.7;
    const test::RenderedFrame moved = test::renderFrame(runner, scene, 64, 48);
    EXPECT_EQ(moved.stats.shadowLayersDrawn, 1);
    expectPyramidMatchesMap(runner, 256, "after the box moved");
}

}  // namespace
}  // namespace shadow
