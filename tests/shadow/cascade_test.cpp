// Stability of directional cascades (engine/src/shadow/light_projection.cpp): each cascade is
// fitted to the bounding sphere of its camera slice (rotation invariant) and its centre is
// snapped to whole texels, so a moving camera moves a map by whole texels only and a turning
// camera does not change its texel size; the maps' contents then follow the world exactly.
#include <gtest/gtest.h>
#include <shadow/shadow_system.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "shadow/soft_test_support.h"

namespace shadow::cascade_test {
namespace {

constexpr int kCascades = 3;
constexpr int kMapSize = 1024;
constexpr float kShadowDistance = 25.0f;
/// Texels next to a map's border not compared (the shifted map brings new content there).
constexpr int kBorderTexels = 4;
/// Largest fraction of compared texels whose depth may differ (by more than kDepthTolerance)
/// between a map and the same map moved by whole texels.
constexpr double kMaxDifferingFraction = 0.005;
/// Depth tolerance (m): float rounding of light-space positions shifted by whole texels.
constexpr float kDepthTolerance = 1e-3f;

/// A large ground with boxes spread from the camera out past the shadow distance, a sun with
/// three cascades, and a camera 5 m above the ground (well above the boxes: the distance to the
/// receivers, where the first cascade starts, does not change while it moves sideways).
struct CascadeScene {
    Scene scene;
    Entity camera;
    Entity sun;
};

CascadeScene makeCascadeScene(float shadowDistance = kShadowDistance) {
    CascadeScene s;
    test::addGround(s.scene, 30.0f);
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 3; ++j) {
            const double height = 0.4 + 0.3 * ((i + j) % 3);
            test::addBox(s.scene, "box", {-6.0 + 6.0 * j, height, 6.0 - 7.0 * i}, {0.6, height, 0.5});
        }
    }
    Light sun = test::pointSizedLight(LightType::Directional);
    Shadow shadow = test::shadowWith(ShadowTechnique::Pcf, kMapSize);
    shadow.cascades = kCascades;
    shadow.shadowDistance = shadowDistance;
    s.sun = addLight(s.scene, "sun", sun, shadow, {0, 20, 0}, glm::normalize(glm::dvec3(0.3, -1.0, 0.45)));
    Camera lens;
    lens.zfar = 200.0f;
    s.camera = addCamera(s.scene, "camera", lens, {0.0, 5.0, 12.0}, {0.0, 0.0, -10.0});
    return s;
}

/// What a frame left in the sun's cascades.
struct CascadeState {
    std::vector<ShadowLayerPlan> layers;
    std::vector<std::vector<float>> depth;  ///< readLayerDepth of each layer, row-major, y up; empty without
};

/// Renders a frame and keeps its cascades' plans and, `withDepth`, their maps (3 x 4 MB read back:
/// most of a frame's time here, spared to the tests that look at the plans only).
CascadeState renderCascades(FrameRunner& runner, CascadeScene& s, bool withDepth = true) {
    test::renderFrame(runner, s.scene, 128, 72);
    CascadeState state;
    const ShadowFrame& frame = runner.shadows().frame();
    if (frame.lights.size() != 1 || frame.lights[0].layers.size() != kCascades) {
        ADD_FAILURE() << "expected one sun with " << kCascades << " cascades";
        return state;
    }
    state.layers = frame.lights[0].layers;
    if (!withDepth) return state;
    for (int k = 0; k < kCascades; ++k) state.depth.push_back(runner.shadows().maps().readLayerDepth(0, k));
    return state;
}

void moveCamera(CascadeScene& s, const glm::dvec3& by) { s.scene.world.get<Transform>(s.camera).translation += by; }

double extentOf(const ShadowLayerPlan& layer) { return 2.0 / layer.clipFromLight[0][0]; }
double texelOf(const ShadowLayerPlan& layer) { return extentOf(layer) / kMapSize; }

/// The light-space x, y of the layer's centre: lightFromWorld = translate(-(centre, top)) * R.
glm::dvec2 centreOf(const ShadowLayerPlan& layer) { return -glm::dvec2(layer.lightFromWorld[3]); }

/// The light's x axis in world space (a horizontal vector for a light that is not vertical).
glm::dvec3 lightXAxis(const ShadowLayerPlan& layer) {
    return glm::normalize(
        glm::dvec3(layer.lightFromWorld[0][0], layer.lightFromWorld[1][0], layer.lightFromWorld[2][0]));
}

