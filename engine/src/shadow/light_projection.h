// Per-light projections and layer fitting: directional cascades, spot frusta, cube faces.
// Pure CPU, in double precision.
#pragma once

#include <shadow/shadow_planner.h>

#include "core/camera.h"
#include "shadow/frustum.h"

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

/// The scene's shadow-relevant geometry for one frame.
struct SceneGeometry {
    std::vector<BoundedEntity> casters;  ///< finite meshes with castShadows, entity order
    DAabb receivers;                     ///< union of finite meshes with receiveShadows
    DAabb everything;                    ///< union of all finite meshes
};

/// Collects casters and receivers from meshes with finite world transforms and triangles into
/// `out`, reusing its storage.
void gatherGeometry(const World& world, SceneGeometry& out);

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
