// CPU-side mesh helpers declared in components.h.
#include <shadow/components.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace shadow {

// Non-finite positions are left out of the box: one bad vertex must not make the bounds of a
// whole mesh NaN (culling would then drop or keep it arbitrarily). Importers reject them
// anyway; this only protects meshes built in code.
namespace {

Aabb finiteBounds(const std::vector<glm::vec3>& positions) {
    Aabb box;
    for (const glm::vec3& p : positions) {
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) box.extend(p);
    }
    return box;
}

}  // namespace

void computeBounds(MeshData& mesh) { mesh.bounds = finiteBounds(mesh.positions); }

namespace {

/// Per vertex, one id per position, welding positions that round to the same point of a grid a
/// millionth of the mesh's extent `box` apart (so a flat-shaded mesh's repeated vertices, and a
/// generated sphere's pole vertices that differ by rounding, count once). `count` is set to the
/// number of ids.
std::vector<std::uint32_t> weldByPosition(const MeshData& mesh, const Aabb& box, std::uint32_t& count) {
    const std::size_t vertexCount = mesh.positions.size();
    const glm::vec3 extent = box.empty() ? glm::vec3(0.0f) : box.extent();
    const double cell = std::max(1e-6 * std::max({extent.x, extent.y, extent.z}), 1e-12);
    auto key = [cell](const glm::vec3& p) {
        std::array<std::int64_t, 3> q{};
        for (int c = 0; c < 3; ++c) {
            const double v = std::isfinite(p[c]) ? static_cast<double>(p[c]) / cell : 0.0;
            q[static_cast<std::size_t>(c)] = static_cast<std::int64_t>(std::llround(std::clamp(v, -4e18, 4e18)));
        }
        return q;
    };
    std::vector<std::pair<std::array<std::int64_t, 3>, std::uint32_t>> byPosition(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i)
        byPosition[i] = {key(mesh.positions[i]), static_cast<std::uint32_t>(i)};
    std::sort(byPosition.begin(), byPosition.end());
    std::vector<std::uint32_t> welded(vertexCount);
    count = 0;
    for (std::size_t i = 0; i < vertexCount; ++i) {
        if (i == 0 || byPosition[i].first != byPosition[i - 1].first) ++count;
        welded[byPosition[i].second] = count - 1;
    }
    return welded;
}

/// Whether every connected part of the triangles `triangles` (vertex indices; parts joined by
/// the welded ids `welded`, `ids` of them) encloses a positive volume: the sum of its
/// triangles' tetrahedra with the box's centre, in double about the centre so that a mesh far
/// from the origin keeps its digits. NaN (a non-finite position) counts as not positive.
bool everyPartOutward(const MeshData& mesh, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                      const std::vector<std::uint32_t>& welded, std::uint32_t ids, const Aabb& box) {
    std::vector<std::uint32_t> part(ids);
    for (std::uint32_t v = 0; v < ids; ++v) part[v] = v;
    const auto root = [&part](std::uint32_t v) {
        while (part[v] != v) v = part[v] = part[part[v]];
        return v;
    };
    for (const std::array<std::uint32_t, 3>& tri : triangles) {
        part[root(welded[tri[0]])] = root(welded[tri[1]]);
        part[root(welded[tri[1]])] = root(welded[tri[2]]);
    }
    const glm::dvec3 centre = 0.5 * (glm::dvec3(box.min) + glm::dvec3(box.max));
    std::vector<double> volume(ids, 0.0);
    std::vector<char> hasTriangle(ids, 0);
    for (const std::array<std::uint32_t, 3>& tri : triangles) {
        const glm::dvec3 a = glm::dvec3(mesh.positions[tri[0]]) - centre;
        const glm::dvec3 b = glm::dvec3(mesh.positions[tri[1]]) - centre;
        const glm::dvec3 c = glm::dvec3(mesh.positions[tri[2]]) - centre;
        const std::uint32_t r = root(welded[tri[0]]);
        volume[r] += glm::dot(a, glm::cross(b, c));
        hasTriangle[r] = 1;
    }
    for (std::uint32_t r = 0; r < ids; ++r) {
        if (hasTriangle[r] != 0 && !(volume[r] > 0.0)) return false;
    }
    return true;
}

/// 2 |volume| / area of the closed surface `triangles` (the divergence theorem about the box's
/// centre, in double): the thickness of a slab. A surface wound inconsistently gives less (parts
/// of its volume cancel), never more.
float meanThickness(const MeshData& mesh, const std::vector<std::array<std::uint32_t, 3>>& triangles, const Aabb& box) {
    const glm::dvec3 centre = 0.5 * (glm::dvec3(box.min) + glm::dvec3(box.max));
    double volume = 0.0;
    double area = 0.0;
    for (const auto& t : triangles) {
        const glm::dvec3 a = glm::dvec3(mesh.positions[t[0]]) - centre;
        const glm::dvec3 b = glm::dvec3(mesh.positions[t[1]]) - centre;
        const glm::dvec3 c = glm::dvec3(mesh.positions[t[2]]) - centre;
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return area > 0.0 ? static_cast<float>(2.0 * std::abs(volume) / area) : 0.0f;
}

/// Whether every vertex of `triangles` lies within 1e-5 of the box's diagonal of the plane of
/// their largest triangle (in double about the box's centre).
bool allInOnePlane(const MeshData& mesh, const std::vector<std::array<std::uint32_t, 3>>& triangles, const Aabb& box) {
    const glm::dvec3 centre = 0.5 * (glm::dvec3(box.min) + glm::dvec3(box.max));
    glm::dvec3 normal(0.0);
    glm::dvec3 origin(0.0);
    for (const auto& t : triangles) {
        const glm::dvec3 a = glm::dvec3(mesh.positions[t[0]]) - centre;
        const glm::dvec3 n =
            glm::cross(glm::dvec3(mesh.positions[t[1]]) - centre - a, glm::dvec3(mesh.positions[t[2]]) - centre - a);
        if (glm::length(n) > glm::length(normal)) normal = n, origin = a;
    }
    if (!(glm::length(normal) > 0.0)) return false;
    normal = glm::normalize(normal);
    const double tolerance = 1e-5 * glm::length(glm::dvec3(box.max) - glm::dvec3(box.min));
    for (const auto& t : triangles) {
        for (std::uint32_t v : t) {
            if (!(std::abs(glm::dot(glm::dvec3(mesh.positions[v]) - centre - origin, normal)) <= tolerance))
                return false;
        }
    }
    return true;
}

}  // namespace

// Welds the positions (weldByPosition), then sorts the edges and checks that each appears
// exactly twice; `solid` also needs each edge once in each direction, and every connected part
// outward (everyPartOutward).
void computeClosed(MeshData& mesh) {
    const std::size_t vertexCount = mesh.positions.size();
    const Aabb box = finiteBounds(mesh.positions);
    std::uint32_t ids = 0;
    const std::vector<std::uint32_t> welded = weldByPosition(mesh, box, ids);
    // Each edge as (lower id, higher id, 1 when it runs from the higher to the lower).
    std::vector<std::array<std::uint32_t, 3>> edges;
    edges.reserve(mesh.indices.size());
    std::vector<std::array<std::uint32_t, 3>> triangles;
    triangles.reserve(mesh.indices.size() / 3);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t* tri = &mesh.indices[t];
        if (tri[0] >= vertexCount || tri[1] >= vertexCount || tri[2] >= vertexCount) continue;
        const std::array<std::uint32_t, 3> v{welded[tri[0]], welded[tri[1]], welded[tri[2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;  // degenerate: covers nothing
        triangles.push_back({tri[0], tri[1], tri[2]});
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = v[static_cast<std::size_t>(e)];
            const std::uint32_t b = v[static_cast<std::size_t>((e + 1) % 3)];
            edges.push_back({std::min(a, b), std::max(a, b), a > b ? 1U : 0U});
        }
    }
    std::sort(edges.begin(), edges.end());
    mesh.closed = !edges.empty();
    bool wound = true;  // every edge once in each direction
    for (std::size_t i = 0; i < edges.size() && mesh.closed;) {
        std::size_t j = i;
        while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
        mesh.closed = j - i == 2;
        wound = wound && mesh.closed && edges[i][2] != edges[i + 1][2];
        i = j;
    }
    mesh.solid = mesh.closed && wound && !box.empty() && everyPartOutward(mesh, triangles, welded, ids, box);
    mesh.thickness = mesh.closed ? meanThickness(mesh, triangles, box) : 0.0f;
    mesh.planar = !box.empty() && allInOnePlane(mesh, triangles, box);
}

namespace {

/// The unit normal of a counter-clockwise triangle, computed in double so that small but
/// valid triangles do not underflow to a zero cross product. Degenerate triangles cover no
/// pixel; they get +Y so no shader ever normalises a zero vector.
glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) return glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::vec3(n / length);
}

/// `values` (one per vertex, or per vertex and target when `per` > 1: `per` blocks of `vertices`)
/// taken at each of `corners`' source vertices; emptied when it does not fit that count.
template <typename T>
void gather(std::vector<T>& values, const std::vector<std::uint32_t>& corners, std::size_t vertices,
            std::size_t per = 1) {
    if (values.size() != vertices * per) {
        values.clear();
        return;
    }
    std::vector<T> out;
    out.reserve(corners.size() * per);
    for (std::size_t block = 0; block < per; ++block) {
        for (const std::uint32_t c : corners) out.push_back(values[block * vertices + c]);
    }
    values = std::move(out);
}

}  // namespace

