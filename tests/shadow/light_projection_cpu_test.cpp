// Per-light projections (engine/src/shadow/light_projection.cpp) against closed forms: a light's
// pose from its node, the camera's clip matrix, the range test against the view, cascade
// splits, the geometry a frame's layers are fitted to, and the layers themselves (spot cone
// with its texel margin, fitted near and far planes, cube faces, cascades snapped to texels).
// No GL: these run in shadow_planner_tests.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "shadow/frustum.h"
#include "shadow/light_projection.h"
#include "shadow/planner_test_support.h"

namespace shadow {
namespace {

using test::at;

/// Every element of `actual` within `tol` of `expected`, relative to max(1, |expected|).
void expectMatrixNear(const glm::dmat4& actual, const glm::dmat4& expected, double tol, const std::string& what) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(actual[c][r], expected[c][r], tol * std::max(1.0, std::abs(expected[c][r])))
                << what << ", column " << c << ", row " << r;
        }
    }
}

glm::dvec3 ndcOf(const glm::dmat4& clipFromX, const glm::dvec3& p) {
    const glm::dvec4 clip = clipFromX * glm::dvec4(p, 1.0);
    return glm::dvec3(clip) / clip.w;
}

/// `cascadeSplits` for `count` cascades, into a new list.
std::vector<double> splitsOf(double near, double far, int count, double lambda) {
    std::vector<double> splits(static_cast<std::size_t>(count) + 1);
    cascadeSplits(near, far, lambda, splits);
    return splits;
}

/// `planLayers` into a new list.
std::vector<ShadowLayerPlan> layersOf(const ShadowLightPlan& plan, const LightPose& pose, const CameraView& camera,
                                      const SceneGeometry& geometry) {
    std::vector<ShadowLayerPlan> layers;
    planLayers(layerInputs(plan, pose), camera, geometry, false, layers);
    return layers;
}

// ---- Pose and camera ----

TEST(LightProjection, LightPoseIsTheNodeOriginAndItsMinusZ) {
    const glm::dvec3 position(1.5, -2.0, 7.25);
    const glm::dquat rotation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(0.3, 1.0, -0.2)));
    WorldTransform wt;
    // A non-uniform scale stretches the -Z column; the direction must come out unit anyway.
    wt.worldFromLocal = glm::translate(glm::dmat4(1.0), position) * glm::mat4_cast(rotation) *
                        glm::scale(glm::dmat4(1.0), glm::dvec3(2.0, 3.0, 4.0));
    const LightPose pose = lightPose(wt);
    const glm::dvec3 expected = rotation * glm::dvec3(0.0, 0.0, -1.0);
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(pose.wsPosition[a], position[a]);
        EXPECT_NEAR(pose.wsDirection[a], expected[a], 1e-12) << "axis " << a;
    }
    EXPECT_NEAR(glm::length(pose.wsDirection), 1.0, 1e-12);
}

TEST(LightProjection, LightPoseFallsBackToMinusZWhenTheNodeHasNoDirection) {
    WorldTransform flat;  // scale 0 along z: the -Z column is zero
    flat.worldFromLocal = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 1.0, 0.0));
    WorldTransform nan;
    nan.worldFromLocal[2][0] = std::numeric_limits<double>::quiet_NaN();
    for (const WorldTransform* wt : {&flat, &nan}) {
        const LightPose pose = lightPose(*wt);
        EXPECT_EQ(pose.wsDirection, glm::dvec3(0.0, 0.0, -1.0));
    }
}

/// A camera at `position` looking along unit `direction`, yfov 0.8, aspect 2, depth [0.5, 50].
CameraView cameraAt(const glm::dvec3& position, const glm::dvec3& direction) {
    CameraView camera;
    camera.wsPosition = position;
    camera.viewFromWorld = lookAlong(position, direction);
    camera.yfov = 0.8f;
    camera.aspect = 2.0f;
    camera.znear = 0.5f;
    camera.zfar = 50.0f;
    return camera;
}

