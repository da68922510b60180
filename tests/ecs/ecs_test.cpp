// Tests for engine/include/shadow/ecs.h: handles, generations, storage and views, including the
// rules for what `each` may change while it runs.

#include <gtest/gtest.h>
#include <shadow/ecs.h>

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace shadow {
namespace {

struct Position {  // aggregate
    float x = 0.0f;
    float y = 0.0f;
};
struct Velocity {  // aggregate
    float dx = 0.0f;
};
struct Marked {};  // tag: empty struct

/// Non-aggregate: user constructor, private state, owns heap memory.
class Label {
public:
    explicit Label(std::string text, int weight = 1) : text_(std::move(text)), weight_(weight) {}
    [[nodiscard]] const std::string& text() const { return text_; }
    [[nodiscard]] int weight() const { return weight_; }

private:
    std::string text_;
    int weight_;
};

/// Move-only component.
struct Owned {
    std::unique_ptr<int> value;
};

/// Visits of `view<Ts...>().each` per entity.
template <typename... Ts>
std::map<std::uint32_t, int> visitCounts(World& world) {
    std::map<std::uint32_t, int> visits;
    world.view<Ts...>().each([&visits](Entity e, Ts&...) { ++visits[e.bits()]; });
    return visits;
}

std::map<std::uint32_t, int> onceEach(const std::vector<Entity>& entities) {
    std::map<std::uint32_t, int> visits;
    for (Entity e : entities) visits[e.bits()] = 1;
    return visits;
}

// ---- Handles --------------------------------------------------------------------------------

TEST(World, NullEntityIsNeverAlive) {
    World world;
    EXPECT_TRUE(Entity().isNull());
    EXPECT_EQ(Entity(), Entity::null());
    EXPECT_FALSE(world.alive(Entity::null()));
    std::vector<Entity> created;
    for (int i = 0; i < 100; ++i) created.push_back(world.create());
    for (Entity e : created) EXPECT_NE(e, Entity::null());
    EXPECT_FALSE(world.alive(Entity::null()));
    EXPECT_FALSE(world.has<Position>(Entity::null()));
    EXPECT_EQ(world.tryGet<Position>(Entity::null()), nullptr);
    world.destroy(Entity::null());  // no-op
    EXPECT_EQ(world.size(), 100u);
}

TEST(World, CreateMakesDistinctLiveEntities) {
    World world;
    const Entity a = world.create();
    const Entity b = world.create();
    EXPECT_NE(a, b);
    EXPECT_TRUE(world.alive(a));
    EXPECT_TRUE(world.alive(b));
    EXPECT_EQ(world.size(), 2u);
}

TEST(World, DestroyMakesHandleStale) {
    World world;
    const Entity e = world.create();
    world.emplace<Position>(e, 1.0f, 2.0f);
    world.emplace<Marked>(e);
    const Entity copy = e;
    world.destroy(e);
    EXPECT_FALSE(world.alive(copy));
    EXPECT_EQ(world.tryGet<Position>(copy), nullptr);
    EXPECT_FALSE(world.has<Position>(copy));
    EXPECT_FALSE(world.has<Marked>(copy));
    EXPECT_EQ(world.count<Position>(), 0u);
    EXPECT_EQ(world.count<Marked>(), 0u);
    EXPECT_EQ(world.size(), 0u);
}

TEST(World, DestroyingAStaleHandleDoesNothing) {
    World world;
    const Entity old = world.create();
    world.destroy(old);
    const Entity reused = world.create();
    world.emplace<Position>(reused);
    world.destroy(old);
    EXPECT_TRUE(world.alive(reused));
    EXPECT_TRUE(world.has<Position>(reused));
}

TEST(World, ReusedSlotGetsADifferentHandle) {
    World world;
    const Entity old = world.create();
    world.emplace<Position>(old, 1.0f, 1.0f);
    world.destroy(old);
    const Entity reused = world.create();
    EXPECT_EQ(reused.index(), old.index());  // the slot is recycled...
    EXPECT_NE(reused.generation(), old.generation());
    EXPECT_NE(reused, old);  // ...but the handle is not
    EXPECT_TRUE(world.alive(reused));
    EXPECT_FALSE(world.alive(old));
    EXPECT_FALSE(world.has<Position>(reused));  // the old entity's components are gone
}

TEST(World, StaleHandleCannotReachTheSlotsNewOwner) {
    World world;
    const Entity old = world.create();
    world.destroy(old);
    const Entity reused = world.create();
    world.emplace<Position>(reused, 3.0f, 4.0f);
    EXPECT_EQ(world.tryGet<Position>(old), nullptr);
    EXPECT_FALSE(world.has<Position>(old));
    EXPECT_FALSE(world.remove<Position>(old));
    EXPECT_TRUE(world.has<Position>(reused));
}

TEST(World, RetiresSlotInsteadOfWrappingItsGeneration) {
    World world;
    std::set<std::uint32_t> seen;
    std::vector<Entity> all;
    const int cycles = static_cast<int>(Entity::kMaxGeneration) + 1 + 200;
    for (int i = 0; i < cycles; ++i) {
        const Entity e = world.create();
        ASSERT_TRUE(seen.insert(e.bits()).second) << "handle reused at cycle " << i;
        ASSERT_TRUE(world.alive(e));
        all.push_back(e);
        world.destroy(e);
    }
    // Slot 0 served generations 0..kMaxGeneration, then retired; slot 1 took over.
    EXPECT_EQ(all[Entity::kMaxGeneration].index(), 0u);
    EXPECT_EQ(all[Entity::kMaxGeneration].generation(), Entity::kMaxGeneration);
    EXPECT_EQ(all[Entity::kMaxGeneration + 1].index(), 1u);
    for (Entity e : all) EXPECT_FALSE(world.alive(e));
    EXPECT_EQ(world.size(), 0u);
    const Entity next = world.create();
    EXPECT_EQ(seen.count(next.bits()), 0u);
    EXPECT_EQ(world.size(), 1u);
}

// ---- Components -----------------------------------------------------------------------------

TEST(World, EmplacesAggregateAndNonAggregateComponents) {
    World world;
    const Entity e = world.create();
    const Position& p = world.emplace<Position>(e, 1.0f, 2.0f);
    EXPECT_EQ(p.x, 1.0f);
    EXPECT_EQ(p.y, 2.0f);
    const Velocity& v = world.emplace<Velocity>(e);  // value-initialised
    EXPECT_EQ(v.dx, 0.0f);
    world.emplace<Label>(e, "lamp", 3);
    EXPECT_EQ(world.get<Label>(e).text(), "lamp");
    EXPECT_EQ(world.get<Label>(e).weight(), 3);
    world.emplace<Owned>(e, std::make_unique<int>(7));
    EXPECT_EQ(*world.get<Owned>(e).value, 7);
    EXPECT_TRUE((world.has<Position, Velocity, Label, Owned>(e)));
}

TEST(World, RemoveKeepsOtherEntitiesComponentsIntact) {
    World world;
    std::vector<Entity> es;
    for (int i = 0; i < 5; ++i) {
        es.push_back(world.create());
        world.emplace<Label>(es.back(), std::string("n").append(std::to_string(i)), i);
        world.emplace<Owned>(es.back(), std::make_unique<int>(i));
    }
    EXPECT_TRUE(world.remove<Label>(es[1]));  // swap-and-pop moves the last one into its place
    EXPECT_TRUE(world.remove<Owned>(es[1]));
    EXPECT_FALSE(world.remove<Label>(es[1]));
    for (int i : {0, 2, 3, 4}) {
        EXPECT_EQ(world.get<Label>(es[i]).text(), std::string("n").append(std::to_string(i)));
        EXPECT_EQ(*world.get<Owned>(es[i]).value, i);
    }
    EXPECT_FALSE(world.has<Label>(es[1]));
    EXPECT_TRUE(world.alive(es[1]));
}

TEST(World, EmplaceOrReplaceAddsThenReplaces) {
    World world;
    const Entity e = world.create();
    world.emplaceOrReplace(e, Position{1.0f, 2.0f});
    EXPECT_EQ(world.get<Position>(e).x, 1.0f);
    world.emplaceOrReplace(e, Position{5.0f, 6.0f});
    EXPECT_EQ(world.get<Position>(e).x, 5.0f);
    EXPECT_EQ(world.get<Position>(e).y, 6.0f);
    EXPECT_EQ(world.count<Position>(), 1u);
    world.emplaceOrReplace(e, Label("a"));
    world.emplaceOrReplace(e, Label("b"));
    EXPECT_EQ(world.get<Label>(e).text(), "b");
    EXPECT_EQ(world.count<Label>(), 1u);
}

TEST(World, CountCountsComponentsOfOneType) {
    World world;
    EXPECT_EQ(world.count<Velocity>(), 0u);  // no pool yet
    std::vector<Entity> es;
    for (int i = 0; i < 4; ++i) {
        es.push_back(world.create());
        world.emplace<Velocity>(es.back());
    }
    world.emplace<Position>(es[0]);
    EXPECT_EQ(world.count<Velocity>(), 4u);
    EXPECT_EQ(world.count<Position>(), 1u);
    world.remove<Velocity>(es[0]);
    world.destroy(es[1]);
    EXPECT_EQ(world.count<Velocity>(), 2u);
    EXPECT_EQ(world.count<Position>(), 1u);
}

TEST(World, HasRequiresEveryListedType) {
    World world;
    const Entity e = world.create();
    world.emplace<Position>(e);
    EXPECT_TRUE(world.has<Position>(e));
    EXPECT_FALSE((world.has<Position, Velocity>(e)));
    world.emplace<Velocity>(e);
    EXPECT_TRUE((world.has<Position, Velocity>(e)));
}

// ---- Views ----------------------------------------------------------------------------------

/// Entities with every subset of {Position, Velocity, Marked}, two of each; returns them by
/// subset bit mask (1 = Position, 2 = Velocity, 4 = Marked).
std::map<int, std::vector<Entity>> populateSubsets(World& world) {
    std::map<int, std::vector<Entity>> bySubset;
    for (int copy = 0; copy < 2; ++copy) {
        for (int mask = 0; mask < 8; ++mask) {
            const Entity e = world.create();
            if (mask & 1) world.emplace<Position>(e, static_cast<float>(mask), 0.0f);
            if (mask & 2) world.emplace<Velocity>(e, static_cast<float>(mask));
            if (mask & 4) world.emplace<Marked>(e);
            bySubset[mask].push_back(e);
        }
    }
    return bySubset;
}

std::vector<Entity> withAll(const std::map<int, std::vector<Entity>>& bySubset, int required) {
    std::vector<Entity> out;
    for (const auto& [mask, entities] : bySubset) {
        if ((mask & required) == required) out.insert(out.end(), entities.begin(), entities.end());
    }
    return out;
}

TEST(World, ViewsVisitExactlyTheEntitiesOwningEveryType) {
    World world;
    const auto bySubset = populateSubsets(world);
    EXPECT_EQ(visitCounts<Position>(world), onceEach(withAll(bySubset, 1)));
    EXPECT_EQ(visitCounts<Marked>(world), onceEach(withAll(bySubset, 4)));
    EXPECT_EQ((visitCounts<Position, Velocity>(world)), onceEach(withAll(bySubset, 3)));
    EXPECT_EQ((visitCounts<Marked, Velocity>(world)), onceEach(withAll(bySubset, 6)));
    EXPECT_EQ((visitCounts<Position, Velocity, Marked>(world)), onceEach(withAll(bySubset, 7)));
    EXPECT_EQ((world.view<Position, Velocity, Marked>().count()), 2u);
}

TEST(World, ViewPassesTheEntitysOwnComponents) {
    World world;
    populateSubsets(world);
    world.view<Position, Velocity>().each([&world](Entity e, Position& p, Velocity& v) {
        EXPECT_EQ(&p, world.tryGet<Position>(e));
        EXPECT_EQ(&v, world.tryGet<Velocity>(e));
        EXPECT_EQ(p.x, v.dx);  // both were set to the subset mask
    });
}

TEST(World, ViewWritesReachTheWorld) {
    World world;
    const auto bySubset = populateSubsets(world);
    world.view<Position, Velocity>().each([](Entity, Position& p, Velocity& v) { p.y = v.dx * 2; });
    for (Entity e : withAll(bySubset, 3)) EXPECT_EQ(world.get<Position>(e).y, world.get<Velocity>(e).dx * 2);
}

TEST(World, AConstWorldGivesConstViewsOfTheSameEntities) {
    World world;
    const auto bySubset = populateSubsets(world);
    const World& reader = world;
    // A const world's view hands out const references only: a reader cannot write through it.
    using ReaderView = decltype(reader.view<Position, Velocity>());
    static_assert(std::is_same_v<ReaderView, View<const Position, const Velocity>>);
    std::map<std::uint32_t, int> visits;
    reader.view<Position, Velocity>().each([&](Entity e, const Position& p, const Velocity& v) {
        ++visits[e.bits()];
        EXPECT_EQ(&p, reader.tryGet<Position>(e));
        EXPECT_EQ(p.x, v.dx);
    });
    EXPECT_EQ(visits, onceEach(withAll(bySubset, 3)));
    EXPECT_EQ((reader.view<Position, Velocity>().count()), withAll(bySubset, 3).size());
    // A mutable world may ask for const components too, mixed with writable ones.
    int visited = 0;
    world.view<const Position, Velocity>().each([&](Entity, const Position& p, Velocity& v) {
        v.dx = p.x;
        ++visited;
    });
    EXPECT_EQ(static_cast<std::size_t>(visited), withAll(bySubset, 3).size());
    EXPECT_TRUE((reader.view<Label>().count() == 0));
}

TEST(World, ViewOfATypeNeverEmplacedVisitsNothing) {
    World world;
    populateSubsets(world);
    EXPECT_TRUE(visitCounts<Label>(world).empty());
    EXPECT_TRUE((visitCounts<Position, Label>(world).empty()));
}

TEST(World, SkipsDestroyedEntitiesInViews) {
    World world;
    auto bySubset = populateSubsets(world);
    world.destroy(bySubset[7][0]);
    EXPECT_EQ((visitCounts<Position, Velocity, Marked>(world)), onceEach({bySubset[7][1]}));
}

// ---- Changing the world during each() ------------------------------------------------------

TEST(World, RemovingVisitedComponentDuringEachVisitsEveryOtherOnce) {
    for (int required : {1, 3, 7}) {
        SCOPED_TRACE(required);
        World world;
        const auto bySubset = populateSubsets(world);
        std::map<std::uint32_t, int> visits;
        auto removeDriver = [&](Entity e, auto&...) {
            ++visits[e.bits()];
            EXPECT_TRUE(world.remove<Position>(e));
        };
        if (required == 1) world.view<Position>().each(removeDriver);
        if (required == 3) world.view<Position, Velocity>().each(removeDriver);
        if (required == 7) world.view<Position, Velocity, Marked>().each(removeDriver);
        EXPECT_EQ(visits, onceEach(withAll(bySubset, required)));
        EXPECT_EQ(world.count<Position>(), withAll(bySubset, 1).size() - visits.size());
    }
}

TEST(World, RemovingVisitedEntitysOtherComponentDuringEachVisitsEveryOtherOnce) {
    World world;
    const auto bySubset = populateSubsets(world);
    std::map<std::uint32_t, int> visits;
    world.view<Position, Velocity>().each([&](Entity e, Position&, Velocity&) {
        ++visits[e.bits()];
        EXPECT_TRUE(world.remove<Velocity>(e));
        EXPECT_TRUE(world.remove<Position>(e));
    });
    EXPECT_EQ(visits, onceEach(withAll(bySubset, 3)));
}

TEST(World, DestroyingVisitedEntityDuringEachVisitsEveryOtherOnce) {
    World world;
    const auto bySubset = populateSubsets(world);
    std::map<std::uint32_t, int> visits;
    world.view<Velocity, Marked>().each([&](Entity e, Velocity&, Marked&) {
        ++visits[e.bits()];
        world.destroy(e);
    });
    const std::vector<Entity> expected = withAll(bySubset, 6);
    EXPECT_EQ(visits, onceEach(expected));
    for (Entity e : expected) EXPECT_FALSE(world.alive(e));
    EXPECT_EQ(world.size(), 16u - expected.size());
}

TEST(World, EntitiesCreatedDuringEachAreNotVisited) {
    World world;
    const auto bySubset = populateSubsets(world);
    std::map<std::uint32_t, int> visits;
    world.view<Position, Velocity>().each([&](Entity e, Position&, Velocity&) {
        ++visits[e.bits()];
        for (int i = 0; i < 50; ++i) {  // enough to force the pools to reallocate
            const Entity fresh = world.create();
            world.emplace<Position>(fresh);
            world.emplace<Velocity>(fresh);
            world.emplace<Label>(fresh, "new");  // a pool created mid-iteration
        }
    });
    const std::vector<Entity> expected = withAll(bySubset, 3);
    EXPECT_EQ(visits, onceEach(expected));
    EXPECT_EQ((world.view<Position, Velocity>().count()), expected.size() * 51);
}

TEST(World, DestroyAndCreateInTheSameVisitSkipsTheNewEntity) {
    World world;
    const auto bySubset = populateSubsets(world);
    std::map<std::uint32_t, int> visits;
    world.view<Position>().each([&](Entity e, Position&) {
        ++visits[e.bits()];
        world.destroy(e);
        const Entity fresh = world.create();  // takes the slot just freed
        world.emplace<Position>(fresh);
    });
    EXPECT_EQ(visits, onceEach(withAll(bySubset, 1)));
    EXPECT_EQ(world.count<Position>(), withAll(bySubset, 1).size());
}

// The documented rule: emplacing a viewed type during each() may reallocate its storage, so a
// component must be looked up again after it; the fresh lookup sees the value written before.
TEST(World, LookupAfterEmplacingSameTypeDuringEachSeesWrittenValue) {
    World world;
    const Entity e = world.create();
    world.emplace<Position>(e);
    bool first = true;
    world.view<Position>().each([&](Entity visited, Position& p) {
        if (!first) return;
        first = false;
        p.x = 42.0f;
        for (int i = 0; i < 100; ++i) world.emplace<Position>(world.create());
        const Position* again = world.tryGet<Position>(visited);
        ASSERT_NE(again, nullptr);
        EXPECT_EQ(again->x, 42.0f);
    });
    EXPECT_EQ(world.count<Position>(), 101u);
}

/// A component whose construction can fail.
struct Fragile {
    explicit Fragile(bool fail) {
        if (fail) throw std::runtime_error("construction failed");
    }
};

// A constructor that throws must leave the pool as it was: no owner without a component.
TEST(World, EmplaceThatThrowsLeavesNoComponentBehind) {
    World world;
    const Entity e = world.create();
    EXPECT_THROW(world.emplace<Fragile>(e, true), std::runtime_error);
    EXPECT_FALSE(world.has<Fragile>(e));
    EXPECT_EQ(world.count<Fragile>(), 0u);
}

}  // namespace
}  // namespace shadow
