// BoxTree (engine/src/shadow/box_tree.cpp), the index of the casters every light's queries walk:
// a query through it must visit exactly the items a walk over the whole list visits, however
// the boxes lie, after a build, after refits while the boxes move, and through rebuilds.
// No GL: these run in shadow_planner_tests.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "shadow/box_tree.h"
#include "shadow/frustum.h"

namespace shadow {
namespace {

/// `count` boxes scattered over a 100 m cube: most small, some long and flat (a ground, a wall),
/// some degenerate (a plane's bounds have no thickness), some in the same place.
std::vector<BoundedEntity> scatteredBoxes(std::mt19937& rng, int count) {
    std::uniform_real_distribution<double> u(-50.0, 50.0);
    std::uniform_real_distribution<double> size(0.0, 2.0);
    std::vector<BoundedEntity> out;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 c(u(rng), u(rng), u(rng));
        glm::dvec3 half(size(rng), size(rng), size(rng));
        if (i % 17 == 0) half *= 20.0;
        if (i % 23 == 0) half.y = 0.0;
        const glm::dvec3 at = i % 31 == 0 && !out.empty() ? out.back().bounds.center() : c;
        out.push_back({Entity(static_cast<std::uint32_t>(i), 0), {at - half, at + half}});
    }
    return out;
}

/// A perspective or orthographic frustum somewhere in the cube, looking anywhere.
Frustum randomFrustum(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const glm::dvec3 eye(40.0 * u(rng), 40.0 * u(rng), 40.0 * u(rng));
    glm::dvec3 forward(u(rng), u(rng), u(rng));
    if (glm::length(forward) < 1e-3) forward = {0.0, -1.0, 0.0};
    const glm::dmat4 view = lookAlong(eye, glm::normalize(forward));
    const double far = 5.0 + 60.0 * (u(rng) + 1.0);
    const glm::dmat4 projection = u(rng) > 0.0
                                      ? glm::perspective(0.2 + 1.2 * (u(rng) + 1.0), 1.0, 0.01 + (u(rng) + 1.0), far)
                                      : glm::ortho(-10.0, 10.0 + 20.0 * (u(rng) + 1.0), -10.0, 10.0, 0.0, far);
    return Frustum::fromMatrix(projection * view);
}

/// The indices a query through `tree` visits, sorted.
template <typename Meets>
std::vector<std::uint32_t> queried(const BoxTree& tree, const Meets& meets) {
    std::vector<std::uint32_t> out;
    tree.forEach(meets, [&](std::uint32_t i) { out.push_back(i); });
    std::sort(out.begin(), out.end());
    return out;
}

/// The indices a walk over `items` accepts, in order.
template <typename Meets>
std::vector<std::uint32_t> walked(const std::vector<BoundedEntity>& items, const Meets& meets) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (meets(items[i].bounds)) out.push_back(static_cast<std::uint32_t>(i));
    }
    return out;
}

/// Queries `tree` with random frusta and slabs and compares each with the walk over `items`;
/// returns how many items the queries found, so that a caller can tell the test was not vacuous.
std::size_t expectQueriesMatchTheWalk(std::mt19937& rng, const BoxTree& tree, const std::vector<BoundedEntity>& items,
                                      const std::string& what) {
    std::size_t found = 0;
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int q = 0; q < 60; ++q) {
        const Frustum f = randomFrustum(rng);
        const auto inFrustum = [&f](const DAabb& box) { return f.intersects(box); };
        const std::vector<std::uint32_t> expected = walked(items, inFrustum);
        EXPECT_EQ(queried(tree, inFrustum), expected) << what << ", frustum " << q;
        EXPECT_EQ(tree.any(inFrustum), !expected.empty()) << what << ", frustum " << q;
        found += expected.size();
        // A slab along a random direction, as a cascade's column is beside boxes in light space.
        const glm::dvec3 n = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) + glm::dvec3(1e-3));
        const double lo = 30.0 * u(rng);
        const double hi = lo + 10.0 * (u(rng) + 1.0);
        const auto inSlab = [&](const DAabb& box) {
            double a = 0.0;
            double b = 0.0;
            for (int i = 0; i < 3; ++i) {
                a += n[i] * (n[i] >= 0.0 ? box.min[i] : box.max[i]);
                b += n[i] * (n[i] >= 0.0 ? box.max[i] : box.min[i]);
            }
            return !(b < lo || a > hi);
        };
        EXPECT_EQ(queried(tree, inSlab), walked(items, inSlab)) << what << ", slab " << q;
    }
    return found;
}

TEST(BoxTree, QueriesVisitExactlyWhatAWalkOverTheListVisits) {
    std::mt19937 rng(11);
    for (const int count : {0, 1, 3, 4, 5, 9, 100, 2000}) {
        const std::vector<BoundedEntity> items = scatteredBoxes(rng, count);
        BoxTree tree;
        tree.build(items);
        EXPECT_EQ(tree.size(), items.size());
        const std::size_t found = expectQueriesMatchTheWalk(rng, tree, items, std::to_string(count) + " boxes");
        if (count >= 100) {
            EXPECT_GT(found, 0u);
        }
    }
}

