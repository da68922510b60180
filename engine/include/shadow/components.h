// The scene's components: plain structs, no registration, no GL types.
//
// Conventions (docs/output_contract.md): metres, seconds, radians; +Y up, right-handed; lights and
// cameras look along their node's -Z.
#pragma once

#include <shadow/ecs.h>
#include <shadow/math.h>
#include <shadow/shared_constants.h>
#include <shadow/techniques.h>

#include <glm/gtc/type_precision.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadow {

/// A readable name, used for GPU labels (`Shadow/<name>/layer<N>`) and messages.
struct Name {
    std::string value;
};

/// Local placement relative to `parent` (or the world when `parent` is null). Double precision
/// so that large coordinates keep their precision until made camera-relative.
struct Transform {
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z
    glm::dvec3 scale{1.0};
    Entity parent;
};

/// Largest world coordinate (m) an entity may reach and still be drawn. Beyond it, float
/// arithmetic relative to the camera keeps no precision worth drawing (a float spaces 1e9 by
/// 64 m) and products of such values overflow, so the transform system treats the entity as
/// non-finite: skipped by every pass and reported. A file may well place a mesh at 1e38 m.
inline constexpr double kMaxWorldCoordinate = 1e9;

/// Whether every coordinate of `p` lies within `kMaxWorldCoordinate` (false for NaN).
[[nodiscard]] inline bool insideWorld(const glm::dvec3& p) {
    return std::abs(p.x) <= kMaxWorldCoordinate && std::abs(p.y) <= kMaxWorldCoordinate &&
           std::abs(p.z) <= kMaxWorldCoordinate;
}

/// Written by `updateTransforms`; read by everything after it.
struct WorldTransform {
    glm::dmat4 worldFromLocal{1.0};
    /// The matrix differs from the last `updateTransforms`' (or the entity is new). It speaks of
    /// one update only: a consumer that may miss updates compares `version` instead.
    bool movedThisFrame = true;
    /// Counts the updates that moved the entity (its matrix, `finite`, or a skinned mesh's pose
    /// changed): whoever remembers the version it last saw knows whether the entity moved since,
    /// however many updates ran in between (a fixed-step simulation updates more often than the
    /// game renders). Starts at 1 with the entity's first update.
    std::uint64_t version = 0;
    /// False when the matrix has a NaN or Inf, or places the entity (a mesh: any of its
    /// vertices) beyond `kMaxWorldCoordinate`; such entities are skipped by rendering.
    bool finite = true;
    /// The rotations of the parent chain composed, scale ignored: what `worldOrientation` takes
    /// where `worldFromLocal` is singular (a scale of 0 somewhere in the chain).
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
};

/// Triangle mesh on the CPU. Shared between mesh instances; uploaded once by the renderer.
struct MeshData {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // one per position
    /// One per position or none: glTF's TEXCOORD_0 ((0,0) the first texel of the image's first
    /// row). Read by a material's `baseColorTexture`; without them it samples texel (0,0).
    std::vector<glm::vec2> texcoords;
    /// One per position or none: the material's second texture-coordinate set (glTF's
    /// TEXCOORD_n of a map that reads another set than the base colour's), read by the maps whose
    /// `MaterialMap::texcoordSet` is 1.
    std::vector<glm::vec2> texcoords1;
    /// One per position or none: the tangent frame of a normal map, xyz the unit tangent (along
    /// +u of the normal map's set) and w = +-1 the handedness, the bitangent being
    /// w * cross(normal, tangent) (glTF's TANGENT, or `computeTangents`).
    std::vector<glm::vec4> tangents;
    std::vector<std::uint32_t> indices;  // triangle list
    Aabb bounds;                         // of `positions`
    /// Skinning (a `Skin` on the instance): one per position or none. `joints` index the
    /// instance's `Skin::joints`; `weights` are non-negative and sum to 1 (the loader
    /// normalises them).
    std::vector<glm::u16vec4> joints;
    std::vector<glm::vec4> weights;
    /// Per joint index, the bounds of the positions it moves (weight > 0), in the mesh's own
    /// space (`computeJointBounds`): what a pose's bounds are computed from.
    std::vector<Aabb> jointBounds;
    /// Morph targets (glTF `primitives[i].targets`), which an instance's `Morph` weights: per
    /// target, a displacement of every position, target-major (target k's at [k * n, (k + 1) * n)
    /// for n positions). `morphNormals` and `morphTangents` (xyz of TANGENT) hold the same layout,
    /// or are empty when no target moves them.
    std::size_t morphTargets = 0;
    std::vector<glm::vec3> morphPositions;
    std::vector<glm::vec3> morphNormals;
    std::vector<glm::vec3> morphTangents;
    /// Per target, the bounds of its position displacements (`computeMorphBounds`): what a
    /// weighted shape's bounds are computed from.
    std::vector<Aabb> morphBounds;
    /// Every edge, matched by position, is shared by exactly two triangles: a watertight surface
    /// (see `computeClosed`). The second-depth modes (`DepthMode`) need closed casters.
    bool closed = false;
    /// Closed, and every edge met once in each direction (its triangles wound alike), each
    /// connected part counter-clockwise seen from outside (a positive volume). A ray from
    /// outside meets such a surface first on a front face, so a depth-only pass whose eye is
    /// outside its bounds stores the same nearest depths with its back faces culled, drawing
    /// about half its fragments (see `computeClosed`).
    bool solid = false;
    /// A closed mesh's mean thickness, 2 x volume / area (mesh units; see `computeClosed`): a
    /// slab's thickness, two thirds of a sphere's radius. 0 for an open mesh. What tells whether
    /// a distance field of some voxel holds the mesh's inside at all.
    float thickness = 0.0f;
    /// Every vertex lies in one plane (to 1e-5 of the bounds' diagonal): a sheet, which a
    /// distance field holds exactly (an open mesh's field is unsigned).
    bool planar = false;
};

