// technique "auto": candidates, cost and error models, the chooser and its hysteresis (see
// auto_technique.h; docs/auto_technique.md says where the numbers come from).
#include <shadow/auto_technique.h>
#include <shadow/stats.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace shadow {
namespace {

constexpr std::array<AutoCandidate, 12> kCandidates{{
    {ShadowTechnique::Hard, 512, 1, 1},
    {ShadowTechnique::Hard, 1024, 1, 1},
    {ShadowTechnique::Hard, 2048, 1, 1},
    {ShadowTechnique::Pcf, 512, 16, 1},
    {ShadowTechnique::Pcf, 1024, 16, 1},
    {ShadowTechnique::Pcf, 2048, 16, 1},
    {ShadowTechnique::Pcss, 512, 8, 8},
    {ShadowTechnique::Pcss, 1024, 8, 8},
    {ShadowTechnique::Pcss, 2048, 8, 8},
    {ShadowTechnique::Pcss, 512, 16, 16},
    {ShadowTechnique::Pcss, 1024, 16, 16},
    {ShadowTechnique::Pcss, 2048, 16, 16},
}};
static_assert(kCandidates[kAutoDefaultCandidate].technique == ShadowTechnique::Pcss &&
                  kCandidates[kAutoDefaultCandidate].mapSize == 1024 &&
                  kCandidates[kAutoDefaultCandidate].pcfSamples == 16 &&
                  kCandidates[kAutoDefaultCandidate].blockerSamples == 16,
              "kAutoDefaultCandidate is the module's defaults");

/// Taps a lookup takes per pixel (the search reads its points in pairs, as 2x2 gathers).
double tapsOf(const AutoCandidate& c) {
    switch (c.technique) {
        case ShadowTechnique::Hard: return 1.0;
        case ShadowTechnique::Pcf: return c.pcfSamples;
        default: return 0.5 * c.blockerSamples + c.pcfSamples;
    }
}

/// Multiplies `scale` by the ratio measured / predicted, damped (a geometric moving average).
void calibrateScale(double& scale, double predictedMs, double measuredMs) {
    if (!(predictedMs > 0.0) || !(measuredMs > 0.0) || !std::isfinite(predictedMs) || !std::isfinite(measuredMs)) {
        return;
    }
    const double ratio = std::clamp(measuredMs / predictedMs, 1.0 / 64.0, 64.0);
    scale = std::clamp(scale * std::pow(ratio, kAutoCalibrationRate), 1e-6, 1e6);
}

// The error model, fitted by benchmarks/fit_auto_error.py to benchmarks/results/error_vs_time.csv
// (27 rows of hard, PCF and PCSS on plates, bunny and default; RMS of log(predicted / measured)
// 0.36, a factor of 1.43). RMSE over a light's penumbra pixels, for a penumbra w texels wide in
// the candidate's map:
//   hard: kEdge * w / (w + kHardBlur), PCF: kEdge * w / (w + kPcfBlur) (a step against a ramp);
//   PCSS: sqrt((kPcssTaps / taps)^2 + (kPcssTexel / w)^2) (the blocker search's sampling, and
//   the penumbra's estimate from few texels).
// RMSE over all its lit pixels: sqrt(share x penumbra^2 + kOtherError^2), share the part of them
// in penumbra, which grows with the penumbra: min(1, kPenumbraShare * w1024 / 1024 +
// kPenumbraShareFloor); kOtherError what no candidate removes (acne, leaks at contact).
constexpr double kEdge = 0.2887;  // a unit step against a linear ramp: 1 / sqrt(12)
// The two blurs are from the per-light rows of benchmarks/auto_budget.py instead (fit_auto_error.py
// --auto-work): PCF's default radius is one texel since the sweep was run, so it blurs a few
// texels, not 26 (per-light fit 3.2); hard's fit is 0, kept at one texel, the map's own step,
// so that a penumbra narrower than a texel is not an error. Within each light the candidates'
// predicted order matches the measured one in 81 % of the pairs (79 % with the sweep's blurs).
constexpr double kHardBlur = 1.0;
constexpr double kPcfBlur = 3.2;
constexpr double kPcssTaps = 0.611;
constexpr double kPcssTexel = 2.839;
constexpr double kPenumbraShare = 0.8441;
constexpr double kPenumbraShareFloor = 0.0;
constexpr double kOtherError = 0.007252;
// One texel (fit_auto_error.py's eighth constant, not refitted with the others): on the per-light
// rows of bash benchmarks/run_auto_budget.sh it raised, with PCSS's error capped at hard's below,
// the share of one light's candidate pairs whose predicted order is the measured one from 81 % to
// 87 % (fence's point-sized spot, whose error falls with the map's size, was predicted the same at
// every size, and its PCSS better than its hard shadow, which it equals).
constexpr double kEdgeBand = 1.0;

// The model from the lit passes' edge counts (AutoLightInput::edgeShare1024, penumbraShare), fitted
// by benchmarks/fit_auto_error.py --auto-work to the per-light rows of bash
// benchmarks/run_auto_budget.sh (docs/auto_technique.md, "Edge counts"). A light's mean squared
// error over its pixels is the sum of two areas times the squared error within each:
//   the band within one texel of the candidate's map of a shadow edge, share edgeShare1024 x
//   1024 / mapSize (a finer map draws its edges nearer where they are), times kBandError[family];
//   its penumbra beyond that band, share penumbraShare, times kPenumbraError[family] (hard: a step
//   for a ramp; PCSS: its blocker search's sampling, kPcssPenumbra16 at 16 + 16 taps, growing as
//   (16 / taps)^kPcssPenumbraPower with fewer).
constexpr std::array<double, 3> kBandError{0.04092, 0.06483, 0.04755};  // hard, PCF, PCSS
constexpr std::array<double, 2> kPenumbraError{0.06222, 0.02282};       // hard, PCF
constexpr double kPcssPenumbra16 = 2.132e-4;
constexpr double kPcssPenumbraPower = 4.266;
/// The counts' model (above) of candidate `c`, for a light whose edges and penumbra were counted.
double countedRmse(const AutoLightInput& in, const AutoCandidate& c) {
    const double band = std::min(1.0, in.edgeShare1024 * 1024.0 / std::max(c.mapSize, 1));
    const double penumbra = std::clamp(in.penumbraShare, 0.0, 1.0);
    const auto family = static_cast<std::size_t>(AutoCostModel::termOf(c)) - 1;
    const double within = c.technique == ShadowTechnique::Pcss
                              ? kPcssPenumbra16 * std::pow(16.0 / std::max(c.blockerSamples, 1), kPcssPenumbraPower)
                              : kPenumbraError[family];
    // kOtherError, as the width model's: what no candidate removes, and no light is predicted
    // free of error because its counts found no edge.
    return std::sqrt(std::min(1.0, kBandError[family] * band + within * penumbra) + kOtherError * kOtherError);
}

}  // namespace

