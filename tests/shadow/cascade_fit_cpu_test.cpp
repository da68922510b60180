// Cascades fitted to the receivers visible on screen (engine/src/shadow/light_projection.cpp,
// measureVisibleReceivers, visibleDepthRange and the sun's splits), on the CPU: the clipped
// depth range of a box against the camera frustum checked against a brute-force vertex
// enumeration of box ∩ frustum, and the planner's splits of whole scenes checked against the
// depths that rays through the screen's pixels meet the receivers at. The rendered side is in
// cascade_fit_test.cpp. No GL: these run in shadow_planner_tests.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <shadow/shadow_planner.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "shadow/light_projection.h"
#include "shadow/planner_test_support.h"

namespace shadow {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The splits round the visible range outwards to steps of 1/16 of its ends' power of two:
/// each end moves by at most this fraction of itself.
constexpr double kQuantization = 1.0 / 16.0;

/// A camera at `position` looking at `target`, the given vertical field of view, 16:9.
CameraView cameraLooking(const glm::dvec3& position, const glm::dvec3& target, float yfov, float znear, float zfar) {
    CameraView camera;
    camera.wsPosition = position;
    camera.viewFromWorld = lookAlong(position, glm::normalize(target - position));
    camera.yfov = yfov;
    camera.aspect = 16.0f / 9.0f;
    camera.znear = znear;
    camera.zfar = zfar;
    return camera;
}

/// The camera frustum's six planes in world space (n, w), inside where dot(n, p) + w >= 0,
/// built independently of the engine from the camera's basis.
std::array<glm::dvec4, 6> worldPlanes(const CameraView& cam, double far) {
    const glm::dmat4 worldFromView = glm::inverse(cam.viewFromWorld);
    const glm::dvec3 right(worldFromView[0]);
    const glm::dvec3 up(worldFromView[1]);
    const glm::dvec3 forward = -glm::dvec3(worldFromView[2]);
    const glm::dvec3 eye(worldFromView[3]);
    const double ty = std::tan(0.5 * static_cast<double>(cam.yfov));
    const double tx = ty * static_cast<double>(cam.aspect);
    auto plane = [&](const glm::dvec3& n, double offset) { return glm::dvec4(n, offset - glm::dot(n, eye)); };
    return {plane(forward, -static_cast<double>(cam.znear)),
            plane(-forward, far),
            plane(right + tx * forward, 0.0),
            plane(-right + tx * forward, 0.0),
            plane(up + ty * forward, 0.0),
            plane(-up + ty * forward, 0.0)};
}

/// The exact view-depth range of box ∩ frustum by brute force: every point where three of the
/// twelve planes (six of the box, six of the frustum) meet and that lies inside all twelve is a
/// vertex of the intersection, and a linear function's extremes over it lie at its vertices.
std::optional<DepthInterval> enumeratedDepth(const CameraView& cam, double far, const DAabb& box) {
    std::vector<glm::dvec4> planes;
    for (const glm::dvec4& p : worldPlanes(cam, far)) planes.push_back(p);
    for (int a = 0; a < 3; ++a) {
        glm::dvec3 n(0.0);
        n[a] = 1.0;
        planes.emplace_back(n, -box.min[a]);
        planes.emplace_back(-n, box.max[a]);
    }
    const glm::dvec3 forward = -glm::dvec3(glm::inverse(cam.viewFromWorld)[2]);
    DepthInterval range{kInf, -kInf};
    for (std::size_t i = 0; i < planes.size(); ++i) {
        for (std::size_t j = i + 1; j < planes.size(); ++j) {
            for (std::size_t k = j + 1; k < planes.size(); ++k) {
                const glm::dmat3 rows =
                    glm::transpose(glm::dmat3(glm::dvec3(planes[i]), glm::dvec3(planes[j]), glm::dvec3(planes[k])));
                if (std::abs(glm::determinant(rows)) < 1e-12) continue;
                const glm::dvec3 p = glm::inverse(rows) * -glm::dvec3(planes[i].w, planes[j].w, planes[k].w);
                const double scale = std::max(1.0, glm::length(p));
                bool inside = true;
                for (const glm::dvec4& q : planes) inside = inside && glm::dot(glm::dvec3(q), p) + q.w >= -1e-9 * scale;
                if (!inside) continue;
                const double depth = glm::dot(p - cam.wsPosition, forward);
                range.nearest = std::min(range.nearest, depth);
                range.farthest = std::max(range.farthest, depth);
            }
        }
    }
    if (!(range.nearest <= range.farthest)) return std::nullopt;
    return range;
}

/// `measureVisibleReceivers` over `boxes` alone.
VisibleReceivers measured(const CameraView& camera, const std::vector<DAabb>& boxes) {
    SceneGeometry g;
    g.receiverBoxes = boxes;
    for (const DAabb& b : boxes) g.receivers.extend(b);
    measureVisibleReceivers(camera, g);
    return g.visible;
}

TEST(CascadeFit, ClippedDepthOfABoxIsTheBruteForceVertexEnumeration) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int clipped = 0;
    int outside = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const glm::dvec3 eye(20.0 * u(rng), 5.0 * u(rng), 20.0 * u(rng));
        const glm::dvec3 target = eye + glm::dvec3(u(rng), 0.5 * u(rng), u(rng));
        const CameraView camera =
            cameraLooking(eye, target, 0.5f + 0.5f * static_cast<float>(u(rng) + 1.0), 0.2f, 30.0f);
        // Boxes up to 16 m wide (some flat, as a ground is) around the camera: inside, outside,
        // across the planes, around the camera.
        const glm::dvec3 centre = eye + glm::dvec3(15.0 * u(rng), 5.0 * u(rng), 15.0 * u(rng));
        glm::dvec3 half(4.0 * (u(rng) + 1.0), 4.0 * (u(rng) + 1.0), 4.0 * (u(rng) + 1.0));
        if (trial % 5 == 0) half.y = 0.0;
        const DAabb box{centre - half, centre + half};
        const VisibleReceivers v = measured(camera, {box});
        const std::optional<DepthInterval> truth = enumeratedDepth(camera, 30.0, box);
        const std::string what = "trial " + std::to_string(trial);
        if (!truth) {
            EXPECT_TRUE(v.boxes.empty()) << what;
            ++outside;
            continue;
        }
        ++clipped;
        ASSERT_EQ(v.boxes.size(), 1u) << what;
        EXPECT_NEAR(v.boxes[0].nearest, truth->nearest, 1e-9 * 30.0) << what;
        EXPECT_NEAR(v.boxes[0].farthest, truth->farthest, 1e-9 * 30.0) << what;
    }
    std::printf("[ measured ] %d boxes meeting the frustum, %d not\n", clipped, outside);
    EXPECT_GT(clipped, 50);
    EXPECT_GT(outside, 50);
}