/// Computes `bounds` from `positions`.
void computeBounds(MeshData& mesh);
/// Computes `jointBounds` from `positions`, `joints` and `weights` (empty without them).
void computeJointBounds(MeshData& mesh);
/// Computes `morphBounds` from `morphPositions`.
void computeMorphBounds(MeshData& mesh);
/// Computes `closed`, `solid`, `thickness` and `planar`: vertices at the same position count as one (a mesh with flat
/// normals repeats them per face), degenerate triangles are ignored, and every remaining edge
/// must belong to exactly two triangles (`solid`: one in each direction, and each connected
/// part of positive volume).
void computeClosed(MeshData& mesh);
/// The triangles of `indices` (three per triangle, each below `vertexCount`) in an order that
/// reuses recently transformed vertices: T. Forsyth's "Linear-Speed Vertex Cache Optimisation"
/// (2006), a greedy walk scoring each vertex by its place in a 32-entry LRU cache and by how few
/// triangles it has left. Each triangle keeps its own three indices in their order (winding and
/// provoking vertex unchanged); only the triangles' order changes. `indices` is returned as it is
/// when it is not whole triangles or an index is out of range. The mesh cache uploads every mesh
/// in this order. What it saves on a rasteriser that shades a vertex once per batch of indices:
/// llvmpipe's model (tests/scene/vertex_cache_order_test.cpp) shades the Stanford bunny's 69666
/// triangles as 1.88 vertices a triangle in their file's order, 0.64 in this one, which took
/// 30 ms to compute.
[[nodiscard]] std::vector<std::uint32_t> vertexCacheOrder(const std::vector<std::uint32_t>& indices,
                                                          std::size_t vertexCount);
/// Replaces a mesh by one with flat normals: every triangle gets its own three vertices (its
/// texture coordinates follow; its tangents are dropped, as glTF asks of a mesh without normals).
void makeFlatNormals(MeshData& mesh);
/// Computes `tangents` from `positions`, `normals` and texture-coordinate set `set` (0:
/// `texcoords`, 1: `texcoords1`), as MikkTSpace does for vertices that are not split: per
/// triangle corner the tangent and bitangent of the uv mapping, projected onto the vertex
/// normal's plane, normalised and weighted by the corner's angle; summed per vertex; the
/// handedness from the bitangent's side. A vertex whose triangles give no direction (no uv
/// change) gets any unit vector perpendicular to its normal. Leaves `tangents` empty when the
/// set or the normals are missing.
void computeTangents(MeshData& mesh, int set);

/// A drawable mesh instance. `castShadows`/`receiveShadows` come from glTF
/// `extras.shadow = {"cast": bool, "receive": bool}`.
struct Mesh {
    std::shared_ptr<const MeshData> data;
    bool castShadows = true;
    bool receiveShadows = true;
};

/// World-space bounds of a mesh instance, written by `updateTransforms`.
struct WorldBounds {
    DAabb box;
};

