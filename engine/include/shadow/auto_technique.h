// `technique: "auto"`: the planner picks a light's technique, map size and tap counts each frame
// (docs/auto_technique.md). Three pure pieces, testable without GL, and the state that ties them
// to frames:
//   `AutoCostModel`    predicted milliseconds of a light's shadow passes and lookups, from what the
//                      planner knows (layers, caster triangles, map texels, screen pixels), its
//                      coefficients scaled to the measured pass timings as the module runs;
//   `autoPredictedRmse` predicted visibility RMSE over the light's lit pixels: from the shares
//                      of its pixels at a shadow edge and in its penumbra that the lit passes
//                      counted (`absorbEdgeCounts`), else from its penumbra's width in texels;
//   `chooseAutoCandidates` the candidates of every auto light that minimise the predicted
//                      screen-weighted error within a budget;
//   `AutoTechniqueState` the choice kept from frame to frame (hysteresis) and the calibration.
//
// What this does not do: VSM/VSSM/MSM/MSM-soft and sdf are not candidates (their costs, chains
// and failure modes are not modelled yet), nor depth modes or cascades; the budget covers the
// auto lights alone.
#pragma once

#include <shadow/techniques.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace shadow {

struct FrameStats;

/// One configuration an auto light may take.
struct AutoCandidate {
    ShadowTechnique technique = ShadowTechnique::Pcss;
    int mapSize = 1024;
    int pcfSamples = 16;      ///< PCF taps (PCSS: its filter's)
    int blockerSamples = 16;  ///< PCSS blocker-search points (unused by hard and PCF)
};

/// The candidates, cheapest family first: hard, PCF (16 taps) and PCSS (16 + 16 taps, the
/// module's defaults; and 8 + 8) at 512, 1024 and 2048 texels.
[[nodiscard]] std::span<const AutoCandidate> autoCandidates();

/// The candidate of the module's defaults, PCSS at 1024 texels with 16 + 16 taps: what an auto
/// light takes while nothing is known of it, and where the chooser starts when the budget
/// affords it for every light.
inline constexpr int kAutoDefaultCandidate = 10;

/// What the lit passes counted of one auto light on a counting frame (shaders/lit.frag.glsl,
/// SG_COUNT_EDGES): the pixels sampled where its lookup ran, those within one texel of a shadow
/// edge (a hard lookup neither 0 nor 1), and those its technique left neither 0 nor 1 (its
/// penumbra and that band); with the map size and technique they were counted in.
struct AutoEdgeCounts {
    std::uint32_t light = 0;  ///< the light's entity (`Entity::bits`)
    std::uint32_t sampled = 0;
    std::uint32_t edge = 0;
    std::uint32_t soft = 0;
    int mapSize = 0;
    ShadowTechnique technique = ShadowTechnique::None;
};

/// What the planner knows of one auto light, from its last planned frame.
struct AutoLightInput {
    /// Screen pixels the light can reach (its screen rectangle), >= 0.
    double pixels = 0.0;
    /// Layers of its map that hold casters (drawn when redrawn), >= 0.
    int layers = 1;
    /// Caster triangles over those layers (a caster in two layers counts twice), >= 0.
    double casterTriangles = 0.0;
    /// Share of its layers redrawn per frame (1: every frame; 0: a static light, cached), [0, 1].
    double redrawShare = 1.0;
    /// Width of its widest penumbra in texels of a 1024-texel map: emitter size x (receiver -
    /// nearest caster) / nearest caster, over the texel's footprint at the receiver. >= 0.
    double penumbraTexels1024 = 0.0;
    /// This light's own measured / predicted shadow passes beyond the model's common scale (its
    /// casters' culling and overdraw, which the triangle count does not see); 1 until measured.
    double passScale = 1.0;
    /// Measured by the lit passes' edge counts (`AutoEdgeCounts`), -1 until then: the share of
    /// its pixels within one texel of a shadow edge in a 1024-texel map (the share counted in
    /// the map it had, times its size / 1024: the band narrows with finer maps), and the share
    /// in its penumbra beyond that band (counted while it ran PCSS; -1 before).
    double edgeShare1024 = -1.0;
    double penumbraShare = -1.0;
};