// Triangles with an index out of range are dropped, as are trailing indices that do not make
// a whole triangle, so the result is always a valid triangle list.
void makeFlatNormals(MeshData& mesh) {
    const std::size_t vertexCount = mesh.positions.size();
    const std::size_t triangleCount = mesh.indices.size() / 3;
    std::vector<std::uint32_t> corners;  // per new vertex, the vertex it copies
    std::vector<glm::vec3> normals;
    corners.reserve(triangleCount * 3);
    normals.reserve(triangleCount * 3);
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::uint32_t* tri = &mesh.indices[3 * t];
        if (tri[0] >= vertexCount || tri[1] >= vertexCount || tri[2] >= vertexCount) continue;
        const glm::vec3 n = faceNormal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
        corners.insert(corners.end(), tri, tri + 3);
        normals.insert(normals.end(), 3, n);
    }
    const bool skinned = mesh.joints.size() == vertexCount && mesh.weights.size() == vertexCount;
    gather(mesh.positions, corners, vertexCount);
    gather(mesh.texcoords, corners, vertexCount);
    gather(mesh.texcoords1, corners, vertexCount);
    if (!skinned) {
        mesh.joints.clear();
        mesh.weights.clear();
    }
    gather(mesh.joints, corners, vertexCount);
    gather(mesh.weights, corners, vertexCount);
    // A target's displaced corners keep the base shape's face normals: flat normals are not morphed.
    gather(mesh.morphPositions, corners, vertexCount, mesh.morphTargets);
    mesh.morphNormals.clear();
    mesh.morphTangents.clear();
    mesh.positions.resize(corners.size());  // a mesh of no whole triangle keeps nothing
    mesh.normals = std::move(normals);
    mesh.indices.resize(corners.size());
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
    mesh.tangents.clear();  // glTF: a mesh without normals ignores its tangents
    computeBounds(mesh);
}