/// An 8-bit RGBA image on the CPU, a material's texture: colour in sRGB, alpha linear. Shared
/// by the materials that use it; uploaded once (with mipmaps) by the renderer.
struct Texture {
    enum class Wrap : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes, the image's first row first
    Wrap wrapS = Wrap::Repeat;
    Wrap wrapT = Wrap::Repeat;
};

/// How a material's alpha (`alpha` times the texture's) is used, as glTF's `alphaMode`.
enum class AlphaMode : std::uint8_t {
    Opaque,  ///< alpha ignored
    Mask,    ///< a cut-out: nothing where alpha < `alphaCutoff`, in every pass and the reference
    Blend,   ///< drawn as a cut-out at `alphaCutoff` (0.5 from glTF): the module does not blend
};

/// The affine map a material map applies to its texture coordinates before sampling: glTF's
/// KHR_texture_transform, uv' = offset + rotate(rotation) * (scale * uv), as a 3x2 matrix (columns:
/// the images of u and v, then the offset). Rotation in radians, turning +u towards -v (the
/// extension's sense).
[[nodiscard]] glm::mat3x2 textureTransform(const glm::vec2& offset, float rotation, const glm::vec2& scale);

/// A material texture other than the base colour: the image, the mesh's texture-coordinate set
/// it reads and the transform applied to it.
struct MaterialMap {
    std::shared_ptr<const Texture> texture;  ///< none: the map is not read
    int texcoordSet = 0;                     ///< 0: `MeshData::texcoords`, 1: `MeshData::texcoords1`
    glm::mat3x2 uvTransform{1.0f};           ///< `textureTransform`; identity by default
};

/// A material of glTF's metallic-roughness model: Lambert diffuse and a GGX specular lobe
/// (shaders/lighting.glsl), with the base-colour texture and alpha modes. A material with any
/// map (`usesMaps`) is shaded from glTF's own parameters per pixel: base colour = `baseColor` x
/// texture, metallic = `metallic` x the metallic-roughness map's B, roughness = `roughness` x
/// its G, diffuse = base x (1 - metallic), specular = mix(0.04, base, metallic); without maps
/// from `albedo`, `specular` and `shininess` (which the glTF loader derives from the same
/// parameters, and a game may set freely).
struct Material {
    glm::vec3 albedo{0.8f};     ///< diffuse reflectance, linear RGB in [0,1]
    glm::vec3 specular{0.04f};  ///< specular reflectance, linear RGB in [0,1]
    /// Roughness, as the exponent n of the Blinn-Phong lobe that matches the GGX lobe of
    /// alpha^2 = 2 / (n + 2) (glTF roughness r: n = 2 / r^4 - 2), [1, 4096].
    float shininess = 32.0f;
    /// Multiplies `albedo`, and `specular` by `metallic` (metals reflect their colour), per pixel.
    /// Read through `MeshData::texcoords` untransformed: the glTF loader bakes the base colour's
    /// KHR_texture_transform into that set (and the inverse into the other maps reading it).
    std::shared_ptr<const Texture> baseColorTexture;
    float metallic = 0.0f;  ///< [0, 1], how much the texture tints `specular`
    float alpha = 1.0f;     ///< base alpha in [0, 1], times the texture's
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;  ///< Mask and Blend: surfaces with alpha below it are holes
    /// Seen from both sides: back faces are drawn and shaded with the normal reversed (glTF's
    /// `doubleSided`). False culls the back faces in the main pass (a closed mesh: on a CPU
    /// rasteriser that halves the triangles it sets up, BENCHMARKS.md, fragment costs). Shadow
    /// passes draw both sides either way.
    bool doubleSided = true;

    /// glTF's parameters, read per pixel by a material with maps (see above).
    glm::vec3 baseColor{0.8f};  ///< linear RGB in [0, 1]
    float roughness = 1.0f;     ///< perceptual roughness in [0, 1] (GGX alpha = roughness^2)
    /// B: metallic, G: roughness (linear), multiplying `metallic` and `roughness`.
    MaterialMap metallicRoughnessMap;
    /// Tangent-space normals (linear, RGB = XYZ in [-1, 1], +Y along +v), read with the mesh's
    /// `tangents`; X and Y are scaled by `normalScale`.
    MaterialMap normalMap;
    float normalScale = 1.0f;
    /// R: ambient occlusion (linear), applied to the ambient term as 1 + strength x (R - 1).
    MaterialMap occlusionMap;
    float occlusionStrength = 1.0f;  ///< [0, 1]
    /// Emitted radiance (linear RGB, W/(sr m^2) in the renderer's units; glTF's emissiveFactor
    /// times KHR_materials_emissive_strength), times `emissiveMap` (sRGB); [0, 1e6].
    glm::vec3 emissive{0.0f};
    MaterialMap emissiveMap;

