// Closed forms of emitter visibility, the analytic truth the ray-traced reference is tested
// against (and that error reports may use directly for builtin:plates).
//
// All areas are exact up to rounding: the disk ∩ rectangle area integrates the circle's chord
// function piecewise with the antiderivative of sqrt(R^2 - x^2); no sampling anywhere.
#pragma once

#include <shadow/scene.h>

#include <glm/glm.hpp>
#include <vector>

namespace shadow::reference {

/// An axis-aligned rectangle [min.x, max.x] x [min.y, max.y]; empty when min > max on an axis.
struct Rect {
    glm::dvec2 min{0.0};
    glm::dvec2 max{0.0};
    [[nodiscard]] bool empty() const { return !(min.x < max.x && min.y < max.y); }
};

/// The intersection of two rectangles (possibly empty).
[[nodiscard]] Rect intersect(const Rect& a, const Rect& b);

/// Area of the disk of radius `radius` centred on `center` intersected with `rect`. Exact.
[[nodiscard]] double diskRectArea(const glm::dvec2& center, double radius, const Rect& rect);

/// Area of the disk intersected with the union of `rects`, by inclusion–exclusion over every
/// subset (the intersection of rectangles is a rectangle). At most 16 rectangles.
[[nodiscard]] double diskRectUnionArea(const glm::dvec2& center, double radius, const std::vector<Rect>& rects);

/// Fraction of a unit disk on the far side of a chord at signed distance `u` from the centre:
/// (acos u − u sqrt(1 − u²)) / π, with u clamped to [−1, 1]. The visible fraction of a disk
/// emitter cut by a straight blocker edge.
[[nodiscard]] double circularSegmentFraction(double u);

/// The exact visible fraction of builtin:plates' disk light (centred on (0, lightHeight, 0),
/// facing down) at world point `wsPoint` below the emitter plane: 1 − area(disk ∩ ∪ plates
/// projected from the point onto the emitter plane) / area(disk). A plate projects as its
/// square scaled by (H − p.y) / (h − p.y) about the point; plates not strictly between the
/// point and the emitter plane do not occlude.
[[nodiscard]] double platesVisibility(const PlatesGeometry& geometry, const glm::dvec3& wsPoint);

}  // namespace shadow::reference
