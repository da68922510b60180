// Per-light projections and layer fitting: directional cascades, spot frusta, cube faces.
// Pure CPU, in double precision.
#pragma once

#include <shadow/shadow_planner.h>

#include "core/camera.h"
#include "shadow/frustum.h"

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

/// A caster or receiver instance with its world bounds.
struct BoundedEntity {
    Entity entity;
    DAabb bounds;
};

/// A range of view depth (m along the camera's axis, the depth cascades split).
struct DepthInterval {
    double nearest = 0.0;
    double farthest = 0.0;
};

/// Where the receivers are visible on screen: the view depths of their boxes clipped to the
/// camera frustum (near plane to the far plane, at most `kMaxShadowReach`). Exact for the boxes
/// (not for the surfaces inside them, nor for occlusion); what directional cascades split.
struct VisibleReceivers {
    bool measured = false;  ///< set by `measureVisibleReceivers`, cleared by `gatherGeometry`
    /// One interval per receiver box that meets the frustum, in no particular order: a light
    /// whose shadowDistance ends inside a gap between receivers fits up to the last of them.
    std::vector<DepthInterval> boxes;
    DepthInterval all{1.0, 0.0};  ///< the union's bounds; nearest > farthest when none is visible
};

/// The scene's shadow-relevant geometry for one frame.
struct SceneGeometry {
    std::vector<BoundedEntity> casters;  ///< finite meshes with castShadows, entity order
    std::vector<DAabb> receiverBoxes;    ///< finite meshes with receiveShadows, each
    DAabb receivers;                     ///< union of `receiverBoxes`
    DAabb everything;                    ///< union of all finite meshes
    VisibleReceivers visible;            ///< `measureVisibleReceivers`, for directional lights
};

/// Collects casters and receivers from meshes with finite world transforms and triangles into
/// `out`, reusing its storage; `out.visible` is left unmeasured.
void gatherGeometry(const World& world, SceneGeometry& out);

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
};

/// The pose of a light's node; its direction is -z of `worldOrientation` (the reference tracer's
/// rule too).
LightPose lightPose(const WorldTransform& wt);

/// False when the light's range sphere misses the camera frustum (only lights with a range).
bool lightAffectsView(const Light& light, const LightPose& pose, const Frustum& cameraFrustum);

/// Fits the layers of a light into `layers`: cascades (directional), one frustum (spot), six
/// faces (point), each with the casters that fall in it. Every field of every layer is written
/// (`dirty` to its default); the storage of the layers' caster lists is reused, and each list
/// holds room for every caster of `geometry`, so that planning the same light again allocates
/// nothing.
void planLayers(const ShadowLightPlan& plan, const LightPose& pose, const CameraView& camera,
                const SceneGeometry& geometry, std::vector<ShadowLayerPlan>& layers);

/// Cascade split distances (m from the camera) for `splits.size() - 1` cascades over
/// [near, far]: lambda * logarithmic + (1 - lambda) * uniform (the "practical" scheme), written
/// to `splits`, first = near, last = far.
void cascadeSplits(double near, double far, double lambda, std::span<double> splits);

}  // namespace shadow
