// The shadow planner's side of technique "auto" (auto_technique.h): per frame, the settings of
// every auto light before its map is sized, and afterwards what the next frame should know of it.
#pragma once

#include <shadow/auto_technique.h>
#include <shadow/shadow_planner.h>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shadow {

/// Owned by `ShadowPlanner`; one per planner.
class AutoPlanning {
public:
    /// Sets `settings` (technique, mapSize, taps), `automatic` and `autoChoice` of every light of
    /// `lights` whose settings ask for auto, from what `learn` kept of it last frame; clamps the
    /// budget (`ShadowLimits::shadowBudgetMs`, warnings into `warnings`). `time`: scene time or NaN.
    void choose(std::vector<ShadowLightPlan>& lights, const ShadowLimits& limits, double time,
                std::vector<Warning>& warnings);
    /// After the frame's layers are planned: what each auto light's next choice starts from, and
    /// what this frame's passes are predicted to take (for `observe`).
    void learn(const World& world, const CameraView& camera, const ShadowFrame& frame);
    /// Calibrates the cost model from the timings of the frame `learn` saw.
    void observe(const FrameStats& stats);
    [[nodiscard]] const AutoCostModel& costs() const { return state_.costs(); }

private:
    struct Known {
        Entity entity;
        AutoLightInput input;  ///< with the measured shares `observe` keeps across frames
        bool seen = false;
    };
    Known* known(Entity e);

    AutoTechniqueState state_;
    std::vector<Known> known_;
    /// Frames whose timings calibrated the cost model, and frames planned, since the auto lights
    /// appeared: the defaults are held until the first reaches `kAutoWarmUpFrames` (or the
    /// second `kAutoWarmUpFramesUntimed`, for a host that never calls observe).
    int learnedFrames_ = 0;
    int plannedFrames_ = 0;
    /// Timed frames still to pass unlearnt after a frame that built programs
    /// (`kAutoSettleFrames`).
    int settling_ = 0;
    bool anyAuto_ = false;   ///< the frame `learn` saw had an auto light
    bool counting_ = false;  ///< the frame planned last counts some auto light's edges
    // Predictions of the frame learn saw, for observe.
    /// Names of the lights whose passes were predicted, into the prepared frame's plans (valid
    /// until the next `prepare`, which `observe` precedes): no copy a frame.
    std::vector<std::string_view> drawnNames_;
    std::vector<std::uint64_t> drawnIds_;  ///< an auto light's entity bits, else 0
    std::vector<double> drawnPredictedMs_;
    std::array<double, kAutoLitTerms> litPredictedMs_{};  ///< the shading term's set by `observe`
    double screenPixels_ = 0.0;                           ///< the frame's, for the shading term
    int shadedLights_ = 0;
    // choose's working lists, kept for their storage.
    std::vector<std::uint64_t> ids_;
    std::vector<AutoLightInput> inputs_;
    std::vector<AutoLightChoice> choices_;
    std::vector<ShadowLightPlan*> plans_;
};

}  // namespace shadow
