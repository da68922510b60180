// The shadow subsystem: every shadowed light gets its own depth texture array
// (directional: cascades as layers; spot: one layer; point: six cube faces).
//
// Two phases per frame, after `updateTransforms`:
//   prepare  (CPU only, testable without GL) decides what this frame needs: which lights are
//            shadowed and can affect the view, each light's layers and matrices, which casters
//            fall in each layer's frustum, which layers are dirty, and the array sizes. The
//            result is a `ShadowFrame`, the hand-off to the GPU phase and to the renderer: one
//            entry per scene light, in scene order (the one index space up to the AOVs).
//   render   draws only the dirty layers, depth only; clears the layers with no caster; leaves
//            every other layer as last frame left it; for PCF and PCSS lights, brings the min/max
//            depth pyramid of every redrawn layer up to date.
// A light with no `Shadow` component or technique None gets no map. Every light's settings out
// of their documented range are clamped once, here, and reported in `ShadowFrame::warnings`.
//
// What this does not do (yet): no atlas packing across lights, no GPU-driven culling.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <shadow/scene.h>
#include <shadow/shadow_shaders.h>
#include <shadow/stats.h>
#include <shadow/warnings.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shadow {

class MeshCache;

/// What a `ShadowCasterDraw::draw` callback gets: the layer being drawn, with the module's depth
/// program current and its framebuffer, viewport and depth state set.
struct CasterDrawContext {
    glm::dmat4 lightFromWorld{1.0};  ///< world -> light view (m; the light looks down -Z)
    glm::dmat4 clipFromLight{1.0};
    float depthScale = 1.0f;  ///< stored depth = lsDepth / depthScale (shadow_depth.frag.glsl)
    bool orthographic = false;
    /// The module's depth program (current): vec3 positions at attribute 0, object transform in
    /// `uLightFromLocal`. A callback may draw with it after `setWorldFromLocal`, or with a program
    /// of its own that writes the same depth (shaders/shadow_depth.frag.glsl) and put this back.
    unsigned program = 0;
    int lightFromLocalLocation = -1;
    /// Points the depth program at object transform `worldFromLocal` for the next draws
    /// (composed with `lightFromWorld` in double, so float precision holds far from the origin).
    void setWorldFromLocal(const glm::dmat4& worldFromLocal) const;
};

/// A shadow caster drawn from the game's own geometry, with nothing mirrored into the module: an
/// entity with a `Transform` (or `WorldTransform`) and this component. The shadow system culls
/// it per layer by `localBounds` and, where it falls in a layer, draws `indexCount` indices of
/// the game's vertex array with the module's depth program, or calls `draw` instead (for the
/// game's instancing, skinning or streaming). The module's own renderer does not draw it in the
/// main pass: a game with such casters lights its own frame (shadowShaderSource, renderMask).
struct ShadowCasterDraw {
    Aabb localBounds;             ///< object space (m): must hold everything the caster draws
    unsigned vertexArray = 0;     ///< the game's vertex array: vec3 float positions at attribute 0
    unsigned indexType = 0x1405;  ///< GL_UNSIGNED_INT, GL_UNSIGNED_SHORT (0x1403) or GL_UNSIGNED_BYTE (0x1401)
    std::size_t indexOffset = 0;  ///< bytes into the vertex array's element buffer
    int indexCount = 0;
    int baseVertex = 0;
    /// When set, called instead of the indexed draw, once per layer the caster falls in.
    std::function<void(const CasterDrawContext&)> draw;
    /// Set by the game in a frame where the geometry changed while the transform did not
    /// (skinning, streaming): the layers it falls in are redrawn. The module does not reset it.
    bool changedThisFrame = false;

    /// Whether it draws anything: a callback, or a vertex array with indices.
    [[nodiscard]] bool drawsSomething() const { return draw != nullptr || (vertexArray != 0 && indexCount > 0); }
};