void absorbEdgeCounts(const AutoEdgeCounts& counts, AutoLightInput& in) {
    if (counts.sampled == 0 || counts.mapSize <= 0) return;
    const double sampled = counts.sampled;
    const double edge = std::min(1.0, counts.edge / sampled) * counts.mapSize / 1024.0;
    auto blend = [](double& kept, double now) { kept = kept < 0.0 ? now : kept + kAutoEdgeRate * (now - kept); };
    blend(in.edgeShare1024, edge);
    if (counts.technique == ShadowTechnique::Pcss) {
        blend(in.penumbraShare, std::clamp((static_cast<double>(counts.soft) - counts.edge) / sampled, 0.0, 1.0));
    }
}

std::span<const AutoCandidate> autoCandidates() { return kCandidates; }

double AutoCostModel::shadowPassMs(const AutoLightInput& in, const AutoCandidate& c) const {
    const double texels = static_cast<double>(c.mapSize) * c.mapSize;
    const double perFrame =
        in.layers * (perLayerMs + texels * perTexelMs) + std::max(in.casterTriangles, 0.0) * perTriangleMs;
    return shadowScale * in.passScale * std::clamp(in.redrawShare, 0.0, 1.0) * perFrame;
}

AutoLitTerm AutoCostModel::termOf(const AutoCandidate& c) {
    switch (c.technique) {
        case ShadowTechnique::Hard: return AutoLitTerm::Hard;
        case ShadowTechnique::Pcf: return AutoLitTerm::Pcf;
        default: return AutoLitTerm::Pcss;
    }
}

double AutoCostModel::lookupMs(const AutoLightInput& in, const AutoCandidate& c) const {
    const auto term = static_cast<std::size_t>(termOf(c));
    return litScale[term] * std::max(in.pixels, 0.0) * (perPixelMs[term - 1] + tapsOf(c) * perTapMs);
}