TEST(LightProjection, CameraClipFromWorldMapsTheViewFrustumToTheClipCube) {
    const CameraView camera = cameraAt({1.0, 2.0, 3.0}, glm::normalize(glm::dvec3(0.2, -0.3, -1.0)));
    const glm::dmat4 clipFromWorld = cameraClipFromWorld(camera);
    const glm::dmat4 worldFromView = glm::inverse(camera.viewFromWorld);
    const double n = 0.5;
    const double f = 50.0;
    // The camera's fields are floats: 0.8f is not 0.8.
    const double ty = std::tan(0.5 * static_cast<double>(camera.yfov));
    const double tx = static_cast<double>(camera.aspect) * ty;
    auto world = [&](double x, double y, double depth) {
        return glm::dvec3(worldFromView * glm::dvec4(x, y, -depth, 1.0));
    };
    // Near and far planes on the axis, and the OpenGL depth curve in between.
    EXPECT_NEAR(ndcOf(clipFromWorld, world(0, 0, n)).z, -1.0, 1e-9);
    EXPECT_NEAR(ndcOf(clipFromWorld, world(0, 0, f)).z, 1.0, 1e-9);
    const double d = 5.0;
    EXPECT_NEAR(ndcOf(clipFromWorld, world(0, 0, d)).z, (f + n) / (f - n) - 2.0 * f * n / ((f - n) * d), 1e-9);
    EXPECT_NEAR((clipFromWorld * glm::dvec4(world(0, 0, d), 1.0)).w, d, 1e-9);
    // The edges of the field of view: yfov vertically, aspect x yfov's tangent horizontally.
    const glm::dvec3 corner = ndcOf(clipFromWorld, world(d * tx, d * ty, d));
    EXPECT_NEAR(corner.x, 1.0, 1e-9);
    EXPECT_NEAR(corner.y, 1.0, 1e-9);
    const glm::dvec3 opposite = ndcOf(clipFromWorld, world(-d * tx, -d * ty, d));
    EXPECT_NEAR(opposite.x, -1.0, 1e-9);
    EXPECT_NEAR(opposite.y, -1.0, 1e-9);
}

// ---- Which lights can reach the view ----

TEST(LightProjection, LightAffectsViewExactlyWhenItsRangeSphereReachesTheFrustum) {
    // The camera at the origin looks down -Z: near plane z = -0.5, far plane z = -50.
    const CameraView camera = cameraAt({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0});
    const Frustum frustum = Frustum::fromMatrix(cameraClipFromWorld(camera));
    auto affects = [&](LightType type, float range, const glm::dvec3& where) {
        Light light;
        light.type = type;
        light.range = range;
        return lightAffectsView(light, {where, {0.0, 0.0, 1.0}}, frustum);
    };
    for (LightType type : {LightType::Spot, LightType::Point}) {
        const std::string what = type == LightType::Spot ? "spot" : "point";
        // 10 m behind the camera: 10.5 m from the near plane.
        EXPECT_FALSE(affects(type, 10.4f, {0, 0, 10})) << what;
        EXPECT_TRUE(affects(type, 10.6f, {0, 0, 10})) << what;
        // 10 m beyond the far plane.
        EXPECT_FALSE(affects(type, 9.9f, {0, 0, -60})) << what;
        EXPECT_TRUE(affects(type, 10.1f, {0, 0, -60})) << what;
        // Beside the view at depth 20: the right plane's inward normal is (-1, 0, -tx) / |.|,
        // so (x, 0, -20) lies (x - 20 tx) / sqrt(1 + tx^2) outside it.
        const double tx = 2.0 * std::tan(0.5 * static_cast<double>(camera.yfov));
        const double outside = (30.0 - 20.0 * tx) / std::sqrt(1.0 + tx * tx);
        EXPECT_FALSE(affects(type, static_cast<float>(0.99 * outside), {30, 0, -20})) << what;
        EXPECT_TRUE(affects(type, static_cast<float>(1.01 * outside), {30, 0, -20})) << what;
        // Range 0 means unlimited: it always may.
        EXPECT_TRUE(affects(type, 0.0f, {0, 0, 1e6})) << what;
    }
    // A directional light reaches everything, whatever its range says.
    EXPECT_TRUE(affects(LightType::Directional, 1.0f, {0, 0, 1e6}));
}

