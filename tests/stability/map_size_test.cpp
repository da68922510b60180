// Shadow-map sizes at the extremes: 1 and 3 texels, the GL limit (16384 on llvmpipe: 1 GiB of
// float depth for one layer), and sizes beyond the limit (clamped with a warning), plus the
// planner's memory budget, which keeps the maps of all lights together (depth and filter chains)
// by a documented, deterministic policy (ShadowLimits::maxShadowBytes). The cases at the limit
// run in the fast tier at a limit lowered to 2048 with the budget in proportion, and in the slow
// tier at the real one.
#include <gtest/gtest.h>
#include <shadow/context.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdint>
#include <fstream>
#include <string>

#include "shadow/map_memory.h"
#include "stability/stability_test_support.h"
#include "test_support.h"

namespace shadow::map_size_test {
namespace {

const glm::dvec3 kBoxCenter{0.0, 1.2, 0.0};
const glm::dvec3 kBoxHalf{0.5, 0.3, 0.4};

Scene boxScene(LightType type, int mapSize) {
    Scene scene;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "box", kBoxCenter, kBoxHalf);
    addCamera(scene, "camera", Camera{}, {0.5, 5.0, 4.5}, {0.0, 0.0, 0.0});
    Light light = test::pointSizedLight(type, 0.7f);
    light.radius = 0.1f;
    light.angularRadius = 0.02f;
    addLight(scene, "light", light, test::shadowWith(ShadowTechnique::Hard, mapSize), {0.3, 4.0, 0.2},
             glm::normalize(glm::dvec3(0.1, -1.0, 0.05)));
    return scene;
}

/// MemAvailable of /proc/meminfo in GiB (0 when unknown).
double availableGiB() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    long long kib = 0;
    std::string unit;
    while (in >> key >> kib >> unit) {
        if (key == "MemAvailable:") return static_cast<double>(kib) / (1024.0 * 1024.0);
    }
    return 0.0;
}

TEST(Stability, TinyMapsOfOneAndThreeTexelsStayFinite) {
    for (LightType type : {LightType::Directional, LightType::Spot, LightType::Point}) {
        for (int size : {1, 3}) {
            Scene scene = boxScene(type, size);
            const std::string name = std::string(type == LightType::Directional ? "sun"
                                                 : type == LightType::Spot      ? "spot"
                                                                                : "point") +
                                     " with a " + std::to_string(size) + "^2 map";
            test::forEveryTechnique(
                scene, 96, 72, name, [&](ShadowTechnique, const test::RenderedFrame& frame, FrameRunner& runner) {
                    EXPECT_EQ(runner.shadows().frame().lights.at(0).mapSize, size);
                    EXPECT_TRUE(frame.stats.warnings.empty()) << name << ":\n" << test::describe(frame.stats.warnings);
                });
        }
    }
}

/// Beyond GL_MAX_TEXTURE_SIZE: clamped to the limit with a warning, never a GL error. The
/// limit is lowered to 2048 here to keep the test fast; the slow tier renders the real one.
TEST(Stability, MapSizeBeyondTheGlLimitIsClampedWithAWarning) {
    for (LightType type : {LightType::Directional, LightType::Spot, LightType::Point}) {
        Scene scene = boxScene(type, INT_MAX);
        test::glContext();
        FrameRunner runner;
        runner.shadows().planner().setLimits({2048, 2048, ShadowLimits{}.maxShadowBytes});
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 96, 72);
        test::expectSaneFrame(frame.images, runner.shadows(), "INT_MAX map");
        const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
        EXPECT_EQ(plan.settings.mapSize, 2048);
        EXPECT_EQ(test::countWarnings(frame.stats.warnings, WarningCode::SettingClamped, "light"), 1)
            << test::describe(frame.stats.warnings);
        EXPECT_GT(test::countGround(frame.images, 0).dark, 100);
    }
}

