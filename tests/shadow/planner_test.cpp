// ShadowPlanner, the CPU "decide" phase of the shadow system: light matrices, the volumes the
// layers cover, cascade splits, layer caching, and which lights get a plan at all. No GL.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "shadow/light_projection.h"

namespace shadow {
namespace {

constexpr double kEps = 1e-9;

Transform at(const glm::dvec3& position) {
    Transform t;
    t.translation = position;
    return t;
}

/// A ground plane, two boxes and a camera that sees them all.
struct TestScene {
    Scene scene;
    Entity camera;
    Entity boxA;  // at (3, 3, 0): beside a light at (0, 3, 0), in its +X cube face only
    Entity boxB;  // at (-3, 3, 0): in the -X cube face only

    TestScene() {
        addMeshInstance(scene.world, "ground", makePlaneMesh(5.0f, 2), at({0, 0, 0}));
        boxA = addMeshInstance(scene.world, "box A", makeBoxMesh(glm::vec3(0.4f)), at({3, 3, 0}));
        boxB = addMeshInstance(scene.world, "box B", makeBoxMesh(glm::vec3(0.4f)), at({-3, 3, 0}));
        camera = addCamera(scene, "camera", Camera{}, {0, 8, 12}, {0, 1, 0});
    }

    /// Runs the systems before `prepare` and returns this frame's camera view.
    CameraView update() {
        animate(scene.world, 0.0);
        (void)updateTransforms(scene.world);
        return makeCameraView(scene.world, camera, 16.0f / 9.0f);
    }

    /// World bounds of every shadow caster.
    std::vector<DAabb> casterBounds() {
        std::vector<DAabb> out;
        scene.world.view<Mesh, WorldBounds>().each([&](Entity, Mesh& m, WorldBounds& b) {
            if (m.castShadows) out.push_back(b.box);
        });
        return out;
    }
};

Shadow hard() {
    Shadow s;
    s.technique = ShadowTechnique::Hard;
    s.mapSize = 512;
    return s;
}

Light lightOf(LightType type) {
    Light l;
    l.type = type;
    l.outerConeAngle = 0.6f;
    return l;
}

/// The upper 3x3 of `m` is a rotation: orthonormal rows, determinant +1, and all finite.
void expectRigid(const glm::dmat4& m, const std::string& what) {
    ASSERT_TRUE(isFinite(m)) << what;
    const glm::dmat3 r(m);
    const glm::dmat3 rrt = r * glm::transpose(r);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(rrt[i][j], i == j ? 1.0 : 0.0, 1e-12) << what;
    }
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-12) << what;
}

glm::dvec4 clipOf(const ShadowLayerPlan& layer, const glm::dvec3& p) {
    return layer.clipFromLight * layer.lightFromWorld * glm::dvec4(p, 1.0);
}

bool laterallyInside(const glm::dvec4& clip) {
    return clip.w > 0.0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
}

