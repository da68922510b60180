// Texture-space helpers of materials declared in components.h: the KHR_texture_transform matrix
// and normal-map tangents.
//
// The tangents follow MikkTSpace (Morten Mikkelsen, "Simulation of Wrinkled Surfaces Revisited",
// 2008), the frame glTF's normal maps are baked in, for meshes whose vertices the file already
// split at uv seams and normal creases (as glTF's are): each triangle corner contributes its
// triangle's uv tangent and bitangent, projected onto the corner's normal plane and normalised,
// weighted by the corner's angle; the vertex sums them. A pixel shader then rebuilds the frame
// as MikkTSpace's does: bitangent = w * cross(normal, tangent), from the interpolated vectors.
#include <shadow/components.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace shadow {

glm::mat3x2 textureTransform(const glm::vec2& offset, float rotation, const glm::vec2& scale) {
    const float c = std::cos(rotation), s = std::sin(rotation);
    // uv' = T * R * S * uv with R = [c s; -s c] (the extension's rows).
    return {glm::vec2(c * scale.x, -s * scale.x), glm::vec2(s * scale.y, c * scale.y), offset};
}

namespace {

/// `v` without its component along unit `n`, normalised; zero when nothing is left.
glm::dvec3 tangentPart(const glm::dvec3& v, const glm::dvec3& n) {
    const glm::dvec3 p = v - n * glm::dot(n, v);
    const double length = glm::length(p);
    return length > 1e-20 && std::isfinite(length) ? p / length : glm::dvec3(0.0);
}

/// The angle of the triangle at corner `p` between edges to `a` and `b` (0 when degenerate).
double cornerAngle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 e1 = a - p, e2 = b - p;
    const double l = glm::length(e1) * glm::length(e2);
    if (!(l > 0.0) || !std::isfinite(l)) return 0.0;
    return std::acos(std::clamp(glm::dot(e1, e2) / l, -1.0, 1.0));
}

/// Per vertex, the angle-weighted sums of the corners' tangents and bitangents.
struct FrameSums {
    std::vector<glm::dvec3> tangent, bitangent;
};

FrameSums sumCorners(const MeshData& mesh, const std::vector<glm::vec2>& uv) {
    const std::size_t n = mesh.positions.size();
    FrameSums sums{std::vector<glm::dvec3>(n, glm::dvec3(0.0)), std::vector<glm::dvec3>(n, glm::dvec3(0.0))};
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::array<std::uint32_t, 3> v{mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        if (v[0] >= n || v[1] >= n || v[2] >= n) continue;
        const glm::dvec3 p0(mesh.positions[v[0]]), p1(mesh.positions[v[1]]), p2(mesh.positions[v[2]]);
        const glm::dvec2 w0(uv[v[0]]), w1(uv[v[1]]), w2(uv[v[2]]);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
        const glm::dvec2 d1 = w1 - w0, d2 = w2 - w0;
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-30) || !std::isfinite(det)) continue;  // no uv area: no direction
        // dP/du and dP/dv of the triangle's linear map from uv to position.
        const glm::dvec3 du = (e1 * d2.y - e2 * d1.y) / det, dv = (e2 * d1.x - e1 * d2.x) / det;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = v[static_cast<std::size_t>(k)];
            const glm::dvec3 normal(mesh.normals[i]);
            const glm::dvec3 p(mesh.positions[i]);
            const glm::dvec3 a(mesh.positions[v[static_cast<std::size_t>((k + 1) % 3)]]);
            const glm::dvec3 b(mesh.positions[v[static_cast<std::size_t>((k + 2) % 3)]]);
            const double weight = cornerAngle(p, a, b);
            sums.tangent[i] += weight * tangentPart(du, normal);
            sums.bitangent[i] += weight * tangentPart(dv, normal);
        }
    }
    return sums;
}

}  // namespace

void computeTangents(MeshData& mesh, int set) {
    const std::vector<glm::vec2>& uv = set == 1 ? mesh.texcoords1 : mesh.texcoords;
    const std::size_t n = mesh.positions.size();
    mesh.tangents.clear();
    if (n == 0 || uv.size() != n || mesh.normals.size() != n) return;
    const FrameSums sums = sumCorners(mesh, uv);
    mesh.tangents.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 normal(mesh.normals[i]);
        glm::dvec3 t = tangentPart(sums.tangent[i], normal);
        if (t == glm::dvec3(0.0)) t = glm::length(normal) > 0.0 ? anyPerpendicular(normal) : glm::dvec3(1.0, 0.0, 0.0);
        const double side = glm::dot(glm::cross(normal, t), sums.bitangent[i]);
        mesh.tangents[i] = glm::vec4(glm::vec3(t), side < 0.0 ? -1.0f : 1.0f);
    }
}

}  // namespace shadow
