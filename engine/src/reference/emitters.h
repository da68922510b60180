// Emitter shapes as docs/output_contract.md defines them, and stratified samples over them.
//
//   spot:        a disk of `Light::radius` centred on the light, perpendicular to the spot axis;
//   point:       a sphere of `Light::radius`, seen from a point as the disk of its silhouette;
//   directional: the cone of half-angle `Light::angularRadius` around the direction towards
//                the light.
// A zero size is a single ray to the light's centre (or along its direction).
//
// Visibility is the *area* fraction of the disk (spot, point) or the *solid-angle* fraction of
// the cone (directional) that a point sees unoccluded: samples are uniform in that measure.
// Samples come from correlated multi-jittered sampling (A. Kensler, "Correlated Multi-Jittered
// Sampling", Pixar Technical Memo 13-01, 2013): for any count N, stratified on a
// ⌊√N⌋ × ⌈N/⌊√N⌋⌉ grid and on N rows and N columns, then mapped to the disk by the
// concentric map (P. Shirley, K. Chiu, "A Low Distortion Map Between Disk and Square", 1997),
// which keeps the strata compact.
#pragma once

#include <shadow/components.h>
#include <shadow/ecs.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

namespace shadow::reference {

/// One light's emitter in world space.
struct Emitter {
    LightType type = LightType::Point;
    glm::dvec3 wsPosition{0.0};  ///< spot/point: centre of the disk or sphere
    /// Unit vector from the scene towards the light: directional, the cone's axis; spot, minus
    /// the spot axis (the disk's normal, facing the lit side). Unused for point lights.
    glm::dvec3 wsTowardLight{0.0, 1.0, 0.0};
    double radius = 0.0;         ///< spot/point (m), clamped to [0, 1e3]
    double angularRadius = 0.0;  ///< directional (rad), clamped to [0, 0.2]
    bool clamped = false;        ///< a size was outside its documented range

    /// True for a hard (zero-size) emitter: one ray per point.
    [[nodiscard]] bool isPointLike() const;
};

/// The emitter of light entity `light` (needs `Light` and a finite `WorldTransform`), or
/// nullopt. The light looks along its node's −Z; scale is ignored.
[[nodiscard]] std::optional<Emitter> emitterOf(const World& world, Entity light);

/// A shadow ray's aim from a point: unit direction and the distance to the emitter sample
/// (infinity for directional lights). `distance` is 0 when the point is inside a point light's
/// sphere or on the emitter itself: such a ray cannot be occluded.
struct ShadowRayAim {
    glm::dvec3 direction{0.0, 1.0, 0.0};
    double distance = 0.0;
};

/// Shadow ray towards the emitter sample that `disk` (a point of the unit disk) picks, seen
/// from `wsPoint`. For a point light the disk is the sphere's silhouette: radius
/// r·sqrt(1 − (r/d)²) at distance d − r²/d from the point, d the distance to the centre. Its
/// rim is the circle where the tangent cone touches the sphere, so the set of directions is
/// exactly the sphere's; samples are uniform over that disk's area (docs/output_contract.md: "seen from any
/// point as a disk facing it"), which differs from uniform solid angle by O((r/d)²).
[[nodiscard]] ShadowRayAim aimAtEmitter(const Emitter& emitter, const glm::dvec3& wsPoint, const glm::dvec2& disk);

/// Sample `index` of `count` of the correlated multi-jittered pattern `pattern`, in [0,1)².
[[nodiscard]] glm::dvec2 multiJitteredSample(std::uint32_t index, std::uint32_t count, std::uint32_t pattern);

/// Shirley–Chiu concentric map of [0,1)² onto the unit disk (area preserving).
[[nodiscard]] glm::dvec2 concentricDisk(const glm::dvec2& square);

/// A well-mixed 32-bit pattern id for (seed, pixel, light), so every pixel and light gets its
/// own independent sample pattern, reproducible for a seed whatever the thread count.
[[nodiscard]] std::uint32_t patternId(std::uint32_t seed, std::uint64_t pixel, std::uint32_t light);

}  // namespace shadow::reference