TEST(CascadeFit, CameraInsideAReceiverSeesItFromTheNearPlane) {
    const CameraView camera = cameraLooking({0.0, 1.0, 0.0}, {0.0, 1.0, -1.0}, 0.8f, 0.1f, 100.0f);
    const VisibleReceivers v = measured(camera, {DAabb{{-5.0, -4.0, -5.0}, {5.0, 6.0, 5.0}}});
    ASSERT_EQ(v.boxes.size(), 1u);
    EXPECT_NEAR(v.all.nearest, 0.1, 1e-7) << "the near plane lies inside the box";
    EXPECT_NEAR(v.all.farthest, 5.0, 1e-12) << "the box's face straight ahead";
}

TEST(CascadeFit, ShadowDistanceEndingInAGapFitsUpToTheLastReceiverBeforeIt) {
    const CameraView camera = cameraLooking({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 0.8f, 0.1f, 100.0f);
    const VisibleReceivers v = measured(camera, {DAabb{{-1, -1, -12}, {1, 1, -10}}, DAabb{{-1, -1, -52}, {1, 1, -50}}});
    ASSERT_EQ(v.boxes.size(), 2u);
    const std::optional<DepthInterval> all = visibleDepthRange(v, 100.0);
    ASSERT_TRUE(all.has_value());
    EXPECT_NEAR(all->nearest, 10.0, 1e-12);
    EXPECT_NEAR(all->farthest, 52.0, 1e-12);
    const std::optional<DepthInterval> within30 = visibleDepthRange(v, 30.0);
    ASSERT_TRUE(within30.has_value());
    EXPECT_NEAR(within30->farthest, 12.0, 1e-12) << "nothing visible between 12 m and the reach";
    const std::optional<DepthInterval> within51 = visibleDepthRange(v, 51.0);
    ASSERT_TRUE(within51.has_value());
    EXPECT_NEAR(within51->farthest, 51.0, 1e-12) << "the far box crosses the reach";
    EXPECT_FALSE(visibleDepthRange(v, 5.0).has_value()) << "no receiver before 5 m";
}

TEST(CascadeFit, FarFromTheOriginTheRangeIsTheSame) {
    const glm::dvec3 shift(1e5, 0.0, -1e5);
    const CameraView here = cameraLooking({0.0, 8.0, 10.0}, {0.0, 0.0, -20.0}, 0.8f, 0.1f, 500.0f);
    const CameraView there =
        cameraLooking(shift + glm::dvec3(0.0, 8.0, 10.0), shift + glm::dvec3(0.0, 0.0, -20.0), 0.8f, 0.1f, 500.0f);
    const DAabb ground{{-200.0, 0.0, -200.0}, {200.0, 0.0, 200.0}};
    const VisibleReceivers a = measured(here, {ground});
    const VisibleReceivers b = measured(there, {DAabb{ground.min + shift, ground.max + shift}});
    ASSERT_EQ(a.boxes.size(), 1u);
    ASSERT_EQ(b.boxes.size(), 1u);
    EXPECT_NEAR(b.all.nearest, a.all.nearest, 1e-6);
    EXPECT_NEAR(b.all.farthest, a.all.farthest, 1e-6);
}

/// A sun with `cascades` cascades over the scene, planned for `camera`.
struct PlannedSun {
    std::vector<double> splits;  ///< visible near, then each cascade's splitFar
    std::vector<ShadowLayerPlan> layers;
};

PlannedSun planSun(Scene& scene, const CameraView& camera) {
    animate(scene.world, 0.0);
    (void)updateTransforms(scene.world);
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(scene.world, camera, scene.lights);
    PlannedSun out;
    for (const ShadowLightPlan& plan : frame.lights) {
        if (plan.light.type == LightType::Directional && plan.hasMap()) out.layers = plan.layers;
    }
    return out;
}

/// Where rays through the centres of a `width` x `height` grid of pixels first meet a receiver
/// box, as view depths within [near, far] (one per ray that meets one): the receivers the
/// camera sees, by brute force.
std::vector<double> firstHitDepths(const CameraView& cam, double far, const std::vector<DAabb>& receivers, int width,
                                   int height) {
    const glm::dmat4 worldFromView = glm::inverse(cam.viewFromWorld);
    const double ty = std::tan(0.5 * static_cast<double>(cam.yfov));
    const double tx = ty * static_cast<double>(cam.aspect);
    std::vector<double> depths;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            // The view-space direction of depth 1, so that t along it is the view depth.
            const glm::dvec3 vsDir((2.0 * (x + 0.5) / width - 1.0) * tx, (1.0 - 2.0 * (y + 0.5) / height) * ty, -1.0);
            const glm::dvec3 dir(worldFromView * glm::dvec4(vsDir, 0.0));
            double nearest = kInf;
            for (const DAabb& box : receivers) {
                double t0 = static_cast<double>(cam.znear);
                double t1 = far;
                for (int a = 0; a < 3 && t0 <= t1; ++a) {
                    if (std::abs(dir[a]) < 1e-300) {
                        if (cam.wsPosition[a] < box.min[a] || cam.wsPosition[a] > box.max[a]) t0 = kInf;
                        continue;
                    }
                    double ta = (box.min[a] - cam.wsPosition[a]) / dir[a];
                    double tb = (box.max[a] - cam.wsPosition[a]) / dir[a];
                    if (ta > tb) std::swap(ta, tb);
                    t0 = std::max(t0, ta);
                    t1 = std::min(t1, tb);
                }
                if (t0 <= t1) nearest = std::min(nearest, t0);
            }
            if (nearest < kInf) depths.push_back(nearest);
        }
    }
    return depths;
}