    /// Whether some of it may be a hole: alpha is tested (Mask or Blend) against a cutoff that
    /// some alpha can fall below.
    [[nodiscard]] bool cutout() const {
        return alphaMode != AlphaMode::Opaque && alphaCutoff > 0.0f &&
               (baseColorTexture != nullptr || alpha < alphaCutoff);
    }
    /// Whether it reads a map besides the base colour (its shading is then the maps variant's).
    [[nodiscard]] bool usesMaps() const {
        return metallicRoughnessMap.texture != nullptr || normalMap.texture != nullptr ||
               occlusionMap.texture != nullptr || emissiveMap.texture != nullptr;
    }
    /// Whether it emits light.
    [[nodiscard]] bool emits() const { return emissive != glm::vec3(0.0f); }
};

/// Skinning of a mesh instance (glTF `skins`): its vertices follow `joints` by the mesh's
/// `MeshData::joints`/`weights`. The instance's own transform is not applied (glTF): a vertex
/// goes to sum_j w_j * jointWorld_j * inverseBind_j * v. `updateTransforms` poses it each frame
/// (the matrices below, the instance's `WorldBounds`, and its moved flag when a joint moved).
struct Skin {
    std::vector<Entity> joints;           ///< entities with a `Transform`
    std::vector<glm::dmat4> inverseBind;  ///< one per joint (identity when the file has none)
    /// Written by `updateTransforms`: the frame the pose is drawn in (a translation near the
    /// skeleton, so that float matrices keep their precision far from the origin), and per joint
    /// frame-from-mesh-space = inverse(worldFromFrame) * jointWorld * inverseBind.
    glm::dmat4 worldFromFrame{1.0};
    std::vector<glm::mat4> frameFromMesh;
    bool posed = false;  ///< false while a joint is missing or not finite: the mesh is not drawn
};

/// The skinned position of vertex `i` of `mesh`, at `p` in the mesh's space (its position, or
/// its morphed one), in `skin`'s frame (`Skin::worldFromFrame`).
[[nodiscard]] glm::vec3 skinnedPosition(const MeshData& mesh, const Skin& skin, std::size_t i, const glm::vec3& p);

/// Most morph targets one draw blends (`Morph::drawn`): with more non-zero weights, the ones of
/// largest magnitude are drawn, alike in every pass and in the reference tracer.
inline constexpr std::size_t kMaxMorphInfluences = SG_MAX_MORPH_INFLUENCES;

/// One morph target a draw blends and its weight.
struct MorphInfluence {
    std::uint32_t target = 0;
    float weight = 0.0f;
    bool operator==(const MorphInfluence&) const = default;
};

/// The morph-target weights of a mesh instance whose mesh has targets (glTF's `weights`: the
/// node's, else the mesh's, else 0), written by a game or by `weights` animation channels. A
/// vertex is drawn at position + sum_k weights[k] * displacement_k (normals and tangents alike,
/// then renormalised), before skinning (glTF). `updateTransforms` picks the targets drawn, the
/// instance's `WorldBounds`, and marks it moved when the drawn weights changed.
struct Morph {
    std::vector<float> weights;  ///< one per target; missing ones count 0, extra ones are ignored
    /// Written by `updateTransforms`: the finite non-zero weights, at most `kMaxMorphInfluences`
    /// of largest magnitude, in target order; empty (a rigid draw) when every weight is 0.
    std::vector<MorphInfluence> drawn;
    /// Written by `updateTransforms`: more weights were non-zero than `kMaxMorphInfluences`.
    bool truncated = false;
    /// Set by `reportTruncatedMorphs` once it warned about this instance: one warning per
    /// entity, not one per frame.
    bool truncationReported = false;
};

/// The position of vertex `i` of `mesh` with `morph`'s drawn targets applied.
[[nodiscard]] glm::vec3 morphedPosition(const MeshData& mesh, const Morph& morph, std::size_t i);

enum class LightType : std::uint8_t { Directional, Spot, Point };

