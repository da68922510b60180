// The transform system's report of what it skipped (engine/src/scene/transforms.cpp): one
// NonFiniteTransform warning per skipped entity, named so a reader can find it. (Rendering with
// such entities is tested in tests/stability/animation_extremes_test.cpp.) And the one rule for a
// node's world orientation (`worldOrientation`), also where its scale is 0.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace shadow {
namespace {

TEST(Transforms, SkippedEntitiesAreReportedByNameOrIndexInVisitOrder) {
    World world;
    const Entity fine = world.create();
    world.emplace<Name>(fine, Name{"fine"});
    world.emplace<Transform>(fine, Transform{});
    const Entity broken = world.create();
    world.emplace<Name>(broken, Name{"nan box"});
    Transform nan;
    nan.translation.x = std::numeric_limits<double>::quiet_NaN();
    world.emplace<Transform>(broken, nan);
    // An unnamed child inherits the parent's NaN and is named by its index.
    const Entity child = world.create();
    Transform local;
    local.parent = broken;
    world.emplace<Transform>(child, local);

    const TransformStats stats = updateTransforms(world);
    ASSERT_EQ(stats.nonFinite, 2);
    std::vector<Warning> warnings;
    reportSkippedTransforms(world, stats, warnings);
    ASSERT_EQ(warnings.size(), stats.skipped.size());
    for (std::size_t i = 0; i < warnings.size(); ++i) {
        const Entity e = stats.skipped[i];
        const std::string element = e == broken ? "nan box" : "entity " + std::to_string(e.index());
        EXPECT_EQ(warnings[i].code, WarningCode::NonFiniteTransform);
        EXPECT_EQ(warnings[i].element, element);
        EXPECT_EQ(warnings[i].message, element +
                                           ": world transform is not finite (NaN, Inf, or beyond 1e+09 m); "
                                           "skipped by every pass");
    }
    // Both are reported, the fine entity is not.
    std::vector<std::string> elements = {warnings[0].element, warnings[1].element};
    std::sort(elements.begin(), elements.end());
    EXPECT_EQ(elements, (std::vector<std::string>{"entity " + std::to_string(child.index()), "nan box"}));
}

TEST(Transforms, NothingSkippedReportsNothing) {
    World world;
    const Entity e = world.create();
    world.emplace<Transform>(e, Transform{});
    const TransformStats stats = updateTransforms(world);
    std::vector<Warning> warnings;
    reportSkippedTransforms(world, stats, warnings);
    EXPECT_TRUE(warnings.empty());
}

// A glTF file can chain nodes deeper than the stack holds frames; resolving the chain must not
// recurse (a chain of 100000 overflowed the 8 MB stack when it did).
// The moved flag speaks of one update; the version counts the updates that moved the entity, so
// that a consumer that skipped updates still sees the move. A child moves with its parent.
TEST(Transforms, VersionCountsTheUpdatesThatMovedTheEntity) {
    World world;
    const Entity parent = world.create();
    world.emplace<Transform>(parent);
    const Entity child = world.create();
    Transform t;
    t.parent = parent;
    world.emplace<Transform>(child, t);
    (void)updateTransforms(world);
    EXPECT_EQ(world.get<WorldTransform>(child).version, 1u);  // new: moved
    (void)updateTransforms(world);
    EXPECT_EQ(world.get<WorldTransform>(child).version, 1u);
    EXPECT_FALSE(world.get<WorldTransform>(child).movedThisFrame);
    world.get<Transform>(parent).translation.x = 2.0;
    (void)updateTransforms(world);
    (void)updateTransforms(world);  // a second update: the flag is gone, the version stays
    EXPECT_FALSE(world.get<WorldTransform>(child).movedThisFrame);
    EXPECT_EQ(world.get<WorldTransform>(child).version, 2u);
    EXPECT_EQ(world.get<WorldTransform>(parent).version, 2u);
}

TEST(Transforms, ResolvesAParentChainDeeperThanTheStack) {
    constexpr int kDepth = 300000;
    World world;
    Entity parent = Entity::null();
    for (int i = 0; i < kDepth; ++i) {
        const Entity e = world.create();
        Transform t;
        t.translation = {0.0, 0.001, 0.0};
        t.parent = parent;
        world.emplace<Transform>(e, t);
        parent = e;
    }
    const TransformStats stats = updateTransforms(world);
    EXPECT_EQ(stats.updated, kDepth);
    EXPECT_EQ(stats.nonFinite, 0);
    EXPECT_NEAR(world.get<WorldTransform>(parent).worldFromLocal[3].y, 0.001 * kDepth, 1e-6);
}

// A parent cycle has no finite answer: every entity on it is skipped, the rest are not.
TEST(Transforms, ParentCycleIsSkipped) {
    World world;
    const Entity root = world.create();
    world.emplace<Transform>(root, Transform{});
    const Entity a = world.create();
    const Entity b = world.create();
    Transform ta;
    ta.parent = b;
    Transform tb;
    tb.parent = a;
    world.emplace<Transform>(a, ta);
    world.emplace<Transform>(b, tb);
    const TransformStats stats = updateTransforms(world);
    EXPECT_EQ(stats.updated, 3);
    EXPECT_EQ(stats.nonFinite, 2);
    EXPECT_TRUE(world.get<WorldTransform>(root).finite);
    EXPECT_FALSE(world.get<WorldTransform>(a).finite);
    EXPECT_FALSE(world.get<WorldTransform>(b).finite);
}

TEST(Transforms, WorldOrientationIsTheNormalisedRotationOfARegularMatrix) {
    const glm::dquat rotation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(0.3, 1.0, -0.2)));
    WorldTransform wt;
    wt.worldFromLocal = glm::translate(glm::dmat4(1.0), glm::dvec3(1, 2, 3)) * glm::mat4_cast(rotation) *
                        glm::scale(glm::dmat4(1.0), glm::dvec3(2.0, 3.0, 4.0));
    wt.rotation = glm::angleAxis(2.0, glm::dvec3(1, 0, 0));  // not read: the matrix is regular
    const glm::dmat3 axes = worldOrientation(wt);
    const glm::dmat3 expected = glm::mat3_cast(rotation);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(glm::length(axes[c] - expected[c]), 0.0, 1e-12) << "column " << c;
}