/// Whole-texel shift of the layer's centre from `before` to `after`; fails when it is not whole.
glm::ivec2 texelShift(const ShadowLayerPlan& before, const ShadowLayerPlan& after, int k) {
    const glm::dvec2 shift = (centreOf(after) - centreOf(before)) / texelOf(before);
    const glm::dvec2 whole = glm::round(shift);
    EXPECT_NEAR(shift.x, whole.x, 1e-6) << "cascade " << k << " moved by a fraction of a texel";
    EXPECT_NEAR(shift.y, whole.y, 1e-6) << "cascade " << k << " moved by a fraction of a texel";
    return glm::ivec2(whole);
}

/// Fraction of the texels away from the border where `after` differs from `before` moved by
/// `shift` texels (after[x, y] shows what before[x + shift.x, y + shift.y] showed).
double differingFraction(const std::vector<float>& before, const std::vector<float>& after, glm::ivec2 shift) {
    int compared = 0;
    int differing = 0;
    for (int y = kBorderTexels; y < kMapSize - kBorderTexels; ++y) {
        for (int x = kBorderTexels; x < kMapSize - kBorderTexels; ++x) {
            const int bx = x + shift.x;
            const int by = y + shift.y;
            if (bx < kBorderTexels || by < kBorderTexels || bx >= kMapSize - kBorderTexels ||
                by >= kMapSize - kBorderTexels) {
                continue;
            }
            ++compared;
            const float a = after[static_cast<std::size_t>(y) * kMapSize + x];
            const float b = before[static_cast<std::size_t>(by) * kMapSize + bx];
            if (std::abs(a - b) > kDepthTolerance) ++differing;
        }
    }
    return compared > 0 ? static_cast<double>(differing) / compared : 1.0;
}