/// A punctual light with the physical size of its emitter (the truth soft shadows approximate).
struct Light {
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};  ///< linear RGB, each in [0, 1e3]
    /// Point/spot: luminous intensity (cd); directional: illuminance (lux), as KHR_lights_punctual.
    /// [0, 1e12], so that no shading can overflow a float.
    float intensity = 1.0f;
    /// Distance where the light's influence ends (m); 0 = infinite. Point and spot only. [0, 1e7].
    float range = 0.0f;
    float innerConeAngle = 0.0f;  ///< spot: full-intensity half-angle (rad), [0, outer)
    /// Spot: cut-off half-angle (rad), (0, pi/2]; shadow maps cover up to 85 degrees of it.
    float outerConeAngle = 0.7853981634f;
    /// Spot: radius (m) of the emitting disk perpendicular to the axis. Point: radius (m) of
    /// the emitting sphere. 0 = a hard shadow. Range [0, 1e3].
    float radius = 0.0f;
    /// Directional: half-angle (rad) of the emitting cone; 0 = a hard shadow. The sun is
    /// about 0.00465. Range [0, 0.2].
    float angularRadius = 0.0f;
};

/// The size of a light's emitter in its own unit: `Light::angularRadius` (rad) for a directional
/// light, `Light::radius` (m) for the others.
[[nodiscard]] inline float emitterSize(const Light& light) {
    return light.type == LightType::Directional ? light.angularRadius : light.radius;
}

/// A light type's name as stats.json spells it ("directional", "spot", "point").
[[nodiscard]] const char* lightTypeName(LightType t);

/// A technique's name as glTF `extras.shadow.technique` and the CLI spell it (the table's
/// "name" column: "none", "hard", "pcf", ...).
[[nodiscard]] const char* techniqueName(ShadowTechnique t);
/// The table's one-line description of technique `t`.
[[nodiscard]] const char* techniqueDescription(ShadowTechnique t);
/// Whether this build offers technique `t`: every Public row; the Baseline rows only in builds
/// with SHADOW_BASELINE_TECHNIQUES (the benchmarks').
[[nodiscard]] bool techniqueAvailable(ShadowTechnique t);
/// How glTF `extras.shadow.technique` and the CLI ask for technique auto (`Shadow::autoTechnique`).
inline constexpr const char* kAutoTechniqueName = "auto";
/// The technique named `name` if this build offers it, or nullopt.
[[nodiscard]] std::optional<ShadowTechnique> techniqueFromName(std::string_view name);
/// The technique of the table named `name`, offered by this build or not: a scene file may name
/// one of any build (the planner replaces one this build lacks, with a warning), or nullopt.
[[nodiscard]] std::optional<ShadowTechnique> techniqueFromAnyName(std::string_view name);
/// The names of the techniques this build offers, comma-separated ("none, hard, ..."), for
/// messages and help.
[[nodiscard]] std::string techniqueNameList();

/// Sample pattern of the PCF filter and the PCSS blocker search, all over the unit disk.
enum class FilterKernel : std::uint8_t {
    Vogel,    ///< golden-angle spiral, rotated per pixel (even coverage for any tap count)
    Poisson,  ///< best-candidate Poisson disk (every prefix well spread), rotated per pixel
    Uniform,  ///< independent uniform points, fresh per pixel
};

/// A kernel's name as glTF `extras.shadow.kernel` spells it ("vogel", "poisson", "uniform").
[[nodiscard]] const char* filterKernelName(FilterKernel k);
/// The kernel named `name`, or nullopt for an unknown name.
[[nodiscard]] std::optional<FilterKernel> filterKernelFromName(std::string_view name);

/// What a shadow map stores per texel: which surface along the light's ray the receivers are
/// compared against.
enum class DepthMode : std::uint8_t {
    Nearest,   ///< the nearest caster (the classic map; needs the bias settings against acne)
    Midpoint,  ///< the mean of the nearest and the second-nearest surface: a lit surface sits
               ///< half a caster's thickness in front of the stored depth, so no bias is needed
    Second,    ///< the second-nearest surface: a lit front face is never compared with itself
};

/// A depth mode's name as glTF `extras.shadow.depthMode` and the CLI spell it ("nearest",
/// "midpoint", "second").
[[nodiscard]] const char* depthModeName(DepthMode m);
/// The depth mode named `name`, or nullopt for an unknown name.
[[nodiscard]] std::optional<DepthMode> depthModeFromName(std::string_view name);

