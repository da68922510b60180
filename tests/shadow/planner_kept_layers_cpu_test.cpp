// ShadowPlanner keeping a light's layers from last frame (engine/src/shadow/planner.cpp,
// keepLayers, with light_projection.cpp's layersHold and the caster tree): a light whose reach
// nothing changed in keeps its layers, and whatever it keeps must be what planning afresh gives.
// Checked against a planner with no history, against a walk over every caster, and against the
// definition of a dirty layer, over frames in which instances, lights and the camera move.
// No GL: these run in shadow_planner_tests.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <shadow/shadow_planner.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadow/frustum.h"
#include "shadow/planner_test_support.h"

namespace shadow {
namespace {

/// Every shadow caster of `world` (finite meshes with triangles that cast, and the game's own)
/// with its world bounds, in entity order: what a layer's list is cut from.
std::vector<std::pair<Entity, DAabb>> everyCaster(const World& world) {
    std::vector<std::pair<Entity, DAabb>> out;
    world.view<Mesh, WorldTransform, WorldBounds>().each([&](Entity e, const Mesh& mesh, const WorldTransform& wt,
                                                             const WorldBounds& wb) {
        if (mesh.castShadows && wt.finite && !wb.box.empty() && mesh.data != nullptr && !mesh.data->indices.empty()) {
            out.emplace_back(e, wb.box);
        }
    });
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return out;
}

/// The casters whose bounds meet `layer`'s frustum, by a walk over all of them.
std::vector<Entity> bruteForceCasters(const std::vector<std::pair<Entity, DAabb>>& casters,
                                      const ShadowLayerPlan& layer) {
    const Frustum f = Frustum::fromMatrix(layer.clipFromLight * layer.lightFromWorld);
    std::vector<Entity> out;
    for (const auto& [e, box] : casters) {
        if (f.intersects(box)) out.push_back(e);
    }
    return out;
}

/// Whether a caster of `layer` moved this frame.
bool aCasterMoved(const World& world, const ShadowLayerPlan& layer) {
    return std::any_of(layer.casters.begin(), layer.casters.end(),
                       [&](Entity e) { return world.get<WorldTransform>(e).movedThisFrame; });
}

/// Counts of what the frames checked, so that a test can tell it was not vacuous.
struct Tally {
    int kept = 0;   ///< layers in view reused
    int dirty = 0;  ///< layers in view redrawn
    /// Layers with the frustum they had whose casters changed, per light type: the case in
    /// which planLayers' `follow` updates a list from the changed casters (that it does, rather
    /// than find the list anew, light_projection_cpu_test.cpp checks; here, that the lists come
    /// out right).
    int followed[3] = {0, 0, 0};
};

/// Compares `frame` (from a planner with history) with a planner planning afresh, the caster
/// lists with a walk over every caster, and each layer's dirty flag with its definition against
/// `last`, the frame before (empty on the first).
void expectAsPlannedAfresh(const World& world, const CameraView& camera, const std::vector<Entity>& lights,
                           const ShadowFrame& frame, const ShadowFrame& last, const std::string& what, Tally& tally) {
    ShadowPlanner fresh;
    const ShadowFrame& truth = fresh.prepare(world, camera, lights);
    ASSERT_EQ(frame.lights.size(), truth.lights.size()) << what;
    EXPECT_EQ(frame.techniquesInUse, truth.techniquesInUse) << what;
    ASSERT_EQ(frame.warnings.size(), truth.warnings.size()) << what;
    for (std::size_t w = 0; w < truth.warnings.size(); ++w) {
        EXPECT_EQ(frame.warnings[w].message, truth.warnings[w].message) << what;
    }
    const std::vector<std::pair<Entity, DAabb>> casters = everyCaster(world);
    for (std::size_t i = 0; i < truth.lights.size(); ++i) {
        const ShadowLightPlan& p = frame.lights[i];
        const ShadowLightPlan& t = truth.lights[i];
        const std::string light = what + ", " + p.name;
        ASSERT_EQ(p.layers.size(), t.layers.size()) << light;
        EXPECT_EQ(p.affectsView, t.affectsView) << light;
        const ShadowLightPlan* before =
            i < last.lights.size() && last.lights[i].entity == p.entity ? &last.lights[i] : nullptr;
        for (std::size_t k = 0; before != nullptr && k < std::min(p.layers.size(), before->layers.size()); ++k) {
            const ShadowLayerPlan& a = p.layers[k];
            const ShadowLayerPlan& was = before->layers[k];
            if (a.lightFromWorld == was.lightFromWorld && a.clipFromLight == was.clipFromLight &&
                a.casters != was.casters) {
                ++tally.followed[static_cast<int>(p.light.type)];
            }
        }
        const bool comparable = before != nullptr && before->affectsView && before->mapSize == p.mapSize &&
                                before->layers.size() == p.layers.size();
        for (std::size_t k = 0; k < t.layers.size(); ++k) {
            const ShadowLayerPlan& a = p.layers[k];
            const ShadowLayerPlan& b = t.layers[k];
            const std::string layer = light + " layer " + std::to_string(k);
            EXPECT_EQ(a.lightFromWorld, b.lightFromWorld) << layer;
            EXPECT_EQ(a.clipFromLight, b.clipFromLight) << layer;
            EXPECT_EQ(a.orthographic, b.orthographic) << layer;
            EXPECT_EQ(a.depthScale, b.depthScale) << layer;
            EXPECT_EQ(a.depthNear, b.depthNear) << layer;
            EXPECT_EQ(a.splitFar, b.splitFar) << layer;
            EXPECT_EQ(a.momentScale, b.momentScale) << layer;
            EXPECT_EQ(a.casters, b.casters) << layer;
            EXPECT_EQ(a.casters, bruteForceCasters(casters, a)) << layer;
            if (!p.affectsView) {
                EXPECT_FALSE(a.dirty) << layer << ": out of view, not drawn";
                continue;
            }
            if (!comparable) {
                EXPECT_TRUE(a.dirty) << layer << ": new in view or reallocated";
                continue;
            }
            const ShadowLayerPlan& was = before->layers[k];
            const bool changed = was.lightFromWorld != a.lightFromWorld || was.clipFromLight != a.clipFromLight ||
                                 was.casters != a.casters || aCasterMoved(world, a);
            EXPECT_EQ(a.dirty, changed) << layer;
            ++(a.dirty ? tally.dirty : tally.kept);
        }
    }
}

/// A ground, `boxes` boxes over 60 m x 60 m, and `lights` lights over them: spots, points and
/// suns (one in six), with ranges or without, fitted or fixed near planes, one in five VSSM, a
/// few in second-depth mode (with their warnings).
struct Playground {
    Scene scene;
    std::vector<Entity> boxes;
    Entity camera;
    std::mt19937 rng{29};

