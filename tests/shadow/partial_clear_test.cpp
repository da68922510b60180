// A redrawn layer clears only the texels its casters (and backgrounds) may have written since it
// was last cleared (ShadowMapGpu::writtenTexels, shadow_maps.cpp): a caster that moves, leaves
// the light's view or stops casting leaves no depth behind. The reference is a fresh renderer
// (its maps allocated and cleared whole) drawing the same scene once: every layer must hold the
// same depths to the bit. A game's caster that draws beyond the bounds it gave is held to them.
#include <shadow/caster_draw.h>
#include <shadow/frame_runner.h>
#include <shadow/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/game_mesh_test_support.h"

namespace shadow::partial_clear_test {
namespace {

constexpr int kMapSize = 256;

struct Case {
    LightType type;
    ShadowTechnique technique;
    const char* name;
};

/// Where the box stands in each frame; `casts` false clears its castShadows.
struct BoxState {
    glm::dvec3 at;
    bool casts = true;
};

/// A ground that only receives (a background of the moment techniques), a box that casts and a
/// post that stays, under one light of `c`'s type and technique.
Scene boxScene(const Case& c, const BoxState& box, Entity* boxEntity = nullptr) {
    Scene scene;
    const Entity ground = test::addGround(scene, 4.0f);
    scene.world.get<Mesh>(ground).castShadows = false;
    const Entity moving = test::addBox(scene, "box", box.at, {0.3, 0.3, 0.3});
    scene.world.get<Mesh>(moving).castShadows = box.casts;
    test::addBox(scene, "post", {-1.0, 0.5, 0.8}, {0.1, 0.5, 0.1});
    Shadow shadow = test::hardShadow(kMapSize);
    shadow.technique = c.technique;
    const glm::dvec3 light = c.type == LightType::Directional ? glm::dvec3(2.0, 8.0, 3.0) : glm::dvec3(0.3, 3.0, 0.4);
    addLight(scene, "light", test::pointSizedLight(c.type, 1.1f), shadow, light,
             c.type == LightType::Point ? glm::dvec3(0.0, -1.0, 0.0) : glm::normalize(-light));
    addCamera(scene, "camera", Camera{}, {0.0, 4.0, 6.0}, {0.0, 0.5, 0.0});
    if (boxEntity != nullptr) *boxEntity = moving;
    return scene;
}

/// Every layer of light 0's map, as `runner` last drew it.
std::vector<std::vector<float>> layers(FrameRunner& runner) {
    std::vector<std::vector<float>> out;
    for (int k = 0; k < runner.shadows().maps().layersOf(0); ++k) {
        out.push_back(runner.shadows().maps().readLayerDepth(0, k));
    }
    return out;
}

/// Texels of `a` that differ from `b`'s, over every layer.
long long differing(const std::vector<std::vector<float>>& a, const std::vector<std::vector<float>>& b) {
    EXPECT_EQ(a.size(), b.size());
    long long n = 0;
    for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) {
        EXPECT_EQ(a[k].size(), b[k].size());
        for (std::size_t i = 0; i < a[k].size() && i < b[k].size(); ++i) n += a[k][i] != b[k][i] ? 1 : 0;
    }
    return n;
}

class PartialClear : public ::testing::TestWithParam<Case> {};

TEST_P(PartialClear, ARedrawnLayerHoldsWhatAFreshMapHolds) {
    const Case c = GetParam();
    test::glContext();
    // The box moves across the light's view, leaves it, comes back, then stops casting.
    const std::vector<BoxState> states{
        {{0.8, 0.4, 0.0}}, {{-0.6, 0.4, -0.9}}, {{60.0, 0.4, 60.0}}, {{0.2, 1.2, 0.5}}, {{0.2, 1.2, 0.5}, false}};
    Entity box;
    Scene scene = boxScene(c, states.front(), &box);
    FrameRunner runner;
    std::vector<std::vector<float>> previous;
    for (std::size_t f = 0; f < states.size(); ++f) {
        scene.world.get<Transform>(box).translation = states[f].at;
        scene.world.get<Mesh>(box).castShadows = states[f].casts;
        test::renderFrame(runner, scene, 48, 32, static_cast<double>(f));
        const std::vector<std::vector<float>> drawn = layers(runner);

        Scene same = boxScene(c, states[f]);
        FrameRunner fresh;
        test::renderFrame(fresh, same, 48, 32, static_cast<double>(f));
        EXPECT_EQ(differing(drawn, layers(fresh)), 0) << "frame " << f;
        // Each change of the box changes the map: the frames test something.
        if (f > 0) {
            EXPECT_GT(differing(drawn, previous), 0) << "frame " << f << " drew what frame " << f - 1 << " did";
        }
        previous = drawn;
    }
}

/// A ground that only receives, a spot light, and a game's box (its own vertex array) at `at`
/// whose bounds say half its size: it draws beyond them.
Scene gameBoxScene(const test::GameMesh& box, const glm::dvec3& at) {
    Scene scene;
    const Entity ground = test::addGround(scene, 4.0f);
    scene.world.get<Mesh>(ground).castShadows = false;
    ShadowCasterDraw draw;
    draw.localBounds = Aabb{box.bounds.min * 0.5f, box.bounds.max * 0.5f};
    draw.vertexArray = GlVertexArray{box.vertexArray};
    draw.indexCount = box.indexCount;
    const Entity e = scene.world.create();
    scene.world.emplace<Transform>(e, test::placed(at));
    scene.world.emplace<ShadowCasterDraw>(e, std::move(draw));
    addLight(scene, "light", test::pointSizedLight(LightType::Spot, 1.1f), test::hardShadow(kMapSize), {0.3, 3.0, 0.4},
             glm::normalize(glm::dvec3(-0.3, -3.0, -0.4)));
    addCamera(scene, "camera", Camera{}, {0.0, 4.0, 6.0}, {0.0, 0.5, 0.0});
    return scene;
}

TEST(PartialClear, AGameCasterBeyondItsBoundsLeavesNoDepthBehind) {
    test::glContext();
    const test::GameMesh box(*makeBoxMesh(glm::vec3(0.6f, 0.3f, 0.6f)));
    const std::vector<glm::dvec3> at{{0.8, 0.4, 0.0}, {-0.7, 0.4, -0.8}, {0.1, 0.4, 0.9}};
    Scene scene = gameBoxScene(box, at.front());
    FrameRunner runner;
    for (std::size_t f = 0; f < at.size(); ++f) {
        scene.world.view<ShadowCasterDraw, Transform>().each(
            [&](Entity, ShadowCasterDraw&, Transform& t) { t.translation = at[f]; });
        test::renderFrame(runner, scene, 48, 32, static_cast<double>(f));
        Scene same = gameBoxScene(box, at[f]);
        FrameRunner fresh;
        test::renderFrame(fresh, same, 48, 32, static_cast<double>(f));
        const std::vector<std::vector<float>> drawn = layers(runner);
        EXPECT_EQ(differing(drawn, layers(fresh)), 0) << "frame " << f;
        const auto [nearest, farthest] = std::minmax_element(drawn.at(0).begin(), drawn.at(0).end());
        EXPECT_LT(*nearest, *farthest) << "frame " << f << ": the box casts into the layer";
    }
}

INSTANTIATE_TEST_SUITE_P(Lights, PartialClear,
                         ::testing::Values(Case{LightType::Spot, ShadowTechnique::Hard, "SpotHard"},
                                           Case{LightType::Point, ShadowTechnique::Pcf, "PointPcf"},
                                           Case{LightType::Directional, ShadowTechnique::Pcss, "SunPcss"},
                                           Case{LightType::Spot, ShadowTechnique::Vsm, "SpotVsmWithBackgrounds"}),
                         [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace shadow::partial_clear_test
