// Signed distance fields of meshes, baked on the CPU, for distance-field soft shadows (a march
// from a shaded point toward a light advances by the field's value each step; the smallest
// k·d/t along the way is the visibility).
//
// What it does: one mesh in, one dense grid of float distances out, in the mesh's local units;
// trilinear sampling on the CPU; a small versioned binary file a game can ship.
// What it does not do: no GL, no upload, no shader code; no sparse or compressed storage; no
// scene-wide field (a game places one field per mesh instance and scales a sample by the
// instance's uniform scale; a non-uniform scale breaks the distance bound).
//
// Distances are exact at every voxel centre (a BVH closest-triangle query, double precision,
// stored as float): never larger than the true distance to the nearest triangle, not only near
// the surface. Between centres `sampleDistance` interpolates, see there for its bound.
//
// Sign rule (flood fill from the grid's boundary): a voxel is outside (positive) when a path of
// steps between neighbouring voxel centres joins it to the boundary without crossing a triangle;
// every other voxel is inside (negative). The rule reads no winding and no normals, so:
//  - a closed mesh is negative inside, whichever way its triangles wind (a flipped mesh too);
//  - a mesh that is not closed, where a hole lets a path through, is positive everywhere (an
//    unsigned field): a single plane, a box without one face. For shadows that is right: a
//    shell casts the shadow of the solid from outside, and a point inside an open box (a room
//    with a missing wall) is not in a caster, so a march starting there must not read "inside,
//    fully shadowed"; it reads the distance to the walls and finds the opening;
//  - several closed parts that overlap read as their union; a cavity sealed inside a mesh reads
//    as inside; a pocket or gap narrower than a voxel may read as inside (a voxel-scale error,
//    at a distance under one voxel from the surface);
//  - a gap narrower than a thousandth of a voxel (unwelded seams) does not let a path through.
// An unsigned (open) surface is a zero-thickness sheet: a march should count a value under
// about one voxel as a hit, as `sampleDistance` on the sheet returns up to √3/2 voxel.
//
// Nothing declared here throws on bad input: a bad mesh, setting or file is an `Error`. Only
// running out of memory throws (std::bad_alloc).
#pragma once

#include <shadow/components.h>
#include <shadow/math.h>
#include <shadow/result.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shadow {

/// Fewest voxels a field may have in total (16³).
inline constexpr int kMinDistanceFieldVoxels = 16 * 16 * 16;
/// Most voxels a field may have in total (256³, 64 MiB of floats): the bake's and the loader's limit.
inline constexpr int kMaxDistanceFieldVoxels = 256 * 256 * 256;
/// Version of the file format `saveDistanceField` writes and `loadDistanceField` reads.
inline constexpr std::uint32_t kDistanceFieldFileVersion = 1;

/// How `bakeDistanceField` lays out and computes a field. Values out of range are an
/// `InvalidArgument` error (a bake is a tool step, not a frame: nothing to carry on with).
struct DistanceFieldSettings {
    /// Most voxels in total, [kMinDistanceFieldVoxels, kMaxDistanceFieldVoxels]. Default 64³
    /// (1 MiB). The voxels are cubes; the longest axis of the mesh gets the most of them, and
    /// the voxel is the smallest for which the whole grid, padding included, fits the budget.
    int voxelBudget = 64 * 64 * 64;
    /// Voxels of empty space between the mesh's bounds and the grid's box on every side, [1, 4].
    /// Default 2: a march sees the field fall off before it leaves the box. A flat mesh gets
    /// 1 + 2·padding voxels across its flat axis.
    int paddingVoxels = 2;
    /// Threads that compute distances, [0, 256]; 0 (the default) = the hardware's threads.
    int threads = 0;
};

/// A dense grid of signed distances to a mesh, in the mesh's local space and units.
struct DistanceField {
    /// Voxels per axis, each at least 2 (1 + 2·padding from a bake).
    glm::ivec3 size{0};
    /// The mesh-local box the grid covers: the mesh's bounds padded, `max = min + size·voxelSize`.
    Aabb box;
    /// Edge of one cubic voxel (mesh-local units), > 0.
    float voxelSize = 0.0f;
    /// Signed distance at each voxel centre `box.min + (i + 0.5)·voxelSize`, negative inside;
    /// `size.x·size.y·size.z` values, x fastest, then y, then z.
    std::vector<float> distances;

