// A bounding-volume hierarchy over world boxes, shared by every light of a frame: the casters
// (each light's frusta then touch only the casters near them), and the boxes of the casters
// that changed since the last frame (each light then asks whether any of them reaches it).
#pragma once

#include <shadow/ecs.h>
#include <shadow/math.h>

#include <array>
#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

namespace shadow {

/// A caster or receiver instance with its world bounds.
struct BoundedEntity {
    Entity entity;
    DAabb bounds;
    /// (A game's caster) it says its geometry changed this frame: the layers holding it are
    /// redrawn even if its bounds stayed.
    bool moved = false;
    /// Its transform's `WorldTransform::version`: a caster whose version differs from the one a
    /// layer was drawn or a list was gathered with moved since, even within its bounds.
    std::uint64_t version = 0;
};

/// A bounding-volume hierarchy over a list of boxes (`BoundedEntity::bounds`), built once
/// (median splits of the centres along the widest axis, a few items a leaf) and refitted while
/// the boxes move. Allocation-free once its storage has grown to the list.
///
/// A query takes one test of a box and applies it to the nodes and the items alike: a node the
/// test rejects is skipped with everything in it. The test must therefore be monotone, rejecting
/// every box inside a box it rejects; "wholly outside one plane" (`Frustum::intersects`) and "wholly
/// beside an interval along one direction" are, in floating point too (each term of a dot product
/// grows with the box, and rounding keeps the order). A query then visits exactly the items a walk
/// over the whole list with the same test would visit, in no particular order.
class BoxTree {
public:
    /// Builds the tree over `items` (their order is what queries report), reusing its storage.
    void build(std::span<const BoundedEntity> items);
    /// Takes the bounds of `items`, the same list as at the last `build` with boxes that moved;
    /// rebuilds instead when the moves have made the tree much looser than a fresh one (the sum
    /// of its nodes' surface areas over twice the built tree's).
    void refit(std::span<const BoundedEntity> items);
    /// Empties the tree, keeping its storage.
    void clear();
    /// The number of items it was built over.
    [[nodiscard]] std::size_t size() const { return items_.size(); }

    /// Calls `visit(i)` for the index i of every item whose box `meets` accepts.
    template <typename Meets, typename Visit>
    void forEach(const Meets& meets, const Visit& visit) const {
        (void)forEachWhile(meets, [&](std::uint32_t i) {
            visit(i);
            return true;
        });
    }
    /// Whether `meets` accepts the box of some item (stops at the first).
    template <typename Meets>
    [[nodiscard]] bool any(const Meets& meets) const {
        return !forEachWhile(meets, [](std::uint32_t) { return false; });
    }
    /// `forEach` while `visit` returns true; false when it stopped the walk.
    template <typename Meets, typename Visit>
    bool forEachWhile(const Meets& meets, const Visit& visit) const {
        if (nodes_.empty()) return true;
        std::array<std::uint32_t, kMaxDepth + 1> stack{};
        std::size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!meets(node.bounds)) continue;
            if (node.count == 0) {
                assert(top + 2 <= stack.size());
                stack[top++] = node.first + 1;
                stack[top++] = node.first;
                continue;
            }
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                if (meets(boxes_[k]) && !visit(items_[k])) return false;
            }
        }
        return true;
    }

private:
    /// A leaf (`count` > 0) holds items [first, first + count) of `items_`; an inner node's
    /// children are nodes `first` and `first` + 1, stored after it (so a backward pass refits).
    struct Node {
        DAabb bounds;
        std::uint32_t first = 0;
        std::uint32_t count = 0;
    };
    static constexpr std::uint32_t kLeafItems = 4;
    /// Median splits halve the items at every level: 64 levels hold any list that fits in memory.
    static constexpr std::size_t kMaxDepth = 64;

    void split(std::span<const BoundedEntity> items, std::uint32_t node);
    void fitBounds();
    [[nodiscard]] double looseness() const;

    std::vector<Node> nodes_;           ///< the root first
    std::vector<std::uint32_t> items_;  ///< indices into the list built over, leaf by leaf
    std::vector<DAabb> boxes_;          ///< the items' boxes in the same order (leaf tests read them in a row)
    double builtLooseness_ = 0.0;       ///< `looseness()` when last built
};

}  // namespace shadow