// ---- Cascade splits ----

TEST(LightProjection, CascadeSplitsAreMonotoneAndFollowTheClosedForms) {
    const double n = 0.1;
    const double f = 100.0;
    for (int count = 1; count <= 4; ++count) {
        for (double lambda : {0.0, 0.25, 0.75, 1.0}) {
            const std::vector<double> s = splitsOf(n, f, count, lambda);
            ASSERT_EQ(s.size(), static_cast<std::size_t>(count) + 1);
            EXPECT_DOUBLE_EQ(s.front(), n);
            EXPECT_DOUBLE_EQ(s.back(), f);
            for (std::size_t i = 1; i < s.size(); ++i) EXPECT_LT(s[i - 1], s[i]) << "count " << count;
            for (int i = 0; i <= count; ++i) {
                const double x = static_cast<double>(i) / count;
                const double uniform = n + (f - n) * x;
                const double logarithmic = n * std::pow(f / n, x);
                EXPECT_NEAR(s[static_cast<std::size_t>(i)], lambda * logarithmic + (1.0 - lambda) * uniform, 1e-9 * f)
                    << "count " << count << " lambda " << lambda << " split " << i;
            }
        }
    }
    // The two ends of the blend, spelled out.
    const std::vector<double> uniform = splitsOf(1.0, 9.0, 4, 0.0);
    EXPECT_NEAR(uniform[1], 3.0, 1e-12);
    EXPECT_NEAR(uniform[2], 5.0, 1e-12);
    const std::vector<double> logarithmic = splitsOf(1.0, 16.0, 4, 1.0);
    EXPECT_NEAR(logarithmic[1], 2.0, 1e-12);
    EXPECT_NEAR(logarithmic[2], 4.0, 1e-12);
    EXPECT_NEAR(logarithmic[3], 8.0, 1e-12);
}

// A camera with near 0, or a shadow distance at or before the near plane, must still give
// finite, non-decreasing splits (the logarithmic term divides by near).
TEST(LightProjection, CascadeSplitsStayFiniteForDegenerateRanges) {
    for (const auto& [near, far] : {std::pair{0.0, 10.0}, std::pair{2.0, 2.0}, std::pair{3.0, 1.0}}) {
        const std::vector<double> s = splitsOf(near, far, 4, 0.75);
        ASSERT_EQ(s.size(), 5u);
        EXPECT_GT(s.front(), 0.0) << near << ".." << far;
        EXPECT_LT(s.front(), s.back()) << near << ".." << far;
        for (std::size_t i = 0; i < s.size(); ++i) {
            EXPECT_TRUE(std::isfinite(s[i])) << near << ".." << far;
            if (i > 0) {
                EXPECT_LE(s[i - 1], s[i]) << near << ".." << far;
            }
        }
    }
}

// ---- The geometry layers are fitted to ----

TEST(LightProjection, GatherGeometryKeepsCastersInEntityOrderAndSkipsWhatDrawsNothing) {
    World world;
    const auto box = makeBoxMesh(glm::vec3(0.5f));
    const Entity both = addMeshInstance(world, "both", box, at({0, 1, 0}));
    const Entity ground = addMeshInstance(world, "ground", makePlaneMesh(5.0f), at({0, 0, 0}));
    world.get<Mesh>(ground).castShadows = false;
    const Entity castOnly = addMeshInstance(world, "cast only", box, at({3, 1, 0}));
    world.get<Mesh>(castOnly).receiveShadows = false;
    // Neither a mesh whose transform is not finite nor one with no triangles widens any fit.
    addMeshInstance(world, "nan", box, at({std::numeric_limits<double>::quiet_NaN(), 0, 0}));
    auto noTriangles = std::make_shared<MeshData>(*box);
    noTriangles->indices.clear();
    addMeshInstance(world, "no triangles", noTriangles, at({20, 0, 0}));
    (void)updateTransforms(world);

    SceneGeometry g;
    g.casters.push_back({world.create(), {}});  // what the list held before: replaced
    g.everything.extend(glm::dvec3(100.0));
    gatherGeometry(world, g);
    ASSERT_EQ(g.casters.size(), 2u);
    EXPECT_TRUE(g.casters[0].entity == both);
    EXPECT_TRUE(g.casters[1].entity == castOnly);
    EXPECT_EQ(g.casters[1].bounds.min, glm::dvec3(2.5, 0.5, -0.5));
    EXPECT_EQ(g.casters[1].bounds.max, glm::dvec3(3.5, 1.5, 0.5));
    EXPECT_EQ(g.receivers.min, glm::dvec3(-5.0, 0.0, -5.0));
    EXPECT_EQ(g.receivers.max, glm::dvec3(5.0, 1.5, 5.0));
    EXPECT_EQ(g.everything.min, glm::dvec3(-5.0, 0.0, -5.0));
    EXPECT_EQ(g.everything.max, glm::dvec3(5.0, 1.5, 5.0));
}

