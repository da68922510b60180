// The second-depth modes (DepthMode): what a layer stores, against the scene's closed form. A
// spot straight above a box on the ground: along the central texel's ray the box's top is the
// nearest surface, its bottom the second; beside the box the ground is the only surface.
#include <shadow/frame_runner.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <gtest/gtest.h>

#include <string>

#include "render/render_test_support.h"
#include "shadow/soft_test_support.h"
#include "test_support.h"

namespace shadow::depth_mode_test {
namespace {

constexpr int kMapSize = 64;
constexpr double kLightHeight = 5.0;
constexpr double kBoxTop = 1.5;
constexpr double kBoxBottom = 0.5;

/// The box floats 0.5 m above the ground, so that the ground under it is a third surface.
Scene boxUnderSpot(DepthMode mode) {
    Scene scene;
    test::addGround(scene, 4.0f);
    test::addBox(scene, "box", {0.0, 1.0, 0.0}, {0.5, 0.5, 0.5});
    Shadow s = test::shadowWith(ShadowTechnique::Hard, kMapSize);
    s.depthMode = mode;
    addLight(scene, "spot", test::pointSizedLight(LightType::Spot, 0.6f), s, {0.0, kLightHeight, 0.0}, {0, -1, 0});
    addCamera(scene, "camera", Camera{}, {0.0, 4.0, 6.0}, {0.0, 0.0, 0.0});
    return scene;
}

struct Stored {
    float centre = 0.0f;  ///< the texel whose ray runs (almost) straight down the box's axis
    float beside = 0.0f;  ///< a texel whose ray meets the ground only
    float scale = 0.0f;   ///< the layer's depth scale: the far depth in metres
    std::vector<Warning> warnings;
};

Stored render(DepthMode mode) {
    Scene scene = boxUnderSpot(mode);
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, 64, 48);
    const std::vector<float> depth = runner.shadows().maps().readLayerDepth(0, 0);
    EXPECT_EQ(depth.size(), static_cast<std::size_t>(kMapSize) * kMapSize);
    Stored s;
    s.scale = runner.shadows().frame().lights.at(0).layers.at(0).depthScale;
    s.centre = depth.at(static_cast<std::size_t>(kMapSize / 2) * kMapSize + kMapSize / 2);
    s.beside = depth.at(static_cast<std::size_t>(kMapSize / 2) * kMapSize + 4);
    s.warnings = frame.stats.warnings;
    EXPECT_EQ(frame.stats.lights.at(0).castersDrawn, mode == DepthMode::Nearest ? 2 : 4) << depthModeName(mode);
    EXPECT_EQ(frame.stats.shadowScratchBytes,
              mode == DepthMode::Nearest ? 0 : static_cast<long long>(kMapSize) * kMapSize * 4);
    return s;
}

TEST(DepthMode, EachModeStoresItsSurfaceAlongTheRay) {
    // The central texel's ray leans half a texel (under 0.5 degrees) off the axis: its
    // distances differ from the axial ones by under 1e-4 relative.
    const double tolerance = 1e-3;
    const Stored nearest = render(DepthMode::Nearest);
    const Stored midpoint = render(DepthMode::Midpoint);
    const Stored second = render(DepthMode::Second);
    EXPECT_NEAR(nearest.centre, kLightHeight - kBoxTop, tolerance);
    EXPECT_NEAR(second.centre, kLightHeight - kBoxBottom, tolerance);
    EXPECT_NEAR(midpoint.centre, kLightHeight - 0.5 * (kBoxTop + kBoxBottom), tolerance);
    // Beside the box the ground is the only surface: the nearest mode stores it, the others the
    // far depth (nothing behind the ground can be shadowed by it).
    EXPECT_LT(nearest.beside, 0.99f * nearest.scale);
    EXPECT_GT(nearest.beside, kLightHeight);
    EXPECT_FLOAT_EQ(midpoint.beside, midpoint.scale);
    EXPECT_FLOAT_EQ(second.beside, second.scale);
    // The ground plane is open: the second-depth modes say so, the nearest mode has no need.
    EXPECT_EQ(test::countWarnings(nearest.warnings, WarningCode::OpenCaster, "spot"), 0);
    EXPECT_EQ(test::countWarnings(midpoint.warnings, WarningCode::OpenCaster, "spot"), 1);
    EXPECT_EQ(test::countWarnings(second.warnings, WarningCode::OpenCaster, "spot"), 1);
}

TEST(DepthMode, ChangingTheModeRedrawsTheLayersAndReusesThemAfter) {
    Scene scene = boxUnderSpot(DepthMode::Nearest);
    test::glContext();
    FrameRunner runner;
    test::renderFrame(runner, scene, 32, 24);
    EXPECT_EQ(test::renderFrame(runner, scene, 32, 24).stats.shadowLayersReused, 1);
    scene.world.view<Shadow>().each([](Entity, Shadow& s) { s.depthMode = DepthMode::Midpoint; });
    const test::RenderedFrame changed = test::renderFrame(runner, scene, 32, 24);
    EXPECT_EQ(changed.stats.shadowLayersDrawn, 1);
    EXPECT_NEAR(runner.shadows().maps().readLayerDepth(0, 0).at(kMapSize / 2 * kMapSize + kMapSize / 2),
                kLightHeight - 1.0, 1e-3);
    EXPECT_EQ(test::renderFrame(runner, scene, 32, 24).stats.shadowLayersReused, 1);
}

}  // namespace
}  // namespace shadow::depth_mode_test