    /// Bytes of `distances` (what a 3D texture of R32F holds).
    [[nodiscard]] std::size_t byteSize() const { return distances.size() * sizeof(float); }
    /// Index into `distances` of voxel `v` (each coordinate in [0, size)).
    [[nodiscard]] std::size_t index(const glm::ivec3& v) const {
        return static_cast<std::size_t>(v.x) +
               static_cast<std::size_t>(size.x) *
                   (static_cast<std::size_t>(v.y) + static_cast<std::size_t>(size.y) * static_cast<std::size_t>(v.z));
    }
    /// Mesh-local centre of voxel `v`.
    [[nodiscard]] glm::vec3 voxelCentre(const glm::ivec3& v) const {
        return box.min + (glm::vec3(v) + 0.5f) * voxelSize;
    }
};

/// Bakes the signed distance field of `mesh`'s triangles (`positions` and `indices`; normals and
/// `bounds` are not read). Triangles of zero area are left out. Errors: a mesh without
/// triangles, indices not a multiple of 3 or out of range, a non-finite position, or no
/// triangle with an area: `InvalidValue`, naming the element (`positions[12]`); positions beyond
/// ±kMaxWorldCoordinate: `LimitExceeded`; settings out of range: `InvalidArgument`.
[[nodiscard]] Result<DistanceField> bakeDistanceField(const MeshData& mesh, const DistanceFieldSettings& settings = {});

/// The voxel edge (in `bounds`' units) a bake of a mesh with these bounds lays out: the smallest
/// for which the padded grid fits `settings.voxelBudget` (what `bakeDistanceField` gives as
/// `DistanceField::voxelSize`). Bounds of no extent on any axis: 0.
[[nodiscard]] float distanceFieldVoxel(const Aabb& bounds, const DistanceFieldSettings& settings = {});

/// The field's distance at mesh-local `localPoint`. Inside the box spanned by the voxel centres:
/// trilinear between the eight nearest centres, never more than √3/2·voxelSize above the true
/// distance (the centres are exact and the distance is 1-Lipschitz) and exact where the distance
/// is linear (the flat side of a plane). Beyond the centres: max(distance to `box`, value at the
/// nearest point q within the centres − |localPoint − q|), a lower bound of the true distance, so
/// a march never oversteps into the mesh from outside (adding |localPoint − q| instead would
/// overestimate by up to 0.4 of the box's size). NaN for a non-finite point; +infinity for a
/// field with fewer than 2 voxels on an axis or a `distances` count other than the size's (never
/// one from a bake or a load).
[[nodiscard]] float sampleDistance(const DistanceField& field, const glm::vec3& localPoint);

/// Writes `field` to `path` (through a temporary file and a rename) in the format
/// `loadDistanceField` reads: little-endian, a 60-byte header ("SHADOWDF", u32 version, i32 size
/// xyz, f32 box min xyz, f32 box max xyz, f32 voxelSize, u64 data bytes) and the distances as
/// f32 in `distances` order. A field that would not load back (bad size, box, voxel size, data
/// count or a non-finite distance) is an `InvalidArgument`; a file that cannot be written
/// `FileUnwritable`.
[[nodiscard]] Status saveDistanceField(const std::string& path, const DistanceField& field);

/// Reads a field written by `saveDistanceField`, checking every header field before reading
/// the data; allocates at most the data a valid header of the file's own length describes.
/// Errors name the file and the field: missing or unreadable `FileUnreadable`; shorter than the
/// header, wrong magic, or data bytes that disagree with the size or the file's length
/// `MalformedFile`; another version `Unsupported`; a size over `kMaxDistanceFieldVoxels`
/// `LimitExceeded`; an axis under 2 voxels, a non-finite or empty box, a voxel size that is not
/// positive or disagrees with the box, or a non-finite distance `InvalidValue`.
[[nodiscard]] Result<DistanceField> loadDistanceField(const std::string& path);

}  // namespace shadow
