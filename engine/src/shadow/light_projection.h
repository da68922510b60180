// Per-light projections and layer fitting: directional cascades, spot frusta, cube faces.
// Pure CPU, in double precision.
#pragma once

#include <shadow/shadow_planner.h>

#include "core/camera.h"
#include "shadow/frustum.h"
#include "shadow/scene_geometry.h"

#include <optional>
#include <span>
#include <vector>

namespace shadow {

/// Largest spot half-angle a shadow map can cover (rad); wider cones are clamped (85 degrees).
inline constexpr float kMaxSpotHalfAngle = 1.4835298642f;

/// Farthest a shadow layer reaches (m), the documented range of `Light::range` and
/// `Shadow::shadowDistance`: far planes, a sun's reach and the width and depth of its layers
/// around the camera are clamped to it, so every number handed to the GPU is a finite float
/// however large the scene's coordinates (a file may place a mesh at 1e38 m; the fuzzer did).
inline constexpr double kMaxShadowReach = 1e7;

/// Measures `geometry.visible` for `camera` once per `gatherGeometry` (later calls return at
/// once): each receiver box clipped against the camera frustum, without allocating once the
/// storage has grown to the receivers' count. Call before planning directional lights; without
/// it their cascades fall back to the distances to the receivers' bounding box.
void measureVisibleReceivers(const CameraView& camera, SceneGeometry& geometry);

/// The view-depth range of the receivers visible within `reach` (m of view depth), if any.
[[nodiscard]] std::optional<DepthInterval> visibleDepthRange(const VisibleReceivers& visible, double reach);

/// Where a light is and where it points, in world space.
struct LightPose {
    glm::dvec3 wsPosition{0.0};
    glm::dvec3 wsDirection{0.0, 0.0, -1.0};  ///< unit, the node's -Z
    friend bool operator==(const LightPose&, const LightPose&) = default;
};

/// The pose of a light's node; its direction is -z of `worldOrientation` (the reference tracer's
/// rule too).
LightPose lightPose(const WorldTransform& wt);

/// False when the light's range sphere misses the camera frustum (only lights with a range).
bool lightAffectsView(const Light& light, const LightPose& pose, const Frustum& cameraFrustum);

/// Everything of a light that `planLayers` reads besides the camera and the geometry: the same
/// inputs over the same geometry (and, for a directional light, the same camera) give the same
/// layers.
struct LayerInputs {
    LightType type = LightType::Point;
    LightPose pose;
    int mapSize = 1;                  ///< texels allocated (`ShadowLightPlan::mapSize`)
    float range = 0.0f;               ///< point, spot: `Light::range` (0: fitted to the scene)
    float outerConeAngle = 0.0f;      ///< spot: `Light::outerConeAngle`
    float nearPlane = 0.0f;           ///< point, spot: `Shadow::nearPlane` (0: fitted per layer)
    int cascades = 1;                 ///< directional: `Shadow::cascades`
    float cascadeSplitLambda = 0.0f;  ///< directional: `Shadow::cascadeSplitLambda`
    float shadowDistance = 0.0f;      ///< directional: `Shadow::shadowDistance`
    /// VSSM (FilterChainKind::SummedMoments in filter_chain.h): the layers' `momentScale` is
    /// fitted to their casters. (plan.technique() is None until the layers exist.)
    bool summedMoments = false;
    /// A technique whose map carries a moment chain (VSM, VSSM, MSM-soft): each layer also lists
    /// the receivers that do not cast (`ShadowLayerPlan::backgrounds`), drawn behind its casters.
    bool backgrounds = false;
    /// A length the scene defines and keeps (the camera's far plane): the layers' extents, depth
    /// ranges and far planes are rounded (for stability while things move) to power-of-two
    /// multiples of it, so that the same scene at another scale gets the same layers at that scale.
    double lengthUnit = 1.0;
    friend bool operator==(const LayerInputs&, const LayerInputs&) = default;
};

/// The layer inputs of the clamped `plan` at `pose`, rounding to multiples of `lengthUnit`.
[[nodiscard]] LayerInputs layerInputs(const ShadowLightPlan& plan, const LightPose& pose, double lengthUnit = 1.0);

/// Fits the layers of a light into `layers`: cascades (directional), one frustum (spot), six
/// faces (point), each with the casters that fall in it. Every field of every layer is written
/// (`dirty` to its default); the storage of the layers' caster lists is reused, and each list
/// holds room for every caster of `geometry`, so that planning the same light again allocates
/// nothing. With `follow`, `layers` must be what `planLayers` gave for the same `light` over
/// the geometry of the last `gatherGeometry`: a layer whose frustum comes out the same then
/// updates its caster list by the changed casters (`SceneGeometry::changed`) that meet it,
/// instead of testing every caster; the layers come out the same either way.
void planLayers(const LayerInputs& light, const CameraView& camera, const SceneGeometry& geometry, bool follow,
                std::vector<ShadowLayerPlan>& layers);

/// A fixed filter radius at the receiver: `metres`, at least `texels` of the receiver's texel
/// footprint (`ShadowLightPlan::pcfRadiusMetres`; `texels` is 0 for a radius set in metres).
struct FilterRadius {
    double metres = 0.0;
    double texels = 0.0;
};

/// Sets each layer's `chainFirstLevel` and `chainLastLevel` (ShadowLayerPlan): for a VSM light
/// the lowest level of its moment chain a lookup reads, `radius` at the receiver (at most
/// `maxFilterTexels`) in the largest texel a receiver of the layer can have (at the farthest
/// corner of the scene's known bounds for a perspective layer), at least 1 (its lookups take level
/// 0 from the depth map), and the highest, the level above log2 of `radius` in the smallest texel
/// (a cascade's one texel; at the nearest point of the bounds, seen at the frustum's corner),
/// within `levels`; for MSM-soft 1 and the top; 0 and the top for every other light.
void fitChainLevels(const LayerInputs& light, ShadowTechnique technique, FilterRadius radius, double maxFilterTexels,
                    int levels, const SceneGeometry& geometry, std::span<ShadowLayerPlan> layers);

/// Whether `planLayers(light, camera, geometry, layers)` would give `layers` back, field for
/// field, when `layers` is what it gave for the same `light` over the geometry of the last
/// `gatherGeometry` and, with `cameraMoved` false, the same camera. A directional light's
/// layers hold when neither the camera nor anything of the geometry changed; a point or spot
/// light's when no changed caster (`SceneGeometry::changed`) meets one of its layers' frusta or,
/// where its near planes are fitted, the widest frusta they are fitted in (and, without a range,
/// the scene's bounds stayed). Its cost grows with the changed casters near the light, not with
/// the scene.
[[nodiscard]] bool layersHold(const LayerInputs& light, bool cameraMoved, const SceneGeometry& geometry,
                              std::span<const ShadowLayerPlan> layers);

/// Cascade split distances (m from the camera) for `splits.size() - 1` cascades over
/// [near, far]: lambda * logarithmic + (1 - lambda) * uniform (the "practical" scheme), written
/// to `splits`, first = near, last = far.
void cascadeSplits(double near, double far, double lambda, std::span<double> splits);

}  // namespace shadow