// ---- The layers ----

/// A shadowed light's plan as `planLayers` receives it.
ShadowLightPlan planFor(LightType type, float range, float nearPlane, int mapSize) {
    ShadowLightPlan plan;
    plan.name = "light";
    plan.light.type = type;
    plan.light.outerConeAngle = 0.5f;
    plan.light.range = range;
    plan.settings.technique = ShadowTechnique::Hard;
    plan.settings.nearPlane = nearPlane;
    plan.settings.mapSize = mapSize;
    plan.mapSize = mapSize;
    return plan;
}

/// Stored depth scale of a perspective layer: the distance to a far-plane corner.
double cornerDistance(double far, double tanHalf) { return far * std::sqrt(1.0 + 2.0 * tanHalf * tanHalf); }

TEST(LightProjection, SpotLayerIsThePerspectiveOfItsConeWithTwoTexelsOfMargin) {
    const ShadowLightPlan plan = planFor(LightType::Spot, 20.0f, 0.25f, 1024);
    const LightPose pose{{1.0, 5.0, -2.0}, glm::normalize(glm::dvec3(0.2, -1.0, 0.1))};
    const std::vector<ShadowLayerPlan> layers = layersOf(plan, pose, cameraAt({0, 2, 6}, {0, 0, -1}), SceneGeometry{});
    ASSERT_EQ(layers.size(), 1u);
    const ShadowLayerPlan& layer = layers[0];
    const double tanHalf = std::tan(0.5) * (1.0 + 4.0 / 1024.0);
    EXPECT_FALSE(layer.orthographic);
    expectMatrixNear(layer.lightFromWorld, lookAlong(pose.wsPosition, pose.wsDirection), 1e-15, "lightFromWorld");
    expectMatrixNear(layer.clipFromLight, glm::perspective(2.0 * std::atan(tanHalf), 1.0, 0.25, 20.0), 1e-12,
                     "clipFromLight");
    EXPECT_FLOAT_EQ(layer.depthNear, 0.25f) << "the fixed near plane";
    EXPECT_FLOAT_EQ(layer.depthScale, static_cast<float>(cornerDistance(20.0, tanHalf)));
    // The cone's edge lands 2 / (1 + 4 / mapSize) texels inside the map's edge: bilinear taps
    // at the edge of the lit area stay in the map.
    const double depth = 7.0;
    const glm::dvec3 ndc = ndcOf(layer.clipFromLight, {depth * std::tan(0.5), 0.0, -depth});
    EXPECT_NEAR((1.0 - ndc.x) * 1024.0 / 2.0, 2.0 / (1.0 + 4.0 / 1024.0), 1e-9);
}

