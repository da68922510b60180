// Where a light can reach on screen: the pixels a pass or a shadow mask must evaluate for it.
// Pure CPU (tested without GL).
#pragma once

#include <shadow/shadow_planner.h>

#include <glm/glm.hpp>

#include <compare>

namespace shadow {

/// A rectangle of pixels (or of a shadow map's texels), [x0, x1) x [y0, y1), GL's bottom-up rows.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    [[nodiscard]] bool empty() const { return x1 <= x0 || y1 <= y0; }
    [[nodiscard]] long long area() const { return empty() ? 0 : static_cast<long long>(x1 - x0) * (y1 - y0); }
    auto operator<=>(const PixelRect&) const = default;
};

/// The smallest rectangle holding `a` and `b` (an empty one adds nothing).
PixelRect unite(const PixelRect& a, const PixelRect& b);

/// The rectangle `a` and `b` share (empty when they share none).
PixelRect intersect(const PixelRect& a, const PixelRect& b);

/// `r` grown by `by` pixels on every side, within a `width` x `height` target.
PixelRect grownWithin(const PixelRect& r, int by, int width, int height);

/// The pixels of a `width` x `height` target that the box `box` covers through `clipFromWorld`:
/// the rectangle of its eight corners' projections, pixels whose centre it may hold rounded out;
/// the whole target where a corner lies at or behind the eye plane (w <= 0: no bounded image).
PixelRect projectedBounds(const glm::dmat4& clipFromWorld, const DAabb& box, int width, int height);

/// What the packing needs of the view to bound each light on screen.
struct ScreenView {
    glm::dmat4 clipFromWorld{1.0};
    int width = 1, height = 1;
    /// World bounds of everything drawn (empty: unknown). A light reaches only the part of its
    /// range inside them, which keeps the screen bounds of a light above a floor to the floor.
    DAabb wsGeometry;
};

/// The pixels light `plan` can reach: the screen rectangle of its range sphere's box (within
/// `view.wsGeometry` when known); the whole screen for a light without a range (directional, or
/// range 0) or whose box reaches behind the camera's eye plane.
PixelRect screenBounds(const ShadowLightPlan& plan, const ScreenView& view);

}  // namespace shadow
