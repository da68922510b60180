// The decide phase of the shadow system: what this frame needs, on the CPU alone (testable
// without GL). `ShadowPlanner::prepare` reads the world (it cannot change it) and decides which
// lights are shadowed and can affect the view, each light's layers and matrices, which casters
// fall in each layer's frustum, which layers are dirty, and the array sizes inside the shadow
// memory budget. The result is a `ShadowFrame`, the hand-off to the shadow maps, the shader
// contract, the mask and the renderer: one entry per scene light, in scene order (the one index
// space up to the AOVs). A light with no `Shadow` component or technique None gets no map. Every
// light's settings out of their documented range are clamped once, here, and reported in
// `ShadowFrame::warnings`.
#pragma once

#include <shadow/auto_technique.h>
#include <shadow/caster_draw.h>
#include <shadow/components.h>
#include <shadow/scene.h>
#include <shadow/warnings.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shadow {

class AutoPlanning;
struct FrameStats;

/// One layer of a light's array as decided by `ShadowPlanner::prepare`.
struct ShadowLayerPlan {
    /// World -> light view (m; the light looks down -Z), in double. The GPU gets it made
    /// relative to the camera.
    glm::dmat4 lightFromWorld{1.0};
    glm::dmat4 clipFromLight{1.0};  ///< light view -> clip (GL's [-1, 1] depth), in double
    bool orthographic = false;      ///< a directional light's cascade (else a perspective frustum)
    float depthScale = 1.0f;        ///< stored depth = lsDepth / depthScale (m per stored unit, > 0)
    float depthNear = 0.0f;         ///< near plane (m)
    /// Spot and point lights: the nearest a blocker can be (m), the same in every layer of the
    /// light: the least distance from the light of any caster in its layers (the far plane when
    /// there is none), or a fixed near plane beyond that (it clips what is nearer). PCSS's,
    /// VSSM's and MSM-soft's blocker search cone is cut there rather than at the fitted near
    /// plane, which is rounded down to a power of two and tilted by the frustum's corner angle,
    /// nor at a fixed near plane set close to the light. A directional light's cascade: the depth
    /// below its top (m) of the top of its highest caster (receivers and rounding raise the top
    /// above it; 0 without casters).
    float blockerNear = 0.0f;
    float splitFar = 0.0f;  ///< directional: camera distance where the cascade ends (m)
    /// VSSM: the power of two >= 1 its summed-area table scales stored depths by before their
    /// fixed point (it holds the moments of min(z momentScale, 1)), so that the farthest
    /// caster's bounds lie in (1/4, 1/2]: a light whose range is 10^6 times the depth of its
    /// scene keeps 2^-24 of the casters' depth as its resolution rather than of its range.
    /// 0 for a layer without casters: its table is not built, and its lookups read lit.
    float momentScale = 1.0f;
    /// MSM-soft: 1, its lookups taking level 0's fetches from the depth map (sg_chainMoments).
    /// VSM: the lowest level of its moment chain that a lookup of this layer reads, the floor of
    /// log2 of the filter radius in the largest texel any receiver of the layer has (its
    /// cascade's texel; a perspective layer's at the farthest corner of the scene's known bounds,
    /// meshes and the game's casters), and at least 1 as MSM-soft's. The chain is built from
    /// there, straight from the depth map, and the levels below are neither built nor read
    /// through the chain.
    int chainFirstLevel = 0;
    /// VSM: the highest level of its moment chain that a lookup of this layer reads, the level
    /// above the floor of log2 of the filter radius in the smallest texel any receiver of the
    /// layer has (its cascade's texel: a cascade's chain is two levels; a perspective layer's at
    /// the nearest point of the scene's known bounds, seen at the frustum's corner). The levels
    /// above are not built. The chain's top level for every other technique.
    int chainLastLevel = 0;
    /// Casters (meshes and `ShadowCasterDraw`s) whose world bounds meet this layer's frustum,
    /// in entity order.
    std::vector<Entity> casters;
    /// A layer with casters of a technique whose map carries a moment chain (VSM, VSSM,
    /// MSM-soft; MSM's one-texel region gained nothing from them, measured): the meshes that
    /// receive but do not cast whose world bounds meet its frustum, in entity order. Where no
    /// caster covers a texel, the layer holds the farthest of them instead of the far depth, so
    /// that a filter region reaching past a shadow's outline averages the blockers with the
    /// ground they stand on rather than with the far plane (which reads as lit well inside the
    /// outline). They never hide a caster, nor shadow anything: no receiver lies behind the
    /// farthest. Empty for the other techniques.
    std::vector<Entity> backgrounds;
    /// Must be drawn this frame: matrices, caster or background set, one's transform or the
    /// allocation changed (or caching is off).
    bool dirty = true;
};