/// One layer of a light's array as decided by `prepare`.
struct ShadowLayerPlan {
    /// World -> light view (m; the light looks down -Z), in double. The GPU gets it made
    /// relative to the camera.
    glm::dmat4 lightFromWorld{1.0};
    glm::dmat4 clipFromLight{1.0};
    bool orthographic = false;
    float depthScale = 1.0f;  ///< stored depth = lsDepth / depthScale
    float depthNear = 0.0f;   ///< near plane (m)
    float splitFar = 0.0f;    ///< directional: camera distance where the cascade ends (m)
    /// VSSM: the power of two >= 1 its summed-area table scales stored depths by before their
    /// fixed point (it holds the moments of min(z momentScale, 1)), so that the farthest
    /// caster's bounds lie in (1/4, 1/2]: a light whose range is 10^6 times the depth of its
    /// scene keeps 2^-24 of the casters' depth as its resolution rather than of its range.
    float momentScale = 1.0f;
    /// Casters (meshes and `ShadowCasterDraw`s) whose world bounds meet this layer's frustum,
    /// in entity order.
    std::vector<Entity> casters;
    /// Must be drawn this frame: matrices, caster set, a caster's transform or the allocation
    /// changed (or caching is off).
    bool dirty = true;
};

/// One scene light as decided by `prepare`: entry i of `ShadowFrame::lights` is light i of
/// `Scene::lights` (the `lights` handed to `prepare`), shadowed or not. This is the one index
/// space from the decide step to the renderer's light records, `FrameStats::lights` and the
/// `visibility_<i>` AOVs.
struct ShadowLightPlan {
    Entity entity;
    int sceneIndex = -1;  ///< position in `Scene::lights` (= the index of this entry)
    std::string name;
    /// False when the entity has no `Light` or `WorldTransform`, or its transform is not finite:
    /// it shades nothing and its visibility is 1.
    bool shaded = false;
    Light light;                             ///< clamped to the documented ranges, once, here
    glm::dvec3 wsPosition{0.0};              ///< light position (point, spot)
    glm::dvec3 wsDirection{0.0, 0.0, -1.0};  ///< unit direction the light travels (node -Z)
    /// Clamped to the documented ranges; `mapSize` is the one asked for. `technique` is the
    /// light's own, None when it has no `Shadow`.
    Shadow settings;
    /// Texels per layer edge allocated: `settings.mapSize`, or less when the shadow texel budget
    /// (`ShadowLimits::maxShadowTexels`) halved it; 0 without a map.
    int mapSize = 0;
    /// The layers of its map; empty when the light has no map this frame (no shadow, technique
    /// None, or dropped by the texel budget).
    std::vector<ShadowLayerPlan> layers;
    bool affectsView = true;

    /// True when the light has a shadow map this frame.
    [[nodiscard]] bool hasMap() const { return !layers.empty(); }
    /// The technique its pixels use: its own when it has a map, None otherwise.
    [[nodiscard]] ShadowTechnique technique() const { return hasMap() ? settings.technique : ShadowTechnique::None; }
};

/// The hand-off from `prepare` to `render` and to the renderer: everything lighting needs.
struct ShadowFrame {
    /// Every scene light, in scene order (see `ShadowLightPlan`).
    std::vector<ShadowLightPlan> lights;
    /// Bit `1 << t` for every technique t (`ShadowTechnique`) some light's pixels use.
    unsigned techniquesInUse = 0;
    /// World bounds of every finite mesh this frame (empty without one): what any light can reach.
    DAabb wsGeometry;
    /// Clamped settings and the texel budget's decisions, one each (codes in warnings.h).
    std::vector<Warning> warnings;
};

/// Limits the planner must respect: the GL implementation's, and the memory the shadow maps
/// may take together.
struct ShadowLimits {
    int maxTextureSize = 16384;
    int maxArrayLayers = 2048;
    /// Texels of every shadowed light's layers together (mapSize^2 x layers), 4 bytes each.
    /// Default 2^28 (1 GiB): one 16384^2 layer, or 256 spot lights at 1024^2. Over budget, the
    /// planner degrades lights deterministically: ranked by distance from the camera (lights
    /// that cannot reach the view count as farthest, directional lights as nearest, ties by
    /// scene order, later first), maps are halved round by round, farthest first, down to 256
    /// texels (a light that asked for less keeps its own); then the farthest lights lose their
    /// shadow (visibility 1) until the rest fit. Each decision is a warning. The ranking follows
    /// the camera: a light whose map size changes is reallocated and redrawn that frame.
    std::int64_t maxShadowTexels = std::int64_t{1} << 28;
};

