// Entities and components.
//
// An `Entity` is a 32-bit handle: 20 bits of slot index and 12 bits of generation. Destroying
// an entity bumps its slot's generation, so every copy of the old handle becomes stale and
// `World::alive` says so. A slot whose generation would wrap is retired, never reused, so a
// stale handle can never alias a new entity.
//
// Components are any movable plain struct; there is no registration. Each component type is
// stored in its own sparse set: a dense array of components packed next to a dense array of
// owners, plus a sparse index from entity slot to dense position. Iteration walks the dense
// arrays; lookup is two array reads.
//
// A `const World` gives views of `const` components only (`view<Ts...>() const` is a
// `View<const Ts...>`): a system that takes the world as `const World&` (the shadow planner, the
// passes that draw) reads it and cannot change it.
//
// Rules during `view<...>().each(f)`:
//   - `f` may read and write the components it receives;
//   - `f` may remove components from, or destroy, the entity it is visiting;
//   - `f` may create entities and emplace components on any entity; such new elements are not
//     visited by the running iteration. Emplacing a component of type T may reallocate T's
//     storage: references to T components that `f` holds are invalid afterwards;
//   - `f` must not remove components of the viewed types from *other* entities (iteration
//     then skips or revisits elements; it does not crash).
// Iteration runs over the dense array of the smallest viewed pool from back to front, which is
// what makes removing the visited element safe (swap-and-pop only moves already-visited ones).
//
// What this does not do: no groups or sorting, no signals, no multithreaded mutation.
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace shadow {

/// A generational entity handle. The default value is the null entity.
class Entity {
public:
    static constexpr std::uint32_t kIndexBits = 20;
    static constexpr std::uint32_t kGenerationBits = 12;
    static constexpr std::uint32_t kIndexMask = (1u << kIndexBits) - 1u;
    static constexpr std::uint32_t kMaxGeneration = (1u << kGenerationBits) - 1u;
    /// Largest number of live entity slots.
    static constexpr std::uint32_t kMaxEntities = kIndexMask;  // the last index is the null slot

    constexpr Entity() = default;
    constexpr Entity(std::uint32_t index, std::uint32_t generation)
        : bits_((generation << kIndexBits) | (index & kIndexMask)) {}

    /// The null entity: never alive.
    static constexpr Entity null() { return Entity(); }

    [[nodiscard]] constexpr std::uint32_t index() const { return bits_ & kIndexMask; }
    [[nodiscard]] constexpr std::uint32_t generation() const { return bits_ >> kIndexBits; }
    [[nodiscard]] constexpr std::uint32_t bits() const { return bits_; }
    [[nodiscard]] constexpr bool isNull() const { return bits_ == kNullBits; }

    friend constexpr bool operator==(Entity a, Entity b) { return a.bits_ == b.bits_; }
    friend constexpr bool operator!=(Entity a, Entity b) { return a.bits_ != b.bits_; }
    friend constexpr bool operator<(Entity a, Entity b) { return a.bits_ < b.bits_; }

private:
    static constexpr std::uint32_t kNullBits = kIndexMask;  // index all ones, generation 0
    std::uint32_t bits_ = kNullBits;
};

namespace detail {

/// Type-erased part of a component pool, so `World::destroy` can strip every component.
class PoolBase {
public:
    virtual ~PoolBase() = default;
    [[nodiscard]] virtual bool contains(Entity e) const = 0;
    virtual bool remove(Entity e) = 0;
    [[nodiscard]] virtual std::size_t size() const = 0;
};

inline std::size_t nextComponentId() {
    static std::size_t counter = 0;
    return counter++;
}

/// A dense id per component type, assigned on first use.
template <typename T>
std::size_t componentId() {
    static const std::size_t id = nextComponentId();
    return id;
}

/// Sparse set of `T` components.
template <typename T>
class Pool final : public PoolBase {
public:
    static constexpr std::uint32_t kAbsent = 0xffffffffu;

    [[nodiscard]] bool contains(Entity e) const override {
        const std::uint32_t i = e.index();
        return i < sparse_.size() && sparse_[i] != kAbsent && owners_[sparse_[i]] == e;
    }

    template <typename... Args>
    T& emplace(Entity e, Args&&... args) {
        assert(!contains(e));
        const std::uint32_t i = e.index();
        if (i >= sparse_.size()) sparse_.resize(i + 1, kAbsent);
        // Build the component first: if its constructor throws, nothing is recorded.
        if constexpr (std::is_aggregate_v<T>) {
            components_.push_back(T{std::forward<Args>(args)...});
        } else {
            components_.emplace_back(std::forward<Args>(args)...);
        }
#if defined(__cpp_exceptions)
        try {
            owners_.push_back(e);
        } catch (...) {
            components_.pop_back();
            throw;
        }
#else
        owners_.push_back(e);  // a game built without exceptions: a failed allocation aborts
#endif
        sparse_[i] = static_cast<std::uint32_t>(owners_.size() - 1);
        return components_.back();
    }

    bool remove(Entity e) override {
        if (!contains(e)) return false;
        const std::uint32_t slot = sparse_[e.index()];
        const std::uint32_t last = static_cast<std::uint32_t>(owners_.size() - 1);
        if (slot != last) {
            components_[slot] = std::move(components_[last]);
            owners_[slot] = owners_[last];
            sparse_[owners_[slot].index()] = slot;
        }
        components_.pop_back();
        owners_.pop_back();
        sparse_[e.index()] = kAbsent;
        return true;
    }

    [[nodiscard]] std::size_t size() const override { return owners_.size(); }

    T* find(Entity e) { return contains(e) ? &components_[sparse_[e.index()]] : nullptr; }
    const T* find(Entity e) const { return contains(e) ? &components_[sparse_[e.index()]] : nullptr; }

    /// The component of `e`, which the caller has checked `contains`.
    T& get(Entity e) { return components_[sparse_[e.index()]]; }
    const T& get(Entity e) const { return components_[sparse_[e.index()]]; }

    [[nodiscard]] Entity ownerAt(std::size_t dense) const { return owners_[dense]; }
    T& atDense(std::size_t dense) { return components_[dense]; }

private:
    std::vector<std::uint32_t> sparse_;
    std::vector<Entity> owners_;
    std::vector<T> components_;
};

/// The pool of component type `T`, const when `T` is (a view of a const world).
template <typename T>
using PoolOf = std::conditional_t<std::is_const_v<T>, const Pool<std::remove_const_t<T>>, Pool<T>>;

}  // namespace detail

class World;

/// Entities that own every component in `Ts...`. Cheap to make; holds pointers into the world.
/// A `const` type in `Ts` is visited as a const reference (the view of a const world has only
/// those).
template <typename... Ts>
class View {
public:
    /// Calls `f(Entity, Ts&...)` for every entity owning all of `Ts`. See the iteration rules
    /// at the top of this header.
    template <typename F>
    void each(F&& f) {
        if (!allPresent()) return;
        std::size_t smallest = 0;
        for (std::size_t k = 1; k < sizeof...(Ts); ++k) {
            if (pools_[k]->size() < pools_[smallest]->size()) smallest = k;
        }
        visit(f, smallest, std::index_sequence_for<Ts...>{});
    }

    /// Number of entities visited by `each` (walks the smallest pool).
    [[nodiscard]] std::size_t count() {
        std::size_t n = 0;
        each([&n](Entity, Ts&...) { ++n; });
        return n;
    }

private:
    friend class World;
    explicit View(std::tuple<detail::PoolOf<Ts>*...> pools)
        : typed_(pools), pools_{static_cast<const detail::PoolBase*>(std::get<detail::PoolOf<Ts>*>(pools))...} {}

    [[nodiscard]] bool allPresent() const {
        for (const detail::PoolBase* p : pools_) {
            if (p == nullptr) return false;
        }
        return true;
    }

    template <typename F, std::size_t... I>
    void visit(F& f, std::size_t driver, std::index_sequence<I...>) {
        const detail::PoolBase* drive = pools_[driver];
        for (std::size_t i = drive->size(); i-- > 0;) {
            // The pool may have shrunk by more than one if `f` broke the rules; clamp.
            if (i >= drive->size()) continue;
            const Entity e = ownerOf(driver, i, std::index_sequence<I...>{});
            if ((std::get<I>(typed_)->contains(e) && ...)) {
                f(e, std::get<I>(typed_)->get(e)...);
            }
        }
    }

    template <std::size_t... I>
    Entity ownerOf(std::size_t which, std::size_t dense, std::index_sequence<I...>) const {
        Entity e;
        ((which == I ? (e = std::get<I>(typed_)->ownerAt(dense), 0) : 0), ...);
        return e;
    }

    std::tuple<detail::PoolOf<Ts>*...> typed_;
    const detail::PoolBase* pools_[sizeof...(Ts)];
};

/// Owns entities and their components.
class World {
public:
    World() = default;
    World(const World&) = delete;
    World& operator=(const World&) = delete;
    World(World&&) noexcept = default;
    World& operator=(World&&) noexcept = default;

    /// Makes a new live entity. Asserts when `Entity::kMaxEntities` slots are exhausted.
    [[nodiscard]] Entity create() {
        if (!freeSlots_.empty()) {
            const std::uint32_t index = freeSlots_.back();
            freeSlots_.pop_back();
            return Entity(index, generations_[index]);
        }
        assert(generations_.size() < Entity::kMaxEntities);
        generations_.push_back(0);
        return Entity(static_cast<std::uint32_t>(generations_.size() - 1), 0);
    }

    /// Removes every component of `e` and makes every handle to it stale. No-op if stale.
    void destroy(Entity e) {
        if (!alive(e)) return;
        for (auto& pool : pools_) {
            if (pool) pool->remove(e);
        }
        const std::uint32_t index = e.index();
        if (generations_[index] < Entity::kMaxGeneration) {
            ++generations_[index];
            freeSlots_.push_back(index);
        } else {
            generations_[index] = kRetired;  // never handed out again
            ++retiredCount_;
        }
    }

    /// True while `e` has not been destroyed.
    [[nodiscard]] bool alive(Entity e) const {
        return !e.isNull() && e.index() < generations_.size() && generations_[e.index()] == e.generation();
    }

    /// Number of live entities.
    [[nodiscard]] std::size_t size() const { return generations_.size() - freeSlots_.size() - retiredCount_; }

    /// Adds a `T` to a live entity that has none; returns it.
    template <typename T, typename... Args>
    T& emplace(Entity e, Args&&... args) {
        assert(alive(e));
        return pool<T>().emplace(e, std::forward<Args>(args)...);
    }

    /// Adds or replaces the `T` of a live entity.
    template <typename T>
    T& emplaceOrReplace(Entity e, T value) {
        if (T* existing = tryGet<T>(e)) {
            *existing = std::move(value);
            return *existing;
        }
        return emplace<T>(e, std::move(value));
    }

    /// Removes the `T` of `e`; returns whether there was one.
    template <typename T>
    bool remove(Entity e) {
        auto* p = findPool<T>();
        return p != nullptr && p->remove(e);
    }

    /// Whether `e` is alive and owns every component in `Ts`.
    template <typename... Ts>
    [[nodiscard]] bool has(Entity e) const {
        return alive(e) && (hasOne<Ts>(e) && ...);
    }

    /// The `T` of `e`; asserts that it exists.
    template <typename T>
    [[nodiscard]] T& get(Entity e) {
        T* c = tryGet<T>(e);
        if (c == nullptr) missingComponent();
        return *c;
    }
    template <typename T>
    [[nodiscard]] const T& get(Entity e) const {
        const T* c = tryGet<T>(e);
        if (c == nullptr) missingComponent();
        return *c;
    }

    /// The `T` of `e`, or null when `e` is stale or has none.
    template <typename T>
    [[nodiscard]] T* tryGet(Entity e) {
        auto* p = findPool<T>();
        return (p != nullptr && alive(e)) ? p->find(e) : nullptr;
    }
    template <typename T>
    [[nodiscard]] const T* tryGet(Entity e) const {
        const auto* p = findPool<T>();
        return (p != nullptr && alive(e)) ? p->find(e) : nullptr;
    }

    /// Entities owning every component in `Ts` (a `const` one visited as a const reference).
    template <typename... Ts>
    [[nodiscard]] View<Ts...> view() {
        static_assert(sizeof...(Ts) > 0);
        return View<Ts...>(std::make_tuple(static_cast<detail::PoolOf<Ts>*>(findPool<std::remove_const_t<Ts>>())...));
    }
    /// The same in a const world: every component visited as a const reference.
    template <typename... Ts>
    [[nodiscard]] View<const Ts...> view() const {
        static_assert(sizeof...(Ts) > 0);
        return View<const Ts...>(std::make_tuple(findPool<std::remove_const_t<Ts>>()...));
    }

    /// Number of `T` components in the world.
    template <typename T>
    [[nodiscard]] std::size_t count() const {
        const auto* p = findPool<T>();
        return p == nullptr ? 0 : p->size();
    }

private:
    static constexpr std::uint32_t kRetired = 0xffffffffu;

    /// `get` of a component the entity lacks: a broken invariant of the caller.
    [[noreturn]] static void missingComponent() {
        assert(!"World::get: the entity has no such component");
        std::abort();
    }

    template <typename T>
    [[nodiscard]] bool hasOne(Entity e) const {
        const auto* p = findPool<T>();
        return p != nullptr && p->contains(e);
    }

    template <typename T>
    detail::Pool<T>* findPool() {
        const std::size_t id = detail::componentId<T>();
        return id < pools_.size() ? static_cast<detail::Pool<T>*>(pools_[id].get()) : nullptr;
    }
    template <typename T>
    const detail::Pool<T>* findPool() const {
        const std::size_t id = detail::componentId<T>();
        return id < pools_.size() ? static_cast<const detail::Pool<T>*>(pools_[id].get()) : nullptr;
    }

    template <typename T>
    detail::Pool<T>& pool() {
        const std::size_t id = detail::componentId<T>();
        if (id >= pools_.size()) pools_.resize(id + 1);
        if (!pools_[id]) pools_[id] = std::make_unique<detail::Pool<T>>();
        return *static_cast<detail::Pool<T>*>(pools_[id].get());
    }

    std::vector<std::uint32_t> generations_;
    std::vector<std::uint32_t> freeSlots_;
    std::size_t retiredCount_ = 0;
    std::vector<std::unique_ptr<detail::PoolBase>> pools_;
};

}  // namespace shadow
