// The bake (validate the mesh, lay out the grid, sign by flood fill, exact distances by BVH
// queries over z-slices on worker threads) and the trilinear sampler.
#include <shadow/components.h>
#include <shadow/distance_field.h>

#include "sdf/enclosed_voxels.h"
#include "sdf/triangle_bvh.h"
#include "sdf/voxel_grid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <system_error>
#include <thread>

namespace shadow {
namespace {

using sdf::Triangle;
using sdf::TriangleBvh;
using sdf::VoxelGrid;

constexpr int kMaxPaddingVoxels = 4;
constexpr int kMaxThreads = 256;

Status checkSettings(const DistanceFieldSettings& s) {
    if (s.voxelBudget < kMinDistanceFieldVoxels || s.voxelBudget > kMaxDistanceFieldVoxels) {
        return Error{ErrorCode::InvalidArgument,
                     "voxelBudget " + std::to_string(s.voxelBudget) + " is outside [" +
                         std::to_string(kMinDistanceFieldVoxels) + ", " + std::to_string(kMaxDistanceFieldVoxels) + "]",
                     "voxelBudget"};
    }
    if (s.paddingVoxels < 1 || s.paddingVoxels > kMaxPaddingVoxels) {
        return Error{ErrorCode::InvalidArgument,
                     "paddingVoxels " + std::to_string(s.paddingVoxels) + " is outside [1, 4]", "paddingVoxels"};
    }
    if (s.threads < 0 || s.threads > kMaxThreads) {
        return Error{ErrorCode::InvalidArgument, "threads " + std::to_string(s.threads) + " is outside [0, 256]",
                     "threads"};
    }
    return Ok{};
}

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

/// The mesh's triangles with an area, or the first thing wrong with the mesh.
Result<std::vector<Triangle>> collectTriangles(const MeshData& mesh) {
    const std::string label = (mesh.name.empty() ? std::string("mesh") : mesh.name) + ": ";
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const std::string element = "positions[" + std::to_string(i) + "]";
        if (!finite(mesh.positions[i]))
            return Error{ErrorCode::InvalidValue, label + element + " is not finite", element};
        if (!insideWorld(glm::dvec3(mesh.positions[i]))) {
            return Error{ErrorCode::LimitExceeded, label + element + " lies beyond ±1e9", element};
        }
    }
    if (mesh.indices.empty()) return Error{ErrorCode::InvalidValue, label + "no triangles", "indices"};
    if (mesh.indices.size() % 3 != 0) {
        return Error{ErrorCode::InvalidValue,
                     label + std::to_string(mesh.indices.size()) + " indices are not a whole number of triangles",
                     "indices"};
    }
    std::vector<Triangle> triangles;
    triangles.reserve(mesh.indices.size() / 3);
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
        for (std::size_t k = i; k < i + 3; ++k) {
            if (mesh.indices[k] >= mesh.positions.size()) {
                const std::string element = "indices[" + std::to_string(k) + "]";
                return Error{ErrorCode::InvalidValue,
                             label + element + " = " + std::to_string(mesh.indices[k]) + " is not below the " +
                                 std::to_string(mesh.positions.size()) + " positions",
                             element};
            }
        }
        const Triangle t{mesh.positions[mesh.indices[i]], mesh.positions[mesh.indices[i + 1]],
                         mesh.positions[mesh.indices[i + 2]]};
        const glm::dvec3 n = glm::cross(glm::dvec3(t.b) - glm::dvec3(t.a), glm::dvec3(t.c) - glm::dvec3(t.a));
        if (glm::dot(n, n) > 0.0) triangles.push_back(t);
    }
    if (triangles.empty()) {
        return Error{ErrorCode::InvalidValue, label + "no triangle has an area (all are degenerate)", "indices"};
    }
    return triangles;
}

Aabb boundsOf(const std::vector<Triangle>& triangles) {
    Aabb box;
    for (const Triangle& t : triangles) {
        box.extend(t.a);
        box.extend(t.b);
        box.extend(t.c);
    }
    return box;
}

/// Voxels per axis for cubic voxels of edge `h` over `extent`, padded.
glm::ivec3 voxelsFor(const glm::dvec3& extent, double h, int padding) {
    glm::ivec3 n;
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / h))) + 2 * padding;
    return n;
}

std::int64_t product(const glm::ivec3& n) { return std::int64_t{n.x} * n.y * n.z; }

/// The smallest voxel (a float, as stored) whose padded grid over `bounds` fits the budget, and
/// the field's box: centred on `bounds`, `size·voxelSize` wide.
DistanceField layOut(const Aabb& bounds, const DistanceFieldSettings& settings) {
    const glm::dvec3 extent = glm::dvec3(bounds.max) - glm::dvec3(bounds.min);
    const double longest = std::max({extent.x, extent.y, extent.z});
    const auto fits = [&](double h) {
        return product(voxelsFor(extent, h, settings.paddingVoxels)) <= settings.voxelBudget;
    };
    // fits(longest): (1 + 2·padding)³ <= 9³ < kMinDistanceFieldVoxels; !fits(lo): the longest
    // axis alone takes the budget.
    double lo = longest / settings.voxelBudget;
    double hi = longest;
    for (int i = 0; i < 64; ++i) {
        const double mid = 0.5 * (lo + hi);
        (fits(mid) ? hi : lo) = mid;
    }
    float h = static_cast<float>(hi);
    while (!fits(h)) h = std::nextafter(h, std::numeric_limits<float>::max());  // float rounded down

    DistanceField field;
    field.voxelSize = h;
    field.size = voxelsFor(extent, h, settings.paddingVoxels);
    const glm::dvec3 centre = 0.5 * (glm::dvec3(bounds.min) + glm::dvec3(bounds.max));
    field.box.min = glm::vec3(centre - 0.5 * glm::dvec3(field.size) * static_cast<double>(h));
    field.box.max = field.box.min + glm::vec3(field.size) * h;
    return field;
}