/// One scene light as decided by `ShadowPlanner::prepare`: entry i of `ShadowFrame::lights` is
/// light i of `Scene::lights` (the `lights` handed to `prepare`), shadowed or not. This is the one index
/// space from the decide step to the renderer's light records, `FrameStats::lights` and the
/// `visibility_<i>` AOVs.
struct ShadowLightPlan {
    Entity entity;        ///< the light's entity
    int sceneIndex = -1;  ///< position in `Scene::lights` (= the index of this entry)
    std::string name;     ///< its `Name`, or "light" without one
    /// False when the entity has no `Light` or `WorldTransform`, or its transform is not finite:
    /// it shades nothing and its visibility is 1.
    bool shaded = false;
    Light light;                             ///< clamped to the documented ranges, once, here
    glm::dvec3 wsPosition{0.0};              ///< light position (point, spot)
    glm::dvec3 wsDirection{0.0, 0.0, -1.0};  ///< unit direction the light travels (node -Z)
    /// Clamped to the documented ranges; `mapSize` is the one asked for. `technique` is the
    /// light's own, None when it has no `Shadow`.
    Shadow settings;
    /// Texels per layer edge allocated: `settings.mapSize`, or less when the shadow memory budget
    /// (`ShadowLimits::maxShadowBytes`) halved it; 0 without a map.
    int mapSize = 0;
    /// The layers of its map; empty when the light has no map this frame (no shadow, technique
    /// None, or dropped by the memory budget).
    std::vector<ShadowLayerPlan> layers;
    /// False when its range cannot reach the camera's frustum: its layers are not drawn.
    bool affectsView = true;
    /// PCF and PCSS: the lookups read the min/max pyramid, built for the layers redrawn this
    /// frame (`ShadowLimits::pyramidTexelsPerPixel`); false for the other techniques.
    bool regionTest = false;
    /// Technique sdf: the casters its march reads through their distance fields (meshes with a
    /// uniform scale in any of its layers' frustums), taken out of the layers' caster lists;
    /// what stays there (a game's own casters, non-uniform scales) casts through its map. Empty
    /// for the other techniques.
    std::vector<Entity> fieldCasters;
    /// `Shadow::autoTechnique`: `settings` hold the planner's choice this frame (`autoChoice`).
    bool automatic = false;
    /// An auto light's choice and its predictions; candidate -1 on its first frame (nothing is
    /// known of it yet: it takes PCSS at 1024 texels and 16 + 16 taps).
    AutoLightChoice autoChoice;
    /// An auto light whose edges the renderer's lit passes count this frame (its first, then one
    /// frame in `kAutoCountEvery`): `FrameStats::edgeCounts` of a later frame, once the GPU is
    /// done, what the error model reads.
    bool countEdges = false;
    /// PCF and VSM: the filter radius (m at the receiver) the lookups take, at least
    /// `kAutoPcfRadiusTexels` texels: `settings.pcfRadius`, or when that is automatic the penumbra
    /// of the light's emitter from a typical caster of its layers (README, "Defaults that
    /// follow the scene"), 0 for an auto light (its PCF is the one-texel filter)
    /// and for the other techniques.
    double pcfRadiusMetres = 0.0;
    /// The widest filter radius (texels at the receiver) its lookups take:
    /// `settings.maxFilterTexels`, or when that is automatic the widest penumbra of its casters
    /// (README, "Defaults that follow the scene").
    float maxFilterTexels = kMostFilterTexels;
    /// Index of `fieldCasters[0]` among every light's field casters, in scene-light order:
    /// where the shader finds its instances (`ShadowMaps::fieldInstances`).
    int fieldFirst = 0;
    /// Index of its first cluster of field casters (SG_SDF_CLUSTER consecutive ones with their
    /// bounding sphere) in the same buffer, after every light's field casters.
    int fieldClusterFirst = 0;

    /// True when the light has a shadow map this frame.
    [[nodiscard]] bool hasMap() const { return !layers.empty(); }
    /// The technique its pixels use: its own when it has a map, None otherwise.
    [[nodiscard]] ShadowTechnique technique() const { return hasMap() ? settings.technique : ShadowTechnique::None; }
};

/// The hand-off from `ShadowPlanner::prepare` to the shadow maps, the shader contract, the mask
/// and the renderer: everything lighting needs.
struct ShadowFrame {
    /// Every scene light, in scene order (see `ShadowLightPlan`).
    std::vector<ShadowLightPlan> lights;
    /// Bit `1 << t` for every technique t (`ShadowTechnique`) some light's pixels use
    /// (`ShadowLightPlan::technique`; None's bit when a light has no map), computed once, here:
    /// the union of the techniques the renderer's passes and a game's `shadowShaderSource` need.
    unsigned techniquesInUse = 0;
    /// World bounds of every finite mesh this frame (empty without one): what any light can reach.
    DAabb wsGeometry;
    /// Clamped settings and the memory budget's decisions, one each (codes in warnings.h).
    std::vector<Warning> warnings;
    /// `ShadowLimits::distanceFieldVoxels`, clamped: the voxels of each mesh's field.
    int distanceFieldVoxels = 64 * 64 * 64;
};