/// World bounds of every receiving mesh of `scene` (after updateTransforms).
std::vector<DAabb> receiverBounds(Scene& scene) {
    std::vector<DAabb> out;
    scene.world.view<Mesh, WorldBounds>().each([&](Entity, const Mesh& m, const WorldBounds& b) {
        if (m.receiveShadows && !b.box.empty()) out.push_back(b.box);
    });
    return out;
}

/// The planner's splits for the scene's sun lie within the visible receivers' range (rounded out
/// by at most kQuantization), and each cascade holds some of the receiver points that rays
/// through the screen's pixels see; prints each cascade's share of those.
void expectCascadesOnVisibleReceivers(Scene& scene, const CameraView& camera, double far, const std::string& what) {
    const PlannedSun sun = planSun(scene, camera);
    ASSERT_FALSE(sun.layers.empty()) << what;
    const std::vector<DAabb> receivers = receiverBounds(scene);
    // 1920 x 1080 rays: on the grazing ground a pixel row spans about 1.5 % of the depth there.
    const std::vector<double> hits = firstHitDepths(camera, far, receivers, 1920, 1080);
    ASSERT_FALSE(hits.empty()) << what;
    const auto [minHit, maxHit] = std::minmax_element(hits.begin(), hits.end());
    // The exact range of the boxes clipped to the frustum holds every sampled hit and ends
    // within the sampling's resolution of them (the boxes include their occluded parts: a
    // little beyond the first hits at most, for these scenes).
    VisibleReceivers visible;
    {
        SceneGeometry g;
        gatherGeometry(scene.world, g);
        measureVisibleReceivers(camera, g);
        visible = g.visible;
    }
    const std::optional<DepthInterval> range = visibleDepthRange(visible, far);
    ASSERT_TRUE(range.has_value()) << what;
    EXPECT_LE(range->nearest, *minHit + 1e-9) << what;
    EXPECT_GE(range->farthest, *maxHit - 1e-9) << what;
    EXPECT_NEAR(range->nearest, *minHit, 0.03 * *minHit) << what << ": the sampled nearest receiver";
    EXPECT_NEAR(range->farthest, *maxHit, 0.03 * *maxHit) << what << ": the sampled farthest receiver";

    // Splits: the last cascade ends at the visible far end, rounded up by at most 1/16.
    const double last = sun.layers.back().splitFar;
    EXPECT_GE(last, range->farthest * (1.0 - 1e-6)) << what;
    EXPECT_LE(last, range->farthest * (1.0 + kQuantization) + 1e-6) << what;
    std::printf("[ measured ] %s: visible receivers %.3f-%.3f m (rays %.3f-%.3f m), splits", what.c_str(),
                range->nearest, range->farthest, *minHit, *maxHit);
    double begin = range->nearest * (1.0 - kQuantization);
    for (std::size_t k = 0; k < sun.layers.size(); ++k) {
        const double end = sun.layers[k].splitFar;
        const auto inside = std::count_if(hits.begin(), hits.end(), [&](double d) { return d >= begin && d < end; });
        std::printf(" | %zu: to %.3f m, %.1f %% of receiver rays", k, end,
                    100.0 * static_cast<double>(inside) / static_cast<double>(hits.size()));
        EXPECT_GT(inside, 0) << what << ": cascade " << k << " [" << begin << ", " << end << ") sees no receiver";
        begin = end;
    }
    std::printf("\n");
}

