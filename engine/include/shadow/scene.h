// Scenes and the CPU systems that run on them each frame.
//
// Frame order (fixed): animate -> updateTransforms -> ShadowSystem::prepare ->
// ShadowSystem::render -> Renderer::render.
//
// Nothing declared here throws on bad input (files, settings, NaN transforms): loaders return an
// `Error`, systems skip or clamp and report. Only running out of memory throws (std::bad_alloc).
#pragma once

#include <shadow/components.h>
#include <shadow/ecs.h>
#include <shadow/result.h>
#include <shadow/warnings.h>

#include <string>
#include <vector>

namespace shadow {

/// One glTF animation of a loaded scene, kept whether it plays or not, so that
/// `playAnimation` switches clips without loading the file again.
struct AnimationClip {
    /// One entity the clip moves.
    struct Target {
        Entity entity;
        std::vector<AnimationChannel> channels;  ///< this clip's channels of the entity
        Transform rest;                          ///< the entity's transform as loaded
        std::vector<float> restWeights;          ///< its `Morph::weights` as loaded (none without)
    };
    std::string name;       ///< the file's name for it, or `animation<i>` when it has none
    double duration = 0.0;  ///< its last key time (s)
    std::vector<Target> targets;
};

/// A loaded or built scene: the world plus the orderings the outputs rely on.
struct Scene {
    World world;
    std::string name;
    /// Light instances in glTF node order; index `i` names `visibility_<i>.exr`.
    std::vector<Entity> lights;
    /// Camera instances in glTF node order; `--camera N` picks one.
    std::vector<Entity> cameras;
    /// Longest animation clip that plays (s); 0 when nothing keyframed plays.
    double animationDuration = 0.0;
    /// The file's animations, in file order (none in a built-in scene).
    std::vector<AnimationClip> clips;
    /// Indices into `clips` of the clips that play: the first alone by default, every one under
    /// `all` (see `playAnimation`).
    std::vector<std::size_t> playing;
    /// What the loader let pass, each naming the file and the element: content the module
    /// drops (`UnsupportedFeature`), graph and mesh repairs (`SceneNodeNotRoot`,
    /// `MissingTexcoord`), lights and transforms (`UnsupportedLight`, `DegenerateTransform`),
    /// settings (`UnknownSetting`, and `ShadowSettingsIgnored` under lenient `GltfLoadOptions`).
    /// Playing appends what the content does once per entity (`MorphTargetsDropped`, by
    /// `FrameRunner::runFrame`).
    std::vector<Warning> warnings;
};

/// How `loadGltf` treats a light's or mesh node's `extras.shadow` that does not parse (a
/// string where a number is due, an unknown technique, a negative mapSize, ...).
struct GltfLoadOptions {
    /// true (the default, and the CLIs): the load fails with one message naming the element.
    /// false (a game that must show what it can): that `extras.shadow` object is ignored, the
    /// light or mesh keeps the documented defaults (a light: hard shadows, mapSize 1024), and a
    /// `ShadowSettingsIgnored` warning goes to `Scene::warnings`. Either way one light's
    /// settings never affect another light. Errors outside `extras.shadow` always fail the load.
    bool strictShadowSettings = true;
    /// Which of the file's animations plays, as `playAnimation` takes it: empty (the default)
    /// the first; `all` every one at once; a clip's index in the file (`2`) or its name. A name
    /// or index the file lacks fails the load with one message naming it and listing the clips.
    std::string animation;
};

/// Makes the clips `choice` names play, replacing the `Animation` of every entity a clip of
/// the scene moves: empty, the first clip; `all`, every clip (an entity several clips move
/// loops with the longest of them); digits, the clip of that index in `Scene::clips`;
/// anything else, the clip of that name (a clip named `all` or by digits is chosen by its
/// index). An entity no playing clip moves gets its transform as loaded back. Sets
/// `Scene::playing` and `animationDuration`. An index or name the scene lacks is an error
/// naming it and listing the clips, and leaves the scene as it was. Never throws.
[[nodiscard]] Status playAnimation(Scene& scene, const std::string& choice);

/// Animation system: writes local `Transform`s from `Animation` and `ProceduralMotion` at
/// absolute time `t` (s). Keyframed clips loop; time is kept in double so `t = 1e7` s works.
/// Non-finite or negative `t` is treated as 0.
void animate(World& world, double t);

/// Counters of the transform system for one frame.
struct TransformStats {
    int updated = 0;  ///< entities with a world matrix
    int moved = 0;    ///< of those, moved this frame
    /// Skipped because their matrix is not finite or reaches beyond `kMaxWorldCoordinate`.
    int nonFinite = 0;
    /// The `nonFinite` entities (their own matrix or an ancestor's has a NaN or Inf, or they
    /// reach beyond the world), in the order visited; empty, and allocating nothing, otherwise.
    std::vector<Entity> skipped;
};

/// Transform system: world matrices parent-first, world bounds of meshes, moved flags.
/// An entity whose matrix is not finite is flagged (`WorldTransform::finite = false`) and so
/// are its descendants; so is one placed (a mesh: with a vertex) beyond `kMaxWorldCoordinate`.
/// It does not affect other entities.
TransformStats updateTransforms(World& world);

/// Appends one `NonFiniteTransform` warning per entity of `stats.skipped`, in that order; the
/// element is the entity's `Name`, or `entity <index>` without one.
void reportSkippedTransforms(const World& world, const TransformStats& stats, std::vector<Warning>& warnings);

/// Appends one `MorphTargetsDropped` warning for each entity whose `Morph::truncated` is set
/// (by the last `updateTransforms`) and that was not reported before, and marks it reported:
/// once per entity, whatever the frames after. The element is the entity's `Name`, or
/// `entity <index>` without one. `FrameRunner::runFrame` calls it into `Scene::warnings`.
void reportTruncatedMorphs(World& world, std::vector<Warning>& warnings);

/// The entity's world orientation as orthonormal, right-handed axes (columns x, y, z; lights
/// and cameras look along -z with +y up): the normalised rotation of `worldFromLocal` where that
/// matrix is regular, else (a scale of 0 in the chain) `WorldTransform::rotation`, the chain's
/// rotations without their scales. One rule for the renderer, the shadow planner and the
/// reference tracer, so that they agree on where a degenerate light points.
[[nodiscard]] glm::dmat3 worldOrientation(const WorldTransform& wt);

/// Camera pose and projection for one frame, derived from a camera entity.
struct CameraView {
    glm::dvec3 wsPosition{0.0};
    glm::dmat4 viewFromWorld{1.0};
    float yfov = 0.8f;
    float aspect = 1.0f;
    float znear = 0.05f;
    float zfar = 500.0f;
    /// The image's size in pixels (0: unknown). The shadow planner weighs a PCF light's pixels on
    /// screen against the map texels its min/max pyramid would read
    /// (`ShadowLimits::pyramidTexelsPerPixel`); unknown, it always builds the pyramid.
    int pixelWidth = 0, pixelHeight = 0;
    friend bool operator==(const CameraView&, const CameraView&) = default;
};

/// The view of camera `camera` (an entity with `Camera` and `WorldTransform`) for an image of
/// the given aspect ratio (used when the camera's own is 0). Scale in the node is ignored.
[[nodiscard]] CameraView makeCameraView(const World& world, Entity camera, float imageAspect);

/// A camera looking at the scene's bounds from above and to the side; for scenes without one.
[[nodiscard]] Entity addDefaultCamera(Scene& scene);

/// Loads `SCENE` as the CLI names it: a `.gltf`/`.glb` path or `builtin:NAME`. Never throws: bad
/// input is an error value naming the file and element.
[[nodiscard]] Result<Scene> loadScene(const std::string& spec, const GltfLoadOptions& options = {});

/// Loads a glTF 2.0 file (`.gltf` with embedded or external buffers, or `.glb`). Never throws:
/// a bad file is an error value naming the file and element.
[[nodiscard]] Result<Scene> loadGltf(const std::string& path, const GltfLoadOptions& options = {});

/// Names of the built-in procedural scenes.
[[nodiscard]] std::vector<std::string> builtinSceneNames();

/// The geometry of builtin:plates, the scene whose visibility has a closed form: a disk light of
/// radius `lightRadius` at height `lightHeight` facing straight down (a spot light), square
/// zero-thickness plates parallel to a receiver plane at y = 0. The visible fraction of the
/// emitter at a receiver point is 1 - area(disk ∩ union of the plates projected from the point
/// onto the emitter plane) / area(disk).
struct PlatesGeometry {
    struct Plate {
        glm::dvec3 center{0.0};  ///< the plate lies in the plane y = center.y
        double halfSize = 0.0;   ///< half the edge of the square (axis aligned)
    };
    double lightHeight = 4.0;
    double lightRadius = 0.4;
    double receiverHalfSize = 4.0;
    std::vector<Plate> plates = {{{-1.0, 1.0, 0.0}, 0.5}, {{1.1, 2.0, 0.4}, 0.35}};
};

/// builtin:plates (see `PlatesGeometry`).
[[nodiscard]] Scene makePlatesScene();

/// Builds a built-in scene by name (without the `builtin:` prefix).
[[nodiscard]] Result<Scene> makeBuiltinScene(const std::string& name);

}  // namespace shadow