/// The parts of the lit pass the calibration scales apart: every shaded light's shading, and
/// the lookups of each candidate family.
enum class AutoLitTerm { Shading, Hard, Pcf, Pcss };
inline constexpr std::size_t kAutoLitTerms = 4;

/// Predicted milliseconds of one light in one candidate; coefficients in ms.
class AutoCostModel {
public:
    /// The shadow passes: redrawShare x (layers x perLayer + triangles x perTriangle + layers x
    /// mapSize^2 x perTexel), times the calibrated scales of the shadow passes (the common
    /// `shadowScale` and the light's `passScale`).
    [[nodiscard]] double shadowPassMs(const AutoLightInput& in, const AutoCandidate& c) const;
    /// The lookups: pixels x (perPixel[family] + taps x perTap), times the calibrated scale of the
    /// candidate's family. Taps: hard 1, PCF `pcfSamples`, PCSS `blockerSamples` / 2 +
    /// `pcfSamples` (the search reads its points in pairs).
    [[nodiscard]] double lookupMs(const AutoLightInput& in, const AutoCandidate& c) const;
    [[nodiscard]] double totalMs(const AutoLightInput& in, const AutoCandidate& c) const {
        return shadowPassMs(in, c) + lookupMs(in, c);
    }
    /// Calibration from a measured shadow pass of `predictedMs` that took `measuredMs`: an
    /// exponential moving average (weight `kAutoCalibrationRate`) of their ratio, clamped to
    /// [1/64, 64] per frame.
    void observeShadowPass(double predictedMs, double measuredMs);
    /// The lit pass as a whole, `predictedMs[t]` the part of term t (scaled): the scales are a
    /// least-squares fit over the recent frames (`kAutoLitMemory`), so terms that run together
    /// are told apart as the mix of families changes from frame to frame.
    void observeLitPass(std::span<const double, kAutoLitTerms> predictedMs, double measuredMs);
    /// Predicted lit pass without lookups, times the shading term's scale: the screen's `pixels`
    /// (perScreenPixel each), each of its `lights` shaded lights' shading (perShadedPixel a pixel)
    /// and the scene's `triangles` drawn by the lit passes (perLitTriangle each).
    [[nodiscard]] double shadingMs(double pixels, int lights, double triangles) const;
    /// The lit-pass term of candidate `c`'s lookups.
    [[nodiscard]] static AutoLitTerm termOf(const AutoCandidate& c);

    double perLayerMs = 0.2;      ///< a layer's bind, clear and draw set-up
    double perTriangleMs = 6e-5;  ///< one caster triangle in one layer
    double perTexelMs = 2.5e-6;   ///< one texel of one layer (clear, raster, read)
    /// A lookup's set-up per pixel the light reaches, per family (hard, PCF, PCSS): the receiver
    /// plane, the region test, PCSS's penumbra estimate. These three and the next two are
    /// llvmpipe's at 320x240: medians over five scenes of the lit pass's growth per pixel
    /// (`python3 benchmarks/fit_auto_error.py --auto-work DIR --lookup-costs` after
    /// `bash benchmarks/run_auto_budget.sh`; one round, so within about 30 % from run to run:
    /// the calibration replaces them within the first frames).
    std::array<double, 3> perPixelMs{3.0e-5, 3.4e-5, 7.5e-5};
    double perTapMs = 6.2e-6;  ///< one tap per pixel
    /// The lit pass without lookups (the shading term), llvmpipe's at 320x240 from the runs
    /// without shadows of the same five scenes (a least-squares fit, the same command): what
    /// the screen costs whatever the lights (raster, material), each shaded light's shading of a
    /// pixel, and a triangle the lit passes draw. The scene's triangles count: builtin:bunny's
    /// frame without shadows takes 3 times builtin:default's with as many lights. (A cost per
    /// shaded light and pixel alone, 40 ns, over-predicted builtin:default's 2.4 ms four times
    /// and left the lookups' scales the rest: auto went over its budget there.)
    double perScreenPixelMs = 2.6e-5;
    double perShadedPixelMs = 1.5e-6;
    double perLitTriangleMs = 7.6e-5;
    double shadowScale = 1.0;  ///< measured / predicted shadow passes (calibrated)
    /// Measured / predicted of each lit-pass term (`AutoLitTerm`), calibrated.
    std::array<double, kAutoLitTerms> litScale{1.0, 1.0, 1.0, 1.0};

private:
    // The lit-pass fit's normal equations over the recent frames (unscaled terms).
    std::array<double, kAutoLitTerms * kAutoLitTerms> litNormal_{};
    std::array<double, kAutoLitTerms> litRhs_{};
};