/// Clamps the fields of `light` to their documented ranges (components.h), NaN to the low end;
/// appends one `SettingClamped` warning per clamped field, its element `who`. A light out of
/// range is drawn as clamped, so one bad light never makes the others' pixels NaN. Never throws.
void clampLight(Light& light, std::string_view who, std::vector<Warning>& warnings);

/// Clamps `s` and `light` (`clampLight`, and a spot's cone to what a map covers, 85 degrees)
/// to the documented ranges; appends one `SettingClamped` warning per clamped field, its
/// element `who`. Never throws.
void clampShadowSettings(Shadow& s, Light& light, const ShadowLimits& limits, const std::string& who,
                         std::vector<Warning>& warnings);

/// CPU half of the shadow system. Keeps last frame's decisions to find what changed, and the
/// storage of its lists: planning a frame like the last allocates nothing.
class ShadowPlanner {
public:
    ShadowPlanner();
    ~ShadowPlanner();
    ShadowPlanner(const ShadowPlanner&) = delete;
    ShadowPlanner& operator=(const ShadowPlanner&) = delete;

    /// Decides this frame's layers. `lights` is the scene's light order.
    const ShadowFrame& prepare(World& world, const CameraView& camera, const std::vector<Entity>& lights);
    /// The last prepared frame.
    [[nodiscard]] const ShadowFrame& frame() const { return frame_; }
    /// With caching off every layer is dirty every frame (reference for cache tests).
    void setCaching(bool enabled) { caching_ = enabled; }
    void setLimits(const ShadowLimits& limits) { limits_ = limits; }

private:
    struct LayerMemory {
        glm::dmat4 lightFromWorld{0.0};
        glm::dmat4 clipFromLight{0.0};
        std::vector<Entity> casters;
    };
    struct LightMemory {
        int mapSize = 0;
        std::vector<LayerMemory> layers;
    };
    void markDirty(World& world, ShadowLightPlan& plan);

    ShadowFrame frame_;
    std::vector<std::pair<Entity, LightMemory>> memory_;
    struct Scratch;  ///< the working lists of `prepare` (planner.cpp), kept for their storage
    std::unique_ptr<Scratch> scratch_;
    ShadowLimits limits_;
    bool caching_ = true;
};

/// GPU resources of the shadow system (opaque outside the engine).
struct ShadowGpu;

/// The shadow subsystem: the planner plus each light's depth texture array.
class ShadowSystem {
public:
    /// Throws `GlError` when `loadGl` has not run (there is no GL to talk to).
    ShadowSystem();
    /// For a game built without exceptions: the system, or the error the constructor would throw.
    [[nodiscard]] static Result<std::unique_ptr<ShadowSystem>> create() noexcept;
    ~ShadowSystem();
    ShadowSystem(const ShadowSystem&) = delete;
    ShadowSystem& operator=(const ShadowSystem&) = delete;

    /// CPU phase (see the header comment). Requires a current GL context only for the limits
    /// read at construction.
    const ShadowFrame& prepare(World& world, const CameraView& camera, const std::vector<Entity>& lights);
    /// GPU phase: draws the dirty layers of the last prepared frame. Adds timings and counters.
    /// A guest in the host's context: the GL state it changes (framebuffer bindings, program,
    /// vertex array, viewport, scissor, depth test/function/mask, culling, blending, colour mask,
    /// texture unit 0's texture and sampler, the active unit) is put back before it returns,
    /// also when it throws. An error the host left pending is read, cleared and reported as a
    /// `HostGlError` warning, never thrown; `GlError` is thrown only for the engine's own.
    void render(World& world, MeshCache& meshes, FrameStats& stats);
    /// `render` for a game built without exceptions: what it would throw, as an error value.
    [[nodiscard]] Status tryRender(World& world, MeshCache& meshes, FrameStats& stats) noexcept;
    /// Per-pass timing into `FrameStats::passes`. Default off: timing brackets every pass with
    /// glFinish on a CPU rasteriser, and on a GPU opens GL_TIME_ELAPSED queries (a host's own
    /// time-elapsed query cannot be open across the call) whose results are read a frame or
    /// more later, never stalling (`FrameStats::timingLagFrames`). FrameRunner turns it on.
    /// Off, `FrameStats::timingMethod` says "off" and no pass is listed.
    void setTiming(bool enabled);

    [[nodiscard]] const ShadowFrame& frame() const { return planner_.frame(); }
    [[nodiscard]] ShadowPlanner& planner() { return planner_; }