/// A 400 m ground, a row of boxes, a sun with four cascades, and a camera 10 m up looking
/// toward the horizon (10 degrees down): the ground runs from the bottom of the screen to its
/// far edge just below the horizon.
Scene horizonScene() {
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(200.0f, 4), test::at({0, 0, 0}));
    for (int i = 0; i < 8; ++i) {
        addMeshInstance(scene.world, "box", makeBoxMesh(glm::vec3(1.0f)),
                        test::at({3.0 * (i % 3) - 3.0, 1.0, -8.0 * i}));
    }
    Light sun;
    sun.type = LightType::Directional;
    Shadow shadow = test::hard();
    shadow.cascades = 4;
    addLight(scene, "sun", sun, shadow, {0, 50, 0}, glm::normalize(glm::dvec3(0.4, -1.0, 0.3)));
    return scene;
}

CameraView horizonCamera() {
    const glm::dvec3 eye(0.0, 10.0, 20.0);
    return cameraLooking(eye, eye + glm::dvec3(0.0, -std::sin(0.175), -std::cos(0.175)), 0.8f, 0.1f, 1000.0f);
}

TEST(CascadeFit, HorizonViewCascadesSplitTheVisibleGround) {
    Scene scene = horizonScene();
    expectCascadesOnVisibleReceivers(scene, horizonCamera(), 1000.0, "horizon");
}

TEST(CascadeFit, DefaultSceneCascadesSplitTheVisibleReceivers) {
    Result<Scene> made = makeBuiltinScene("default");
    ASSERT_TRUE(made) << made.error().message;
    Scene scene = std::move(made).value();
    animate(scene.world, 0.0);
    (void)updateTransforms(scene.world);
    const CameraView camera = makeCameraView(scene.world, scene.cameras.front(), 640.0f / 360.0f);
    expectCascadesOnVisibleReceivers(scene, camera, camera.zfar, "builtin:default");
}