TEST(LightProjection, SpotNearPlaneIsThePowerOfTwoBeforeTheNearestCasterInItsFrustum) {
    World world;
    const Entity below = world.create();
    const Entity aside = world.create();
    const ShadowLightPlan plan = planFor(LightType::Spot, 20.0f, 0.0f, 1024);
    const LightPose pose{{0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}};
    const double tanHalf = std::tan(0.5) * (1.0 + 4.0 / 1024.0);
    // The near plane clips by axial depth; a caster at distance d may be as shallow as d times
    // the cosine of the frustum's corner ray, and 10 % is kept in hand.
    const double cornerCos = 1.0 / std::sqrt(1.0 + 2.0 * tanHalf * tanHalf);
    SceneGeometry g;
    g.casters.push_back({below, {{-0.5, 1.0, -0.5}, {0.5, 2.0, 0.5}}});  // 3 m below the light
    g.casters.push_back({aside, {{9.5, 1.0, -0.5}, {10.5, 2.0, 0.5}}});  // outside the cone
    const CameraView camera = cameraAt({0, 2, 6}, {0, 0, -1});
    {
        const ShadowLayerPlan layer = layersOf(plan, pose, camera, g).at(0);
        const double expected = std::exp2(std::floor(std::log2(0.9 * 3.0 * cornerCos)));
        EXPECT_EQ(expected, 2.0) << "0.9 x 3 m x " << cornerCos;
        EXPECT_FLOAT_EQ(layer.depthNear, 2.0f);
        ASSERT_EQ(layer.casters.size(), 1u);
        EXPECT_TRUE(layer.casters[0] == below) << "the caster outside the cone is culled";
    }
    {
        // With only the caster outside the cone, nothing pulls the near plane in: the largest
        // power of two below 0.9 x far x cornerCos (14.2 m), at most half the far plane.
        g.casters.erase(g.casters.begin());
        const ShadowLayerPlan layer = layersOf(plan, pose, camera, g).at(0);
        EXPECT_FLOAT_EQ(layer.depthNear, 8.0f);
        EXPECT_TRUE(layer.casters.empty());
    }
}