double AutoCostModel::shadingMs(double pixels, int lights, double triangles) const {
    const double unscaled = std::max(pixels, 0.0) * (perScreenPixelMs + std::max(lights, 0) * perShadedPixelMs) +
                            std::max(triangles, 0.0) * perLitTriangleMs;
    return litScale[static_cast<std::size_t>(AutoLitTerm::Shading)] * unscaled;
}

void AutoCostModel::observeShadowPass(double predictedMs, double measuredMs) {
    calibrateScale(shadowScale, predictedMs, measuredMs);
}

void AutoCostModel::observeLitPass(std::span<const double, kAutoLitTerms> predictedMs, double measuredMs) {
    // Least squares over the recent frames, measured = sum_t unscaled_t x scale_t, each frame
    // weighted kAutoLitMemory^age, pulled towards the scales held (weight kAutoLitPrior of the
    // data's own): the scales of terms that ran together alone are told apart as the mix of
    // families changes; a term that never ran keeps its scale.
    std::array<double, kAutoLitTerms> unscaled{};
    double total = 0.0;
    for (std::size_t t = 0; t < kAutoLitTerms; ++t) {
        unscaled[t] = std::max(predictedMs[t], 0.0) / litScale[t];
        total += unscaled[t];
    }
    if (!(total > 0.0) || !(measuredMs > 0.0) || !std::isfinite(total) || !std::isfinite(measuredMs)) return;
    double trace = 0.0;
    for (std::size_t r = 0; r < kAutoLitTerms; ++r) {
        for (std::size_t c = 0; c < kAutoLitTerms; ++c) {
            litNormal_[r * kAutoLitTerms + c] =
                kAutoLitMemory * litNormal_[r * kAutoLitTerms + c] + unscaled[r] * unscaled[c];
        }
        litRhs_[r] = kAutoLitMemory * litRhs_[r] + unscaled[r] * measuredMs;
        trace += litNormal_[r * kAutoLitTerms + r];
    }
    std::array<double, kAutoLitTerms*(kAutoLitTerms + 1)> m{};  // [normal + prior | rhs + prior x scale]
    for (std::size_t r = 0; r < kAutoLitTerms; ++r) {
        const double prior = kAutoLitPrior[r] * trace / kAutoLitTerms;
        for (std::size_t c = 0; c < kAutoLitTerms; ++c) m[r * 5 + c] = litNormal_[r * kAutoLitTerms + c];
        m[r * 5 + r] += prior;
        m[r * 5 + kAutoLitTerms] = litRhs_[r] + prior * litScale[r];
    }
    for (std::size_t k = 0; k < kAutoLitTerms; ++k) {  // symmetric positive definite: no pivoting
        for (std::size_t r = k + 1; r < kAutoLitTerms; ++r) {
            const double f = m[r * 5 + k] / m[k * 5 + k];
            for (std::size_t c = k; c <= kAutoLitTerms; ++c) m[r * 5 + c] -= f * m[k * 5 + c];
        }
    }
    std::array<double, kAutoLitTerms> x{};
    for (std::size_t k = kAutoLitTerms; k-- > 0;) {
        double v = m[k * 5 + kAutoLitTerms];
        for (std::size_t c = k + 1; c < kAutoLitTerms; ++c) v -= m[k * 5 + c] * x[c];
        x[k] = v / m[k * 5 + k];
    }
    for (std::size_t t = 0; t < kAutoLitTerms; ++t) {
        if (std::isfinite(x[t])) litScale[t] = std::clamp(x[t], 1e-3, 1e3);
    }
}

double autoPredictedRmse(const AutoLightInput& in, const AutoCandidate& c) {
    if (in.edgeShare1024 >= 0.0 && in.penumbraShare >= 0.0) return countedRmse(in, c);
    // The map's own step widens every edge by kEdgeBand of the candidate's texels: a penumbra
    // narrower than that (a point-sized light's, 0) still leaves an edge whose error shrinks with
    // the map's resolution.
    const double w1024 = std::max(in.penumbraTexels1024, 0.0) + kEdgeBand * 1024.0 / std::max(c.mapSize, 1);
    const double w = w1024 * c.mapSize / 1024.0;
    const double hard = kEdge * w / (w + kHardBlur);
    double penumbra = 0.0;
    switch (c.technique) {
        case ShadowTechnique::Hard: penumbra = hard; break;
        case ShadowTechnique::Pcf: penumbra = kEdge * w / (w + kPcfBlur); break;
        default: {
            // Never more than hard's at the same map: with no penumbra to estimate, PCSS filters
            // over its narrowest kernel, the edge hard shadows have.
            const double taps = kPcssTaps / std::max(c.blockerSamples, 1);
            const double texel = kPcssTexel / std::max(w, 1e-3);
            penumbra = std::min({kEdge, std::sqrt(taps * taps + texel * texel), hard});
        }
    }
    const double share = std::min(1.0, kPenumbraShare * w1024 / 1024.0 + kPenumbraShareFloor);
    return std::sqrt(share * penumbra * penumbra + kOtherError * kOtherError);
}