// Nothing visible (the camera looks at the sky) falls back to the receivers' bounding box, as a
// scene planned without the measurement does: finite splits, increasing.
TEST(CascadeFit, NoVisibleReceiverFallsBackToTheReceiversBounds) {
    Scene scene = horizonScene();
    animate(scene.world, 0.0);
    (void)updateTransforms(scene.world);
    const glm::dvec3 eye(0.0, 10.0, 20.0);
    const CameraView sky = cameraLooking(eye, eye + glm::dvec3(0.0, 1.0, -0.2), 0.8f, 0.1f, 1000.0f);
    SceneGeometry g;
    gatherGeometry(scene.world, g);
    measureVisibleReceivers(sky, g);
    EXPECT_TRUE(g.visible.boxes.empty());
    EXPECT_FALSE(visibleDepthRange(g.visible, 1000.0).has_value());

    ShadowPlanner planner;
    const ShadowLightPlan sun = planner.prepare(scene.world, sky, scene.lights).lights.at(0);
    ASSERT_EQ(sun.layers.size(), 4u);
    // What planLayers gives for geometry that was never measured.
    SceneGeometry plain;
    gatherGeometry(scene.world, plain);
    std::vector<ShadowLayerPlan> unmeasured;
    planLayers(layerInputs(sun, {sun.wsPosition, sun.wsDirection}), sky, plain, false, unmeasured);
    ASSERT_EQ(unmeasured.size(), sun.layers.size());
    float previous = 0.0f;
    for (std::size_t k = 0; k < sun.layers.size(); ++k) {
        EXPECT_TRUE(std::isfinite(sun.layers[k].splitFar)) << "cascade " << k;
        EXPECT_GT(sun.layers[k].splitFar, previous) << "cascade " << k;
        EXPECT_EQ(sun.layers[k].splitFar, unmeasured[k].splitFar) << "cascade " << k;
        previous = sun.layers[k].splitFar;
    }
    // The farthest corner of the 400 m ground from the camera.
    EXPECT_NEAR(previous, glm::length(glm::dvec3(200.0, 10.0, 220.0)), 1e-3);
}

// A huge view: ground 2000 km wide, far plane and reach at 10 000 km: finite splits in order.
TEST(CascadeFit, HugeDepthRangeGivesFiniteIncreasingSplits) {
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(1e6f, 1), test::at({0, 0, 0}));
    Light sun;
    sun.type = LightType::Directional;
    Shadow shadow = test::hard();
    shadow.cascades = 4;
    addLight(scene, "sun", sun, shadow, {0, 50, 0}, glm::normalize(glm::dvec3(0.4, -1.0, 0.3)));
    const glm::dvec3 eye(1e5, 2.0, 1e5);
    const CameraView camera = cameraLooking(eye, eye + glm::dvec3(0.0, -0.05, -1.0), 0.8f, 0.01f, 1e8f);
    const PlannedSun sun2 = planSun(scene, camera);
    ASSERT_EQ(sun2.layers.size(), 4u);
    float previous = 0.0f;
    for (const ShadowLayerPlan& layer : sun2.layers) {
        EXPECT_TRUE(std::isfinite(layer.splitFar));
        EXPECT_GT(layer.splitFar, previous);
        EXPECT_LE(layer.splitFar, static_cast<float>(kMaxShadowReach));
        EXPECT_TRUE(isFinite(layer.lightFromWorld));
        EXPECT_TRUE(isFinite(layer.clipFromLight));
        previous = layer.splitFar;
    }
}

// When nothing moves, consecutive frames give bit-identical splits and matrices, and every
// cascade is reused.
TEST(CascadeFit, StillCameraGivesIdenticalSplitsAndCleanLayers) {
    Scene scene = horizonScene();
    animate(scene.world, 0.0);
    (void)updateTransforms(scene.world);
    const CameraView camera = horizonCamera();
    ShadowPlanner planner;
    const std::vector<ShadowLayerPlan> first = planner.prepare(scene.world, camera, scene.lights).lights[0].layers;
    (void)updateTransforms(scene.world);  // a frame in which nothing moved
    const std::vector<ShadowLayerPlan>& second = planner.prepare(scene.world, camera, scene.lights).lights[0].layers;
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t k = 0; k < first.size(); ++k) {
        EXPECT_EQ(first[k].splitFar, second[k].splitFar) << "cascade " << k;
        EXPECT_EQ(first[k].lightFromWorld, second[k].lightFromWorld) << "cascade " << k;
        EXPECT_EQ(first[k].clipFromLight, second[k].clipFromLight) << "cascade " << k;
        EXPECT_TRUE(first[k].dirty) << "cascade " << k << " drawn on the first frame";
        EXPECT_FALSE(second[k].dirty) << "cascade " << k << " reused";
    }
}

}  // namespace
}  // namespace shadow
