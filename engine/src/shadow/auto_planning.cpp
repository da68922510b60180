// The shadow planner's side of technique "auto" (auto_planning.h).
#include "shadow/auto_planning.h"

#include <shadow/stats.h>

#include "core/camera.h"
#include "core/screen_bounds.h"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace shadow {
namespace {

/// Pixels assumed when the image's size is unknown (`CameraView::pixelWidth` 0).
constexpr double kUnknownScreenPixels = 640.0 * 360.0;

/// Writes candidate `c` into `plan`'s settings, its map no larger than the GL allows.
void apply(const AutoCandidate& c, const ShadowLimits& limits, ShadowLightPlan& plan) {
    plan.settings.technique = c.technique;
    plan.settings.mapSize = std::clamp(c.mapSize, 1, std::max(1, limits.maxTextureSize));
    plan.settings.pcfSamples = c.pcfSamples;
    plan.settings.blockerSamples = c.blockerSamples;
    plan.mapSize = plan.settings.mapSize;
}

/// The candidate-like description of `plan`'s own settings, for the cost of a light the planner
/// did not choose for: the moment and field techniques are costed as PCSS (their own costs are
/// not modelled).
AutoCandidate settingsOf(const ShadowLightPlan& plan) {
    const Shadow& s = plan.settings;
    const ShadowTechnique t = s.technique == ShadowTechnique::Hard || s.technique == ShadowTechnique::Pcf
                                  ? s.technique
                                  : ShadowTechnique::Pcss;
    return {t, plan.mapSize, s.pcfSamples, s.blockerSamples};
}

/// Triangles of caster `e`'s draw (a mesh's, or a game's indexed draw's), 0 when unknown.
double trianglesOf(const World& world, Entity e) {
    if (const Mesh* mesh = world.tryGet<Mesh>(e); mesh != nullptr && mesh->data != nullptr) {
        return static_cast<double>(mesh->data->indices.size()) / 3.0;
    }
    const ShadowCasterDraw* own = world.tryGet<ShadowCasterDraw>(e);
    return own != nullptr ? own->indexCount / 3.0 : 0.0;
}

/// Width in texels of a 1024-texel map of layer `layer`'s widest penumbra: from the nearest
/// caster (`blockerNear`) to the far end of its depth range, for `plan`'s emitter.
double penumbraTexels1024(const ShadowLightPlan& plan, const ShadowLayerPlan& layer) {
    const double scale = layer.clipFromLight[0][0];  // perspective: 1 / tan(half angle); ortho: 2 / width
    const double far = layer.depthScale;
    if (!(scale > 0.0) || !(far > 0.0)) return 0.0;
    if (layer.orthographic) {
        const double depth = std::max(far - static_cast<double>(layer.blockerNear), 0.0);
        return std::tan(static_cast<double>(plan.light.angularRadius)) * depth * scale * 1024.0;
    }
    const double nearest = std::max(static_cast<double>(layer.blockerNear), 1e-3);
    if (far <= nearest) return 0.0;
    return plan.light.radius * 1024.0 * (far - nearest) * scale / (nearest * far);
}

/// What the cost and error models read of `plan` (a light with a map) this frame;
/// `redrawShare` the share of its layers with casters redrawn this frame.
AutoLightInput describe(const World& world, const ScreenView& view, const ShadowLightPlan& plan) {
    AutoLightInput in;
    in.pixels = static_cast<double>(screenBounds(plan, view).area());
    in.layers = 0;
    int drawn = 0;
    for (const ShadowLayerPlan& layer : plan.layers) {
        if (layer.casters.empty()) continue;
        ++in.layers;
        drawn += layer.dirty ? 1 : 0;
        for (Entity caster : layer.casters) in.casterTriangles += trianglesOf(world, caster);
        in.penumbraTexels1024 = std::max(in.penumbraTexels1024, penumbraTexels1024(plan, layer));
    }
    in.redrawShare = in.layers > 0 ? static_cast<double>(drawn) / in.layers : 0.0;
    return in;
}

}  // namespace

AutoPlanning::Known* AutoPlanning::known(Entity e) {
    for (Known& k : known_) {
        if (k.entity == e) return &k;
    }
    return nullptr;
}