TEST(LightProjection, PointLayersAreTheSixCubeFacesReachingThePowerOfTwoAboveTheScene) {
    const ShadowLightPlan plan = planFor(LightType::Point, 0.0f, 0.5f, 512);  // range 0: unlimited
    const LightPose pose{{0.0, 3.0, 0.0}, {0.0, -1.0, 0.0}};
    SceneGeometry g;
    g.everything = {{-5.0, 0.0, -5.0}, {5.0, 1.0, 5.0}};
    // Farthest scene corner: (5, 0, 5), sqrt(59) = 7.7 m from the light; far rounds up to 8 m.
    const double far = 8.0;
    const double tanHalf = 1.0 + 4.0 / 512.0;  // 45 degrees and two texels
    const std::vector<ShadowLayerPlan> layers = layersOf(plan, pose, cameraAt({0, 2, 6}, {0, 0, -1}), g);
    ASSERT_EQ(layers.size(), 6u);
    // The order the shader's cubeFace() indexes: +X, -X, +Y, -Y, +Z, -Z.
    const glm::dvec3 faces[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (std::size_t k = 0; k < 6; ++k) {
        const std::string what = "face " + std::to_string(k);
        expectMatrixNear(layers[k].lightFromWorld, lookAlong(pose.wsPosition, faces[k]), 1e-15, what);
        expectMatrixNear(layers[k].clipFromLight, glm::perspective(2.0 * std::atan(tanHalf), 1.0, 0.5, far), 1e-12,
                         what);
        EXPECT_FLOAT_EQ(layers[k].depthScale, static_cast<float>(cornerDistance(far, tanHalf))) << what;
        EXPECT_EQ(test::cubeFace(faces[k]), static_cast<int>(k));
    }
}

/// A sun (three cascades, 1024^2) over a 10 m x 10 m ground seen from (x, 3, 8).
struct SunOverGround {
    ShadowLightPlan plan = planFor(LightType::Directional, 0.0f, 0.0f, 1024);
    LightPose pose{{0.0, 10.0, 0.0}, glm::normalize(glm::dvec3(0.3, -1.0, 0.2))};
    SceneGeometry geometry;

    SunOverGround() {
        plan.settings.cascades = 3;
        geometry.receivers = {{-5.0, 0.0, -5.0}, {5.0, 0.0, 5.0}};
        geometry.everything = geometry.receivers;
    }
    std::vector<ShadowLayerPlan> layers(double cameraX) const {
        const glm::dvec3 eye(cameraX, 3.0, 8.0);
        return layersOf(plan, pose, cameraAt(eye, glm::normalize(-eye)), geometry);
    }
};

TEST(LightProjection, DirectionalCascadesSplitTheDistancesToTheReceivers) {
    const SunOverGround sun;
    const std::vector<ShadowLayerPlan> layers = sun.layers(0.0);
    ASSERT_EQ(layers.size(), 3u);
    // Cascades start at the nearest receiver point (3 m up, 3 m in front of the ground's edge)
    // and end at the farthest ground corner, (+-5, 0, -5).
    const double nearest = std::sqrt(3.0 * 3.0 + 3.0 * 3.0);
    const double farthest = std::sqrt(5.0 * 5.0 + 3.0 * 3.0 + 13.0 * 13.0);
    const std::vector<double> splits = splitsOf(nearest, farthest, 3, sun.plan.settings.cascadeSplitLambda);
    const glm::dmat4 rotation = lookAlong(glm::dvec3(0.0), sun.pose.wsDirection);
    for (std::size_t k = 0; k < 3; ++k) {
        const std::string what = "cascade " + std::to_string(k);
        EXPECT_TRUE(layers[k].orthographic) << what;
        EXPECT_FLOAT_EQ(layers[k].splitFar, static_cast<float>(splits[k + 1])) << what;
        EXPECT_EQ(layers[k].depthNear, 0.0f) << what;
        // The light's rotation, then a translation in light space only.
        expectMatrixNear(glm::dmat4(glm::dmat3(layers[k].lightFromWorld)), glm::dmat4(glm::dmat3(rotation)), 1e-15,
                         what);
    }
}

// A moving camera must move a cascade by whole texels only, or its shadow edges crawl.
TEST(LightProjection, DirectionalCascadeCentresSnapToWholeTexels) {
    const SunOverGround sun;
    for (double cameraX : {0.0, 0.0137, 0.5, -1.3}) {
        const std::vector<ShadowLayerPlan> layers = sun.layers(cameraX);
        for (std::size_t k = 0; k < layers.size(); ++k) {
            const ShadowLayerPlan& layer = layers[k];
            // A square ortho box centred on the layer's origin: extent = 2 / clipFromLight[0][0].
            EXPECT_DOUBLE_EQ(layer.clipFromLight[0][0], layer.clipFromLight[1][1]);
            EXPECT_EQ(layer.clipFromLight[3][0], 0.0);
            EXPECT_EQ(layer.clipFromLight[3][1], 0.0);
            const double texel = 2.0 / layer.clipFromLight[0][0] / 1024.0;
            for (int a = 0; a < 2; ++a) {
                const double texels = layer.lightFromWorld[3][a] / texel;
                EXPECT_NEAR(texels, std::round(texels), 1e-6)
                    << "camera x " << cameraX << ", cascade " << k << ", axis " << a;
            }
        }
    }
}

// The planner plans into last frame's layers to reuse their caster lists: every field must come
// out as planning into an empty list gives, whatever the list held (here a sun's cascades).
TEST(LightProjection, PlanningIntoUsedLayersGivesWhatPlanningAfreshGives) {
    const SunOverGround sun;
    World world;
    SceneGeometry g = sun.geometry;
    g.casters.push_back({world.create(), {{-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}}});
    const CameraView camera = cameraAt({0, 3, 8}, glm::normalize(glm::dvec3(0, -3, -8)));
    std::vector<ShadowLayerPlan> layers;
    planLayers(layerInputs(sun.plan, sun.pose), camera, g, false, layers);
    for (ShadowLayerPlan& layer : layers) layer.dirty = false;

    const ShadowLightPlan bulb = planFor(LightType::Point, 0.0f, 0.0f, 512);
    const LightPose bulbPose{{0.0, 3.0, 0.0}, {0.0, -1.0, 0.0}};
    planLayers(layerInputs(bulb, bulbPose), camera, g, false, layers);
    const std::vector<ShadowLayerPlan> fresh = layersOf(bulb, bulbPose, camera, g);
    ASSERT_EQ(layers.size(), fresh.size());
    for (std::size_t k = 0; k < fresh.size(); ++k) {
        const std::string what = "face " + std::to_string(k);
        EXPECT_EQ(layers[k].lightFromWorld, fresh[k].lightFromWorld) << what;
        EXPECT_EQ(layers[k].clipFromLight, fresh[k].clipFromLight) << what;
        EXPECT_EQ(layers[k].orthographic, fresh[k].orthographic) << what;
        EXPECT_EQ(layers[k].depthScale, fresh[k].depthScale) << what;
        EXPECT_EQ(layers[k].depthNear, fresh[k].depthNear) << what;
        EXPECT_EQ(layers[k].splitFar, fresh[k].splitFar) << what;
        EXPECT_EQ(layers[k].casters, fresh[k].casters) << what;
        EXPECT_EQ(layers[k].dirty, fresh[k].dirty) << what;
    }
}

// Planning again with `follow` updates a layer whose frustum stayed from the changed casters
// alone, and finds its list anew when many cross it. Told apart by an entity planted in the list
// (no caster of the scene): the update leaves it, finding the list anew drops it.
TEST(LightProjection, AFollowedListChangesOnlyByTheChangedCastersUnlessManyCrossed) {
    Scene scene;
    World& world = scene.world;
    std::vector<Entity> boxes;
    for (int i = 0; i < 40; ++i) {
        boxes.push_back(addMeshInstance(world, "box", makeBoxMesh(glm::vec3(0.2f)),
                                        at({0.5 * (i % 8) - 1.75, 0.2, 0.5 * (i / 8) - 1.0})));
    }
    // A fixed near plane and a range: the spot's matrices do not follow its casters.
    const ShadowLightPlan spot = planFor(LightType::Spot, 12.0f, 0.5f, 512);
    const LightPose pose{{0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}};
    const LayerInputs inputs = layerInputs(spot, pose);
    const CameraView camera = cameraAt({0, 3, 8}, glm::normalize(glm::dvec3(0, -3, -8)));
    SceneGeometry g;
    const auto gather = [&] {
        (void)updateTransforms(world);
        gatherGeometry(world, g);
    };
    gather();
    std::vector<ShadowLayerPlan> layers;
    planLayers(inputs, camera, g, false, layers);
    ASSERT_EQ(layers.size(), 1u);
    ASSERT_EQ(layers[0].casters.size(), 40u) << "every box under the cone";
    const glm::dmat4 clip = layers[0].clipFromLight;

    // One box leaves the cone, one moves within it: the list follows.
    world.get<Transform>(boxes[3]).translation = {40.0, 0.2, 0.0};
    world.get<Transform>(boxes[9]).translation.x += 0.1;
    gather();
    planLayers(inputs, camera, g, true, layers);
    EXPECT_EQ(layers[0].clipFromLight, clip);
    EXPECT_EQ(layers[0].casters, layersOf(spot, pose, camera, g)[0].casters);
    EXPECT_EQ(layers[0].casters.size(), 39u);

    // Nothing changed: a followed list is left as it was, planted entity and all.
    const Entity planted(Entity::kMaxEntities - 1, 0);
    layers[0].casters.push_back(planted);
    gather();
    planLayers(inputs, camera, g, true, layers);
    EXPECT_TRUE(test::contains(layers[0].casters, planted)) << "the list was found anew";
    EXPECT_EQ(layers[0].casters.size(), 40u);

    // It comes back: an odd number of its entries meet the cone, one box crossed.
    world.get<Transform>(boxes[3]).translation = {0.0, 0.2, 1.5};
    gather();
    planLayers(inputs, camera, g, true, layers);
    EXPECT_TRUE(test::contains(layers[0].casters, planted));
    EXPECT_TRUE(test::contains(layers[0].casters, boxes[3]));

    // Twenty leave: more than a few crossed, the list is found anew, the planted entity gone.
    for (int i = 20; i < 40; ++i) world.get<Transform>(boxes[static_cast<std::size_t>(i)]).translation.x += 60.0;
    gather();
    planLayers(inputs, camera, g, true, layers);
    EXPECT_FALSE(test::contains(layers[0].casters, planted));
    EXPECT_EQ(layers[0].casters, layersOf(spot, pose, camera, g)[0].casters);
    EXPECT_EQ(layers[0].casters.size(), 20u);
}

}  // namespace
}  // namespace shadow
