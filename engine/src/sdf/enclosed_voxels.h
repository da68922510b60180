// The sign of a baked field: which voxels no path from the grid's boundary reaches without
// crossing a triangle (the rule of distance_field.h). Private to src/sdf.
#pragma once

#include "sdf/triangle_bvh.h"
#include "sdf/voxel_grid.h"

#include <cstdint>
#include <vector>

namespace shadow::sdf {

/// Fraction of a voxel by which each triangle is widened when deciding whether a step between
/// neighbouring centres crosses it: a step through a shared edge or corner, or through a seam
/// narrower than this, counts as crossing. Errs toward "enclosed", never lets a path leak
/// between two triangles that meet.
inline constexpr double kCrossingTolerance = 1e-3;

/// One byte per voxel of `grid` (x fastest): 1 where the voxel is enclosed (inside), 0 where a
/// path of steps between neighbouring centres joins it to a boundary voxel without crossing one
/// of `triangles`. Boundary voxels are always outside: `grid` must hold the triangles at least
/// one voxel away from its faces.
[[nodiscard]] std::vector<std::uint8_t> enclosedVoxels(const std::vector<Triangle>& triangles, const VoxelGrid& grid);

}  // namespace shadow::sdf
