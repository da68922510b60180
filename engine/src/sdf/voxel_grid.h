// The voxel lattice of a field being baked, in double: where each voxel centre is, and the
// grid coordinates in which centre (i, j, k) sits at (i, j, k). Private to src/sdf.
#pragma once

#include <shadow/math.h>

#include <cstddef>

namespace shadow::sdf {

struct VoxelGrid {
    glm::ivec3 size{0};
    glm::dvec3 origin{0.0};  ///< min corner of the box (the corner of voxel 0, not its centre)
    double voxelSize = 0.0;

    [[nodiscard]] std::size_t count() const {
        return static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z);
    }
    /// Index of voxel (x, y, z), x fastest (the order of `DistanceField::distances`).
    [[nodiscard]] std::size_t index(int x, int y, int z) const {
        return static_cast<std::size_t>(x) +
               static_cast<std::size_t>(size.x) *
                   (static_cast<std::size_t>(y) + static_cast<std::size_t>(size.y) * static_cast<std::size_t>(z));
    }
    /// Distance in `index` between a voxel and its neighbour one step up axis `axis`.
    [[nodiscard]] std::size_t stride(int axis) const {
        return axis == 0 ? 1
                         : (axis == 1 ? static_cast<std::size_t>(size.x) : static_cast<std::size_t>(size.x) * size.y);
    }
    [[nodiscard]] glm::dvec3 centre(int x, int y, int z) const {
        return origin + (glm::dvec3(x, y, z) + 0.5) * voxelSize;
    }
    [[nodiscard]] glm::dvec3 toGrid(const glm::dvec3& p) const { return (p - origin) / voxelSize - 0.5; }
};

}  // namespace shadow::sdf