/// Weight of a frame one frame older in the lit pass's fit (about 20 frames of memory).
inline constexpr double kAutoLitMemory = 0.95;
/// Pull of the scales held in that fit, per term, against the data's mean weight per term: keeps
/// a term the frames cannot tell apart where it was. One light's frames show its shading only
/// together with its lookups, whatever the family, so they fix each family's total and the
/// differences between families but not the split; the shading is held ten times firmer, and
/// the lookups take what the frames show beyond it.
inline constexpr std::array<double, kAutoLitTerms> kAutoLitPrior{0.1, 0.01, 0.01, 0.01};

/// Weight of the newest frame in the calibration's moving averages.
inline constexpr double kAutoCalibrationRate = 0.3;

/// Predicted visibility RMSE of a light over its lit pixels in candidate `c`: from its counted
/// shares (`edgeShare1024`, `penumbraShare`) once the lit passes counted both, else from its
/// penumbra's width in texels of `c`'s map (docs/auto_technique.md states both fits and their
/// errors).
[[nodiscard]] double autoPredictedRmse(const AutoLightInput& in, const AutoCandidate& c);

/// The candidate (index into `autoCandidates()`) per light that minimises the pixel-weighted sum
/// of predicted mean squared errors, sum pixels x rmse^2, with the summed predicted time within
/// `budgetMs` (0 or infinite: no budget, each light takes its least error). Greedy: every light
/// starts at the module's defaults when their predicted time is within the budget (give or take
/// `kAutoSwitchGain`, the predictions' own error), else at its cheapest candidate, and the
/// budget then keeps `kAutoBudgetHeadroom` of itself free for the predictions' error; then the
/// move of most error saved per millisecond that still fits is taken until none fits. Over budget at
/// the cheapest, the cheapest stay. Starting from the defaults, the error model only ever moves a
/// light where it predicts less error: its absolute figures are rough (a factor of 1.5 on the
/// scenes it was fitted on, docs/auto_technique.md), and the defaults are the configuration
/// measured best in general, so a budget that affords them is never spent on a worse one.
[[nodiscard]] std::vector<int> chooseAutoCandidates(std::span<const AutoLightInput> lights, const AutoCostModel& costs,
                                                    double budgetMs);

/// Hysteresis: a light moves to a new candidate only when the chooser has preferred it for
/// `kAutoConfirmFrames` frames in a row, and either its predicted error is lower by more than
/// `kAutoSwitchGain` and at least `kAutoHoldSeconds` of scene time passed since its last switch
/// (`kAutoHoldFrames` frames without a time), or the choices held are predicted over the budget,
/// the new candidate is cheaper and either the hold passed or the light made its first choice
/// less than the hold ago (its calibration settling): after its first second no light switches
/// twice within the hold.
inline constexpr int kAutoConfirmFrames = 3;
inline constexpr double kAutoSwitchGain = 0.1;
inline constexpr double kAutoHoldSeconds = 1.0;
inline constexpr int kAutoHoldFrames = 30;