TEST(Cascade, SubTexelCameraMoveKeepsMapContents) {
    CascadeScene s = makeCascadeScene();
    test::glContext();
    FrameRunner runner;
    // Every frame redraws every layer, so equal contents come from the same rasterisation and
    // not from a reused layer.
    runner.shadows().planner().setCaching(false);
    const CascadeState start = renderCascades(runner, s);
    ASSERT_EQ(start.layers.size(), static_cast<std::size_t>(kCascades));
    const double texel0 = texelOf(start.layers[0]);
    for (int k = 0; k < kCascades; ++k) {
        std::printf("[ measured ] cascade %d: extent %.4f m, texel %.5f m, splitFar %.3f m, %zu casters\n", k,
                    extentOf(start.layers[k]), texelOf(start.layers[k]), start.layers[k].splitFar,
                    start.layers[k].casters.size());
    }

    // A sub-texel move keeps each layer's matrices unless it carries the centre across a snap
    // boundary (chance ~ move / texel per axis). A move of 1 % of a texel cannot do so both ways
    // on one axis, so for each cascade one of +move and -move must keep the matrices. Any
    // change must be one whole texel, with the contents shifted by exactly that; a 40 % move
    // checks the same with boundaries crossed for sure in some cascade and axis.
    std::vector<bool> keptBySome(kCascades, false);
    for (double fraction : {0.01, 0.4}) {
        const glm::dvec3 subTexel = fraction * texel0 * glm::normalize(glm::dvec3(1.0, 0.0, 0.5));
        for (double sign : {1.0, -1.0}) {
            moveCamera(s, sign * subTexel);
            const CascadeState moved = renderCascades(runner, s);
            moveCamera(s, -sign * subTexel);
            ASSERT_EQ(moved.layers.size(), static_cast<std::size_t>(kCascades));
            for (int k = 0; k < kCascades; ++k) {
                const ShadowLayerPlan& a = start.layers[k];
                const ShadowLayerPlan& b = moved.layers[k];
                EXPECT_EQ(b.clipFromLight, a.clipFromLight) << "cascade " << k << ": extent or depth range changed";
                const glm::ivec2 shift = texelShift(a, b, k);
                EXPECT_LE(std::abs(shift.x) + std::abs(shift.y), 2) << "cascade " << k;
                const bool kept = b.lightFromWorld == a.lightFromWorld;
                if (kept && fraction < 0.1) keptBySome[k] = true;
                const double differing = differingFraction(start.depth[k], moved.depth[k], shift);
                std::printf(
                    "[ measured ] move %+.2f texel0, cascade %d: matrices %s, shift (%d, %d), %.5f "
                    "of texels "
                    "differ\n",
                    sign * fraction, k, kept ? "kept" : "changed", shift.x, shift.y, differing);
                EXPECT_LT(differing, kMaxDifferingFraction) << "cascade " << k;
                if (kept) {
                    EXPECT_EQ(differing, 0.0) << "cascade " << k << ": same matrices, different contents";
                }
            }
        }
    }
    for (int k = 0; k < kCascades; ++k) EXPECT_TRUE(keptBySome[k]) << "cascade " << k << " followed a sub-texel move";

    // A move of exactly three texels of cascade 0 along the light's x axis: cascade 0 moves by
    // exactly three texels, the coarser cascades by a whole number near 3 * texel0 / texelK,
    // and every map shows the same world, shifted.
    const glm::dvec3 threeTexels = 3.0 * texel0 * lightXAxis(start.layers[0]);
    moveCamera(s, threeTexels);
    const CascadeState moved = renderCascades(runner, s);
    ASSERT_EQ(moved.layers.size(), static_cast<std::size_t>(kCascades));
    for (int k = 0; k < kCascades; ++k) {
        const ShadowLayerPlan& a = start.layers[k];
        const ShadowLayerPlan& b = moved.layers[k];
        EXPECT_EQ(b.clipFromLight, a.clipFromLight) << "cascade " << k << ": extent or depth range changed";
        const glm::ivec2 shift = texelShift(a, b, k);
        const double expected = 3.0 * texel0 / texelOf(a);
        if (k == 0) {
            EXPECT_EQ(shift, glm::ivec2(3, 0));
        } else {
            EXPECT_GE(shift.x, static_cast<int>(std::floor(expected))) << "cascade " << k;
            EXPECT_LE(shift.x, static_cast<int>(std::ceil(expected))) << "cascade " << k;
            EXPECT_EQ(shift.y, 0) << "cascade " << k;
        }
        const double differing = differingFraction(start.depth[k], moved.depth[k], shift);
        // Control: compared one texel off along the light's y axis, the maps differ (the
        // ground's depth grows along y; along x, the light's horizontal axis, it is constant),
        // so the comparison above can tell a shifted map from a moved one.
        const double control = differingFraction(start.depth[k], moved.depth[k], shift + glm::ivec2(0, 1));
        std::printf(
            "[ measured ] 3-texel move, cascade %d: shift (%d, %d) (%.2f texels of it), %.5f of "
            "texels "
            "differ (one texel off: %.3f)\n",
            k, shift.x, shift.y, expected, differing, control);
        EXPECT_LT(differing, kMaxDifferingFraction) << "cascade " << k;
        EXPECT_GT(control, 0.5) << "cascade " << k << ": the depth comparison cannot see a one-texel shift";
    }
}

/// Cascades fit the receivers visible on screen, so turning the camera changes what they cover;
/// they must change in steps, not with every frame of a slow turn (the splits' ends are rounded
/// to 1/16 of their power of two, and each cascade's edge is quantized): a turn of 0.25 degrees a
/// frame over 12 degrees, at three pitches, changes the extents and splits in at most a fifth of
/// the frames.
TEST(Cascade, CameraRotationChangesCascadesInSteps) {
    CascadeScene s = makeCascadeScene();
    test::glContext();
    FrameRunner runner;
    Transform& camera = s.scene.world.get<Transform>(s.camera);
    const glm::dvec3 position = camera.translation;
    for (double pitchDeg : {-60.0, -20.0, -5.0}) {
        int changes = 0;
        int frames = 0;
        std::vector<ShadowLayerPlan> previous;
        for (double yawDeg = 0.0; yawDeg <= 12.0; yawDeg += 0.25) {
            const double yaw = yawDeg * test::kPi / 180.0;
            const double pitch = pitchDeg * test::kPi / 180.0;
            const glm::dvec3 forward(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                     -std::cos(pitch) * std::cos(yaw));
            camera.rotation = rotationLookingAlong(forward);
            camera.translation = position;
            const CascadeState turned = renderCascades(runner, s, false);
            ASSERT_EQ(turned.layers.size(), static_cast<std::size_t>(kCascades));
            if (!previous.empty()) {
                bool changed = false;
                for (int k = 0; k < kCascades; ++k) {
                    changed = changed || extentOf(turned.layers[k]) != extentOf(previous[k]) ||
                              turned.layers[k].splitFar != previous[k].splitFar;
                }
                changes += changed ? 1 : 0;
                ++frames;
            }
            previous = turned.layers;
        }
        std::printf("[ measured ] pitch %.0f: cascades changed in %d of %d frames of the turn\n", pitchDeg, changes,
                    frames);
        EXPECT_LE(changes, frames / 5) << "pitch " << pitchDeg;
    }
}

