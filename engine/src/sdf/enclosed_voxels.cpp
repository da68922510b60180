// Crossings are found per triangle and axis the way a scanline voxeliser finds them: each
// lattice line through voxel centres along the axis that pierces the triangle's projection
// meets the triangle at one point, and blocks the step between the two centres around it.
// A flood fill from the boundary over unblocked steps then leaves the enclosed voxels.
#include "sdf/enclosed_voxels.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace shadow::sdf {
namespace {

/// For each axis, one byte per voxel: 1 where the step from that voxel to its neighbour one up
/// the axis crosses a triangle.
using Crossings = std::array<std::vector<std::uint8_t>, 3>;

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

/// Marks the steps along `axis` that triangle `g` (corners in grid coordinates) crosses.
void markCrossings(const std::array<glm::dvec3, 3>& g, const VoxelGrid& grid, int axis,
                   std::vector<std::uint8_t>& blocked) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    // With (axis, u, v) cyclic, the normal's axis component is the projection's doubled area.
    const glm::dvec3 normal = glm::cross(g[1] - g[0], g[2] - g[0]);
    if (normal[axis] == 0.0) return;  // parallel to the lines: the other two axes' steps see it
    const double orientation = normal[axis] > 0.0 ? 1.0 : -1.0;
    std::array<glm::dvec2, 3> p{};
    for (int i = 0; i < 3; ++i) p[i] = glm::dvec2(g[i][u], g[i][v]);
    std::array<double, 3> edgeLength{};
    for (int i = 0; i < 3; ++i) edgeLength[i] = glm::length(p[(i + 1) % 3] - p[i]);

    const double tol = kCrossingTolerance;
    const glm::dvec2 lo = glm::min(glm::min(p[0], p[1]), p[2]) - tol;
    const glm::dvec2 hi = glm::max(glm::max(p[0], p[1]), p[2]) + tol;
    const double axisMin = std::min({g[0][axis], g[1][axis], g[2][axis]});
    const double axisMax = std::max({g[0][axis], g[1][axis], g[2][axis]});
    const int jBegin = std::max(0, static_cast<int>(std::ceil(lo.x)));
    const int jEnd = std::min(grid.size[u] - 1, static_cast<int>(std::floor(hi.x)));
    const int kBegin = std::max(0, static_cast<int>(std::ceil(lo.y)));
    const int kEnd = std::min(grid.size[v] - 1, static_cast<int>(std::floor(hi.y)));
    for (int k = kBegin; k <= kEnd; ++k) {
        for (int j = jBegin; j <= jEnd; ++j) {
            const glm::dvec2 q(j, k);
            bool inside = true;
            for (int i = 0; i < 3 && inside; ++i) {
                // Signed distance of q from edge i's line, positive on the triangle's side.
                inside = orientation * cross2(p[(i + 1) % 3] - p[i], q - p[i]) >= -tol * edgeLength[i];
            }
            if (!inside) continue;
            const double t =
                std::clamp(g[0][axis] - (normal[u] * (q.x - p[0].x) + normal[v] * (q.y - p[0].y)) / normal[axis],
                           axisMin, axisMax);
            // The steps [i, i + 1] that [t - tol, t + tol] touches.
            const int first = std::max(0, static_cast<int>(std::ceil(t - tol)) - 1);
            const int last = std::min(grid.size[axis] - 2, static_cast<int>(std::floor(t + tol)));
            glm::ivec3 voxel(0);
            voxel[u] = j;
            voxel[v] = k;
            for (int i = first; i <= last; ++i) {
                voxel[axis] = i;
                blocked[grid.index(voxel.x, voxel.y, voxel.z)] = 1;
            }
        }
    }
}

Crossings findCrossings(const std::vector<Triangle>& triangles, const VoxelGrid& grid) {
    Crossings crossings;
    for (auto& blocked : crossings) blocked.assign(grid.count(), 0);
    for (const Triangle& t : triangles) {
        const std::array<glm::dvec3, 3> g = {grid.toGrid(glm::dvec3(t.a)), grid.toGrid(glm::dvec3(t.b)),
                                             grid.toGrid(glm::dvec3(t.c))};
        for (int axis = 0; axis < 3; ++axis) markCrossings(g, grid, axis, crossings[axis]);
    }
    return crossings;
}

bool onBoundary(const VoxelGrid& grid, int x, int y, int z) {
    return x == 0 || y == 0 || z == 0 || x == grid.size.x - 1 || y == grid.size.y - 1 || z == grid.size.z - 1;
}

}  // namespace

std::vector<std::uint8_t> enclosedVoxels(const std::vector<Triangle>& triangles, const VoxelGrid& grid) {
    const Crossings crossings = findCrossings(triangles, grid);
    std::vector<std::uint8_t> enclosed(grid.count(), 1);
    std::vector<std::size_t> open;  // reached, neighbours not yet visited
    for (int z = 0; z < grid.size.z; ++z) {
        for (int y = 0; y < grid.size.y; ++y) {
            for (int x = 0; x < grid.size.x; ++x) {
                if (!onBoundary(grid, x, y, z)) continue;
                enclosed[grid.index(x, y, z)] = 0;
                open.push_back(grid.index(x, y, z));
            }
        }
    }
    const std::array<std::size_t, 3> stride = {grid.stride(0), grid.stride(1), grid.stride(2)};
    while (!open.empty()) {
        const std::size_t at = open.back();
        open.pop_back();
        const glm::ivec3 voxel(static_cast<int>(at % grid.size.x), static_cast<int>(at / grid.size.x % grid.size.y),
                               static_cast<int>(at / stride[2]));
        const auto visit = [&](std::size_t next) {
            if (enclosed[next] == 0) return;
            enclosed[next] = 0;
            open.push_back(next);
        };
        for (int axis = 0; axis < 3; ++axis) {
            if (voxel[axis] + 1 < grid.size[axis] && crossings[axis][at] == 0) visit(at + stride[axis]);
            if (voxel[axis] > 0 && crossings[axis][at - stride[axis]] == 0) visit(at - stride[axis]);
        }
    }
    return enclosed;
}

}  // namespace shadow::sdf
