// Closest-triangle distance queries over a triangle soup: a bounding-volume hierarchy searched
// nearest box first and pruned by the best distance found so far. Private to src/sdf.
#pragma once

#include <shadow/math.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace shadow::sdf {

/// One triangle by its corners (mesh-local).
struct Triangle {
    glm::vec3 a{0.0f};
    glm::vec3 b{0.0f};
    glm::vec3 c{0.0f};
};

/// Squared distance from `p` to the closest point of triangle `t` (Ericson, Real-Time Collision
/// Detection, 5.1.5: the Voronoi region of `p` among the corners, edges and face), in double.
/// `t` must have an area (its cross product is not zero).
[[nodiscard]] double pointTriangleDistance2(const glm::dvec3& p, const Triangle& t);

/// A BVH over triangles with an area, answering "how far is the nearest triangle".
class TriangleBvh {
public:
    /// Builds the hierarchy (median splits on the longest axis of the centroids, up to
    /// `kLeafTriangles` per leaf). `triangles` must not be empty.
    explicit TriangleBvh(std::vector<Triangle> triangles);

    /// The nearest triangle to a point and its squared distance.
    struct Nearest {
        double distance2 = 0.0;
        std::uint32_t triangle = 0;  ///< index in the hierarchy's own order, for `hint`
    };

    /// The triangle nearest to `p`. `hint` is any triangle index (the hierarchy's order): the
    /// search starts with the distance to it as its bound, so the nearest triangle of a nearby
    /// point (the previous voxel's) prunes almost all of the hierarchy at once.
    [[nodiscard]] Nearest nearest(const glm::dvec3& p, std::uint32_t hint) const;

    [[nodiscard]] std::size_t triangleCount() const { return triangles_.size(); }
    /// Bytes the hierarchy holds (nodes and triangles), for the bake's memory report.
    [[nodiscard]] std::size_t byteSize() const;

    static constexpr std::uint32_t kLeafTriangles = 4;

private:
    /// A leaf holds triangles [first, first + count); an inner node (count 0) has its children
    /// at nodes `first` and `first + 1`.
    struct Node {
        Aabb box;
        std::uint32_t first = 0;
        std::uint32_t count = 0;
    };

    /// Fills `nodes_` over the triangles `order[0, count)`, reordering it (a work list, not recursion).
    void build(std::uint32_t count, const std::vector<glm::vec3>& centroids, std::vector<std::uint32_t>& order);
    std::vector<Node> nodes_;
    std::vector<Triangle> triangles_;
};

}  // namespace shadow::sdf
