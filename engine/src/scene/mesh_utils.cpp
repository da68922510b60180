// CPU-side mesh helpers declared in components.h.
#include <shadow/components.h>

#include <cmath>

namespace shadow {

// Non-finite positions are left out of the box: one bad vertex must not make the bounds of a
// whole mesh NaN (culling would then drop or keep it arbitrarily). Importers reject them
// anyway; this only protects meshes built in code.
void computeBounds(MeshData& mesh) {
    mesh.bounds = Aabb{};
    for (const glm::vec3& p : mesh.positions) {
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) mesh.bounds.extend(p);
    }
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

}  // namespace

// Triangles with an index out of range are dropped, as are trailing indices that do not make
// a whole triangle, so the result is always a valid triangle list.
void makeFlatNormals(MeshData& mesh) {
    const std::size_t vertexCount = mesh.positions.size();
    const std::size_t triangleCount = mesh.indices.size() / 3;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    positions.reserve(triangleCount * 3);
    normals.reserve(triangleCount * 3);
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::uint32_t* tri = &mesh.indices[3 * t];
        if (tri[0] >= vertexCount || tri[1] >= vertexCount || tri[2] >= vertexCount) continue;
        const glm::vec3 n = faceNormal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
        for (int k = 0; k < 3; ++k) {
            positions.push_back(mesh.positions[tri[k]]);
            normals.push_back(n);
        }
    }
    mesh.indices.resize(positions.size());
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
        mesh.indices[i] = static_cast<std::uint32_t>(i);
    }
    mesh.positions = std::move(positions);
    mesh.normals = std::move(normals);
    computeBounds(mesh);
}

}  // namespace shadow
