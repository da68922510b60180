// Per-frame statistics: pass timings and the counters that show what work was skipped.
#pragma once

#include <shadow/warnings.h>

#include <string>
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
    int layersDrawn = 0;      ///< redrawn this frame
    int layersReused = 0;     ///< unchanged since the last frame, not redrawn
    int layersCleared = 0;    ///< no caster in the layer's frustum: cleared, not drawn
    int castersDrawn = 0;     ///< draw calls into this light's layers
    bool affectsView = true;  ///< false when the light cannot reach anything the camera sees
};

/// Everything measured in one frame. Timings are milliseconds.
struct FrameStats {
    std::string renderer;  ///< GL_RENDERER
    /// "wall-clock-fence" on CPU rasterisers (timer queries miss rasterisation there),
    /// "timer-query" on GPUs.
    std::string timingMethod;
    std::vector<PassTiming> passes;
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
    int mainPasses = 0;
    int programsCompiled = 0;  ///< shader programs built this frame (0 in steady state)
    /// Entities whose world matrix (or an ancestor's) is not finite, skipped by every pass
    /// (`TransformStats::nonFinite`); each is also a `NonFiniteTransform` warning.
    int entitiesSkippedNonFinite = 0;
    /// The frame's warnings: non-finite transforms first, then the shadow planner's
    /// (`ShadowFrame::warnings`: clamped settings, the texel budget's decisions).
    std::vector<Warning> warnings;

    /// Total time of the passes whose name starts with `prefix`.
    [[nodiscard]] double passMs(const std::string& prefix) const {
        double sum = 0.0;
        for (const PassTiming& p : passes) {
            if (p.name.rfind(prefix, 0) == 0) sum += p.ms;
        }
        return sum;
    }
};

}  // namespace shadow
