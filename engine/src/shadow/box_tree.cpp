#include "shadow/box_tree.h"

#include <algorithm>
#include <numeric>

namespace shadow {

void BoxTree::build(std::span<const BoundedEntity> items) {
    nodes_.clear();
    items_.resize(items.size());
    boxes_.resize(items.size());
    std::iota(items_.begin(), items_.end(), std::uint32_t{0});
    if (!items.empty()) {
        // A binary tree over n items with leaves of at least one item has fewer than 2n nodes.
        nodes_.reserve(2 * items.size());
        nodes_.push_back({DAabb{}, 0, static_cast<std::uint32_t>(items.size())});
        // Each split appends its children: the walk reaches them in turn, level by level.
        for (std::uint32_t node = 0; node < nodes_.size(); ++node) split(items, node);
    }
    for (std::size_t k = 0; k < items_.size(); ++k) boxes_[k] = items[items_[k]].bounds;
    fitBounds();
    builtLooseness_ = looseness();
}

void BoxTree::refit(std::span<const BoundedEntity> items) {
    if (items.size() != items_.size()) {
        build(items);
        return;
    }
    for (std::size_t k = 0; k < items_.size(); ++k) boxes_[k] = items[items_[k]].bounds;
    fitBounds();
    if (looseness() > 2.0 * builtLooseness_) build(items);
}

void BoxTree::clear() {
    nodes_.clear();
    items_.clear();
    boxes_.clear();
    builtLooseness_ = 0.0;
}

/// Splits the items of leaf `node`, when it holds more than `kLeafItems`, at the median of their
/// centres along the axis the centres spread widest, into two leaves appended to the tree.
void BoxTree::split(std::span<const BoundedEntity> items, std::uint32_t node) {
    const std::uint32_t first = nodes_[node].first;
    const std::uint32_t count = nodes_[node].count;
    if (count <= kLeafItems) return;
    DAabb centres;
    for (std::uint32_t k = first; k < first + count; ++k) centres.extend(items[items_[k]].bounds.center());
    const glm::dvec3 spread = centres.extent();
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    const std::uint32_t half = count / 2;
    const auto begin = items_.begin() + first;
    std::nth_element(begin, begin + half, begin + count, [&](std::uint32_t a, std::uint32_t b) {
        return items[a].bounds.center()[axis] < items[b].bounds.center()[axis];
    });
    const auto child = static_cast<std::uint32_t>(nodes_.size());
    nodes_[node].first = child;
    nodes_[node].count = 0;
    nodes_.push_back({DAabb{}, first, half});
    nodes_.push_back({DAabb{}, first + half, count - half});
}

/// Every node's bounds from its items' or its children's, children (stored after) first.
void BoxTree::fitBounds() {
    for (std::size_t n = nodes_.size(); n-- > 0;) {
        Node& node = nodes_[n];
        DAabb bounds;
        if (node.count == 0) {
            bounds = nodes_[node.first].bounds;
            bounds.extend(nodes_[node.first + 1].bounds);
        } else {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k) bounds.extend(boxes_[k]);
        }
        node.bounds = bounds;
    }
}

/// The sum of the nodes' surface areas: what a query pays for, roughly, when it walks the tree.
double BoxTree::looseness() const {
    double sum = 0.0;
    for (const Node& node : nodes_) {
        const glm::dvec3 e = node.bounds.extent();
        sum += e.x * e.y + e.y * e.z + e.z * e.x;
    }
    return sum;
}

}  // namespace shadow
