// Per-frame statistics: pass timings and the counters that show what work was skipped.
#pragma once

#include <shadow/auto_technique.h>
#include <shadow/warnings.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shadow {

/// Wall time of one GPU pass (shadow layer, main pass, readback).
struct PassTiming {
    std::string name;  ///< debug-group name, e.g. "Shadow/sun/layer0", "Main/Lit"
    double ms = 0.0;
};

/// What the shadow system did for one light this frame.
struct LightShadowStats {
    int sceneIndex = -1;  ///< `<i>` of visibility_<i>.exr
    std::string name;
    std::string type;          ///< "directional" | "spot" | "point"
    std::string technique;     ///< the technique its pixels use: "none" | "hard" | "pcf" | "pcss" | …
    int mapSize = 0;           ///< texels per layer edge actually allocated (0 = no map)
    int requestedMapSize = 0;  ///< the light's mapSize setting (clamped to the GL limit); 0 without a shadow
    int layers = 0;
    int layersDrawn = 0;    ///< redrawn this frame
    int layersReused = 0;   ///< unchanged since the last frame, not redrawn
    int layersCleared = 0;  ///< no caster in the layer's frustum: cleared, not drawn
    int castersDrawn = 0;   ///< draw calls into this light's layers
    /// Draw calls of its moment layers' backgrounds (ShadowLayerPlan::backgrounds), besides.
    int backgroundsDrawn = 0;
    /// Of `castersDrawn`: solid meshes (`MeshData::solid`) and game casters
    /// (`ShadowCasterDraw::solid`) drawn with their back faces culled, the nearest depths
    /// unchanged at about half the fragments.
    int castersCulled = 0;
    /// PCF, PCSS: the depth texels their min/max pyramids read this frame, over the layers
    /// rebuilt: the tiles that hold a texel the layer's casters can have drawn (the others are
    /// cleared to the far depth's range).
    long long pyramidTexelsRead = 0;
    bool affectsView = true;  ///< false when the light cannot reach anything the camera sees
    /// PCF, PCSS: the lookups read the min/max pyramid this frame (`ShadowLightPlan::regionTest`).
    bool regionTest = false;
    /// Its map was made this frame (first frame, or a new size or layer count): its texture name
    /// changed and every layer was drawn.
    bool mapAllocated = false;
    /// GPU memory of its shadow map (32-bit depth) and of its filter chain (min/max pyramid for
    /// PCF and PCSS, depth moments for VSM, MSM and MSM-soft, the summed-area table for VSSM; 0
    /// for the others), in bytes.
    long long mapBytes = 0;
    long long filterChainBytes = 0;
    /// PCF, VSM: the filter radius (m at the receiver) its lookups took, at least one texel's
    /// footprint (`ShadowLightPlan::pcfRadiusMetres`; 0: the texel's alone).
    double pcfRadiusMetres = 0.0;
    /// The widest filter radius (texels) its lookups took (`ShadowLightPlan::maxFilterTexels`).
    float maxFilterTexels = 0.0f;
    /// The taps it ran with.
    int pcfSamples = 0;
    int blockerSamples = 0;
    /// Technique auto (`Shadow::autoTechnique`): the planner chose `technique`, `mapSize` and the
    /// taps; `autoChoice` is what it predicted of them and the inputs it chose from (candidate
    /// -1 and all 0 while nothing is known of the light yet).
    bool automatic = false;
    AutoLightChoice autoChoice;
};