/// Limits the planner must respect: the GL implementation's, and the memory the shadow maps
/// may take together.
struct ShadowLimits {
    int maxTextureSize = 16384;  ///< GL_MAX_TEXTURE_SIZE: the largest `mapSize` (texels)
    int maxArrayLayers = 2048;   ///< GL_MAX_ARRAY_TEXTURE_LAYERS
    /// GPU memory every shadowed light's maps take together (bytes): its depth array (4 bytes a
    /// texel, mapSize^2 x layers) and the filter chain its technique reads (the min/max pyramid
    /// of PCF and PCSS, the moments of VSM, MSM and MSM-soft, the summed-area table of VSSM), as
    /// `shadowMapBytes` counts them and `LightShadowStats::mapBytes` + `filterChainBytes`
    /// report them. Default 2^30 (1 GiB): one hard 16384^2 layer, a VSM spot at 8192^2 (0.75
    /// GiB), or 256 hard spot lights at 1024^2. Over budget, the planner degrades lights
    /// deterministically: ranked by distance from the camera (lights that cannot reach the view
    /// count as farthest, directional lights as nearest, ties by scene order, later first), maps
    /// are halved round by round, farthest first, down to 256 texels (a light that asked for less
    /// keeps its own); then the farthest lights lose their shadow (visibility 1) until the rest
    /// fit. Each decision is a warning. The ranking follows the camera: a light whose map size
    /// changes is reallocated and redrawn that frame. Range: >= 0 (0: no light has a map).
    std::int64_t maxShadowBytes = std::int64_t{1} << 30;
    /// Technique sdf: most voxels of one mesh's distance field (`DistanceFieldSettings::
    /// voxelBudget`), [kMinDistanceFieldVoxels, kMaxDistanceFieldVoxels], clamped. Default 64^3
    /// (1 MiB a field; the Stanford bunny's voxel 2 cm at 1.2 m tall). A field whose longest
    /// axis would pass the atlas's 128 voxels is baked again with its budget cut by the cube of
    /// that excess, until it fits (or reaches the minimum and is refused with a warning).
    /// Changing it bakes every field again on the next frame.
    int distanceFieldVoxels = 64 * 64 * 64;
    /// PCF and PCSS: map texels the min/max pyramid may read per pixel its light can reach on
    /// screen (`CameraView::pixelWidth` x `pixelHeight`, the light's screen rectangle). The
    /// pyramid lets the lit pass skip the taps (PCSS: the blocker search too) of pixels whose
    /// filter region is wholly lit or in umbra, at the price of reading every texel of every
    /// redrawn layer; where the redrawn layers hold more texels than this many per pixel, the
    /// light goes without it (`ShadowLightPlan::regionTest` false: every pixel takes its taps,
    /// the same visibility). Measured on llvmpipe: about 2.5 ns a texel to build, 15-30 ns of PCF
    /// taps saved per pixel (BENCHMARKS.md, fragment costs), so 6. PCSS spares more per known
    /// pixel but knows fewer: a receiver sloped to the light is known lit only where its own
    /// depths across the search region stay within the bias, so most of its lit area searches
    /// either way. With caching off, PCSS's frame without the pyramid was 18-38 % shorter at
    /// 320x240 (plates, bunny, default: tens of texels a pixel) and 7-24 % longer at 1920x1080
    /// (`builtin:bunny-spot`, default: under 6); at 1280x720 on bunny-spot (about 5) 5 % shorter,
    /// within the run-to-run noise: the same limit serves both techniques. Range >= 0 (0: never a
    /// pyramid for a redrawn layer; a very large value: always). A frame that redraws no layer
    /// always reads the pyramid.
    float pyramidTexelsPerPixel = 6.0f;
    /// Milliseconds per frame the lights with `Shadow::autoTechnique` may spend together on their
    /// shadow passes and their lookups in the lit pass, as the planner predicts them
    /// (`AutoCostModel`, calibrated by `ShadowPlanner::observe`). The planner picks each auto
    /// light's technique, map size and taps to minimise the predicted screen-weighted error within
    /// it (docs/auto_technique.md). Default 0: no budget (each auto light takes the candidate of
    /// least predicted error). Range >= 0; NaN, infinite or negative values count as 0, with a
    /// `SettingClamped` warning for NaN and negative ones.
    double shadowBudgetMs = 0.0;
};

