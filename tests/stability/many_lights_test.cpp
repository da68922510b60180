// Many shadowed lights: 1, 8, 64 and 256. Each light owns a texture array and is sampled in
// passes of eight (renderer.cpp), so 256 lights are 32 main passes. Every light is either
// rendered or degraded by the memory budget's documented policy (ShadowLimits::maxShadowBytes):
// never a crash, a GL error, NaN, or a light silently lost.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "stability/stability_test_support.h"
#include "test_support.h"

namespace shadow::many_lights_test {
namespace {

const glm::dvec3 kBoxHalf{0.4, 0.6, 0.4};

glm::dvec3 boxCentre(int i) { return {-4.0 + 2.0 * i, 0.6, 0.0}; }

/// A ground with a row of boxes, and `count` spot and point lights (alternating) in a grid
/// above it, every one shadowed, the techniques taking turns (one program holds them all).
Scene manyLights(int count, int mapSize) {
    const std::vector<ShadowTechnique> offered = test::offeredShadowTechniques();
    Scene scene;
    test::addGround(scene, 8.0f);
    for (int i = 0; i < 5; ++i) test::addBox(scene, "box" + std::to_string(i), boxCentre(i), kBoxHalf);
    addCamera(scene, "camera", Camera{}, {0.0, 9.0, 9.0}, {0.0, 0.0, 0.0});
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    for (int i = 0; i < count; ++i) {
        const double x = -6.0 + 12.0 * ((i % side) + 0.5) / side;
        const double z = -6.0 + 12.0 * ((i / side) + 0.5) / side;
        const LightType type = i % 2 == 0 ? LightType::Spot : LightType::Point;
        Light light = test::pointSizedLight(type, 0.9f);  // PCSS of a point-sized light is hard
        light.intensity = 40.0f / static_cast<float>(count);
        light.range = 12.0f;
        const ShadowTechnique technique = offered[static_cast<std::size_t>(i / 2) % 4];
        addLight(scene, "light" + std::to_string(i), light, test::shadowWith(technique, mapSize), {x, 3.0, z},
                 {0, -1, 0});
    }
    return scene;
}

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Ground pixels beyond the edge band whose shadow disagrees with ray casting, as a fraction of
/// the ground pixels lit by each light, summed over the lights (each light's own shadow in its
/// own visibility AOV).
double mismatchesBeyondBand(const test::RenderedFrame& frame, const Scene& scene, const ShadowFrame& plans) {
    std::vector<DAabb> boxes;
    for (int i = 0; i < 5; ++i) boxes.push_back(test::boxBounds(boxCentre(i), kBoxHalf));
    int beyond = 0;
    int ground = 0;
    for (const ShadowLightPlan& plan : plans.lights) {
        const WorldTransform& wt = scene.world.get<WorldTransform>(plan.entity);
        const test::AnalyticLight light{plan.light.type, glm::dvec3(wt.worldFromLocal[3]), {0, -1, 0}};
        // Four texels: two for the map's placement of an edge, two for PCF's 5 cm radius.
        const test::GeometryAgreement m = test::compareWithGeometry(
            frame.images, frame.images.visibility.at(static_cast<std::size_t>(plan.sceneIndex)), plan, light, boxes,
            4.0, plan.light.outerConeAngle);
        beyond += m.outsideBand;
        ground += m.groundPixels;
    }
    return static_cast<double>(beyond) / std::max(ground, 1);
}

TEST(Stability, ManyShadowedLightsRenderEachItsOwnShadow) {
    test::glContext();
    // One runner for every scene: the program of all four techniques is compiled once (1.5 s on
    // llvmpipe). A new scene's entities are new, so nothing of the last scene's maps is reused.
    FrameRunner runner;
    for (int count : {1, 8, 64, 256}) {
        Scene scene = manyLights(count, 256);
        const auto t0 = std::chrono::steady_clock::now();
        const test::RenderedFrame first = test::renderFrame(runner, scene, 96, 72);
        const double firstMs = msSince(t0);
        const auto t1 = std::chrono::steady_clock::now();
        const test::RenderedFrame steady = test::renderFrame(runner, scene, 96, 72);
        const double steadyMs = msSince(t1);
        const std::string name = std::to_string(count) + " lights";
        test::expectSaneFrame(steady.images, runner.shadows(), name);
        ASSERT_EQ(steady.images.visibility.size(), static_cast<std::size_t>(count));
        EXPECT_EQ(runner.shadows().frame().lights.size(), static_cast<std::size_t>(count)) << name;
        EXPECT_EQ(steady.stats.mainPasses, (count + 7) / 8) << name;
        EXPECT_TRUE(steady.stats.warnings.empty()) << name << ":\n" << test::describe(steady.stats.warnings);
        const double beyond = mismatchesBeyondBand(steady, scene, runner.shadows().frame());
        test::reportFigure(name + " (256^2 maps, 96x72): first frame", firstMs, " ms");
        test::reportFigure(name + ": steady frame (every layer reused)", steadyMs, " ms");
        test::reportFigure(name + ": main passes of the steady frame", steady.stats.passMs("Main/"), " ms");
        test::reportFigure(name + ": shadow passes of the first frame", first.stats.passMs("Shadow/"), " ms");
        test::reportFigure(name + ": ground beyond the edge band disagreeing with geometry", beyond);
        // The bound of the hard-shadow acceptance tests (tests/render/hard_shadow_test.cpp).
        EXPECT_LT(beyond, 0.001) << name;
    }
}

/// 64 lights at 2048^2 ask for 32 x (1 + 6) x 2^22 texels of 4 bytes and their filter chains: more
/// than 3.5 x 2^30 bytes, over three and a half times the default budget. The budget halves the
/// maps, farthest lights first, and every light keeps a shadow.
TEST(Stability, MemoryBudgetHalvesFarLightsFirstAndKeepsEveryShadow) {
    constexpr int kLights = 64;
    constexpr int kAsked = 2048;
    test::glContext();
    Scene scene = manyLights(kLights, kAsked);
    FrameRunner runner;
    const auto t0 = std::chrono::steady_clock::now();
    const test::RenderedFrame frame = test::renderFrame(runner, scene, 96, 72);
    test::reportFigure("64 lights at 2048^2 under the default budget: first frame", msSince(t0), " ms");
    test::expectSaneFrame(frame.images, runner.shadows(), "64 lights at 2048");
    const ShadowFrame& plans = runner.shadows().frame();
    ASSERT_EQ(plans.lights.size(), static_cast<std::size_t>(kLights));
    for (const ShadowLightPlan& p : plans.lights) ASSERT_TRUE(p.hasMap()) << p.name << " lost its shadow";
    std::int64_t total = 0;  // as allocated: the depth arrays and filter chains stats.json reports
    int reduced = 0;
    for (const LightShadowStats& ls : frame.stats.lights) total += ls.mapBytes + ls.filterChainBytes;
    for (const ShadowLightPlan& p : plans.lights) reduced += p.mapSize < kAsked ? 1 : 0;
    test::reportFigure("64 lights at 2048^2: bytes allocated / budget",
                       static_cast<double>(total) / static_cast<double>(ShadowLimits{}.maxShadowBytes));
    test::reportFigure("64 lights at 2048^2: lights with a reduced map", reduced);
    EXPECT_LE(total, ShadowLimits{}.maxShadowBytes);
    EXPECT_GT(reduced, 0);
    EXPECT_EQ(static_cast<int>(frame.stats.warnings.size()), reduced) << "one warning per reduced light";
    for (const ShadowLightPlan& p : plans.lights) {
        EXPECT_EQ(test::countWarnings(frame.stats.warnings, WarningCode::MapSizeReduced, p.name),
                  p.mapSize < kAsked ? 1 : 0)
            << p.name;
    }
}

}  // namespace
}  // namespace shadow::many_lights_test