/// The farthest view depth at which a ray through the 128x72 image meets the receivers' top
/// faces (the ground y = 0 within +-30 m, the boxes' tops), sampled at every pixel centre.
double farthestVisibleDepth(const CameraView& view, const std::vector<DAabb>& tops) {
    const glm::dmat4 worldFromView = glm::inverse(view.viewFromWorld);
    const double ty = std::tan(0.5 * view.yfov);
    const double tx = ty * view.aspect;
    double farthest = 0.0;
    for (int y = 0; y < 72; ++y) {
        for (int x = 0; x < 128; ++x) {
            const glm::dvec3 dirView(tx * ((x + 0.5) / 64.0 - 1.0), ty * (1.0 - (y + 0.5) / 36.0), -1.0);
            const glm::dvec3 dir = glm::dvec3(worldFromView * glm::dvec4(dirView, 0.0));
            double nearestT = std::numeric_limits<double>::infinity();
            for (const DAabb& top : tops) {
                if (dir.y >= 0.0) continue;
                const double t = (top.max.y - view.wsPosition.y) / dir.y;
                const glm::dvec3 p = view.wsPosition + t * dir;
                if (t > 0.0 && p.x >= top.min.x && p.x <= top.max.x && p.z >= top.min.z && p.z <= top.max.z)
                    nearestT = std::min(nearestT, t);
            }
            if (std::isfinite(nearestT)) farthest = std::max(farthest, nearestT);  // t is the view depth
        }
    }
    return farthest;
}

/// The first cascade starts at the nearest visible receiver and the split distances grow to the
/// shadow distance or, without one, to the farthest receiver seen on screen (rounded out by at
/// most 1/16 of its power of two: the split's stability rounding).
TEST(Cascade, SplitsIncreaseToTheShadowDistance) {
    for (float shadowDistance : {kShadowDistance, 0.0f}) {
        CascadeScene s = makeCascadeScene(shadowDistance);
        test::glContext();
        FrameRunner runner;
        const CascadeState state = renderCascades(runner, s, false);
        ASSERT_EQ(state.layers.size(), static_cast<std::size_t>(kCascades));
        // Without a shadow distance, the bound is the farthest receiver in view (the 60 m ground
        // and the boxes on it), nearer than the far plane (200 m).
        std::vector<DAabb> tops{test::boxBounds({0, 0, 0}, {30, 0, 30})};
        s.scene.world.view<WorldBounds>().each([&](Entity, WorldBounds& b) { tops.push_back(b.box); });
        const double visible = farthestVisibleDepth(runner.lastCamera(), tops);
        const double bound = shadowDistance > 0.0f ? shadowDistance : visible;
        double previous = 0.0;
        for (int k = 0; k < kCascades; ++k) {
            const double splitFar = state.layers[k].splitFar;
            std::printf("[ measured ] shadowDistance %.0f: cascade %d ends at %.4f m\n", shadowDistance, k, splitFar);
            EXPECT_GT(splitFar, previous) << "cascade " << k;
            previous = splitFar;
        }
        if (shadowDistance > 0.0f) {
            EXPECT_NEAR(previous, bound, 1e-4 * bound) << "the last cascade does not end at the shadow distance";
        } else {
            EXPECT_GE(previous, 0.99 * bound) << "the last cascade stops before the farthest visible receiver";
            EXPECT_LE(previous, bound + std::exp2(std::ceil(std::log2(bound))) / 16.0 + 0.01 * bound)
                << "the last cascade reaches past the farthest visible receiver";
        }
    }
}

}  // namespace
}  // namespace shadow::cascade_test