namespace {

/// Error a candidate leaves, weighted by the light's pixels (the chooser's objective).
double weightedError(const AutoLightInput& in, const AutoCandidate& c) {
    const double rmse = autoPredictedRmse(in, c);
    return std::max(in.pixels, 1.0) * rmse * rmse;
}

}  // namespace

std::vector<int> chooseAutoCandidates(std::span<const AutoLightInput> lights, const AutoCostModel& costs,
                                      double budgetMs) {
    const std::span<const AutoCandidate> candidates = autoCandidates();
    const int n = static_cast<int>(candidates.size());
    std::vector<int> choice(lights.size(), 0);
    const bool unlimited = !(budgetMs > 0.0) || !std::isfinite(budgetMs);
    double spent = 0.0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        int pick = 0;
        for (int k = 1; k < n; ++k) {
            const auto& c = candidates[static_cast<std::size_t>(k)];
            const auto& p = candidates[static_cast<std::size_t>(pick)];
            const bool better = unlimited ? weightedError(lights[i], c) < weightedError(lights[i], p)
                                          : costs.totalMs(lights[i], c) < costs.totalMs(lights[i], p);
            if (better) pick = k;
        }
        choice[i] = pick;
        spent += costs.totalMs(lights[i], candidates[static_cast<std::size_t>(pick)]);
    }
    if (unlimited) return choice;
    double defaults = 0.0;
    for (const AutoLightInput& light : lights) defaults += costs.totalMs(light, candidates[kAutoDefaultCandidate]);
    double limit = (1.0 - kAutoBudgetHeadroom) * budgetMs;
    if (defaults <= (1.0 + kAutoSwitchGain) * budgetMs) {
        std::fill(choice.begin(), choice.end(), kAutoDefaultCandidate);
        spent = defaults;
        limit = budgetMs;
    }
    // Moves by error saved per millisecond, the best that fits first, until none fits.
    for (;;) {
        double bestRate = 0.0;
        std::size_t bestLight = 0;
        int bestPick = -1;
        double bestExtra = 0.0;
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const AutoCandidate& now = candidates[static_cast<std::size_t>(choice[i])];
            const double nowError = weightedError(lights[i], now);
            const double nowMs = costs.totalMs(lights[i], now);
            for (int k = 0; k < n; ++k) {
                const AutoCandidate& c = candidates[static_cast<std::size_t>(k)];
                const double saved = nowError - weightedError(lights[i], c);
                const double extra = costs.totalMs(lights[i], c) - nowMs;
                if (!(saved > 0.0) || (extra > 0.0 && spent + extra > limit)) continue;
                const double rate = extra > 0.0 ? saved / extra : std::numeric_limits<double>::infinity();
                if (rate > bestRate) {
                    bestRate = rate;
                    bestLight = i;
                    bestPick = k;
                    bestExtra = extra;
                }
            }
        }
        if (bestPick < 0) return choice;
        choice[bestLight] = bestPick;
        spent += bestExtra;
    }
}

bool AutoTechniqueState::mayMove(const Held& h, bool gains, bool cheaper, double time) {
    const bool waited =
        std::isfinite(time) ? time - h.switchedAt >= kAutoHoldSeconds : h.framesSinceSwitch >= kAutoHoldFrames;
    // Over budget, a move to a cheaper candidate is taken without a gain in error, and in the
    // light's first second (the calibration settling on what its first choices really cost)
    // without waiting for the hold; after that every move waits for it, so that a dearer move
    // measured over the budget is not undone within the second.
    const bool settling =
        std::isfinite(time) ? time - h.firstAt < kAutoHoldSeconds : h.framesSinceFirst < kAutoHoldFrames;
    return (gains && waited) || (cheaper && (settling || waited));
}

AutoTechniqueState::Held& AutoTechniqueState::held(std::uint64_t id) {
    for (Held& h : held_) {
        if (h.id == id) return h;
    }
    // A new light starts from the other auto lights' own scales (their geometric mean).
    double logSum = 0.0;
    for (const Held& other : held_) logSum += std::log(other.passScale);
    const double start = held_.empty() ? 1.0 : std::exp(logSum / static_cast<double>(held_.size()));
    Held& h = held_.emplace_back();
    h.id = id;
    h.passScale = start;
    return h;
}