    Playground(int boxCount, int lightCount) {
        std::uniform_real_distribution<double> u(-30.0, 30.0);
        addMeshInstance(scene.world, "ground", makePlaneMesh(32.0f), test::at({0, 0, 0}));
        const auto box = makeBoxMesh(glm::vec3(0.4f));
        for (int i = 0; i < boxCount; ++i) {
            boxes.push_back(
                addMeshInstance(scene.world, "box " + std::to_string(i), box, test::at({u(rng), 0.4, u(rng)})));
        }
        for (int i = 0; i < lightCount; ++i) {
            Light light =
                test::lightOf(i % 6 == 5 ? LightType::Directional : (i % 2 == 0 ? LightType::Spot : LightType::Point));
            light.range = i % 4 == 3 ? 0.0f : 8.0f;
            light.outerConeAngle = 0.7f;
            Shadow s = test::hard();
            s.nearPlane = i % 3 == 0 ? 0.25f : 0.0f;
            if (i % 5 == 4) s.technique = ShadowTechnique::Vssm;
            if (i % 7 == 6) s.depthMode = DepthMode::Second;
            if (light.type == LightType::Directional) s.cascades = 1 + i % 4;
            addLight(scene, "light " + std::to_string(i), light, s, {u(rng), 3.0, u(rng)},
                     glm::normalize(glm::dvec3(0.2, -1.0, 0.1)));
        }
        camera = addCamera(scene, "camera", Camera{}, {-35, 14, -35}, {0, 0, 0});
    }