VoxelGrid gridOf(const DistanceField& field) {
    return VoxelGrid{field.size, glm::dvec3(field.box.min), static_cast<double>(field.voxelSize)};
}

/// `d` as a float no larger than `d`, so that rounding never makes a distance overestimate.
float roundedDown(double d) {
    const float f = static_cast<float>(d);
    return static_cast<double>(f) > d ? std::nextafter(f, 0.0f) : f;
}

/// Exact unsigned distances of slice `z`. Each query starts from the nearest triangle of the
/// voxel before it, whose distance is at most one voxel more than the answer (the distance is
/// 1-Lipschitz) and usually the answer itself.
void sliceDistances(int z, const TriangleBvh& bvh, const VoxelGrid& grid, std::vector<float>& out) {
    std::uint32_t rowStart = 0;  // nearest triangle of voxel (0, y - 1, z)
    for (int y = 0; y < grid.size.y; ++y) {
        std::uint32_t previous = rowStart;
        for (int x = 0; x < grid.size.x; ++x) {
            const TriangleBvh::Nearest nearest = bvh.nearest(grid.centre(x, y, z), previous);
            out[grid.index(x, y, z)] = roundedDown(std::sqrt(nearest.distance2));
            previous = nearest.triangle;
            if (x == 0) rowStart = nearest.triangle;
        }
    }
}

/// Runs `sliceDistances` over every slice on `threads` threads (the caller's among them). A
/// thread that cannot be started leaves its share to the others.
std::vector<float> unsignedDistances(const TriangleBvh& bvh, const VoxelGrid& grid, int threads) {
    std::vector<float> out(grid.count());
    std::atomic<int> nextSlice{0};
    const auto work = [&] {
        for (int z = nextSlice++; z < grid.size.z; z = nextSlice++) sliceDistances(z, bvh, grid, out);
    };
    std::vector<std::thread> workers;
    for (int i = 1; i < threads; ++i) {
        try {
            workers.emplace_back(work);
        } catch (const std::system_error&) {
            break;
        }
    }
    work();
    for (std::thread& worker : workers) worker.join();
    return out;
}

int threadCount(const DistanceFieldSettings& settings) {
    if (settings.threads > 0) return settings.threads;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace

Result<DistanceField> bakeDistanceField(const MeshData& mesh, const DistanceFieldSettings& settings) {
    const Status valid = checkSettings(settings);
    if (!valid.ok()) return valid.error();
    Result<std::vector<Triangle>> triangles = collectTriangles(mesh);
    if (!triangles.ok()) return triangles.error();

    DistanceField field = layOut(boundsOf(*triangles), settings);
    const VoxelGrid grid = gridOf(field);
    const std::vector<std::uint8_t> enclosed = sdf::enclosedVoxels(*triangles, grid);
    const TriangleBvh bvh(std::move(*triangles));
    field.distances = unsignedDistances(bvh, grid, threadCount(settings));
    for (std::size_t i = 0; i < field.distances.size(); ++i) {
        if (enclosed[i] != 0) field.distances[i] = -field.distances[i];
    }
    return field;
}

float sampleDistance(const DistanceField& field, const glm::vec3& localPoint) {
    if (!finite(localPoint)) return std::numeric_limits<float>::quiet_NaN();
    const bool sampleable =
        field.size.x >= 2 && field.size.y >= 2 && field.size.z >= 2 &&
        field.distances.size() == static_cast<std::size_t>(field.size.x) * field.size.y * field.size.z;
    if (!sampleable) return std::numeric_limits<float>::infinity();
    // Grid coordinates: voxel centre i at i. q is the nearest point within the centres.
    const glm::vec3 g = (localPoint - field.box.min) / field.voxelSize - 0.5f;
    const glm::vec3 last = glm::vec3(field.size - 1);
    const glm::vec3 gq = glm::clamp(g, glm::vec3(0.0f), last);
    const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(gq)), field.size - 2);
    const glm::vec3 f = gq - glm::vec3(i0);
    float value = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 offset((corner & 1) != 0, (corner & 2) != 0, (corner & 4) != 0);
        const glm::vec3 w = glm::mix(1.0f - f, f, glm::vec3(offset));
        value += w.x * w.y * w.z * field.distances[field.index(i0 + offset)];
    }
    if (gq == g) return value;
    const float toCentres = glm::length(g - gq) * field.voxelSize;
    const glm::vec3 toBox = glm::max(glm::max(field.box.min - localPoint, localPoint - field.box.max), glm::vec3(0.0f));
    return std::max(glm::length(toBox), value - toCentres);
}

float distanceFieldVoxel(const Aabb& bounds, const DistanceFieldSettings& settings) {
    const glm::vec3 extent = bounds.max - bounds.min;
    if (!(std::max({extent.x, extent.y, extent.z}) > 0.0f)) return 0.0f;
    return layOut(bounds, settings).voxelSize;
}

}  // namespace shadow