/// The limits of the test context (GL_MAX_TEXTURE_SIZE: 16384 on llvmpipe) with the default
/// budget, 2^30 bytes: one hard layer at the limit.
ShadowLimits glLimits() {
    test::glContext();
    const GlInfo info = queryGlInfo();
    return {info.maxTextureSize, info.maxArrayLayers, ShadowLimits{}.maxShadowBytes};
}

/// The same proportions at a tenth of the cost: a limit of 2048 and a budget of one hard layer
/// of that size (16 MiB).
ShadowLimits loweredLimits() { return {2048, 2048, std::int64_t{4} * 2048 * 2048}; }

std::string atTheLimit(const ShadowLimits& limits) { return std::to_string(limits.maxTextureSize) + "^2"; }

/// A spot with mapSize INT_MAX gets the limit, one layer that the budget just allows, with a
/// warning; its depths finite and inside the layer's range. A point light asking for the same
/// gets six faces halved by the budget until they fit (at the real limit: 4096, 0.375 GiB).
void expectMapsAtTheLimit(const ShadowLimits& limits) {
    test::glContext();
    {
        Scene scene = boxScene(LightType::Spot, INT_MAX);
        FrameRunner runner;
        runner.shadows().planner().setLimits(limits);
        const auto t0 = std::chrono::steady_clock::now();
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 96, 72);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        test::reportFigure("spot at " + atTheLimit(limits) + " (" + queryGlInfo().renderer + "): first frame", ms,
                           " ms");
        test::expectSaneAovs(frame.images);
        const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
        EXPECT_EQ(plan.mapSize, limits.maxTextureSize);
        EXPECT_TRUE(test::hasWarning(frame.stats.warnings, WarningCode::SettingClamped, "light"))
            << test::describe(frame.stats.warnings);
        EXPECT_GT(test::countGround(frame.images, 0).dark, 100);
        // The depths themselves: finite and inside the layer's range.
        const test::ShadowMapCheck maps = test::checkShadowMaps(runner.shadows());
        EXPECT_EQ(maps.nonFinite, 0);
        EXPECT_EQ(maps.outOfRange, 0);
    }
    {
        Scene scene = boxScene(LightType::Point, INT_MAX);
        FrameRunner runner;
        runner.shadows().planner().setLimits(limits);
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 96, 72);
        test::expectSaneAovs(frame.images);
        const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
        test::reportFigure(
            "point asking for INT_MAX under a limit of " + atTheLimit(limits) + ": map edge after the budget",
            plan.mapSize);
        EXPECT_LT(plan.mapSize, limits.maxTextureSize);
        EXPECT_LE(std::int64_t{4} * plan.mapSize * plan.mapSize * 6, limits.maxShadowBytes);
        EXPECT_TRUE(test::hasWarning(frame.stats.warnings, WarningCode::MapSizeReduced, "light"))
            << test::describe(frame.stats.warnings);
    }
}

TEST(Stability, MapAtALoweredLimitRendersWithinItsBudget) { expectMapsAtTheLimit(loweredLimits()); }

// The real limit: 1 GiB of depth for the spot's one layer.
TEST(Stability, SlowMapAtTheGlLimitRendersWhenMemoryAllows) {
    const ShadowLimits limits = glLimits();
    const double layerGiB = static_cast<double>(limits.maxTextureSize) * limits.maxTextureSize * 4.0 / (1u << 30);
    // The layer, its readback, and llvmpipe's staging copy.
    if (availableGiB() < 4.0 * layerGiB + 1.0) {
        GTEST_SKIP() << "needs " << 4.0 * layerGiB + 1.0 << " GiB free for a " << atTheLimit(limits) << " layer";
    }
    expectMapsAtTheLimit(limits);
}