/// The value of a length setting of `Shadow` that asks for one derived from the scene: each
/// such setting says what it is relative to (the shadow texel's footprint at the receiver, the
/// distance field's voxel), so that the same asset at any scale casts the same shadow. A user's
/// explicit metres still win. glTF `extras.shadow` spells it "auto" (or -1).
inline constexpr float kAutomatic = -1.0f;
/// `Shadow::constantBias` when automatic: this fraction of the shadow texel's footprint (m) at
/// the receiver (0.5 mm where a texel covers 1 cm).
inline constexpr float kAutoConstantBiasTexels = 0.05f;
/// `Shadow::pcfRadius` when automatic: at least this many shadow texels at the receiver.
inline constexpr float kAutoPcfRadiusTexels = 1.0f;
/// `Shadow::sdfStartOffset` when automatic: this fraction of the median field voxel.
inline constexpr float kAutoSdfStartOffsetVoxels = 0.125f;
/// `Shadow::sdfMinStep` when automatic: this fraction of the median field voxel.
inline constexpr float kAutoSdfMinStepVoxels = 0.25f;
/// `Shadow::contactLength` when automatic: the shorter of this many shadow texels' footprint at
/// the receiver (the detail the map's bias and filter lose) and `kAutoContactLengthPixels`
/// pixels' footprint on screen (what the image resolves, and a bound on the march's false
/// hits behind objects).
inline constexpr float kAutoContactLengthTexels = 4.0f;
inline constexpr float kAutoContactLengthPixels = 32.0f;

/// `Shadow::maxFilterTexels` when automatic: the widest penumbra times this (the casters' boxes
/// bound their shapes, the penumbra estimates of the filters err), at least
/// `kAutoLeastFilterTexels` (the fixed default before: narrower saves no tap, and VSSM's
/// narrow regions darkened an open plane under a sun at 0.5 degrees), at most
/// `kMostFilterTexels`.
inline constexpr float kAutoFilterTexelsMargin = 1.25f;
/// The margin of VSSM and MSM-soft: none. Their regions (a summed-area square of half-width
/// r sqrt(3) / 2, mip fetches whose tents reach past r) already span beyond the radius, and their
/// blocker estimates run wide where the clamp lets them (MSM-soft on builtin:plates-boxes 0.0421
/// -> 0.0240 of RMSE against the ray-traced truth, docs/tuning.md).
inline constexpr float kAutoMomentFilterTexelsMargin = 1.0f;
inline constexpr float kAutoLeastFilterTexels = 32.0f;
/// The widest `Shadow::maxFilterTexels`.
inline constexpr float kMostFilterTexels = 256.0f;

/// Whether a length setting asks for the automatic value (`kAutomatic`).
[[nodiscard]] inline bool isAutomatic(float setting) { return setting == kAutomatic; }

