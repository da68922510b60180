#include "sdf/triangle_bvh.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <utility>

namespace shadow::sdf {

double pointTriangleDistance2(const glm::dvec3& p, const Triangle& t) {
    const glm::dvec3 a(t.a);
    const glm::dvec3 b(t.b);
    const glm::dvec3 c(t.c);
    const glm::dvec3 ab = b - a;
    const glm::dvec3 ac = c - a;
    const glm::dvec3 ap = p - a;
    const double d1 = glm::dot(ab, ap);
    const double d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return glm::dot(ap, ap);  // corner a

    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp);
    const double d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return glm::dot(bp, bp);  // corner b

    const auto distance2To = [&p](const glm::dvec3& q) {
        const glm::dvec3 d = p - q;
        return glm::dot(d, d);
    };
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return distance2To(a + ab * (d1 / (d1 - d3)));  // edge ab

    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp);
    const double d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return glm::dot(cp, cp);  // corner c

    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return distance2To(a + ac * (d2 / (d2 - d6)));  // edge ac

    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        return distance2To(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));  // edge bc
    }
    const double denom = 1.0 / (va + vb + vc);  // the face: va + vb + vc = |ab × ac|² > 0
    return distance2To(a + ab * (vb * denom) + ac * (vc * denom));
}

namespace {

/// Squared distance from `p` to `box` (0 inside).
float boxDistance2(const Aabb& box, const glm::vec3& p) {
    const glm::vec3 d = glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f));
    return glm::dot(d, d);
}

Aabb triangleBounds(const Triangle& t) {
    Aabb box;
    box.extend(t.a);
    box.extend(t.b);
    box.extend(t.c);
    return box;
}

}  // namespace

TriangleBvh::TriangleBvh(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
    assert(!triangles_.empty());
    std::vector<glm::vec3> centroids(triangles_.size());
    std::vector<std::uint32_t> order(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        centroids[i] = (triangles_[i].a + triangles_[i].b + triangles_[i].c) / 3.0f;
        order[i] = static_cast<std::uint32_t>(i);
    }
    nodes_.reserve(2 * (triangles_.size() / kLeafTriangles + 1));
    nodes_.emplace_back();
    build(static_cast<std::uint32_t>(order.size()), centroids, order);
    std::vector<Triangle> sorted(triangles_.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = triangles_[order[i]];
    triangles_ = std::move(sorted);
}

// Median splits keep the tree balanced: its depth is about log2(triangles / kLeafTriangles),
// which bounds the work list here and the search's stack.
void TriangleBvh::build(std::uint32_t count, const std::vector<glm::vec3>& centroids,
                        std::vector<std::uint32_t>& order) {
    struct Task {
        std::uint32_t node, begin, end;
    };
    std::vector<Task> tasks{{0, 0, count}};
    while (!tasks.empty()) {
        const Task t = tasks.back();
        tasks.pop_back();
        Aabb box;
        Aabb centroidBox;
        for (std::uint32_t i = t.begin; i < t.end; ++i) {
            box.extend(triangleBounds(triangles_[order[i]]));
            centroidBox.extend(centroids[order[i]]);
        }
        nodes_[t.node].box = box;
        if (t.end - t.begin <= kLeafTriangles) {
            nodes_[t.node].first = t.begin;
            nodes_[t.node].count = t.end - t.begin;
            continue;
        }
        const glm::vec3 extent = centroidBox.extent();
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const std::uint32_t mid = t.begin + (t.end - t.begin) / 2;
        std::nth_element(order.begin() + t.begin, order.begin() + mid, order.begin() + t.end,
                         [&](std::uint32_t l, std::uint32_t r) { return centroids[l][axis] < centroids[r][axis]; });
        const auto left = static_cast<std::uint32_t>(nodes_.size());
        nodes_[t.node].first = left;
        nodes_[t.node].count = 0;
        nodes_.emplace_back();
        nodes_.emplace_back();
        tasks.push_back({left + 1, mid, t.end});
        tasks.push_back({left, t.begin, mid});
    }
}

TriangleBvh::Nearest TriangleBvh::nearest(const glm::dvec3& p, std::uint32_t hint) const {
    assert(hint < triangles_.size());
    Nearest best{pointTriangleDistance2(p, triangles_[hint]), hint};
    const glm::vec3 fp(p);
    std::array<std::uint32_t, 64> stack{};
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (static_cast<double>(boxDistance2(node.box, fp)) > best.distance2) continue;
        if (node.count > 0) {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                const double d2 = pointTriangleDistance2(p, triangles_[i]);
                if (d2 < best.distance2) best = {d2, i};
            }
            continue;
        }
        // The nearer child goes on top, so that it is searched first and tightens the bound.
        const double left = boxDistance2(nodes_[node.first].box, fp);
        const double right = boxDistance2(nodes_[node.first + 1].box, fp);
        const bool leftFirst = left <= right;
        assert(top + 2 <= stack.size());
        if ((leftFirst ? right : left) <= best.distance2) stack[top++] = leftFirst ? node.first + 1 : node.first;
        if ((leftFirst ? left : right) <= best.distance2) stack[top++] = leftFirst ? node.first : node.first + 1;
    }
    return best;
}

std::size_t TriangleBvh::byteSize() const {
    return nodes_.capacity() * sizeof(Node) + triangles_.capacity() * sizeof(Triangle);
}

}  // namespace shadow::sdf
