#include "shadow/emitter_radius.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadow {
namespace {

/// Distance along the unit ray `origin + t dir` (t >= 0) at which it leaves `box`; negative when
/// the ray misses it or the box lies behind the origin.
double exitDistance(const glm::dvec3& origin, const glm::dvec3& dir, const DAabb& box) {
    double enter = 0.0;
    double exit = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (origin[a] < box.min[a] || origin[a] > box.max[a]) return -1.0;
            continue;
        }
        const double t0 = (box.min[a] - origin[a]) / dir[a];
        const double t1 = (box.max[a] - origin[a]) / dir[a];
        enter = std::max(enter, std::min(t0, t1));
        exit = std::min(exit, std::max(t0, t1));
    }
    return enter <= exit ? exit : -1.0;
}

/// The half-width (m) of the penumbra cast from `point` onto the receiver behind it along the
/// light's ray, or a negative value when the ray meets no receiver.
double pointPenumbra(const LayerInputs& light, double emitterSize, const glm::dvec3& point, const DAabb& receivers) {
    const bool directional = light.type == LightType::Directional;
    const glm::dvec3 fromLight = point - light.pose.wsPosition;
    const double toBlocker = directional ? 0.0 : glm::length(fromLight);
    if (!directional && !(toBlocker > 0.0)) return -1.0;
    const glm::dvec3 dir = directional ? light.pose.wsDirection : fromLight / toBlocker;
    const double gap = exitDistance(point, dir, receivers);
    if (!(gap > 0.0)) return gap < 0.0 ? -1.0 : 0.0;  // (+0: the exit of a ray that starts on the bounds may be -0)
    if (directional) return gap * std::tan(emitterSize);
    // A spot's disk seen from the receiver: its area's equivalent disk (sg_apparentEmitterSize).
    const double size =
        light.type == LightType::Spot
            ? emitterSize * std::sqrt(std::clamp(glm::dot(dir, light.pose.wsDirection), 0.0, 1.0))
            : emitterSize;
    return gap * size / toBlocker;
}

/// The narrowest penumbra (m) one caster's box casts: the least over its corners, or a negative
/// value when no corner's ray meets a receiver, or when none meets one behind it (the whole box
/// lies on the receivers' far side, as a ground plane does: it casts onto nothing).
double casterPenumbra(const LayerInputs& light, double emitterSize, const DAabb& caster, const DAabb& receivers) {
    double narrowest = -1.0;
    double widest = 0.0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner((k & 1) != 0 ? caster.max.x : caster.min.x, (k & 2) != 0 ? caster.max.y : caster.min.y,
                                (k & 4) != 0 ? caster.max.z : caster.min.z);
        const double w = pointPenumbra(light, emitterSize, corner, receivers);
        if (w >= 0.0 && (narrowest < 0.0 || w < narrowest)) narrowest = w;
        widest = std::max(widest, w);
    }
    return widest > 0.0 ? narrowest : -1.0;
}

}  // namespace

double emitterFilterRadius(const LayerInputs& light, double emitterSize, const SceneGeometry& geometry,
                           std::span<const ShadowLayerPlan> layers, std::vector<double>& scratch) {
    scratch.clear();
    if (!(emitterSize > 0.0) || geometry.receivers.empty()) return 0.0;
    for (const ShadowLayerPlan& layer : layers) {
        // Both lists are in entity order: one walk through the scene's casters per layer.
        auto it = geometry.casters.begin();
        for (const Entity e : layer.casters) {
            it = std::lower_bound(it, geometry.casters.end(), e,
                                  [](const BoundedEntity& b, Entity x) { return b.entity < x; });
            if (it == geometry.casters.end()) break;
            if (it->entity != e) continue;
            const double w = casterPenumbra(light, emitterSize, it->bounds, geometry.receivers);
            if (w >= 0.0) scratch.push_back(w);
        }
    }
    if (scratch.empty()) return 0.0;
    const auto upper = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
    std::nth_element(scratch.begin(), upper, scratch.end());
    if (scratch.size() % 2 == 1) return *upper;
    return 0.5 * (*upper + *std::max_element(scratch.begin(), upper));  // the two middle ones' mean
}

}  // namespace shadow
