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

/// The penumbra cast from `point` onto the receiver behind it along the light's ray: its
/// half-width (m), negative when the ray meets no receiver, and the receiver's point.
struct PointPenumbra {
    double width = -1.0;
    glm::dvec3 receiver{0.0};
};

PointPenumbra pointPenumbra(const LayerInputs& light, double emitterSize, const glm::dvec3& point,
                            const DAabb& receivers) {
    const bool directional = light.type == LightType::Directional;
    const glm::dvec3 fromLight = point - light.pose.wsPosition;
    const double toBlocker = directional ? 0.0 : glm::length(fromLight);
    if (!directional && !(toBlocker > 0.0)) return {};
    const glm::dvec3 dir = directional ? light.pose.wsDirection : fromLight / toBlocker;
    const double gap = exitDistance(point, dir, receivers);
    if (gap < 0.0) return {};
    const glm::dvec3 receiver = point + std::max(gap, 0.0) * dir;
    if (!(gap > 0.0)) return {0.0, receiver};  // (+0: the exit of a ray that starts on the bounds may be -0)
    if (directional) return {gap * std::tan(emitterSize), receiver};
    // A spot's disk seen from the receiver: its area's equivalent disk (sg_apparentEmitterSize).
    const double size = light.type == LightType::Spot
                            ? emitterSize * std::sqrt(std::clamp(glm::dot(dir, light.pose.wsDirection), 0.0, 1.0))
                            : emitterSize;
    return {gap * size / toBlocker, receiver};
}

/// Calls `visit(box)` with the world bounds of every caster of `layers` (`geometry.casters`), and
/// `layer`, once per layer it is in.
template <typename Visit>
void forEachCaster(const SceneGeometry& geometry, std::span<const ShadowLayerPlan> layers, const Visit& visit) {
    for (const ShadowLayerPlan& layer : layers) {
        // Both lists are in entity order: one walk through the scene's casters per layer.
        auto it = geometry.casters.begin();
        for (const Entity e : layer.casters) {
            it = std::lower_bound(it, geometry.casters.end(), e,
                                  [](const BoundedEntity& b, Entity x) { return b.entity < x; });
            if (it == geometry.casters.end()) break;
            if (it->entity == e) visit(it->bounds, layer);
        }
    }
}

/// Corner `k` (0-7) of `box`.
glm::dvec3 corner(const DAabb& box, int k) {
    return {(k & 1) != 0 ? box.max.x : box.min.x, (k & 2) != 0 ? box.max.y : box.min.y,
            (k & 4) != 0 ? box.max.z : box.min.z};
}

/// The narrowest penumbra (m) one caster's box casts: the least over its corners, or a negative
/// value when no corner's ray meets a receiver, or when none meets one behind it (the whole box
/// lies on the receivers' far side, as a ground plane does: it casts onto nothing).
double casterPenumbra(const LayerInputs& light, double emitterSize, const DAabb& caster, const DAabb& receivers) {
    double narrowest = -1.0;
    double widest = 0.0;
    for (int k = 0; k < 8; ++k) {
        const double w = pointPenumbra(light, emitterSize, corner(caster, k), receivers).width;
        if (w >= 0.0 && (narrowest < 0.0 || w < narrowest)) narrowest = w;
        widest = std::max(widest, w);
    }
    return widest > 0.0 ? narrowest : -1.0;
}

/// The footprint (m) of one texel of `layer` at `point`; 0 behind a perspective layer's light.
double texelAt(const ShadowLayerPlan& layer, int mapSize, const glm::dvec3& point) {
    const double perAxial = 2.0 / (layer.clipFromLight[0][0] * mapSize);
    if (layer.orthographic) return perAxial;
    const double axial = -(layer.lightFromWorld * glm::dvec4(point, 1.0)).z;
    return axial > 0.0 ? perAxial * axial : 0.0;
}

}  // namespace

double emitterFilterRadius(const LayerInputs& light, double emitterSize, const SceneGeometry& geometry,
                           std::span<const ShadowLayerPlan> layers, std::vector<double>& scratch) {
    scratch.clear();
    if (!(emitterSize > 0.0) || geometry.receivers.empty()) return 0.0;
    forEachCaster(geometry, layers, [&](const DAabb& box, const ShadowLayerPlan&) {
        const double w = casterPenumbra(light, emitterSize, box, geometry.receivers);
        if (w >= 0.0) scratch.push_back(w);
    });
    if (scratch.empty()) return 0.0;
    const auto upper = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
    std::nth_element(scratch.begin(), upper, scratch.end());
    if (scratch.size() % 2 == 1) return *upper;
    return 0.5 * (*upper + *std::max_element(scratch.begin(), upper));  // the two middle ones' mean
}

double widestPenumbraTexels(const LayerInputs& light, double emitterSize, const SceneGeometry& geometry,
                            std::span<const ShadowLayerPlan> layers) {
    if (!(emitterSize > 0.0) || geometry.receivers.empty()) return 0.0;
    double widest = 0.0;
    forEachCaster(geometry, layers, [&](const DAabb& box, const ShadowLayerPlan& layer) {
        for (int k = 0; k < 8; ++k) {
            const PointPenumbra p = pointPenumbra(light, emitterSize, corner(box, k), geometry.receivers);
            const double texel = texelAt(layer, light.mapSize, p.receiver);
            if (p.width > 0.0 && texel > 0.0) widest = std::max(widest, p.width / texel);
        }
    });
    return widest;
}

}  // namespace shadow
