#include "closed_forms.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace shadow::reference {
namespace {

/// Antiderivative of sqrt(R² − x²) on [−R, R]: ½ (x sqrt(R² − x²) + R² asin(x / R)).
double halfChordIntegral(double x, double radius) {
    const double r2 = radius * radius;
    const double xc = std::clamp(x, -radius, radius);
    return 0.5 * (xc * std::sqrt(std::max(r2 - xc * xc, 0.0)) + r2 * std::asin(xc / radius));
}

/// ∫_a^b f(x) dx where f is either the constant `c` (isCircle false) or `sign`·sqrt(R² − x²).
double integratePiece(bool isCircle, double sign, double c, double a, double b, double radius) {
    if (!isCircle) return c * (b - a);
    return sign * (halfChordIntegral(b, radius) - halfChordIntegral(a, radius));
}

}  // namespace

Rect intersect(const Rect& a, const Rect& b) { return Rect{glm::max(a.min, b.min), glm::min(a.max, b.max)}; }

double diskRectArea(const glm::dvec2& center, double radius, const Rect& rect) {
    if (!(radius > 0.0) || rect.empty()) return 0.0;
    // Disk at the origin; integrate the length of the vertical chord inside [y0, y1] over x.
    const double x0 = std::max(rect.min.x - center.x, -radius);
    const double x1 = std::min(rect.max.x - center.x, radius);
    const double y0 = rect.min.y - center.y;
    const double y1 = rect.max.y - center.y;
    if (!(x0 < x1)) return 0.0;

    // Break points: where the circle's upper or lower half crosses y0 or y1. Between two of
    // them the chord's top is either y1 or the circle, its bottom y0 or the circle.
    std::vector<double> cuts{x0, x1};
    for (const double y : {y0, y1}) {
        if (std::abs(y) < radius) {
            const double xs = std::sqrt(radius * radius - y * y);
            for (const double x : {-xs, xs}) {
                if (x > x0 && x < x1) cuts.push_back(x);
            }
        }
    }
    std::sort(cuts.begin(), cuts.end());

    double area = 0.0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double a = cuts[k];
        const double b = cuts[k + 1];
        if (!(a < b)) continue;
        const double xm = 0.5 * (a + b);
        const double s = std::sqrt(std::max(radius * radius - xm * xm, 0.0));
        const bool topIsCircle = s < y1;
        const bool bottomIsCircle = -s > y0;
        const double top = topIsCircle ? s : y1;
        const double bottom = bottomIsCircle ? -s : y0;
        if (top <= bottom) continue;  // the chord misses [y0, y1] on this whole piece
        area +=
            integratePiece(topIsCircle, 1.0, y1, a, b, radius) - integratePiece(bottomIsCircle, -1.0, y0, a, b, radius);
    }
    return std::max(area, 0.0);
}

double diskRectUnionArea(const glm::dvec2& center, double radius, const std::vector<Rect>& rects) {
    assert(rects.size() <= 16);
    const std::size_t n = rects.size();
    double area = 0.0;
    for (std::size_t subset = 1; subset < (std::size_t{1} << n); ++subset) {
        Rect common{glm::dvec2(-HUGE_VAL), glm::dvec2(HUGE_VAL)};
        int members = 0;
        for (std::size_t k = 0; k < n; ++k) {
            if ((subset >> k) & 1u) {
                common = intersect(common, rects[k]);
                ++members;
            }
        }
        if (common.empty()) continue;
        const double sign = (members % 2 == 1) ? 1.0 : -1.0;
        area += sign * diskRectArea(center, radius, common);
    }
    return std::max(area, 0.0);
}

double circularSegmentFraction(double u) {
    u = std::clamp(u, -1.0, 1.0);
    return (std::acos(u) - u * std::sqrt(1.0 - u * u)) / std::numbers::pi;
}

double platesVisibility(const PlatesGeometry& geometry, const glm::dvec3& wsPoint) {
    const double emitterY = geometry.lightHeight;
    const double radius = geometry.lightRadius;
    if (!(radius > 0.0) || !(wsPoint.y < emitterY)) return 1.0;
    std::vector<Rect> shadows;
    for (const PlatesGeometry::Plate& plate : geometry.plates) {
        const double h = plate.center.y;
        if (!(h > wsPoint.y && h < emitterY)) continue;
        // q ↦ p + (q − p)·(H − p.y)/(h − p.y): the plate's square seen from p on the plane y = H.
        const double scale = (emitterY - wsPoint.y) / (h - wsPoint.y);
        const glm::dvec2 p(wsPoint.x, wsPoint.z);
        const glm::dvec2 c(plate.center.x, plate.center.z);
        const glm::dvec2 half(plate.halfSize);
        shadows.push_back(Rect{p + (c - half - p) * scale, p + (c + half - p) * scale});
    }
    const double blocked = diskRectUnionArea(glm::dvec2(0.0), radius, shadows);
    const double diskArea = std::numbers::pi * radius * radius;
    return std::clamp(1.0 - blocked / diskArea, 0.0, 1.0);
}

}  // namespace shadow::reference