/// Every moment technique asking for the limit: those that add a filter chain reduced by the
/// memory budget until depth and chain fit, warned, and drawn, where counting depth texels alone
/// let them run out of memory (GL_OUT_OF_MEMORY at the real limit); chainless msm as asked.
void expectEveryTechniqueReducedToTheBudget(const ShadowLimits& limits) {
    test::glContext();
    for (const ShadowTechnique technique :
         {ShadowTechnique::Vsm, ShadowTechnique::Vssm, ShadowTechnique::Msm, ShadowTechnique::MsmSoft}) {
        const std::string name = techniqueName(technique);
        Scene scene = boxScene(LightType::Spot, limits.maxTextureSize);
        scene.world.get<Shadow>(scene.lights[0]).technique = technique;
        FrameRunner runner;
        runner.shadows().planner().setLimits(limits);
        const auto t0 = std::chrono::steady_clock::now();
        test::RenderedFrame frame;
        ASSERT_NO_THROW(frame = test::renderFrame(runner, scene, 96, 72)) << name;
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
        const LightShadowStats& ls = frame.stats.lights.at(0);
        test::reportFigure(name + " asking for " + atTheLimit(limits) + ": map edge after the budget", plan.mapSize);
        test::reportFigure(name + ": map and chain (MiB)",
                           static_cast<double>(ls.mapBytes + ls.filterChainBytes) / (1 << 20));
        test::reportFigure(name + ": first frame", ms, " ms");
        // A technique with a chain is halved to fit; hard-edged msm, chainless, fits as asked.
        const bool chain = filterChainOf(technique).has_value();
        EXPECT_EQ(plan.mapSize < limits.maxTextureSize, chain) << name;
        EXPECT_LE(ls.mapBytes + ls.filterChainBytes, limits.maxShadowBytes) << name;
        EXPECT_EQ(test::hasWarning(frame.stats.warnings, WarningCode::MapSizeReduced, "light"), chain)
            << name << ":\n"
            << test::describe(frame.stats.warnings);
        EXPECT_GT(test::countGround(frame.images, 0).dark, 100) << name << ": the box casts its shadow";
    }
}

TEST(Stability, EveryTechniqueAtALoweredLimitRendersReducedToTheBudget) {
    expectEveryTechniqueReducedToTheBudget(loweredLimits());
}

TEST(Stability, SlowEveryTechniqueAtTheGlLimitRendersReducedToTheMemoryBudget) {
    // The maps (at most the 1 GiB budget), llvmpipe's staging copies and the readbacks.
    if (availableGiB() < 4.0) GTEST_SKIP() << "needs 4 GiB free";
    expectEveryTechniqueReducedToTheBudget(glLimits());
}

// ---- The memory budget's policy, on the planner alone ----

/// Four spot lights at increasing distance from the camera (scene order deliberately not
/// distance order), a sun, and a spot behind the camera whose range cannot reach the view.
struct BudgetScene {
    Scene scene;
    CameraView view;

    BudgetScene() {
        test::addGround(scene, 20.0f);
        test::addBox(scene, "box", kBoxCenter, kBoxHalf);
        addCamera(scene, "camera", Camera{}, {0.0, 5.0, 8.0}, {0.0, 0.0, 0.0});
        const double distances[] = {6.0, 2.0, 12.0, 9.0};  // from the camera, along -z
        for (int i = 0; i < 4; ++i) {
            addLight(scene, "spot" + std::to_string(i), test::pointSizedLight(LightType::Spot),
                     test::shadowWith(ShadowTechnique::Hard, 1024), {0.0, 5.0, 8.0 - distances[i]}, {0, -1, 0});
        }
    }
    const ShadowFrame& prepare(ShadowPlanner& planner) {
        (void)updateTransforms(scene.world);
        view = makeCameraView(scene.world, scene.cameras[0], 1.0f);
        return planner.prepare(scene.world, view, scene.lights);
    }
};

int mapSizeOf(const ShadowFrame& frame, const std::string& name) {
    for (const ShadowLightPlan& p : frame.lights) {
        if (p.name == name) return p.mapSize;
    }
    return 0;  // no shadow
}