TEST(Transforms, WorldOrientationOfAZeroScaleNodeIsItsChainsRotations) {
    // A parent turned about Y holds a child with scale 0 turned about X: the world matrix of the
    // child is singular, but glTF's TRS still says where it points.
    World world;
    Transform parent;
    parent.rotation = glm::angleAxis(0.5, glm::dvec3(0, 1, 0));
    parent.scale = glm::dvec3(2.0);
    const Entity p = world.create();
    world.emplace<Transform>(p, parent);
    Transform child;
    child.parent = p;
    child.rotation = glm::angleAxis(-1.2, glm::dvec3(1, 0, 0));
    child.scale = glm::dvec3(0.0);
    const Entity c = world.create();
    world.emplace<Transform>(c, child);
    (void)updateTransforms(world);
    const glm::dmat3 axes = worldOrientation(world.get<WorldTransform>(c));
    const glm::dmat3 expected = glm::mat3_cast(parent.rotation * child.rotation);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(glm::length(axes[k] - expected[k]), 0.0, 1e-12) << "column " << k;
    // The same answer as the matrix gives at any scale but 0.
    world.get<Transform>(c).scale = glm::dvec3(1e-3, 5.0, 0.25);
    (void)updateTransforms(world);
    const glm::dmat3 scaled = worldOrientation(world.get<WorldTransform>(c));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(glm::length(scaled[k] - expected[k]), 0.0, 1e-12) << "column " << k;
}

}  // namespace
}  // namespace shadow