/// Per-light shadow settings. A light with no `Shadow` component, or technique `None`, gets no
/// shadow map at all. Values out of range are clamped to the stated range by the shadow system
/// and the clamp is reported in stats.json.
struct Shadow {
    ShadowTechnique technique = ShadowTechnique::Hard;
    /// glTF `"technique": "auto"`: the shadow planner chooses `technique` (hard, PCF or PCSS),
    /// `mapSize`, `pcfSamples` and `blockerSamples` for this light every frame, within
    /// `ShadowLimits::shadowBudgetMs` (docs/auto_technique.md); the four fields set here are
    /// then ignored (the rest hold); technique None still means no shadow. Default false.
    bool autoTechnique = false;
    /// Edge of one shadow-map layer in texels, [1, GL_MAX_TEXTURE_SIZE]. Default 1024.
    int mapSize = 1024;
    /// Constant depth bias (m), [0, 10], or `kAutomatic` (the default): `kAutoConstantBiasTexels`
    /// of the shadow texel's footprint at the receiver, so that the margin follows the scale of the
    /// scene. A margin for surfaces whose interpolated normals leave their triangles; the float
    /// error of the compared depths is covered by the sampler itself (a few ulps of the magnitudes
    /// involved), so a caster nearer its receiver than this along the light ray still shadows it.
    float constantBias = kAutomatic;
    /// Slope-scaled bias in shadow-map texels: the depth offset grows with the texel's world
    /// footprint times tan(angle between normal and light), [0, 16]. Default 1.5. Each texel a
    /// tap compares is compared with the receiver's plane at that texel's own centre, so a plane
    /// needs none of it: the receiver's own taps take a fifth (for surfaces that bend within a
    /// texel), filter taps 8 texels away or farther the whole (shaders/shadow_receiver.glsl).
    float slopeBias = 1.5f;
    /// Normal offset in shadow-map texels: the receiver point moves along its normal by this
    /// many texel footprints, scaled by sin(angle), [0, 16]. Default 0: the per-texel receiver
    /// plane leaves no acne for it to hide, and every texel of offset lets light into the
    /// umbra next to a caster (on the bunny, half a texel took the sun's hard-shadow umbra leak
    /// from 2.6 to 6.0 %). The seeds' textbook PCSS adds one texel to it.
    float normalOffset = 0.0f;
    /// PCF filter radius (m) at the receiver, [0, 10], or `kAutomatic` (the default): the
    /// penumbra the light's emitter casts from a typical caster of its layers (each caster's
    /// narrowest, across the gap to the receiver behind it; the median over the casters: a
    /// floating caster's width, none for one resting on its receiver), at least
    /// `kAutoPcfRadiusTexels` shadow texels at the receiver. Both hold at any scale of the scene
    /// (a radius in metres blurs a centimetre-sized asset away and leaves a city block hard). A
    /// light with `autoTechnique` keeps the texel. VSM filters the same radius. The radius taken
    /// is `LightShadowStats::pcfRadiusMetres`.
    float pcfRadius = kAutomatic;
    /// VSM and VSSM light-bleeding reduction: Chebyshev bounds below this fraction read as shadow
    /// and the rest is stretched back to [0, 1], [0, 0.95]. Default 0. Higher removes more of the
    /// light that leaks where casters overlap at different depths, and narrows and darkens every
    /// penumbra. Off by default, measured against the ray-traced truth at 320x240: 0.2 took the
    /// VSSM penumbra RMSE on builtin:plates from 0.055 to 0.112 (VSM's RMSE 0.079 to 0.083) and
    /// changed the bunny's by under 2 % (its leak comes from the curved receiver, not from
    /// overlapping casters).
    float lightBleedReduction = 0.0f;
    /// Sample pattern of PCF and the blocker search. Default Vogel.
    FilterKernel kernel = FilterKernel::Vogel;
    /// Most taps of the PCF filter, [1, 64]. Default 16. A pixel takes about one tap per texel of
    /// its filter disk's area, PCF at least 6 where its radius is half a texel or more (each a
    /// bilinear 2x2 comparison), up to this many, and none where the layer's min/max pyramid
    /// shows the whole disk lit or in umbra.
    int pcfSamples = 16;
    /// Points of the PCSS blocker search disk, [1, 64]; it reads them in pairs, each pair as one
    /// gather of 2x2 depth texels (half the fetches, twice the depths). Default 16.
    int blockerSamples = 16;
    /// Largest filter radius in texels at the receiver (the clamp of PCSS's penumbra and of every
    /// filter's region), [1, 256], or `kAutomatic` (the default): the widest penumbra the light's
    /// emitter can cast from the casters of its layers onto the receivers behind them (every
    /// corner of every caster's box, in the texels of the layer where its ray meets the
    /// receiver), times `kAutoFilterTexelsMargin` (VSSM and MSM-soft:
    /// `kAutoMomentFilterTexelsMargin`), within [`kAutoLeastFilterTexels`, 256]. So a
    /// wide emitter's penumbra is not cut, and a narrow one's estimate cannot run wider than the
    /// scene allows. The clamp taken is `LightShadowStats::maxFilterTexels`; the filter chains
    /// are sized for 256.
    float maxFilterTexels = kAutomatic;
    /// Directional: number of cascades, [1, 4]. Default 1.
    int cascades = 1;
    /// Directional: blend between uniform (0) and logarithmic (1) cascade splits, [0, 1].
    float cascadeSplitLambda = 0.75f;
    /// Directional: fraction of each cascade's depth range, at its far end, over which the
    /// next cascade is blended in, [0, 0.5]. Default 0.1.
    float cascadeBlend = 0.1f;
    /// Directional: how far from the camera shadows are drawn (m), 0 = the camera's far plane.
    float shadowDistance = 0.0f;
    /// Spot/point: near plane of the shadow projection (m), (0, range). 0 = automatic.
    float nearPlane = 0.0f;
    /// What the map stores (`DepthMode`). Default Nearest. Midpoint and Second draw every layer
    /// twice (the second pass keeps the nearest surface behind the first) and are meant to be
    /// used with zero constant and slope bias; they need closed (watertight) casters: where a
    /// ray meets one surface only, the texel stores the far depth and casts nothing, and the
    /// shadow system warns (`OpenCaster`) for every light whose layers hold an open caster.
    DepthMode depthMode = DepthMode::Nearest;
    /// Technique sdf: most steps of the march toward the light, [4, 256]. Default 48. A march
    /// ends earlier when it leaves every field caster's bounds, reaches the light or is hit.
    /// Fewer steps also step coarser beside a caster: no step there is shorter than 12 /
    /// sdfSteps of the emitter's cone radius (up to one voxel of the caster's field), so a small
    /// budget still reaches the casters beyond.
    int sdfSteps = 48;
    /// Technique sdf: how far (m) the march starts from the receiver, along its normal and
    /// along the ray, [0, 1], or `kAutomatic` (the default): `kAutoSdfStartOffsetVoxels` of the
    /// median voxel (m) of the light's field casters. A caster nearer its receiver than this is
    /// passed over; a march starting closer reads the receiver's own field, whose interpolation
    /// error near a curved surface is a fraction of a voxel, and darkens lit surfaces (acne).
    /// Measured on builtin:bunny (fields of 64^3 voxels, voxel 2 cm) against the ray-traced truth,
    /// per light (`shadow_render builtin:bunny --technique sdf --sdf-start-offset M`, then
    /// `shadow_compare --mask lit_<i>.exr`): 1 mm made 2-13 times the acne of 2.5 mm (1/8 voxel,
    /// 0.09-0.15 % of lit pixels); 5 mm, 1 cm and 2 cm let 1.7-2.3, 3.2-4.8 and 5-9 times as many
    /// umbra pixels above 0.5 into the bunny's shadows.
    float sdfStartOffset = kAutomatic;
    /// Technique sdf: the shortest step (m), [1e-4, 1], or `kAutomatic` (the default):
    /// `kAutoSdfMinStepVoxels` of the median voxel of the light's field casters. Smaller follows
    /// thin gaps closer, at more steps. Beside a caster the cone's share (`sdfSteps`) may
    /// lengthen it.
    float sdfMinStep = kAutomatic;
    /// Screen-space contact shadows: a short march from each receiver toward the light through
    /// the surfaces on screen, multiplied into the light's visibility, for detail the map's texels
    /// cannot hold (a small object on the ground under a sun whose cascades span hundreds of
    /// metres). Drawn by the renderer's screen-space visibility stage (`RenderOptions::
    /// screenVisibility`, which `Auto` turns on for such a light); forward passes and a game's own
    /// shader leave them out. Default off.
    bool contactShadows = false;
    /// How far (m) the contact march reaches, [0, 10], or `kAutomatic` (the default): the
    /// shorter of `kAutoContactLengthTexels` shadow texels and `kAutoContactLengthPixels` screen
    /// pixels at the receiver.
    float contactLength = kAutomatic;
};