void AutoTechniqueState::choose(std::span<const std::uint64_t> ids, std::span<const AutoLightInput> inputs,
                                double budgetMs, double time, std::span<AutoLightChoice> out) {
    // Each light with its own shadow-pass scale, as calibrated.
    scaled_.assign(inputs.begin(), inputs.end());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        for (const Held& h : held_) scaled_[i].passScale = h.id == ids[i] ? h.passScale : scaled_[i].passScale;
    }
    inputs = scaled_;
    const std::vector<int> best = chooseAutoCandidates(inputs, costs_, budgetMs);
    const std::span<const AutoCandidate> candidates = autoCandidates();
    const auto at = [&](int k) -> const AutoCandidate& { return candidates[static_cast<std::size_t>(k)]; };
    double current = 0.0;  // predicted time of the choices held, for the budget test
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const Held* h = nullptr;
        for (const Held& k : held_) h = k.id == ids[i] ? &k : h;
        current += costs_.totalMs(inputs[i], at(h != nullptr && h->current >= 0 ? h->current : best[i]));
    }
    const bool overBudget =
        budgetMs > 0.0 && std::isfinite(budgetMs) && current > (1.0 + kAutoBudgetTolerance) * budgetMs;
    for (Held& h : held_) h.seen = false;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        Held& h = held(ids[i]);
        h.seen = true;
        ++h.framesSinceSwitch;
        ++h.framesSinceFirst;
        if (std::isfinite(time) && time < h.switchedAt) h.switchedAt = time;  // the scene's clock went back
        if (std::isfinite(time) && time < h.firstAt) h.firstAt = time;
        if (h.current < 0 || best[i] == h.current) {
            if (h.current < 0) {
                h.switchedAt = h.firstAt = std::isfinite(time) ? time : 0.0;
                h.framesSinceSwitch = h.framesSinceFirst = 0;
            }
            h.current = best[i];
            h.pending = -1;
            h.pendingFrames = 0;
        } else {
            h.pendingFrames = h.pending == best[i] ? h.pendingFrames + 1 : 1;
            h.pending = best[i];
            const bool gains = autoPredictedRmse(inputs[i], at(best[i])) <
                               (1.0 - kAutoSwitchGain) * autoPredictedRmse(inputs[i], at(h.current));
            const bool cheaper =
                overBudget && costs_.totalMs(inputs[i], at(best[i])) < costs_.totalMs(inputs[i], at(h.current));
            if (h.pendingFrames >= kAutoConfirmFrames && mayMove(h, gains, cheaper, time)) {
                h.current = best[i];
                h.pending = -1;
                h.pendingFrames = 0;
                h.switchedAt = std::isfinite(time) ? time : 0.0;
                h.framesSinceSwitch = 0;
            }
        }
        const AutoCandidate& c = at(h.current);
        out[i] = {h.current, costs_.shadowPassMs(inputs[i], c), costs_.lookupMs(inputs[i], c),
                  autoPredictedRmse(inputs[i], c), inputs[i]};
    }
    std::erase_if(held_, [](const Held& h) { return !h.seen; });
}

void AutoTechniqueState::calibrate(std::span<const std::string_view> names, std::span<const std::uint64_t> ids,
                                   std::span<const double> predictedShadowMs,
                                   std::span<const double, kAutoLitTerms> predictedLitMs, const FrameStats& stats) {
    std::string prefix;
    const std::size_t n = std::min({names.size(), ids.size(), predictedShadowMs.size()});
    for (std::size_t i = 0; i < n; ++i) {
        prefix.assign("Shadow/").append(names[i]).append("/");
        const double measured = stats.passMs(prefix);
        // An auto light calibrates its own scale against its whole prediction; the other lights
        // the common scale (which a new auto light starts from, with the others' own scales).
        Held* own = nullptr;
        for (Held& h : held_) own = ids[i] != 0 && h.id == ids[i] ? &h : own;
        if (own != nullptr) {
            calibrateScale(own->passScale, own->passScale * predictedShadowMs[i], measured);
        } else {
            costs_.observeShadowPass(predictedShadowMs[i], measured);
        }
    }
    costs_.observeLitPass(predictedLitMs, stats.passMs("Main/Lit"));
}

}  // namespace shadow
