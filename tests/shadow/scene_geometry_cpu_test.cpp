// gatherGeometry (engine/src/shadow/scene_geometry.cpp): what changed since the last gather, on
// which the planner keeps a light's layers, and the caster tree it keeps in step with the
// casters. No GL: these run in shadow_planner_tests.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <algorithm>
#include <vector>

#include "shadow/planner_test_support.h"
#include "shadow/scene_geometry.h"

namespace shadow {
namespace {

using test::at;

/// A ground and 40 boxes in a row (enough to be indexed), settled: gathered twice, so that the
/// next gather compares with a frame in which nothing moved.
struct Gathered {
    Scene scene;
    World& world = scene.world;
    Entity ground;
    std::vector<Entity> boxes;
    SceneGeometry g;

    Gathered() {
        ground = addMeshInstance(world, "ground", makePlaneMesh(10.0f), at({0, 0, 0}));
        world.get<Mesh>(ground).castShadows = false;
        for (int i = 0; i < 40; ++i) {
            boxes.push_back(addMeshInstance(world, "box", makeBoxMesh(glm::vec3(0.5f)), at({3.0 * i, 1, 0})));
        }
        gather();
        gather();
    }
    void gather() {
        (void)updateTransforms(world);
        gatherGeometry(world, g);
    }
    void move(Entity e, const glm::dvec3& to) { world.get<Transform>(e).translation = to; }
    [[nodiscard]] std::vector<Entity> changedEntities() const {
        std::vector<Entity> out;
        for (const BoundedEntity& c : g.changed) out.push_back(c.entity);
        return out;
    }
};

TEST(SceneGeometry, NothingChangesWhenNothingMoved) {
    Gathered s;
    EXPECT_TRUE(s.g.changed.empty());
    EXPECT_FALSE(s.g.receiversChanged);
    EXPECT_FALSE(s.g.everythingChanged);
    EXPECT_EQ(s.g.casterTree.size(), s.g.casters.size());
    EXPECT_EQ(s.g.changedTree.size(), 0u);
}

TEST(SceneGeometry, AMovedCasterListsTheBoxItLeftAndTheBoxItTook) {
    Gathered s;
    const DAabb before = s.g.casters[1].bounds;
    s.move(s.boxes[1], {3, 1, 2});
    s.gather();
    ASSERT_EQ(s.g.changed.size(), 2u);
    EXPECT_TRUE(s.g.changed[0].entity == s.boxes[1] && s.g.changed[1].entity == s.boxes[1]);
    EXPECT_EQ(s.g.changed[0].bounds, before);
    EXPECT_EQ(s.g.changed[1].bounds, s.g.casters[1].bounds);
    EXPECT_EQ(s.g.changed[1].bounds.min, glm::dvec3(2.5, 0.5, 1.5));
    EXPECT_TRUE(s.g.receiversChanged);
    EXPECT_FALSE(s.g.everythingChanged) << "the box stayed inside the ground's bounds";
    EXPECT_TRUE(anyChangedMeets(s.g, [](const DAabb& b) { return b.max.z > 1.0; })) << "the box it took";
    EXPECT_TRUE(anyChangedMeets(s.g, [](const DAabb& b) { return b.max.z < 1.0 && b.min.x > 2.0; }))
        << "the box it left";
    EXPECT_FALSE(anyChangedMeets(s.g, [](const DAabb& b) { return b.min.x > 4.0; })) << "no other box";
    // The tree was refitted: it finds the box where it is now, not where it was.
    int foundNow = 0;
    s.g.casterTree.forEach([](const DAabb& b) { return b.max.z > 1.0; }, [&](std::uint32_t) { ++foundNow; });
    EXPECT_EQ(foundNow, 1);
    s.gather();
    EXPECT_TRUE(s.g.changed.empty()) << "settled again";
}

TEST(SceneGeometry, ACasterTurnedWithinItsBoundsIsListedTwiceWithItsBox) {
    Gathered s;
    // A half turn about y (exactly: w 0, y 1) leaves a cube's bounds as they were, bit for bit;
    // its layers must still redraw. It left and took the same box: two entries, so that a
    // frustum meets an even number of them (it neither entered nor left).
    const DAabb box = s.world.get<WorldBounds>(s.boxes[2]).box;
    s.world.get<Transform>(s.boxes[2]).rotation = glm::dquat(0.0, 0.0, 1.0, 0.0);
    s.gather();
    ASSERT_EQ(s.g.changed.size(), 2u);
    for (const BoundedEntity& c : s.g.changed) {
        EXPECT_TRUE(c.entity == s.boxes[2]);
        EXPECT_EQ(c.bounds, box);
    }
    EXPECT_FALSE(s.g.receiversChanged);
}

TEST(SceneGeometry, CastersThatComeAndGoAreListedAndTheTreeIsRebuilt) {
    Gathered s;
    const Entity added = addMeshInstance(s.world, "new", makeBoxMesh(glm::vec3(0.5f)), at({-5, 1, -5}));
    s.world.get<Mesh>(s.boxes[0]).castShadows = false;  // no longer a caster, still a receiver
    s.gather();
    const std::vector<Entity> changed = s.changedEntities();
    ASSERT_EQ(changed.size(), 2u);
    EXPECT_TRUE(std::find(changed.begin(), changed.end(), added) != changed.end());
    EXPECT_TRUE(std::find(changed.begin(), changed.end(), s.boxes[0]) != changed.end());
    EXPECT_TRUE(s.g.receiversChanged);
    EXPECT_EQ(s.g.casters.size(), 40u);
    EXPECT_EQ(s.g.casterTree.size(), 40u);
}

TEST(SceneGeometry, AGameCasterIsListedEveryFrameItSaysItChanged) {
    Scene scene;
    const Entity own = test::addGameCaster(scene, {0, 1, 0}, true);
    SceneGeometry g;
    for (int frame = 0; frame < 3; ++frame) {
        (void)updateTransforms(scene.world);
        gatherGeometry(scene.world, g);
        // The first frame it appeared (the box it took); then it left and took the same box.
        ASSERT_EQ(g.changed.size(), frame == 0 ? 1u : 2u) << "frame " << frame;
        for (const BoundedEntity& c : g.changed) EXPECT_TRUE(c.entity == own);
    }
    scene.world.get<ShadowCasterDraw>(own).changedThisFrame = false;
    (void)updateTransforms(scene.world);
    gatherGeometry(scene.world, g);
    EXPECT_TRUE(g.changed.empty());
}

}  // namespace
}  // namespace shadow