    CameraView update() {
        (void)updateTransforms(scene.world);
        return makeCameraView(scene.world, camera, 16.0f / 9.0f);
    }
};

TEST(PlannerKeptLayers, EveryFrameIsWhatPlanningAfreshGivesWhileInstancesLightsAndCameraMove) {
    Playground play(400, 30);
    std::mt19937& rng = play.rng;
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<std::size_t> anyBox(0, play.boxes.size() - 1);
    ShadowPlanner planner;
    ShadowFrame last;
    Tally tally;
    for (int frame = 0; frame < 40; ++frame) {
        World& world = play.scene.world;
        // Most frames a few boxes move: a little (within a light's reach), far (from one light's
        // reach into another's), or up to the lights' height (nearer a light than its fitted
        // near plane); some frames many move (indexed apart), some frames nothing moves.
        const int moving = frame % 4 == 3 ? 0 : (frame % 10 == 6 ? 60 : 1 + frame % 5);
        for (int k = 0; k < moving; ++k) {
            glm::dvec3& p = world.get<Transform>(play.boxes[anyBox(rng)]).translation;
            if (k % 3 == 0) p += glm::dvec3(0.3 * u(rng), 0.0, 0.3 * u(rng));
            if (k % 3 == 1) p += glm::dvec3(20.0 * u(rng), 0.0, 20.0 * u(rng));
            if (k % 3 == 2) p.y = p.y > 1.0 ? 0.4 : 2.3;
        }
        if (frame % 9 == 4) {
            // A light moves, one stops casting, one is added, the camera turns.
            world.get<Transform>(play.scene.lights[static_cast<std::size_t>(frame) % play.scene.lights.size()])
                .translation += glm::dvec3(0.5, 0.0, 0.0);
            world.get<Mesh>(play.boxes[anyBox(rng)]).castShadows = frame % 2 == 0;
            play.boxes.push_back(addMeshInstance(world, "late box", makeBoxMesh(glm::vec3(0.3f)),
                                                 test::at({20.0 * u(rng), 0.3, 20.0 * u(rng)})));
            world.get<Transform>(play.camera).translation += glm::dvec3(1.0, 0.0, 0.0);
        }
        if (frame % 13 == 12) world.get<Transform>(play.boxes[anyBox(rng)]).rotation = glm::dquat(0.0, 0.0, 1.0, 0.0);
        const CameraView camera = play.update();
        const ShadowFrame& now = planner.prepare(world, camera, play.scene.lights);
        expectAsPlannedAfresh(world, camera, play.scene.lights, now, last, "frame " + std::to_string(frame), tally);
        last = now;
    }
    // Not vacuous: layers were kept and layers were redrawn, and casters entered and left
    // layers of every type whose frusta stayed.
    EXPECT_GT(tally.kept, 100);
    EXPECT_GT(tally.dirty, 20);
    for (const LightType type : {LightType::Directional, LightType::Spot, LightType::Point}) {
        EXPECT_GT(tally.followed[static_cast<int>(type)], 3) << "light type " << static_cast<int>(type);
    }
}

/// Two spots 10 m apart, a box under each, and a camera that sees both.
struct TwoSpots {
    Scene scene;
    Entity boxA;
    Entity boxB;
    Entity camera;

