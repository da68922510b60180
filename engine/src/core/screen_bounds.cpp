#include "core/screen_bounds.h"

#include <algorithm>
#include <cmath>

namespace shadow {

PixelRect screenBounds(const ShadowLightPlan& plan, const ScreenView& view) {
    const PixelRect whole{0, 0, view.width, view.height};
    if (plan.light.type == LightType::Directional || !(plan.light.range > 0.0f)) return whole;
    DAabb reach;
    reach.extend(plan.wsPosition - glm::dvec3(plan.light.range));
    reach.extend(plan.wsPosition + glm::dvec3(plan.light.range));
    if (!view.wsGeometry.empty()) {
        reach.min = glm::max(reach.min, view.wsGeometry.min);
        reach.max = glm::min(reach.max, view.wsGeometry.max);
        if (reach.empty()) return {};  // nothing drawn within its range
    }
    return projectedBounds(view.clipFromWorld, reach, view.width, view.height);
}

PixelRect projectedBounds(const glm::dmat4& clipFromWorld, const DAabb& box, int width, int height) {
    const PixelRect whole{0, 0, width, height};
    glm::dvec2 lo(1e300), hi(-1e300);
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 corner = box.corner(c);
        const glm::dvec4 clip = clipFromWorld * glm::dvec4(corner, 1.0);
        if (!(clip.w > 1e-9)) return whole;
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
    }
    auto pixel = [](double ndc, int size, bool up) {
        const double p = (ndc * 0.5 + 0.5) * size;
        return static_cast<int>(std::clamp(up ? std::ceil(p) : std::floor(p), 0.0, static_cast<double>(size)));
    };
    return {pixel(lo.x, width, false), pixel(lo.y, height, false), pixel(hi.x, width, true), pixel(hi.y, height, true)};
}

PixelRect unite(const PixelRect& a, const PixelRect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

PixelRect intersect(const PixelRect& a, const PixelRect& b) {
    return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

PixelRect grownWithin(const PixelRect& r, int by, int width, int height) {
    return intersect({r.x0 - by, r.y0 - by, r.x1 + by, r.y1 + by}, {0, 0, width, height});
}

}  // namespace shadow