/// Cube face (+X,-X,+Y,-Y,+Z,-Z) of a direction, as the shader's cubeFace() chooses it.
int cubeFace(const glm::dvec3& d) {
    const glm::dvec3 a = glm::abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

const ShadowLightPlan* planOf(const ShadowFrame& frame, const std::string& name) {
    for (const ShadowLightPlan& p : frame.lights) {
        if (p.name == name) return &p;
    }
    return nullptr;
}

bool contains(const std::vector<Entity>& v, Entity e) {
    return std::find(v.begin(), v.end(), e) != v.end();
}

// ---- Matrices and covered volumes ----

TEST(Planner, DirectionalMatricesAreRigidForAxisAlignedDirections) {
    const std::vector<glm::dvec3> directions = {{0, -1, 0}, {0, 1, 0},  {1, 0, 0},     {-1, 0, 0},
                                                {0, 0, 1},  {0, 0, -1}, {0.3, -1, 0.2}};
    for (const glm::dvec3& d : directions) {
        TestScene t;
        addLight(t.scene, "sun", lightOf(LightType::Directional), hard(), {0, 10, 0}, d);
        const CameraView view = t.update();
        ShadowPlanner planner;
        const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
        ASSERT_EQ(frame.lights.size(), 1u);
        ASSERT_EQ(frame.lights[0].layers.size(), 1u);
        const ShadowLayerPlan& layer = frame.lights[0].layers[0];
        const std::string what = "direction (" + std::to_string(d.x) + ", " + std::to_string(d.y) +
                                 ", " + std::to_string(d.z) + ")";
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
    const std::vector<glm::dvec3> directions = {{0, -1, 0}, {0, 1, 0},  {1, 0, 0},     {-1, 0, 0},
                                                {0, 0, 1},  {0, 0, -1}, {0.5, -1, 0.3}};
    for (const glm::dvec3& d : directions) {
        TestScene t;
        addLight(t.scene, "sun", lightOf(LightType::Directional), hard(), {0, 10, 0}, d);
        const CameraView view = t.update();
        ShadowPlanner planner;
        const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
        ASSERT_EQ(frame.lights.size(), 1u);
        const ShadowLayerPlan& layer = frame.lights[0].layers[0];
        for (const DAabb& box : t.casterBounds()) {
            for (int i = 0; i < 8; ++i) {
                const glm::dvec4 clip = clipOf(layer, box.corner(i));
                for (int a = 0; a < 3; ++a) {
                    EXPECT_LE(std::abs(clip[a] / clip.w), 1.0 + kEps)
                        << "direction (" << d.x << ", " << d.y << ", " << d.z << "), corner " << i
                        << ", axis " << a;
                }
            }
        }
        EXPECT_EQ(layer.casters.size(), 3u) << "every caster is in the only layer";
    }
}

/// Every caster corner that falls inside a perspective layer's lateral bounds lies between its
/// near and far planes (clip z in [-w, w]): a caster cut by the near plane casts a partial
/// shadow.
void expectPerspectiveDepthRangeHoldsCasters(const ShadowLightPlan& plan,
                                             const std::vector<DAabb>& casters) {
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
                EXPECT_GE(clip.z, -clip.w * (1.0 + kEps))
                    << plan.name << " layer " << k << ": caster corner at axial depth " << -ls.z
                    << " m is in front of the near plane " << layer.depthNear << " m";
                EXPECT_LE(clip.z, clip.w * (1.0 + kEps))
                    << plan.name << " layer " << k << ": beyond the far plane";
            }
        }
    }
    EXPECT_GT(checked, 0) << plan.name
                          << ": no caster corner inside any layer; the check is vacuous";
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

/// A ground, one box centred at `boxCenter` and one light; checks the light's depth range.
void expectOffAxisCasterBetweenNearAndFar(const Light& light, const glm::dvec3& position,
                                          const glm::dvec3& boxCenter) {
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(5.0f), at({0, 0, 0}));
    addMeshInstance(scene.world, "box", makeBoxMesh({0.8f, 0.4f, 0.6f}), at(boxCenter));
    const Entity camera = addCamera(scene, "camera", Camera{}, {0, 6, 8}, {0, 0, 0});
    addLight(scene, "lamp", light, hard(), position, {0, -1, 0});
    (void)updateTransforms(scene.world);
    ShadowPlanner planner;
    const ShadowFrame& frame =
        planner.prepare(scene.world, makeCameraView(scene.world, camera, 1.0f), scene.lights);
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
    for (std::size_t k = 0; k < 6; ++k)
        expectRigid(plan.layers[k].lightFromWorld, "face " + std::to_string(k));

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
        for (const ShadowLayerPlan& layer : plan.layers) maxNear = std::max(maxNear, static_cast<double>(layer.depthNear));
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
        if (!laterallyInside(clipOf(plan.layers[static_cast<std::size_t>(cubeFace(d))], p)))
            ++outsideOwnFace;
    }
    EXPECT_EQ(uncovered, 0);
    EXPECT_EQ(outsideOwnFace, 0);
}

