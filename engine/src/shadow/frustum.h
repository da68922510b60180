// Frustum culling in double precision, for casters against shadow layers and lights against
// the camera.
#pragma once

#include <shadow/math.h>

#include <array>

namespace shadow {

/// Six planes (a,b,c,d) with a*x + b*y + c*z + d >= 0 inside, from a clip-from-world matrix.
struct Frustum {
    std::array<glm::dvec4, 6> planes{};

    /// The frustum of `clipFromWorld` (OpenGL clip space, -w <= x,y,z <= w).
    static Frustum fromMatrix(const glm::dmat4& clipFromWorld) {
        Frustum f;
        const glm::dmat4 m = glm::transpose(clipFromWorld);  // rows of the matrix as columns
        f.planes[0] = m[3] + m[0];
        f.planes[1] = m[3] - m[0];
        f.planes[2] = m[3] + m[1];
        f.planes[3] = m[3] - m[1];
        f.planes[4] = m[3] + m[2];
        f.planes[5] = m[3] - m[2];
        for (glm::dvec4& p : f.planes) {
            const double len = glm::length(glm::dvec3(p));
            if (len > 0.0) p /= len;
        }
        return f;
    }

    /// False only when `box` lies wholly outside one plane (conservative).
    [[nodiscard]] bool intersects(const DAabb& box) const {
        if (box.empty()) return false;
        for (const glm::dvec4& p : planes) {
            const glm::dvec3 n(p);
            const glm::dvec3 far(n.x >= 0 ? box.max.x : box.min.x, n.y >= 0 ? box.max.y : box.min.y,
                                 n.z >= 0 ? box.max.z : box.min.z);
            if (glm::dot(n, far) + p.w < 0.0) return false;
        }
        return true;
    }

    /// False only when the sphere lies wholly outside one plane.
    [[nodiscard]] bool intersectsSphere(const glm::dvec3& center, double radius) const {
        for (const glm::dvec4& p : planes) {
            if (glm::dot(glm::dvec3(p), center) + p.w < -radius) return false;
        }
        return true;
    }
};

}  // namespace shadow