void computeMorphBounds(MeshData& mesh) {
    const std::size_t n = mesh.positions.size();
    mesh.morphBounds.assign(mesh.morphTargets, Aabb{});
    if (mesh.morphPositions.size() != n * mesh.morphTargets) return;
    for (std::size_t k = 0; k < mesh.morphTargets; ++k) {
        for (std::size_t i = 0; i < n; ++i) mesh.morphBounds[k].extend(mesh.morphPositions[k * n + i]);
    }
}

glm::vec3 morphedPosition(const MeshData& mesh, const Morph& morph, std::size_t i) {
    glm::vec3 p = mesh.positions[i];
    const std::size_t n = mesh.positions.size();
    for (const MorphInfluence& m : morph.drawn) {
        const std::size_t at = m.target * n + i;
        if (at < mesh.morphPositions.size()) p += m.weight * mesh.morphPositions[at];
    }
    return p;
}

void computeJointBounds(MeshData& mesh) {
    mesh.jointBounds.clear();
    const std::size_t n = mesh.positions.size();
    if (mesh.joints.size() != n || mesh.weights.size() != n) return;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3& p = mesh.positions[i];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) continue;
        for (int k = 0; k < 4; ++k) {
            if (!(mesh.weights[i][k] > 0.0f)) continue;
            const std::size_t j = mesh.joints[i][k];
            if (j >= mesh.jointBounds.size()) mesh.jointBounds.resize(j + 1);
            mesh.jointBounds[j].extend(mesh.positions[i]);
        }
    }
}

glm::vec3 skinnedPosition(const MeshData& mesh, const Skin& skin, std::size_t i, const glm::vec3& position) {
    const glm::vec4 p(position, 1.0f);
    glm::vec4 out(0.0f);
    for (int k = 0; k < 4; ++k) {
        const float w = mesh.weights[i][k];
        const std::size_t j = mesh.joints[i][k];
        if (w > 0.0f && j < skin.frameFromMesh.size()) out += w * (skin.frameFromMesh[j] * p);
    }
    return glm::vec3(out);
}

}  // namespace shadow