    TwoSpots() {
        addMeshInstance(scene.world, "ground", makePlaneMesh(20.0f), test::at({0, 0, 0}));
        boxA = addMeshInstance(scene.world, "box A", makeBoxMesh(glm::vec3(0.4f)), test::at({-5, 0.4, 0}));
        boxB = addMeshInstance(scene.world, "box B", makeBoxMesh(glm::vec3(0.4f)), test::at({5, 0.4, 0}));
        Light spot = test::lightOf(LightType::Spot);
        spot.range = 6.0f;
        addLight(scene, "A", spot, test::hard(), {-5, 4, 0}, {0, -1, 0});
        addLight(scene, "B", spot, test::hard(), {5, 4, 0}, {0, -1, 0});
        camera = addCamera(scene, "camera", Camera{}, {0, 12, 16}, {0, 0, 0});
    }
    CameraView update() {
        (void)updateTransforms(scene.world);
        return makeCameraView(scene.world, camera, 16.0f / 9.0f);
    }
    void move(Entity e, const glm::dvec3& to) { scene.world.get<Transform>(e).translation = to; }
};

/// Layer 0 of the light named `name` in `frame`; throws when the frame has no such light or layer.
const ShadowLayerPlan& firstLayer(const ShadowFrame& frame, const char* name) {
    const ShadowLightPlan* plan = test::planOf(frame, name);
    if (plan == nullptr || plan->layers.empty()) throw std::runtime_error(std::string("no layer of light ") + name);
    return plan->layers[0];
}

TEST(PlannerKeptLayers, ALightKeepsItsLayersUntilAnInstanceInItsReachMoves) {
    TwoSpots t;
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    for (int frame = 0; frame < 3; ++frame) {
        const ShadowFrame& still = planner.prepare(t.scene.world, t.update(), t.scene.lights);
        EXPECT_FALSE(firstLayer(still, "A").dirty) << "frame " << frame;
        EXPECT_FALSE(firstLayer(still, "B").dirty) << "frame " << frame;
    }
    t.move(t.boxA, {-5.2, 0.4, 0});
    const ShadowFrame& moved = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    EXPECT_TRUE(firstLayer(moved, "A").dirty) << "box A moved under A";
    EXPECT_TRUE(test::contains(firstLayer(moved, "A").casters, t.boxA));
    EXPECT_FALSE(firstLayer(moved, "B").dirty) << "nothing moved under B";
    const ShadowFrame& after = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    EXPECT_FALSE(firstLayer(after, "A").dirty) << "settled again";
    // The camera moves: a spot's layers do not follow it.
    t.scene.world.get<Transform>(t.camera).translation += glm::dvec3(2.0, 1.0, 0.0);
    const ShadowFrame& turned = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    EXPECT_FALSE(firstLayer(turned, "A").dirty);
    EXPECT_FALSE(firstLayer(turned, "B").dirty);
}

TEST(PlannerKeptLayers, AnInstanceMovingNearerTheLightThanItsNearPlanePullsTheNearPlaneIn) {
    TwoSpots t;
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const float nearBefore = planner.prepare(t.scene.world, t.update(), t.scene.lights).lights[0].layers[0].depthNear;
    // 0.6 m under light A: in front of its near plane (fitted to box A, 3 m down), so outside the
    // layer's own frustum, but inside the widest frustum the near plane is fitted in.
    t.move(t.boxB, {-5, 3.0, 0});
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowLightPlan* a = test::planOf(frame, "A");
    ASSERT_NE(a, nullptr);
    EXPECT_LT(a->layers[0].depthNear, nearBefore);
    EXPECT_LT(a->layers[0].depthNear, 0.6f);
    EXPECT_TRUE(a->layers[0].dirty);
    EXPECT_TRUE(test::contains(a->layers[0].casters, t.boxB));
}

TEST(PlannerKeptLayers, AnInstanceMovingFromOneLightsReachIntoAnothersRedrawsBoth) {
    TwoSpots t;
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    t.move(t.boxA, {5.5, 0.4, 0.5});  // from under A to beside box B, under B
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowLightPlan* a = test::planOf(frame, "A");
    const ShadowLightPlan* b = test::planOf(frame, "B");
    ASSERT_NE(a, nullptr);
    ASSERT_NE(b, nullptr);
    EXPECT_TRUE(a->layers[0].dirty) << "A lost box A";
    EXPECT_FALSE(test::contains(a->layers[0].casters, t.boxA));
    EXPECT_TRUE(b->layers[0].dirty) << "B gained box A";
    EXPECT_TRUE(test::contains(b->layers[0].casters, t.boxA));
    EXPECT_TRUE(test::contains(b->layers[0].casters, t.boxB));
    const ShadowFrame& settled = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    EXPECT_FALSE(firstLayer(settled, "A").dirty);
    EXPECT_FALSE(firstLayer(settled, "B").dirty);
}

}  // namespace
}  // namespace shadow