/// Frames the module's defaults are held when auto lights appear, their timings calibrating the
/// cost model, before the first choice (without timings, `kAutoWarmUpFramesUntimed` frames): the
/// first choice then knows what the defaults cost here, not what the built-in coefficients say.
inline constexpr int kAutoWarmUpFrames = 3;
inline constexpr int kAutoWarmUpFramesUntimed = 10;
/// Timed frames after a frame that built programs whose timings the cost model does not learn
/// from: over the 70 fixed-configuration runs of benchmarks/run_auto_budget.sh, the first frame
/// after the compile took 1.17-1.25x the steady frame (median of two runs' runs; mean up to
/// 1.37x), the next ones 1.03-1.07x (fit_auto_error.py --settle). Learnt, it made the warm-up
/// price the defaults 1.5-2x too high on a quiet machine, and a budget equal to their measured
/// cost bought hard shadows.
inline constexpr int kAutoSettleFrames = 1;
/// The lit passes count an auto light's edges (`AutoEdgeCounts`) on its first planned frame and
/// one frame in this many after it; the planner learns no timing from those frames (each
/// counted pixel of every SIMD group runs the count's hard lookup and atomic additions).
inline constexpr int kAutoCountEvery = 8;
/// Weight of the newest count in the measured shares' moving average.
inline constexpr double kAutoEdgeRate = 0.5;
/// Updates `in`'s measured shares (`edgeShare1024`, `penumbraShare`) from one frame's counts:
/// nothing when none were sampled; the penumbra share only from counts taken while it ran PCSS
/// (hard's and PCF's visibility tell nothing of the emitter's penumbra).
void absorbEdgeCounts(const AutoEdgeCounts& counts, AutoLightInput& in);

/// Share of a budget below the defaults' cost the chooser leaves unspent, so that choices
/// predicted a little under the budget still fit it when measured.
inline constexpr double kAutoBudgetHeadroom = 0.1;
/// The choices held count as over the budget (and a light may move to a cheaper candidate
/// without waiting for the error's gain) only when predicted over it by more than this share:
/// the spread of a steady frame's prediction (predicted shadow passes within 1-6 % of measured,
/// docs/auto_technique.md). Without it a choice whose cost is the budget itself (a budget set to
/// what the defaults measured) was kept or dropped by a few per cent of noise in the first
/// frames' calibration, and once dropped never came back (builtin:plates-boxes bought hard
/// shadows at the defaults' own cost).
inline constexpr double kAutoBudgetTolerance = 0.05;

/// One auto light's choice and what it was predicted to cost.
struct AutoLightChoice {
    int candidate = -1;  ///< into `autoCandidates()`; -1 before the first choice
    double predictedShadowPassMs = 0.0;
    double predictedLookupMs = 0.0;
    double predictedRmse = 0.0;
    AutoLightInput input;  ///< what the choice was made from
};

/// The choice of every auto light kept from frame to frame, and the calibrated cost model.
class AutoTechniqueState {
public:
    /// Chooses for this frame's auto lights, `ids` identifying each across frames (entity
    /// indices), `inputs` what is known of each; writes `out[i]`. `time` is the scene time (s),
    /// NaN when unknown (the hold is then counted in frames).
    void choose(std::span<const std::uint64_t> ids, std::span<const AutoLightInput> inputs, double budgetMs,
                double time, std::span<AutoLightChoice> out);
    /// Calibrates the cost model from a frame's pass timings (its shadow passes per light, named
    /// "Shadow/<light>/…", and its "Main/Lit*" passes) against what was predicted for it.
    /// `predictedShadowMs[i]` and `names[i]` belong to the lights whose passes were drawn.
    /// `ids[i]` the light's identity when it is an auto light (its own `passScale` is
    /// calibrated too), else 0.
    void calibrate(std::span<const std::string_view> names, std::span<const std::uint64_t> ids,
                   std::span<const double> predictedShadowMs, std::span<const double, kAutoLitTerms> predictedLitMs,
                   const FrameStats& stats);
    [[nodiscard]] const AutoCostModel& costs() const { return costs_; }
    [[nodiscard]] AutoCostModel& costs() { return costs_; }

private:
    struct Held {
        std::uint64_t id = 0;
        int current = -1;
        int pending = -1;
        int pendingFrames = 0;
        double switchedAt = 0.0;  ///< scene time of the last switch
        int framesSinceSwitch = 0;
        double firstAt = 0.0;  ///< scene time of the first choice
        int framesSinceFirst = 0;
        double passScale = 1.0;  ///< `AutoLightInput::passScale`, calibrated
        bool seen = false;
    };
    Held& held(std::uint64_t id);
    /// The hysteresis' test for a move the chooser confirmed: `gains` its error gain is enough,
    /// `cheaper` it is a cheaper move while over the budget.
    static bool mayMove(const Held& h, bool gains, bool cheaper, double time);
    AutoCostModel costs_;
    std::vector<Held> held_;
    std::vector<AutoLightInput> scaled_;  ///< this frame's inputs with each light's passScale
};

}  // namespace shadow