/// GPU memory (bytes) of the maps of one light with technique `technique`, `layers` layers of
/// `mapSize`^2 texels and filter radius `maxFilterTexels` (the `Shadow` field): its depth array
/// and the filter chain the technique reads, as the shadow maps allocate them; 0 for None.
[[nodiscard]] std::int64_t shadowMapBytes(ShadowTechnique technique, int mapSize, int layers, float maxFilterTexels);

/// Clamps the fields of `light` to their documented ranges (components.h), NaN to the low end;
/// appends one `SettingClamped` warning per clamped field, its element `who`. A light out of
/// range is drawn as clamped, so one bad light never makes the others' pixels NaN. Never throws.
void clampLight(Light& light, std::string_view who, std::vector<Warning>& warnings);

/// Clamps `s` and `light` (`clampLight`, and a spot's cone to what a map covers, 85 degrees)
/// to the documented ranges; appends one `SettingClamped` warning per clamped field, its
/// element `who`. Never throws.
void clampShadowSettings(Shadow& s, Light& light, const ShadowLimits& limits, const std::string& who,
                         std::vector<Warning>& warnings);

/// The decide phase. Keeps last frame's decisions to find what changed (which layers are dirty),
/// and the storage of its lists: planning a frame like the last allocates nothing.
class ShadowPlanner {
public:
    ShadowPlanner();
    ~ShadowPlanner();
    ShadowPlanner(const ShadowPlanner&) = delete;
    ShadowPlanner& operator=(const ShadowPlanner&) = delete;

    /// Decides this frame's layers. `lights` is the scene's light order. Reads the world only;
    /// what it remembers between frames (last frame's matrices and casters per layer) is its own.
    const ShadowFrame& prepare(const World& world, const CameraView& camera, const std::vector<Entity>& lights);
    /// The last prepared frame.
    [[nodiscard]] const ShadowFrame& frame() const { return frame_; }
    /// Scene time (s) of the frames prepared from now on: auto lights switch at most once a
    /// second of it (`kAutoHoldSeconds`). Never set (NaN), the hold is counted in frames.
    void setSceneTime(double seconds) { sceneTime_ = seconds; }
    /// Calibrates the auto lights' cost model from the pass timings of the frame last prepared
    /// (`FrameStats::passes`: its shadow passes and "Main/Lit*"). Without calls the model keeps
    /// its defaults, measured on llvmpipe. A frame without auto lights costs nothing here.
    void observe(const FrameStats& stats);
    /// The auto lights' calibrated cost model.
    [[nodiscard]] const AutoCostModel& autoCosts() const;
    /// With caching off every layer is dirty every frame (reference for cache tests).
    void setCaching(bool enabled) { caching_ = enabled; }
    /// The limits the next `prepare` respects.
    void setLimits(const ShadowLimits& limits) { limits_ = limits; }
    /// The limits in force.
    [[nodiscard]] const ShadowLimits& limits() const { return limits_; }

private:
    struct LayerMemory {
        glm::dmat4 lightFromWorld{0.0};
        glm::dmat4 clipFromLight{0.0};
        std::vector<Entity> casters;
        /// Each caster's `WorldTransform::version` when the layer was drawn: what its validity is
        /// keyed on, however many transform updates ran between two frames.
        std::vector<std::uint64_t> versions;
        /// Likewise of its backgrounds (ShadowLayerPlan::backgrounds).
        std::vector<Entity> backgrounds;
        std::vector<std::uint64_t> backgroundVersions;
    };
    struct LightMemory {
        int mapSize = 0;
        DepthMode depthMode = DepthMode::Nearest;
        std::vector<LayerMemory> layers;
    };
    /// The layers of `plan`, a light with a map this frame, and which of them are dirty: last
    /// frame's kept (`keepLayers`), or planned again; and whether it reads its pyramid (`regionTest`).
    void planMap(const World& world, const CameraView& camera, ShadowLightPlan& plan, bool cameraMoved);
    void markDirty(const World& world, ShadowLightPlan& plan);
    /// Keeps last frame's layers of `plan`, planned for the same light with the same inputs,
    /// when planning them again would give them back (nothing in its reach changed), with the
    /// dirty flags `markDirty` would give; false when they must be planned.
    bool keepLayers(const World& world, ShadowLightPlan& plan, bool cameraMoved);

    ShadowFrame frame_;
    std::vector<std::pair<Entity, LightMemory>> memory_;
    struct Scratch;  ///< the working lists of `prepare` (planner.cpp), kept for their storage
    std::unique_ptr<Scratch> scratch_;
    std::unique_ptr<AutoPlanning> auto_;  ///< auto lights' choices and calibration (auto_planning.h)
    double sceneTime_ = std::numeric_limits<double>::quiet_NaN();
    ShadowLimits limits_;
    bool caching_ = true;
};

}  // namespace shadow