TEST(BoxTree, RefittedTreeFollowsMovingBoxes) {
    std::mt19937 rng(12);
    std::vector<BoundedEntity> items = scatteredBoxes(rng, 1500);
    BoxTree tree;
    tree.build(items);
    std::uniform_real_distribution<double> step(-3.0, 3.0);
    std::uniform_int_distribution<std::size_t> pick(0, items.size() - 1);
    for (int frame = 0; frame < 12; ++frame) {
        // A few boxes each frame, and in frame 6 all of them, far: the refit must hold either way
        // (the second rebuilds, the tree having grown too loose).
        const int moving = frame == 6 ? static_cast<int>(items.size()) : 15;
        for (int k = 0; k < moving; ++k) {
            BoundedEntity& item = frame == 6 ? items[static_cast<std::size_t>(k)] : items[pick(rng)];
            const glm::dvec3 d(step(rng), step(rng), step(rng));
            item.bounds.min += frame == 6 ? 10.0 * d : d;
            item.bounds.max += frame == 6 ? 10.0 * d : d;
        }
        tree.refit(items);
        EXPECT_EQ(tree.size(), items.size());
        expectQueriesMatchTheWalk(rng, tree, items, "frame " + std::to_string(frame));
    }
}

TEST(BoxTree, AnyStopsAtTheFirstAcceptedItem) {
    std::mt19937 rng(13);
    const std::vector<BoundedEntity> items = scatteredBoxes(rng, 300);
    BoxTree tree;
    tree.build(items);
    int tested = 0;
    EXPECT_TRUE(tree.any([&](const DAabb&) {
        ++tested;
        return true;
    }));
    // The root, the nodes down to the first leaf, and its first item.
    EXPECT_LT(tested, 20);
    EXPECT_FALSE(tree.any([](const DAabb&) { return false; }));
    tree.clear();
    EXPECT_EQ(tree.size(), 0u);
    EXPECT_FALSE(tree.any([](const DAabb&) { return true; }));
}

/// The bounds of `box`'s eight corners under `m`, one corner at a time.
DAabb cornerBounds(const glm::dmat4& m, const DAabb& box) {
    DAabb out;
    for (int i = 0; i < 8; ++i) out.extend(glm::dvec3(m * glm::dvec4(box.corner(i), 1.0)));
    return out;
}

// transformBounds gives the corners' bounds bit for bit, and a box inside another gets bounds
// inside the other's (what the light-space queries through the tree rely on), for rotations,
// scales, shears and translations far from the origin, and for float boxes as their doubles.
TEST(TransformBounds, EqualsTheCornersBoundsBitForBitAndGrowsWithTheBox) {
    std::mt19937 rng(14);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const std::vector<BoundedEntity> items = scatteredBoxes(rng, 400);
    int inner = 0;
    for (int trial = 0; trial < 200; ++trial) {
        glm::dvec3 axis(u(rng), u(rng), u(rng));
        if (glm::length(axis) < 1e-3) axis = {0.0, 1.0, 0.0};
        glm::dmat4 m = glm::rotate(glm::dmat4(1.0), 3.0 * u(rng), glm::normalize(axis));
        if (trial % 3 == 1) m = glm::scale(m, glm::dvec3(1.0 + u(rng), 0.01 + std::abs(u(rng)), 3.0));
        if (trial % 5 == 2) m[1][0] += 0.7 * u(rng);  // a shear
        m[3] = glm::dvec4(1e5 * u(rng), 1e3 * u(rng), -1e5 * u(rng), 1.0);
        for (std::size_t i = 0; i < items.size(); i += 7) {
            const DAabb& box = items[i].bounds;
            const DAabb fast = transformBounds(m, box);
            const DAabb slow = cornerBounds(m, box);
            ASSERT_EQ(fast.min, slow.min) << "trial " << trial << ", box " << i;
            ASSERT_EQ(fast.max, slow.max) << "trial " << trial << ", box " << i;
            // A box inside: its bounds inside, whatever the rounding.
            DAabb shrunk = box;
            shrunk.min = glm::mix(box.min, box.max, 0.3 * (u(rng) + 1.0) * 0.5);
            shrunk.max = glm::mix(shrunk.min, box.max, 0.5 * (u(rng) + 1.0));
            const DAabb in = transformBounds(m, shrunk);
            ASSERT_TRUE(glm::all(glm::greaterThanEqual(in.min, fast.min)) &&
                        glm::all(glm::lessThanEqual(in.max, fast.max)))
                << "trial " << trial << ", box " << i;
            ++inner;
        }
        const Aabb single{glm::vec3(-0.3f, 0.1f, 2.5f), glm::vec3(0.7f, 0.100001f, 9.0f)};
        const DAabb asDouble{glm::dvec3(single.min), glm::dvec3(single.max)};
        ASSERT_EQ(transformBounds(m, single), cornerBounds(m, asDouble)) << "trial " << trial;
    }
    EXPECT_GT(inner, 10000);
    EXPECT_TRUE(transformBounds(glm::dmat4(1.0), DAabb{}).empty());
}

}  // namespace
}  // namespace shadow