// ---- Cascade splits ----

TEST(Planner, CascadeSplitsAreMonotoneAndFollowTheClosedForms) {
    const double n = 0.1;
    const double f = 100.0;
    for (int count = 1; count <= 4; ++count) {
        for (double lambda : {0.0, 0.25, 0.75, 1.0}) {
            const std::vector<double> s = cascadeSplits(n, f, count, lambda);
            ASSERT_EQ(s.size(), static_cast<std::size_t>(count) + 1);
            EXPECT_DOUBLE_EQ(s.front(), n);
            EXPECT_DOUBLE_EQ(s.back(), f);
            for (std::size_t i = 1; i < s.size(); ++i)
                EXPECT_LT(s[i - 1], s[i]) << "count " << count;
            for (int i = 0; i <= count; ++i) {
                const double x = static_cast<double>(i) / count;
                const double uniform = n + (f - n) * x;
                const double logarithmic = n * std::pow(f / n, x);
                EXPECT_NEAR(s[static_cast<std::size_t>(i)],
                            lambda * logarithmic + (1.0 - lambda) * uniform, 1e-9 * f)
                    << "count " << count << " lambda " << lambda << " split " << i;
            }
        }
    }
    // The two ends of the blend, spelled out.
    const std::vector<double> uniform = cascadeSplits(1.0, 9.0, 4, 0.0);
    EXPECT_NEAR(uniform[1], 3.0, 1e-12);
    EXPECT_NEAR(uniform[2], 5.0, 1e-12);
    const std::vector<double> logarithmic = cascadeSplits(1.0, 16.0, 4, 1.0);
    EXPECT_NEAR(logarithmic[1], 2.0, 1e-12);
    EXPECT_NEAR(logarithmic[2], 4.0, 1e-12);
    EXPECT_NEAR(logarithmic[3], 8.0, 1e-12);
}

// ---- Caching ----

/// A point light beside box A and box B (near plane and range fixed so that moving a box
/// cannot change its matrices), a narrow spot over the middle that sees neither box, and a
/// directional light.
struct CachingScene : TestScene {
    CachingScene() {
        Light point = lightOf(LightType::Point);
        point.range = 20.0f;
        Shadow s = hard();
        s.nearPlane = 0.1f;
        addLight(scene, "bulb", point, s, {0, 3, 0}, {0, -1, 0});
        Light spot = lightOf(LightType::Spot);
        spot.outerConeAngle = 0.3f;
        spot.range = 20.0f;
        addLight(scene, "spot", spot, s, {0, 6, 0}, {0, -1, 0});
        addLight(scene, "sun", lightOf(LightType::Directional), hard(), {0, 10, 0}, {0.2, -1, 0.1});
    }

    void move(Entity e, const glm::dvec3& to) { scene.world.get<Transform>(e).translation = to; }
};

std::vector<bool> dirtyFlags(const ShadowFrame& frame) {
    std::vector<bool> out;
    for (const ShadowLightPlan& p : frame.lights) {
        for (const ShadowLayerPlan& l : p.layers) out.push_back(l.dirty);
    }
    return out;
}

TEST(Planner, EveryLayerIsDirtyOnTheFirstFrame) {
    CachingScene t;
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 3u);
    const std::vector<bool> dirty = dirtyFlags(frame);
    EXPECT_EQ(dirty.size(), 8u);
    EXPECT_TRUE(std::all_of(dirty.begin(), dirty.end(), [](bool d) { return d; }));
}

TEST(Planner, ReusesEveryLayerWhenNothingMoved) {
    CachingScene t;
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 3u);
    for (const ShadowLightPlan& p : frame.lights) {
        for (std::size_t k = 0; k < p.layers.size(); ++k)
            EXPECT_FALSE(p.layers[k].dirty) << p.name << " layer " << k;
    }
}