    /// The GL texture name of the depth array of light entity `light`, 0 when it has no map: the
    /// same from frame to frame whatever the lights' order, until the map is made anew (a new
    /// size or layer count, e.g. from the texel budget), which `LightShadowStats::mapAllocated`
    /// reports.
    [[nodiscard]] unsigned textureOfLight(Entity light) const;
    /// The GL texture name of the depth array of scene light `i`, 0 when it has no map.
    [[nodiscard]] unsigned textureOf(std::size_t i) const;
    /// The GL texture name of the filter chain of scene light `i` (an array, one mip chain per
    /// layer): the min/max depth pyramid of PCF and PCSS lights (RG32F), the depth moments of VSM
    /// lights (RG32F) and of MSM and MSM-soft lights (RGBA32F), the summed-area table of VSSM
    /// lights (RGBA32F, one level: shaders/shadow_summed_area_format.glsl);
    /// 0 when it has none. It is what unit SG_UNIT_SHADOW_MINMAX + slot reads.
    [[nodiscard]] unsigned minMaxOf(std::size_t i) const;
    /// Reads layer `layer` of scene light `i` as linear depth in metres (debug views, tests);
    /// empty when it has no such layer.
    [[nodiscard]] std::vector<float> readLayerDepth(std::size_t i, int layer) const;

    /// The public shader contract (shadow_shaders.h): uploads the records of scene lights
    /// `sceneLights` of the last prepared frame (slot i is `sceneLights[i]`), positions relative
    /// to `wsCamera`, into buffers the system owns, and returns what a game's shader reads. Call
    /// after `render`. A light without a map this frame reads as lit. The buffers are rewritten
    /// by the next call. Throws `std::invalid_argument` for more than SG_MAX_LIGHTS_PER_PASS
    /// lights or an index that is not a scene light; `GlError` for an error of its own.
    const ShadowShaderInputs& shaderInputs(std::span<const int> sceneLights, const glm::dvec3& wsCamera);
    /// `shaderInputs` for a game built without exceptions.
    [[nodiscard]] Result<const ShadowShaderInputs*> tryShaderInputs(std::span<const int> sceneLights,
                                                                    const glm::dvec3& wsCamera) noexcept;
    /// Binds `inputs` at `points`: the three uniform buffers (whole), and per slot the depth
    /// array with the comparison sampler and with the raw-depth sampler, and the pyramid. These
    /// bindings are the host's draw state: they stay after the call (nothing else changes).
    void bindShaderInputs(const ShadowShaderInputs& inputs, const ShadowBindingPoints& points = {}) const;
    /// What `bindShaderInputs` binds besides the light and layer blocks: the kernel block, and
    /// per slot i < SG_MAX_LIGHTS_PER_PASS the maps of scene light `sceneLights[i]` (-1 or a
    /// slot beyond the span: none). For a renderer that keeps its own light and layer records.
    void bindShadowResources(std::span<const int> sceneLights, const ShadowBindingPoints& points = {}) const;
    /// Writes the screen-space shadow mask of scene lights `sceneLights` (up to
    /// SG_MAX_MASK_LIGHTS; light i in channel i) of the last prepared and rendered frame into
    /// `request.target` (see `ShadowMaskRequest`). Each light's technique is the one the module's
    /// renderer uses, compiled only for the light configurations asked for. A guest like
    /// `render`: the GL state it changes is put back, a host error pending before the call is a
    /// `HostGlError` warning in `stats`. Throws `std::invalid_argument` naming the problem for
    /// too many lights, a light that is not a scene light, a zero texture or a size below 1;
    /// `GlError` when the target cannot be drawn to.
    void renderMask(std::span<const int> sceneLights, const ShadowMaskRequest& request, FrameStats& stats);
    /// `renderMask` for a game built without exceptions.
    [[nodiscard]] Status tryRenderMask(std::span<const int> sceneLights, const ShadowMaskRequest& request,
                                       FrameStats& stats) noexcept;

private:
    struct ShaderInputsGpu;
    struct MaskGpu;
    ShadowPlanner planner_;
    std::unique_ptr<ShadowGpu> gpu_;
    std::unique_ptr<ShaderInputsGpu> inputs_;
    std::unique_ptr<MaskGpu> mask_;  ///< made on the first `renderMask`
};

}  // namespace shadow