/// A perspective camera looking along its node's -Z.
struct Camera {
    float yfov = 0.8f;    ///< vertical field of view (rad), (0, pi)
    float znear = 0.05f;  ///< near plane (m), > 0
    float zfar = 500.0f;  ///< far plane (m), > znear
    /// Width / height; 0 = take it from the output image.
    float aspectRatio = 0.0f;
};

/// One keyframed channel of a glTF animation, targeting the entity that owns it.
struct AnimationChannel {
    /// `Weights` writes the entity's `Morph::weights` (glTF's `weights` path).
    enum class Path : std::uint8_t { Translation, Rotation, Scale, Weights };
    enum class Interpolation : std::uint8_t { Linear, Step, CubicSpline };
    Path path = Path::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;  ///< strictly increasing key times (s)
    /// Key values: xyz (w unused) or quaternion xyzw; `Weights`: `width` vec4s per value, the
    /// morph weights four by four (the last padded with 0). CUBICSPLINE stores three values per
    /// key: in-tangent, value, out-tangent.
    std::vector<glm::vec4> values;
    std::uint32_t width = 1;  ///< vec4s per value: 1, or ceil(targets / 4) for `Weights`
};

/// Keyframed animation of one entity's `Transform`. The clip loops with period `duration`.
struct Animation {
    std::vector<AnimationChannel> channels;
    double duration = 0.0;  ///< loop period (s); the clip's last key time
};

/// Procedural motion of one entity's `Transform`, evaluated at absolute time `t` (s).
struct ProceduralMotion {
    enum class Kind : std::uint8_t {
        Orbit,  ///< translation = center + radius * (cos, 0, sin)(speed * t + phase) around +Y
        Bob,    ///< translation = center + axis * amplitude * sin(speed * t + phase)
        Spin,   ///< rotation = angle-axis(speed * t + phase, axis); translation kept
    };
    Kind kind = Kind::Spin;
    glm::dvec3 center{0.0};
    glm::dvec3 axis{0.0, 1.0, 0.0};
    double radius = 1.0;
    double amplitude = 1.0;
    double speed = 1.0;  ///< rad/s
    double phase = 0.0;  ///< rad
};

}  // namespace shadow