/// Moves `box` to `to` after a settled frame and checks that exactly the layers that held it
/// before or after are dirty.
void expectOnlyLayersOfMovedCasterDirty(CachingScene& t, Entity box, const glm::dvec3& to) {
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowFrame before = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    t.move(box, to);
    const ShadowFrame& after = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(before.lights.size(), after.lights.size());
    int expectedDirty = 0;
    int clean = 0;
    for (std::size_t i = 0; i < after.lights.size(); ++i) {
        const ShadowLightPlan& p = after.lights[i];
        ASSERT_EQ(p.layers.size(), before.lights[i].layers.size());
        for (std::size_t k = 0; k < p.layers.size(); ++k) {
            const bool holds = contains(before.lights[i].layers[k].casters, box) ||
                               contains(p.layers[k].casters, box);
            EXPECT_EQ(p.layers[k].dirty, holds) << p.name << " layer " << k;
            expectedDirty += holds ? 1 : 0;
            clean += holds ? 0 : 1;
        }
    }
    // Guards against a vacuous pass: something moved, and something must stay cached.
    EXPECT_GT(expectedDirty, 0);
    EXPECT_GT(clean, 0);
}

TEST(Planner, MovingOneCasterDirtiesOnlyTheLayersHoldingIt) {
    CachingScene t;
    // Box A stays in the bulb's +X face: that face and the sun's layer redraw; the bulb's other
    // faces and the spot, which never see box A, stay cached.
    expectOnlyLayersOfMovedCasterDirty(t, t.boxA, {3, 3, 0.3});
}

TEST(Planner, CasterCrossingCubeFacesDirtiesBothFaces) {
    CachingScene t;
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    t.move(t.boxA, {0, 3, 3});  // from the +X face to the +Z face of the bulb
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowLightPlan* bulb = planOf(frame, "bulb");
    ASSERT_NE(bulb, nullptr);
    ASSERT_EQ(bulb->layers.size(), 6u);
    EXPECT_TRUE(bulb->layers[0].dirty) << "+X face lost box A";
    EXPECT_TRUE(bulb->layers[4].dirty) << "+Z face gained box A";
    EXPECT_FALSE(bulb->layers[1].dirty) << "-X face holds only box B and the ground";
    EXPECT_FALSE(bulb->layers[2].dirty) << "+Y face holds nothing";
    EXPECT_FALSE(bulb->layers[3].dirty) << "-Y face holds only the ground";
    EXPECT_FALSE(bulb->layers[5].dirty) << "-Z face never held box A";
    const ShadowLightPlan* spot = planOf(frame, "spot");
    ASSERT_NE(spot, nullptr);
    EXPECT_FALSE(spot->layers[0].dirty) << "the spot sees neither position of box A";
}

TEST(Planner, CachingOffMakesEveryLayerDirty) {
    CachingScene t;
    ShadowPlanner planner;
    planner.setCaching(false);
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const std::vector<bool> dirty = dirtyFlags(frame);
    ASSERT_EQ(dirty.size(), 8u);
    EXPECT_TRUE(std::all_of(dirty.begin(), dirty.end(), [](bool d) { return d; }));
}

TEST(Planner, LayerWithoutCastersHasEmptyCasterList) {
    CachingScene t;
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowLightPlan* bulb = planOf(frame, "bulb");
    ASSERT_NE(bulb, nullptr);
    ASSERT_EQ(bulb->layers.size(), 6u);
    EXPECT_TRUE(bulb->layers[2].casters.empty()) << "nothing lies above the bulb";
    EXPECT_TRUE(contains(bulb->layers[0].casters, t.boxA));
    EXPECT_FALSE(contains(bulb->layers[0].casters, t.boxB));
    EXPECT_TRUE(contains(bulb->layers[1].casters, t.boxB));
    EXPECT_FALSE(contains(bulb->layers[1].casters, t.boxA));
}

// ---- Settings and which lights get a plan ----

bool hasWarning(const std::vector<std::string>& warnings, const std::string& a,
                const std::string& b) {
    return std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) {
        return w.find(a) != std::string::npos && w.find(b) != std::string::npos;
    });
}

