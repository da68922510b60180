// The layers the shadow planner fits (engine/src/shadow/light_projection.cpp's planLayers, run
// through ShadowPlanner::prepare on whole scenes): rigid light matrices, and volumes that hold
// every caster (directional boxes, spot and cube-face depth ranges, cube faces covering every
// direction). No GL: these run in shadow_planner_tests.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "shadow/planner_test_support.h"

namespace shadow {
namespace {

using test::at;
using test::clipOf;
using test::cubeFace;
using test::expectRigid;
using test::hard;
using test::kClipEps;
using test::laterallyInside;
using test::lightOf;
using test::TestScene;

/// The six axis directions and one oblique one: the cases a light basis built from a fixed "up"
/// gets wrong.
std::vector<glm::dvec3> sunDirections(const glm::dvec3& oblique) {
    return {{0, -1, 0}, {0, 1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}, oblique};
}

/// The only layer the planner gives a sun shining along `d` over `t`'s scene.
ShadowLayerPlan planSun(TestScene& t, const glm::dvec3& d) {
    addLight(t.scene, "sun", lightOf(LightType::Directional), hard(), {0, 10, 0}, d);
    const CameraView view = t.update();
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
    EXPECT_EQ(frame.lights.size(), 1u);
    EXPECT_EQ(frame.lights.at(0).layers.size(), 1u);
    return frame.lights.at(0).layers.at(0);
}

TEST(Planner, DirectionalMatricesAreRigidForAxisAlignedDirections) {
    for (const glm::dvec3& d : sunDirections({0.3, -1, 0.2})) {
        TestScene t;
        const ShadowLayerPlan layer = planSun(t, d);
        const std::string what =
            "direction (" + std::to_string(d.x) + ", " + std::to_string(d.y) + ", " + std::to_string(d.z) + ")";
        expectRigid(layer.lightFromWorld, what);
        EXPECT_TRUE(isFinite(layer.clipFromLight)) << what;
        EXPECT_TRUE(layer.orthographic) << what;
        // The light looks down its -Z: the world direction must map to (0, 0, -1).
        const glm::dvec3 ls(layer.lightFromWorld * glm::dvec4(glm::normalize(d), 0.0));
        EXPECT_NEAR(ls.x, 0.0, 1e-12) << what;
        EXPECT_NEAR(ls.y, 0.0, 1e-12) << what;
        EXPECT_NEAR(ls.z, -1.0, 1e-12) << what;
    }
}

TEST(Planner, DirectionalOrthoBoxContainsEveryCaster) {
    for (const glm::dvec3& d : sunDirections({0.5, -1, 0.3})) {
        TestScene t;
        const ShadowLayerPlan layer = planSun(t, d);
        for (const DAabb& box : t.casterBounds()) {
            for (int i = 0; i < 8; ++i) {
                const glm::dvec4 clip = clipOf(layer, box.corner(i));
                for (int a = 0; a < 3; ++a) {
                    EXPECT_LE(std::abs(clip[a] / clip.w), 1.0 + kClipEps)
                        << "direction (" << d.x << ", " << d.y << ", " << d.z << "), corner " << i << ", axis " << a;
                }
            }
        }
        EXPECT_EQ(layer.casters.size(), 3u) << "every caster is in the only layer";
    }
}

/// Every caster corner that falls inside a perspective layer's lateral bounds lies between its
/// near and far planes (clip z in [-w, w]): a caster cut by the near plane casts a partial
/// shadow.
void expectPerspectiveDepthRangeHoldsCasters(const ShadowLightPlan& plan, const std::vector<DAabb>& casters) {
    int checked = 0;
    for (std::size_t k = 0; k < plan.layers.size(); ++k) {
        const ShadowLayerPlan& layer = plan.layers[k];
        EXPECT_FALSE(layer.orthographic);
        for (const DAabb& box : casters) {
            for (int i = 0; i < 8; ++i) {
                const glm::dvec4 clip = clipOf(layer, box.corner(i));
                if (!laterallyInside(clip)) continue;
                ++checked;
                const glm::dvec3 ls(layer.lightFromWorld * glm::dvec4(box.corner(i), 1.0));
                EXPECT_GE(clip.z, -clip.w * (1.0 + kClipEps))
                    << plan.name << " layer " << k << ": caster corner at axial depth " << -ls.z
                    << " m is in front of the near plane " << layer.depthNear << " m";
                EXPECT_LE(clip.z, clip.w * (1.0 + kClipEps)) << plan.name << " layer " << k << ": beyond the far plane";
            }
        }
    }
    EXPECT_GT(checked, 0) << plan.name << ": no caster corner inside any layer; the check is vacuous";
}

TEST(Planner, SpotNearAndFarContainTheCasters) {
    TestScene t;
    addLight(t.scene, "spot", lightOf(LightType::Spot), hard(), {3, 6, 0}, {0, -1, 0});
    const CameraView view = t.update();
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    ASSERT_EQ(frame.lights[0].layers.size(), 1u);
    expectRigid(frame.lights[0].layers[0].lightFromWorld, "spot");
    expectPerspectiveDepthRangeHoldsCasters(frame.lights[0], t.casterBounds());
}

/// The stored depth (stored units) of the farthest corner of the bounds of the casters of
/// `layer`, as the depth pass stores depth: the distance from a perspective light, the axial
/// depth for a sun.
double farthestCasterStored(World& world, const ShadowLayerPlan& layer) {
    double farthest = 0.0;
    for (Entity e : layer.casters) {
        const DAabb& b = world.get<WorldBounds>(e).box;
        for (int k = 0; k < 8; ++k) {
            const glm::dvec3 c((k & 1) != 0 ? b.max.x : b.min.x, (k & 2) != 0 ? b.max.y : b.min.y,
                               (k & 4) != 0 ? b.max.z : b.min.z);
            const glm::dvec3 ls(layer.lightFromWorld * glm::dvec4(c, 1.0));
            farthest = std::max(farthest, layer.orthographic ? -ls.z : glm::length(ls));
        }
    }
    return farthest / layer.depthScale;
}

// VSSM's summed-area table scales stored depths by the layer's moment scale before its 24-bit
// fixed point: a power of two that puts the farthest caster in (1/4, 1/2], so that a light
// whose range dwarfs its scene keeps the table's resolution on the casters; 1 where the
// casters already reach past 1/4.
TEST(Planner, MomentScalePutsTheFarthestCasterInTheUpperHalfOfTheFixedPoint) {
    double largest = 0.0;
    for (double range : {10.0, 1e3, 1e6}) {
        for (LightType type : {LightType::Spot, LightType::Point, LightType::Directional}) {
            TestScene t;
            Light light = lightOf(type);
            light.range = type == LightType::Directional ? 0.0f : static_cast<float>(range);
            Shadow vssm = hard();
            vssm.technique = ShadowTechnique::Vssm;
            addLight(t.scene, "light", light, vssm, {0.5, 6, 0.2}, glm::normalize(glm::dvec3(0.1, -1, 0.05)));
            // The same light with hard shadows: no table, no scale (the planner skips the corners).
            addLight(t.scene, "hard light", light, hard(), {0.5, 6, 0.2}, glm::normalize(glm::dvec3(0.1, -1, 0.05)));
            const CameraView view = t.update();
            ShadowPlanner planner;
            const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
            ASSERT_EQ(frame.lights.size(), 2u);
            for (const ShadowLayerPlan& layer : frame.lights[1].layers) EXPECT_EQ(layer.momentScale, 1.0f);
            const std::string what = std::string(type == LightType::Spot    ? "spot"
                                                 : type == LightType::Point ? "point"
                                                                            : "sun") +
                                     ", range " + std::to_string(range);
            int checked = 0;
            for (const ShadowLayerPlan& layer : frame.lights[0].layers) {
                const double s = layer.momentScale;
                if (layer.casters.empty()) {
                    EXPECT_EQ(s, 0.0) << what << ": no casters, no table";
                    continue;
                }
                EXPECT_EQ(std::exp2(std::round(std::log2(s))), s) << what << ": a power of two (exact scaling)";
                const double far = farthestCasterStored(t.scene.world, layer);
                if (far > 0.25) {
                    EXPECT_EQ(s, 1.0) << what;
                } else {
                    EXPECT_GT(far * s, 0.25) << what;
                    EXPECT_LE(far * s, 0.5) << what;
                }
                largest = std::max(largest, s);
                ++checked;
            }
            EXPECT_GT(checked, 0) << what;
        }
    }
    EXPECT_GE(largest, 65536.0) << "a 10^6 m range over a 6 m scene scales by at least 2^16";
}

/// A ground, one box centred at `boxCenter` and one light; checks the light's depth range.
void expectOffAxisCasterBetweenNearAndFar(const Light& light, const glm::dvec3& position, const glm::dvec3& boxCenter) {
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(5.0f), at({0, 0, 0}));
    addMeshInstance(scene.world, "box", makeBoxMesh({0.8f, 0.4f, 0.6f}), at(boxCenter));
    const Entity camera = addCamera(scene, "camera", Camera{}, {0, 6, 8}, {0, 0, 0});
    addLight(scene, "lamp", light, hard(), position, {0, -1, 0});
    (void)updateTransforms(scene.world);
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(scene.world, makeCameraView(scene.world, camera, 1.0f), scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    std::vector<DAabb> casters;
    scene.world.view<WorldBounds>().each([&](Entity, WorldBounds& b) { casters.push_back(b.box); });
    expectPerspectiveDepthRangeHoldsCasters(frame.lights[0], casters);
}

// The automatic near plane must hold casters off the axis too: their axial depth is smaller
// than their distance from the light. Here the box's nearest point (1.0, 1.8, 0) is 1.56 m
// from the light but only 1.2 m along its axis.
TEST(Planner, SpotNearPlaneHoldsOffAxisCasterNearTheLight) {
    Light spot = lightOf(LightType::Spot);
    spot.outerConeAngle = 1.0f;
    expectOffAxisCasterBetweenNearAndFar(spot, {0, 3, 0}, {1.8, 1.4, 0});
}

// The same for a cube face: the box lies 45 degrees below the light towards +X, so its corners
// sit off the axes of both the +X and the -Y face.
TEST(Planner, PointNearPlaneHoldsCasterOffTheFaceAxes) {
    expectOffAxisCasterBetweenNearAndFar(lightOf(LightType::Point), {-2.0, 3.4, 0}, {0, 1.4, 0});
}

/// Distance from `p` to the box `b` (0 inside).
double distanceTo(const glm::dvec3& p, const DAabb& b) {
    return glm::length(glm::max(glm::max(b.min - p, p - b.max), glm::dvec3(0.0)));
}

// Where a blocker can be nearest: a spot's layer and every face of a point light hold the least
// distance from the light to a caster's bounds (the point light's over all six faces, as a
// search disk may cross into another face), or a fixed near plane beyond it.
TEST(Planner, PerspectiveLayersHoldTheDistanceOfTheNearestCaster) {
    for (const LightType type : {LightType::Spot, LightType::Point}) {
        for (const float fixedNear : {0.0f, 0.05f, 3.0f}) {
            Scene scene;
            addMeshInstance(scene.world, "ground", makePlaneMesh(5.0f), at({0, 0, 0}));
            addMeshInstance(scene.world, "box", makeBoxMesh({0.5f, 0.5f, 0.5f}), at({0.3, 1.0, 0.0}));
            const Entity camera = addCamera(scene, "camera", Camera{}, {0, 6, 8}, {0, 0, 0});
            Shadow s = hard();
            s.nearPlane = fixedNear;
            addLight(scene, "lamp", lightOf(type), s, {0, 4, 0}, {0, -1, 0});
            (void)updateTransforms(scene.world);
            ShadowPlanner planner;
            const ShadowFrame& frame =
                planner.prepare(scene.world, makeCameraView(scene.world, camera, 1.0f), scene.lights);
            ASSERT_EQ(frame.lights.size(), 1u);
            double nearest = 1e30;
            scene.world.view<WorldBounds>().each([&](Entity, WorldBounds& b) {
                nearest = std::min(nearest, distanceTo({0, 4, 0}, b.box));
            });
            const std::string what =
                std::string(type == LightType::Spot ? "spot" : "point") + ", near plane " + std::to_string(fixedNear);
            EXPECT_NEAR(nearest, 2.5, 1e-6) << what << ": the box's top, 1.5 m up, is 2.5 m below the light";
            const double expected = std::max(nearest, static_cast<double>(fixedNear));
            for (const ShadowLayerPlan& layer : frame.lights[0].layers) {
                EXPECT_NEAR(layer.blockerNear, expected, 1e-5) << what;
            }
        }
    }
}

// A sun's cascade: the depth below the layer's top of its highest caster's top. Here a tall
// receiver-only wall raises the layer's top 3 m above the box, the highest caster.
TEST(Planner, CascadesHoldTheDepthOfTheirHighestCaster) {
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(5.0f), at({0, 0, 0}));
    const Entity box = addMeshInstance(scene.world, "box", makeBoxMesh({0.5f, 0.5f, 0.5f}), at({0.3, 1.0, 0.0}));
    const Entity wall = addMeshInstance(scene.world, "wall", makeBoxMesh({0.1f, 2.25f, 0.5f}), at({-2.0, 2.25, 0.0}));
    scene.world.get<Mesh>(wall).castShadows = false;
    const Entity camera = addCamera(scene, "camera", Camera{}, {0, 6, 8}, {0, 0, 0});
    addLight(scene, "sun", lightOf(LightType::Directional), hard(), {0, 10, 0}, {0, -1, 0});
    (void)updateTransforms(scene.world);
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(scene.world, makeCameraView(scene.world, camera, 1.0f), scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    int checked = 0;
    for (const ShadowLayerPlan& layer : frame.lights[0].layers) {
        if (std::find(layer.casters.begin(), layer.casters.end(), box) == layer.casters.end()) continue;
        // The box's top face, 1.5 m up: its depth below the layer's top.
        const double boxTop = -(layer.lightFromWorld * glm::dvec4(0.3, 1.5, 0.0, 1.0)).z;
        const double wallTop = -(layer.lightFromWorld * glm::dvec4(-2.0, 4.5, 0.0, 1.0)).z;
        EXPECT_NEAR(layer.blockerNear, boxTop, 1e-4);
        EXPECT_GT(boxTop, wallTop + 2.9) << "the wall, a receiver only, holds the top 3 m above the box";
        ++checked;
    }
    EXPECT_GT(checked, 0);
}

TEST(Planner, PointLightFacesKeepTheirCastersBetweenNearAndFar) {
    TestScene t;
    addLight(t.scene, "bulb", lightOf(LightType::Point), hard(), {0, 3, 0}, {0, -1, 0});
    const CameraView view = t.update();
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    expectPerspectiveDepthRangeHoldsCasters(frame.lights[0], t.casterBounds());
}

TEST(Planner, PointLightSixFacesCoverEveryDirection) {
    TestScene t;
    const glm::dvec3 position(0.5, 3.0, -0.25);
    addLight(t.scene, "bulb", lightOf(LightType::Point), hard(), position, {0, -1, 0});
    const CameraView view = t.update();
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    const ShadowLightPlan& plan = frame.lights[0];
    ASSERT_EQ(plan.layers.size(), 6u);
    for (std::size_t k = 0; k < 6; ++k) expectRigid(plan.layers[k].lightFromWorld, "face " + std::to_string(k));

    std::mt19937 rng(7);
    std::normal_distribution<double> gauss;
    int uncovered = 0;
    int outsideOwnFace = 0;
    for (int s = 0; s < 20000; ++s) {
        glm::dvec3 d(gauss(rng), gauss(rng), gauss(rng));
        if (glm::length(d) < 1e-6) continue;
        d = glm::normalize(d);
        // Each face fits its own near plane; a point at distance r has axial depth >= r/sqrt(3)
        // in the face that holds it, so r between sqrt(3)*max(near) and far is in every range.
        double maxNear = 0.0;
        for (const ShadowLayerPlan& layer : plan.layers)
            maxNear = std::max(maxNear, static_cast<double>(layer.depthNear));
        const double far = plan.layers[0].depthScale / std::sqrt(3.0);
        const double r = std::sqrt(std::sqrt(3.0) * maxNear * far);
        const glm::dvec3 p = position + d * r;
        bool covered = false;
        for (const ShadowLayerPlan& layer : plan.layers) {
            const glm::dvec4 c = clipOf(layer, p);
            covered = covered || (laterallyInside(c) && std::abs(c.z) <= c.w);
        }
        if (!covered) ++uncovered;
        // The face the shader picks for the direction must hold it.
        if (!laterallyInside(clipOf(plan.layers[static_cast<std::size_t>(cubeFace(d))], p))) ++outsideOwnFace;
    }
    EXPECT_EQ(uncovered, 0);
    EXPECT_EQ(outsideOwnFace, 0);
}

}  // namespace
}  // namespace shadow