void AutoPlanning::choose(std::vector<ShadowLightPlan>& lights, const ShadowLimits& limits, double time,
                          std::vector<Warning>& warnings) {
    ids_.clear();
    inputs_.clear();
    plans_.clear();
    bool any = false;
    const bool warm = learnedFrames_ >= kAutoWarmUpFrames || plannedFrames_ >= kAutoWarmUpFramesUntimed;
    const bool cadence = plannedFrames_ % kAutoCountEvery == 0;
    counting_ = false;
    for (ShadowLightPlan& plan : lights) {
        if (!plan.settings.autoTechnique || plan.settings.technique == ShadowTechnique::None) continue;
        any = true;
        plan.automatic = true;
        const Known* k = known(plan.entity);
        // A new light is counted on its first frame, at the defaults (PCSS: its penumbra too).
        plan.countEdges = cadence || k == nullptr;
        counting_ = counting_ || plan.countEdges;
        if (k != nullptr && warm) {
            ids_.push_back(plan.entity.bits());
            inputs_.push_back(k->input);
            plans_.push_back(&plan);
        } else {
            apply(autoCandidates()[kAutoDefaultCandidate], limits, plan);  // nothing known yet, or warming up
        }
    }
    if (!any) {
        learnedFrames_ = plannedFrames_ = 0;  // the next auto lights warm up again
        return;
    }
    ++plannedFrames_;
    double budget = limits.shadowBudgetMs;
    if (std::isnan(budget) || budget < 0.0) {
        warnings.push_back({WarningCode::SettingClamped, "shadowBudgetMs",
                            "shadowBudgetMs " + std::to_string(budget) + " is not >= 0: no budget (0)"});
        budget = 0.0;
    }
    choices_.resize(ids_.size());
    state_.choose(ids_, inputs_, budget, time, choices_);
    const std::span<const AutoCandidate> candidates = autoCandidates();
    for (std::size_t i = 0; i < plans_.size(); ++i) {
        plans_[i]->autoChoice = choices_[i];
        apply(candidates[static_cast<std::size_t>(choices_[i].candidate)], limits, *plans_[i]);
    }
}

void AutoPlanning::learn(const World& world, const CameraView& camera, const ShadowFrame& frame) {
    anyAuto_ =
        std::any_of(frame.lights.begin(), frame.lights.end(), [](const ShadowLightPlan& p) { return p.automatic; });
    if (!anyAuto_) {
        known_.clear();
        return;
    }
    const bool sized = camera.pixelWidth > 0 && camera.pixelHeight > 0;
    const ScreenView view{cameraClipFromWorld(camera), sized ? camera.pixelWidth : 640,
                          sized ? camera.pixelHeight : 360, frame.wsGeometry};
    const double screen = sized ? static_cast<double>(camera.pixelWidth) * camera.pixelHeight : kUnknownScreenPixels;
    const auto shaded = std::count_if(frame.lights.begin(), frame.lights.end(),
                                      [](const ShadowLightPlan& p) { return p.shaded && p.affectsView; });
    const AutoCostModel& costs = state_.costs();
    litPredictedMs_.fill(0.0);
    // The shading term waits for the frame's triangles, which the renderer counts (observe).
    screenPixels_ = screen;
    shadedLights_ = static_cast<int>(shaded);
    drawnNames_.clear();
    drawnIds_.clear();
    drawnPredictedMs_.clear();
    for (Known& k : known_) k.seen = false;
    for (const ShadowLightPlan& plan : frame.lights) {
        if (!plan.hasMap() || !plan.affectsView) continue;
        const AutoLightInput in = describe(world, view, plan);
        const AutoCandidate c = settingsOf(plan);
        litPredictedMs_[static_cast<std::size_t>(AutoCostModel::termOf(c))] += costs.lookupMs(in, c);
        if (in.redrawShare > 0.0 && c.technique == plan.settings.technique) {
            drawnNames_.push_back(plan.name);
            drawnIds_.push_back(plan.automatic ? plan.entity.bits() : 0);
            drawnPredictedMs_.push_back(costs.shadowPassMs(in, c));
        }
        if (!plan.automatic) continue;
        Known* k = known(plan.entity);
        if (k == nullptr) k = &known_.emplace_back(Known{plan.entity, in, false});
        const AutoLightInput before = k->input;
        k->input = in;
        k->input.redrawShare = before.redrawShare + kAutoCalibrationRate * (in.redrawShare - before.redrawShare);
        k->input.edgeShare1024 = before.edgeShare1024;
        k->input.penumbraShare = before.penumbraShare;
        k->seen = true;
    }
    std::erase_if(known_, [](const Known& k) { return !k.seen; });
}

void AutoPlanning::observe(const FrameStats& stats) {
    if (!anyAuto_) return;
    // The edge counts the GPU finished (a frame or more old): a light gone since has none kept.
    for (const AutoEdgeCounts& counts : stats.edgeCounts) {
        for (Known& k : known_) {
            if (k.entity.bits() == counts.light) absorbEdgeCounts(counts, k.input);
        }
    }
    // A frame that built programs timed their compile too, and the frames right after it are
    // slower than the steady state (kAutoSettleFrames): nothing to learn of the passes.
    if (stats.programsCompiled > 0) {
        settling_ = kAutoSettleFrames;
        return;
    }
    if (counting_) return;  // the count's own work is in this frame's lit passes
    if (settling_ > 0) {
        --settling_;
        return;
    }
    ++learnedFrames_;
    // The lit pass without lookups, from the triangles the main passes drew (each lit pass
    // draws the scene; FrameStats::mainTriangles).
    litPredictedMs_[static_cast<std::size_t>(AutoLitTerm::Shading)] =
        state_.costs().shadingMs(screenPixels_, shadedLights_, static_cast<double>(stats.mainTriangles));
    state_.calibrate(drawnNames_, drawnIds_, drawnPredictedMs_, litPredictedMs_, stats);
}

}  // namespace shadow