namespace shadow {

// ---- Building scenes in code (built-in scenes, tests, games) ----

/// An axis-aligned box of the given half extents centred on the origin, flat normals.
[[nodiscard]] std::shared_ptr<MeshData> makeBoxMesh(const glm::vec3& halfExtents);
/// A square in the XZ plane (normal +Y), `halfSize` from the centre, `cells` x `cells` quads.
[[nodiscard]] std::shared_ptr<MeshData> makePlaneMesh(float halfSize, int cells = 1);
/// A UV sphere with smooth normals.
[[nodiscard]] std::shared_ptr<MeshData> makeSphereMesh(float radius, int segments = 32, int rings = 16);

/// Reads a Wavefront OBJ (positions and polygon faces; smooth normals are computed).
[[nodiscard]] Result<std::shared_ptr<MeshData>> loadObjMesh(const std::string& path);

/// Where Debian's glmark2-data installs the Stanford bunny (used by builtin:bunny).
inline constexpr const char* kBunnyObjPath = "/usr/share/glmark2/models/bunny.obj";

/// The rotation that makes a node's -Z point along unit `direction` (robust for straight up/down).
[[nodiscard]] glm::dquat rotationLookingAlong(const glm::dvec3& direction);

/// Adds a mesh instance with a name, transform and material; returns its entity.
Entity addMeshInstance(World& world, const std::string& name, std::shared_ptr<const MeshData> mesh,
                       const Transform& transform, const Material& material = {});

/// Adds a light at `position` shining along `direction`, with `shadow` settings (technique None
/// adds no `Shadow` component), and appends it to `scene.lights`.
Entity addLight(Scene& scene, const std::string& name, const Light& light, const Shadow& shadow,
                const glm::dvec3& position, const glm::dvec3& direction);

/// Adds a camera at `position` looking at `target`, and appends it to `scene.cameras`.
Entity addCamera(Scene& scene, const std::string& name, const Camera& camera, const glm::dvec3& position,
                 const glm::dvec3& target);

}  // namespace shadow