TEST(Planner, ClampShadowSettingsClampsAndNamesTheField) {
    const ShadowLimits limits{4096, 2048};
    {
        Shadow s;
        s.mapSize = 0;
        Light l;
        std::vector<std::string> warnings;
        clampShadowSettings(s, l, limits, "lamp", warnings);
        EXPECT_EQ(s.mapSize, 1);
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_TRUE(hasWarning(warnings, "lamp", "mapSize")) << warnings[0];
    }
    {
        Shadow s;
        s.mapSize = 100000;
        s.constantBias = -1.0f;
        s.pcfRadius = std::nanf("");
        Light l;
        l.radius = -2.0f;
        std::vector<std::string> warnings;
        clampShadowSettings(s, l, limits, "lamp", warnings);
        EXPECT_EQ(s.mapSize, 4096);
        EXPECT_EQ(s.constantBias, 0.0f);
        EXPECT_TRUE(std::isfinite(s.pcfRadius));
        EXPECT_EQ(l.radius, 0.0f);
        EXPECT_EQ(warnings.size(), 4u);
        EXPECT_TRUE(hasWarning(warnings, "lamp", "mapSize"));
        EXPECT_TRUE(hasWarning(warnings, "lamp", "constantBias"));
        EXPECT_TRUE(hasWarning(warnings, "lamp", "pcfRadius"));
        EXPECT_TRUE(hasWarning(warnings, "lamp", "radius"));
    }
    {
        Shadow s;  // the defaults are in range: nothing to say
        Light l;
        std::vector<std::string> warnings;
        clampShadowSettings(s, l, limits, "lamp", warnings);
        EXPECT_TRUE(warnings.empty());
    }
}

TEST(Planner, PrepareClampsMapSizeToTheLimitsAndWarns) {
    TestScene t;
    Shadow s = hard();
    s.mapSize = 8192;
    addLight(t.scene, "big lamp", lightOf(LightType::Spot), s, {0, 5, 0}, {0, -1, 0});
    ShadowPlanner planner;
    planner.setLimits({2048, 2048});
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    EXPECT_EQ(frame.lights[0].mapSize, 2048);
    EXPECT_EQ(frame.lights[0].settings.mapSize, 2048);
    EXPECT_TRUE(hasWarning(frame.warnings, "big lamp", "mapSize"));
}

TEST(Planner, LightsWithoutShadowOrWithTechniqueNoneGetNoPlan) {
    TestScene t;
    Shadow none = hard();
    none.technique = ShadowTechnique::None;
    addLight(t.scene, "unshadowed", lightOf(LightType::Point), none, {0, 4, 0},
             {0, -1, 0});  // no Shadow component
    const Entity shadowed =
        addLight(t.scene, "shadowed", lightOf(LightType::Spot), hard(), {0, 5, 0}, {0, -1, 0});
    const Entity switchedOff =
        addLight(t.scene, "switched off", lightOf(LightType::Point), hard(), {1, 4, 0}, {0, -1, 0});
    t.scene.world.get<Shadow>(switchedOff).technique = ShadowTechnique::None;
    ASSERT_FALSE(t.scene.world.has<Shadow>(t.scene.lights[0]));

    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 3u) << "one entry per scene light";
    EXPECT_FALSE(frame.lights[0].hasMap());
    EXPECT_FALSE(frame.lights[2].hasMap());
    EXPECT_TRUE(frame.lights[1].hasMap());
    EXPECT_EQ(frame.lights[1].entity, shadowed);
    EXPECT_EQ(frame.lights[1].sceneIndex, 1);
    EXPECT_EQ(frame.lights[1].name, "shadowed");
    EXPECT_EQ(frame.techniquesInUse, (1u << static_cast<unsigned>(ShadowTechnique::None)) |
                                         (1u << static_cast<unsigned>(ShadowTechnique::Hard)));
}

}  // namespace
}  // namespace shadow