/// Everything measured in one frame. Timings are milliseconds.
///
/// One `FrameStats` reused frame after frame (`FrameRunner::runFrame(…, FrameStats&)`) costs no
/// allocation in steady state: `reset` keeps the storage of its lists and of the strings in
/// them, and `addPass` and `addLight` reuse it.
struct FrameStats {
    std::string renderer;  ///< GL_RENDERER
    /// "wall-clock-fence" on CPU rasterisers (timer queries miss rasterisation there),
    /// "timer-query" on GPUs.
    std::string timingMethod;
    /// The passes timed, in the order they ran. With timer queries they are an earlier frame's:
    /// queries are read a frame or more later, so that timing never waits for the GPU.
    std::vector<PassTiming> passes;
    /// How many frames before this one the passes in `passes` ran (0 with the wall clock).
    int timingLagFrames = 0;
    double cpuAnimateMs = 0.0;
    double cpuTransformsMs = 0.0;
    double cpuShadowPrepareMs = 0.0;
    double cpuRenderSubmitMs = 0.0;
    /// Per scene light, index = position in `Scene::lights` (every light, shadowed or not).
    std::vector<LightShadowStats> lights;
    int shadowLayersDrawn = 0;
    int shadowLayersReused = 0;
    int shadowLayersCleared = 0;
    int shadowDrawCalls = 0;
    int mainDrawCalls = 0;
    /// Triangles the main passes drew (every pass: a scene drawn by two lit passes counts twice).
    std::int64_t mainTriangles = 0;
    int mainPasses = 0;
    /// Shader programs built this frame (compiled, or loaded from the program cache) by the shadow
    /// passes, the mask and the lit passes; 0 in steady state.
    int programsCompiled = 0;
    /// GPU memory of the nearest-depth scratch the second-depth modes draw through (one 32-bit
    /// depth texture of the largest map in such a mode, shared by every light; 0 without one).
    long long shadowScratchBytes = 0;
    /// Technique sdf: GPU memory of the distance-field atlas and instance records (bytes), the
    /// fields baked this frame and the time their bakes took (a mesh is baked once, when a light
    /// first marches through it).
    long long distanceFieldBytes = 0;
    int distanceFieldsBaked = 0;
    double distanceFieldBakeMs = 0.0;
    /// Entities whose world matrix (or an ancestor's) is not finite, skipped by every pass
    /// (`TransformStats::nonFinite`); each is also a `NonFiniteTransform` warning.
    int entitiesSkippedNonFinite = 0;
    /// Technique auto: the lit passes' edge counts of its lights (`ShadowLightPlan::countEdges`)
    /// that the GPU finished since the last frame, read back without waiting for it: usually
    /// those of the frame before, counted at one pixel in each 2x2 block.
    std::vector<AutoEdgeCounts> edgeCounts;
    /// The frame's warnings: non-finite transforms first, then the shadow planner's
    /// (`ShadowFrame::warnings`: clamped settings, the memory budget's decisions).
    std::vector<Warning> warnings;

    /// Total time of the passes whose name starts with `prefix`.
    [[nodiscard]] double passMs(const std::string& prefix) const {
        double sum = 0.0;
        for (const PassTiming& p : passes) {
            if (p.name.rfind(prefix, 0) == 0) sum += p.ms;
        }
        return sum;
    }

    /// Makes these the stats of a new frame: every number 0, every string and list empty. The
    /// entries of `passes` and `lights` are set aside, for `addPass` and `addLight` to reuse.
    void reset() {
        FrameStats next;
        next.renderer = std::move(renderer);
        next.renderer.clear();
        next.timingMethod = std::move(timingMethod);
        next.timingMethod.clear();
        next.passes = std::move(passes);
        next.sparePasses_ = std::move(sparePasses_);
        setAside(next.passes, next.sparePasses_);
        next.lights = std::move(lights);
        next.spareLights_ = std::move(spareLights_);
        setAside(next.lights, next.spareLights_);
        next.edgeCounts = std::move(edgeCounts);
        next.edgeCounts.clear();
        next.warnings = std::move(warnings);
        next.warnings.clear();
        *this = std::move(next);
    }

    /// Appends the timing of the pass `name`.
    void addPass(std::string_view name, double ms) {
        PassTiming& p = passes.emplace_back();
        if (!sparePasses_.empty()) {
            p.name = std::move(sparePasses_.back().name);
            sparePasses_.pop_back();
        }
        p.name.assign(name);
        p.ms = ms;
    }

    /// Appends the stats of the next scene light, every field at its default.
    LightShadowStats& addLight() {
        LightShadowStats& ls = lights.emplace_back();
        if (!spareLights_.empty()) {
            LightShadowStats& spare = spareLights_.back();
            auto reuse = [](std::string& to, std::string& from) {
                to = std::move(from);
                to.clear();
            };
            reuse(ls.name, spare.name);
            reuse(ls.type, spare.type);
            reuse(ls.technique, spare.technique);
            spareLights_.pop_back();
        }
        return ls;
    }

private:
    /// Moves the entries of `list` to `spare`, last first: the next frame's entry k reuses the
    /// storage of this frame's entry k.
    template <typename T>
    static void setAside(std::vector<T>& list, std::vector<T>& spare) {
        while (!list.empty()) {
            spare.push_back(std::move(list.back()));
            list.pop_back();
        }
    }

    std::vector<PassTiming> sparePasses_;
    std::vector<LightShadowStats> spareLights_;
};

}  // namespace shadow