TEST(Stability, MemoryBudgetHalvesTheFarthestLightsFirst) {
    BudgetScene b;
    ShadowPlanner planner;
    // Room for three hard 1024^2 maps (4 bytes a texel) and a bit: halving the farthest (spot2)
    // is not enough, halving the next farthest (spot3) is.
    planner.setLimits({16384, 2048, 4 * (3 * 1024 * 1024 + 1000)});
    const ShadowFrame& frame = b.prepare(planner);
    EXPECT_EQ(mapSizeOf(frame, "spot0"), 1024);
    EXPECT_EQ(mapSizeOf(frame, "spot1"), 1024);
    EXPECT_EQ(mapSizeOf(frame, "spot2"), 512);
    EXPECT_EQ(mapSizeOf(frame, "spot3"), 512);
    EXPECT_TRUE(test::hasWarning(frame.warnings, WarningCode::MapSizeReduced, "spot2"));
    EXPECT_TRUE(test::hasWarning(frame.warnings, WarningCode::MapSizeReduced, "spot3"));
    EXPECT_EQ(frame.warnings.size(), 2u) << test::describe(frame.warnings);
    // Deterministic: the same decision every frame.
    const ShadowFrame& again = b.prepare(planner);
    EXPECT_EQ(mapSizeOf(again, "spot2"), 512);
    EXPECT_EQ(mapSizeOf(again, "spot0"), 1024);
}

TEST(Stability, MemoryBudgetDropsTheFarthestShadowsWhenHalvingIsNotEnough) {
    BudgetScene b;
    // A sun (distance 0: the nearest) with two cascades.
    Shadow sunShadow = test::shadowWith(ShadowTechnique::Hard, 1024);
    sunShadow.cascades = 2;
    addLight(b.scene, "sun", test::pointSizedLight(LightType::Directional), sunShadow, {0, 10, 0}, {0.2, -1, 0.1});
    ShadowPlanner planner;
    // Two layers of the floor size (256^2) fit, and nothing more: every map is halved to 256,
    // then the farthest lose their shadow until only the two nearest layers are left (the sun's
    // two cascades); every decision is one warning.
    planner.setLimits({16384, 2048, 4 * 2 * 256 * 256});
    const ShadowFrame& frame = b.prepare(planner);
    const auto withMap =
        std::count_if(frame.lights.begin(), frame.lights.end(), [](const ShadowLightPlan& p) { return p.hasMap(); });
    ASSERT_EQ(withMap, 1);
    const ShadowLightPlan& sun = frame.lights.back();
    EXPECT_EQ(sun.name, "sun");
    EXPECT_TRUE(sun.hasMap());
    EXPECT_EQ(sun.mapSize, 256);
    EXPECT_TRUE(test::hasWarning(frame.warnings, WarningCode::MapSizeReduced, "sun"));
    for (int i = 0; i < 4; ++i) {
        EXPECT_TRUE(test::hasWarning(frame.warnings, WarningCode::ShadowDropped, "spot" + std::to_string(i)));
    }
    EXPECT_EQ(frame.warnings.size(), 5u) << test::describe(frame.warnings);
}

TEST(Stability, MemoryBudgetRanksLightsThatCannotReachTheViewAsFarthest) {
    BudgetScene b;
    // Near the camera but behind it, with a range that ends before the view begins.
    Light unseen = test::pointSizedLight(LightType::Spot);
    unseen.range = 1.0f;
    addLight(b.scene, "behind", unseen, test::shadowWith(ShadowTechnique::Hard, 1024), {0.0, 5.0, 12.0}, {0, 0, 1});
    ShadowPlanner planner;
    planner.setLimits({16384, 2048, 4 * (4 * 1024 * 1024 + 512 * 512)});
    const ShadowFrame& frame = b.prepare(planner);
    EXPECT_EQ(mapSizeOf(frame, "behind"), 512);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(mapSizeOf(frame, "spot" + std::to_string(i)), 1024);
}

}  // namespace
}  // namespace shadow::map_size_test
