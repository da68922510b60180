// Small geometric types shared by every subsystem.
//
// World-space positions and matrices are kept in double on the CPU so that a scene far from
// the origin (10^5 m) keeps millimetre precision; the GPU only ever sees float values made
// relative to the camera or the light.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <limits>

namespace shadow {

/// Axis-aligned box. Default-constructed boxes are empty (min > max).
template <typename Vec>
struct BasicAabb {
    using Scalar = typename Vec::value_type;
    Vec min{std::numeric_limits<Scalar>::max()};
    Vec max{std::numeric_limits<Scalar>::lowest()};

    [[nodiscard]] bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    bool operator==(const BasicAabb&) const = default;
    void extend(const Vec& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const BasicAabb& b) {
        if (b.empty()) return;
        extend(b.min);
        extend(b.max);
    }
    [[nodiscard]] Vec center() const { return (min + max) * Scalar(0.5); }
    [[nodiscard]] Vec extent() const { return max - min; }
    /// The eight corners, bit k of the index choosing max over min on axis k.
    [[nodiscard]] Vec corner(int i) const {
        return Vec((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
    }
};

using Aabb = BasicAabb<glm::vec3>;
using DAabb = BasicAabb<glm::dvec3>;

/// Bounds of `box` (float or double) after the affine transform `m`: exactly the bounds of its
/// eight corners transformed by `m * dvec4(corner, 1)`, bit for bit, at the cost of one corner.
/// Each output coordinate sums one term per input axis, in the order glm's product sums them;
/// the corner that makes every term least (greatest) makes the rounded sum least (greatest),
/// since rounding keeps the order. For the same reason the bounds grow with the box: a box
/// inside another gives bounds inside its bounds (a monotone test for `BoxTree`).
template <typename Vec>
DAabb transformBounds(const glm::dmat4& m, const BasicAabb<Vec>& box) {
    DAabb out;
    if (box.empty()) return out;
    const glm::dvec3 lo(box.min);
    const glm::dvec3 hi(box.max);
    glm::dvec3 least[3];
    glm::dvec3 most[3];
    for (int axis = 0; axis < 3; ++axis) {
        const glm::dvec3 column(m[axis]);
        const glm::dvec3 a = column * lo[axis];
        const glm::dvec3 b = column * hi[axis];
        least[axis] = glm::min(a, b);
        most[axis] = glm::max(a, b);
    }
    const glm::dvec3 translation(m[3]);
    out.min = (least[0] + least[1]) + (least[2] + translation);
    out.max = (most[0] + most[1]) + (most[2] + translation);
    return out;
}

/// True when every element of the matrix is finite.
inline bool isFinite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(m[c][r])) return false;
        }
    }
    return true;
}

/// A unit vector perpendicular to `axis` that is stable when `axis` is close to any
/// coordinate axis (picks the world axis least aligned with `axis` to cross with).
inline glm::dvec3 anyPerpendicular(const glm::dvec3& axis) {
    const glm::dvec3 a = glm::abs(axis);
    const glm::dvec3 pick = (a.x <= a.y && a.x <= a.z) ? glm::dvec3(1, 0, 0)
                            : (a.y <= a.z)             ? glm::dvec3(0, 1, 0)
                                                       : glm::dvec3(0, 0, 1);
    return glm::normalize(glm::cross(axis, pick));
}

/// `v` made unit and perpendicular to unit `axis` (one Gram-Schmidt step); any perpendicular of
/// `axis` where `v` is zero or parallel to it. With `axis`, the two columns of a rotation.
inline glm::dvec3 perpendicularPart(const glm::dvec3& axis, const glm::dvec3& v) {
    const glm::dvec3 rest = v - axis * glm::dot(v, axis);
    const double length = glm::length(rest);
    return length > 0.0 && length > 1e-12 * glm::length(v) ? rest / length : anyPerpendicular(axis);
}

/// View matrix looking from `eye` along unit `forward`, robust for any `forward` including
/// straight up or down: the up vector is world +Y unless `forward` is within ~0.6 degrees of
/// it, then a perpendicular axis is chosen instead.
inline glm::dmat4 lookAlong(const glm::dvec3& eye, const glm::dvec3& forward) {
    const glm::dvec3 f = glm::normalize(forward);
    glm::dvec3 up(0, 1, 0);
    if (std::abs(glm::dot(f, up)) > 0.99995) up = anyPerpendicular(f);
    const glm::dvec3 s = glm::normalize(glm::cross(f, up));
    const glm::dvec3 u = glm::cross(s, f);
    glm::dmat4 m(1.0);
    m[0][0] = s.x;
    m[1][0] = s.y;
    m[2][0] = s.z;
    m[0][1] = u.x;
    m[1][1] = u.y;
    m[2][1] = u.z;
    m[0][2] = -f.x;
    m[1][2] = -f.y;
    m[2][2] = -f.z;
    m[3][0] = -glm::dot(s, eye);
    m[3][1] = -glm::dot(u, eye);
    m[3][2] = glm::dot(f, eye);
    return m;
}

}  // namespace shadow
