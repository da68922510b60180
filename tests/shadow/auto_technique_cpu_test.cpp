// Technique auto (engine/src/shadow/auto_technique.cpp, auto_planning.cpp): the chooser against
// its budget, the hysteresis against inputs that flip, the calibration, and the planner's use.
#include <gtest/gtest.h>
#include <shadow/auto_technique.h>

#include "shadow/planner_test_support.h"

#include <array>
#include <cmath>
#include <shadow/stats.h>
#include <string>
#include <string_view>
#include <limits>
#include <utility>
#include <vector>

namespace shadow {
namespace {

/// Three lights: a wide penumbra on a large share of the screen, a narrow one, one with many
/// caster triangles.
std::vector<AutoLightInput> threeLights() {
    AutoLightInput wide;
    wide.pixels = 200000;
    wide.penumbraTexels1024 = 60;
    AutoLightInput narrow;
    narrow.pixels = 50000;
    narrow.penumbraTexels1024 = 2;
    AutoLightInput heavy;
    heavy.pixels = 100000;
    heavy.layers = 6;
    heavy.casterTriangles = 400000;
    heavy.penumbraTexels1024 = 20;
    return {wide, narrow, heavy};
}

double timeOf(const std::vector<AutoLightInput>& in, const std::vector<int>& pick, const AutoCostModel& costs) {
    double ms = 0.0;
    for (std::size_t i = 0; i < in.size(); ++i) ms += costs.totalMs(in[i], autoCandidates()[pick[i]]);
    return ms;
}

double errorOf(const std::vector<AutoLightInput>& in, const std::vector<int>& pick) {
    double e = 0.0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const double r = autoPredictedRmse(in[i], autoCandidates()[pick[i]]);
        e += in[i].pixels * r * r;
    }
    return e;
}

TEST(AutoTechnique, ChooserStaysWithinTheBudgetAndSpendsMoreOnlyForLessError) {
    const std::vector<AutoLightInput> in = threeLights();
    const AutoCostModel costs;
    double cheapest = 0.0;
    for (const AutoLightInput& l : in) {
        double least = std::numeric_limits<double>::infinity();
        for (const AutoCandidate& c : autoCandidates()) least = std::min(least, costs.totalMs(l, c));
        cheapest += least;
    }
    double lastError = std::numeric_limits<double>::infinity();
    for (const double scale : {1.0, 1.5, 2.0, 4.0, 8.0}) {
        const double budget = cheapest * scale;
        const std::vector<int> pick = chooseAutoCandidates(in, costs, budget);
        ASSERT_EQ(pick.size(), in.size());
        EXPECT_LE(timeOf(in, pick, costs), budget * (1 + 1e-12)) << "budget " << budget;
        const double error = errorOf(in, pick);
        EXPECT_LE(error, lastError * (1 + 1e-12)) << "a larger budget must not raise the error";
        lastError = error;
        // No single change of one light that fits what the chooser spends lowers the error
        // (greedy's fixpoint): the whole budget when it affords the defaults, else all but the
        // headroom.
        const std::vector<int> defaults(in.size(), kAutoDefaultCandidate);
        const double limit = timeOf(in, defaults, costs) <= (1.0 + kAutoSwitchGain) * budget
                                 ? budget
                                 : (1.0 - kAutoBudgetHeadroom) * budget;
        for (std::size_t i = 0; i < in.size(); ++i) {
            for (int k = 0; k < static_cast<int>(autoCandidates().size()); ++k) {
                std::vector<int> other = pick;
                other[i] = k;
                if (timeOf(in, other, costs) <= limit) {
                    EXPECT_GE(errorOf(in, other), error * (1 - 1e-9));
                }
            }
        }
    }
    // Over budget even at the cheapest: the cheapest, every light.
    const std::vector<int> starved = chooseAutoCandidates(in, costs, cheapest * 0.5);
    EXPECT_NEAR(timeOf(in, starved, costs), cheapest, cheapest * 1e-12);
}

TEST(AutoTechnique, WithoutBudgetEachLightTakesItsLeastPredictedError) {
    const std::vector<AutoLightInput> in = threeLights();
    const std::vector<int> pick = chooseAutoCandidates(in, AutoCostModel{}, 0.0);
    for (std::size_t i = 0; i < in.size(); ++i) {
        for (const AutoCandidate& c : autoCandidates()) {
            EXPECT_LE(autoPredictedRmse(in[i], autoCandidates()[pick[i]]), autoPredictedRmse(in[i], c));
        }
    }
    // A wide penumbra is soft: PCSS.
    EXPECT_EQ(autoCandidates()[pick[0]].technique, ShadowTechnique::Pcss);
}

TEST(AutoTechnique, ErrorModelFallsWithMapSizeAndTapsAndHardMissesWidePenumbrae) {
    AutoLightInput l;
    l.pixels = 1000;
    l.penumbraTexels1024 = 20;
    const auto rmse = [&](ShadowTechnique t, int size, int taps) {
        return autoPredictedRmse(l, {t, size, taps, taps});
    };
    EXPECT_LT(rmse(ShadowTechnique::Pcss, 2048, 16), rmse(ShadowTechnique::Pcss, 1024, 16));
    EXPECT_LT(rmse(ShadowTechnique::Pcss, 1024, 16), rmse(ShadowTechnique::Pcss, 1024, 8));
    l.penumbraTexels1024 = 100;
    EXPECT_LT(rmse(ShadowTechnique::Pcss, 1024, 16), 0.5 * rmse(ShadowTechnique::Hard, 1024, 1));
}

TEST(AutoTechnique, EdgeCountsBecomeSharesOfA1024MapAndThePenumbraOnlyFromPcss) {
    AutoLightInput l;
    absorbEdgeCounts({}, l);  // nothing sampled: nothing known
    EXPECT_EQ(l.edgeShare1024, -1.0);
    EXPECT_EQ(l.penumbraShare, -1.0);
    // 2 % of the pixels within a texel of an edge in a 2048 map: 4 % in a 1024 map, whose texels
    // are twice as wide; PCSS's 12 % of soft pixels less that band is its penumbra.
    absorbEdgeCounts({.sampled = 1000, .edge = 20, .soft = 120, .mapSize = 2048, .technique = ShadowTechnique::Pcss},
                     l);
    EXPECT_DOUBLE_EQ(l.edgeShare1024, 0.04);
    EXPECT_DOUBLE_EQ(l.penumbraShare, 0.10);
    // Hard's soft pixels are its band alone: the penumbra stays; the band moves by kAutoEdgeRate.
    absorbEdgeCounts({.sampled = 1000, .edge = 10, .soft = 10, .mapSize = 1024, .technique = ShadowTechnique::Hard}, l);
    EXPECT_DOUBLE_EQ(l.edgeShare1024, 0.04 + kAutoEdgeRate * (0.01 - 0.04));
    EXPECT_DOUBLE_EQ(l.penumbraShare, 0.10);
}

TEST(AutoTechnique, CountedErrorModelOrdersPointAndAreaLightsCandidates) {
    const auto rmse = [](const AutoLightInput& l, ShadowTechnique t, int size, int taps) {
        return autoPredictedRmse(l, {t, size, taps, taps});
    };
    // A point-sized light (no penumbra) whose edges cover 3 % of its pixels in a 1024 map: the
    // width model predicts the same small error at every size; the counts' falls with the map's
    // texel, about as 1 / sqrt(size) (fence's spot: 0.101, 0.080, 0.065 measured at 512-2048).
    AutoLightInput point;
    point.penumbraTexels1024 = 0.0;
    point.edgeShare1024 = 0.03;
    point.penumbraShare = 0.0;
    const double hard512 = rmse(point, ShadowTechnique::Hard, 512, 1);
    const double hard2048 = rmse(point, ShadowTechnique::Hard, 2048, 1);
    EXPECT_NEAR(hard512 / hard2048, 2.0, 0.1);  // 2, less the floor every light keeps (kOtherError)
    EXPECT_GT(hard2048, 0.02);
    // An area light's wide penumbra over 10 % of its pixels: PCSS 16 + 16 best, then 8 + 8, then
    // PCF's fixed blur, hard worst; and the band's error is the same for every map's size to within it.
    AutoLightInput area;
    area.penumbraTexels1024 = 120.0;
    area.edgeShare1024 = 0.004;
    area.penumbraShare = 0.10;
    EXPECT_LT(rmse(area, ShadowTechnique::Pcss, 1024, 16), rmse(area, ShadowTechnique::Pcss, 1024, 8));
    EXPECT_LT(rmse(area, ShadowTechnique::Pcss, 1024, 8), rmse(area, ShadowTechnique::Pcf, 1024, 16));
    EXPECT_LT(rmse(area, ShadowTechnique::Pcf, 1024, 16), rmse(area, ShadowTechnique::Hard, 1024, 1));
    EXPECT_GT(rmse(area, ShadowTechnique::Hard, 2048, 1), 0.9 * rmse(area, ShadowTechnique::Hard, 512, 1));
}

TEST(AutoTechnique, BudgetThatAffordsTheDefaultsNeverBuysMoreErrorThanThem) {
    // A budget equal to the defaults' predicted time: whatever the greedy would have bought from
    // the cheapest candidates up (here the wide penumbra's 2048-texel map, paid for with the
    // narrow one's hard shadow), each light keeps the defaults or takes one predicted better.
    // The bunny's three lights as the planner saw them at 320x240 (a sun, a spot, a point light).
    std::vector<AutoLightInput> in(3);
    for (std::size_t i = 0; i < 3; ++i) {
        in[i].pixels = 76800;
        in[i].casterTriangles = 70000.0 * (i == 2 ? 6 : 1);
        in[i].layers = i == 2 ? 6 : 1;
        in[i].penumbraTexels1024 = std::array<double, 3>{33.4, 41.2, 48.8}[i];
    }
    const AutoCostModel costs;
    const AutoCandidate& defaults = autoCandidates()[kAutoDefaultCandidate];
    double budget = 0.0;
    for (const AutoLightInput& l : in) budget += costs.totalMs(l, defaults);
    for (const double share : {1.0, 1.05, 1.5}) {
        const std::vector<int> pick = chooseAutoCandidates(in, costs, share * budget);
        for (std::size_t i = 0; i < in.size(); ++i) {
            EXPECT_LE(autoPredictedRmse(in[i], autoCandidates()[pick[i]]), autoPredictedRmse(in[i], defaults))
                << "light " << i << ", budget x" << share;
        }
        EXPECT_LE(timeOf(in, pick, costs), std::max(share, 1.0 + kAutoSwitchGain) * budget + 1e-9);
    }
    // Well below the defaults, the cheapest-first greedy keeps within the budget (or at the
    // cheapest candidates, when even they exceed it).
    double cheapest = 0.0;
    for (const AutoLightInput& l : in) {
        double least = std::numeric_limits<double>::infinity();
        for (const AutoCandidate& c : autoCandidates()) least = std::min(least, costs.totalMs(l, c));
        cheapest += least;
    }
    const std::vector<int> tight = chooseAutoCandidates(in, costs, 0.6 * budget);
    EXPECT_LE(timeOf(in, tight, costs), std::max(0.6 * budget, cheapest) + 1e-9);
}

TEST(AutoTechnique, HysteresisSwitchesAtMostOnceASecondUnderFlippingInputs) {
    AutoTechniqueState state;
    AutoLightInput soft;
    soft.pixels = 100000;
    soft.penumbraTexels1024 = 80;
    AutoLightInput sharp = soft;
    sharp.penumbraTexels1024 = 0.5;
    const std::uint64_t id = 7;
    std::vector<AutoLightChoice> out(1);
    int switches = 0;
    int last = -1;
    const double dt = 1.0 / 60.0;
    // Inputs that prefer other candidates, flipping every 4 frames for 3 seconds.
    for (int f = 0; f < 180; ++f) {
        const AutoLightInput in = (f / 4) % 2 == 0 ? soft : sharp;
        state.choose({&id, 1}, {&in, 1}, 0.0, f * dt, out);
        if (last >= 0 && out[0].candidate != last) ++switches;
        last = out[0].candidate;
    }
    EXPECT_LE(switches, 3) << "at most one switch per second of scene time";
    // A lasting change is followed, after the hold.
    AutoTechniqueState steady;
    steady.choose({&id, 1}, {&soft, 1}, 0.0, 0.0, out);
    const int first = out[0].candidate;
    int at = -1;
    for (int f = 1; f < 180 && at < 0; ++f) {
        steady.choose({&id, 1}, {&sharp, 1}, 0.0, f * dt, out);
        if (out[0].candidate != first) at = f;
    }
    ASSERT_GE(at, 0) << "never followed a lasting change";
    EXPECT_GE(at * dt, kAutoHoldSeconds - 1e-9);
    EXPECT_LE(at * dt, kAutoHoldSeconds + kAutoConfirmFrames * dt + 1e-9);
}

/// A light of a wide penumbra that `state` has chosen for without a budget (its least
/// error, a dear candidate) at scene time 0; returns that choice's predicted ms.
double startAtLeastError(AutoTechniqueState& state, AutoLightInput& in, std::uint64_t id,
                         std::vector<AutoLightChoice>& out) {
    in.pixels = 100000;
    in.penumbraTexels1024 = 40;
    out.assign(1, {});
    state.choose({&id, 1}, {&in, 1}, 0.0, 0.0, out);
    return state.costs().totalMs(in, autoCandidates()[out[0].candidate]);
}

TEST(AutoTechnique, OverBudgetMovesToACheaperCandidateWithoutWaitingForTheHold) {
    AutoTechniqueState state;
    AutoLightInput in;
    const std::uint64_t id = 3;
    std::vector<AutoLightChoice> out;
    const double dear = startAtLeastError(state, in, id, out);
    const double budget = 0.25 * dear;
    const double dt = 1.0 / 60.0;
    int at = -1;
    for (int f = 1; f < 30 && at < 0; ++f) {
        state.choose({&id, 1}, {&in, 1}, budget, f * dt, out);
        if (state.costs().totalMs(in, autoCandidates()[out[0].candidate]) <= budget) at = f;
    }
    EXPECT_EQ(at, kAutoConfirmFrames) << "within the budget after the confirmation frames, not after the hold";
}

TEST(AutoTechnique, AChoicePredictedWithinTheToleranceOverTheBudgetIsKept) {
    // A budget a few per cent under the held choice's predicted cost (prediction noise): kept for
    // two seconds; one further under than the tolerance: moved within the confirmation frames.
    const double dt = 1.0 / 60.0;
    for (const double over : {0.5 * kAutoBudgetTolerance, 2.0 * kAutoBudgetTolerance}) {
        AutoTechniqueState state;
        AutoLightInput in;
        const std::uint64_t id = 9;
        std::vector<AutoLightChoice> out;
        const double dear = startAtLeastError(state, in, id, out);
        const int held = out[0].candidate;
        int movedAt = -1;
        for (int f = 1; f < 120 && movedAt < 0; ++f) {
            state.choose({&id, 1}, {&in, 1}, dear / (1.0 + over), f * dt, out);
            if (out[0].candidate != held) movedAt = f;
        }
        if (over < kAutoBudgetTolerance) {
            EXPECT_EQ(movedAt, -1) << "predicted " << over << " over the budget: within the tolerance";
        } else {
            EXPECT_EQ(movedAt, kAutoConfirmFrames) << "predicted " << over << " over the budget";
        }
    }
}

TEST(AutoTechnique, AfterItsFirstSecondALightOverBudgetStillWaitsForTheHold) {
    AutoTechniqueState state;
    AutoLightInput in;
    const std::uint64_t id = 5;
    std::vector<AutoLightChoice> out;
    const double dt = 1.0 / 60.0;
    const double dear = startAtLeastError(state, in, id, out);
    // Past the first second, a budget at half the dear choice: one move down, then a budget
    // far below that asks for another before the hold has passed since the first.
    std::vector<std::pair<double, int>> switches;
    int last = out[0].candidate;
    for (int f = 1; f < 240; ++f) {
        const double t = 1.5 + f * dt;
        const double budget = t < 2.0 ? 0.5 * dear : 1e-6;
        state.choose({&id, 1}, {&in, 1}, budget, t, out);
        if (out[0].candidate != last) switches.emplace_back(t, out[0].candidate);
        last = out[0].candidate;
    }
    ASSERT_GE(switches.size(), 2u) << "both budgets were followed";
    EXPECT_LT(switches[0].first, 2.0) << "the first move down: the hold since the first choice had passed";
    EXPECT_GE(switches[1].first - switches[0].first, kAutoHoldSeconds - 1e-9) << "the second waited for the hold";
}

TEST(AutoTechnique, CalibrationConvergesToTheMeasuredRatio) {
    AutoCostModel costs;
    for (int i = 0; i < 60; ++i) {
        const double predicted = 4.0 * costs.shadowScale;
        costs.observeShadowPass(predicted, 4.0 * 2.5);  // the GPU is 2.5 times slower than the defaults
    }
    EXPECT_NEAR(costs.shadowScale, 2.5, 2.5 * 1e-3);
    costs.observeShadowPass(1.0, 0.0);  // nothing measured (timing off): unchanged
    EXPECT_NEAR(costs.shadowScale, 2.5, 2.5 * 1e-3);
}

TEST(AutoTechnique, LitPassTermsAreToldApartAsTheMixOfFamiliesChanges) {
    // The truth: shading costs 0.5x the defaults' prediction, hard lookups 0.1x, PCSS 3x. Frames
    // alternate between a light in hard and the same light in PCSS, as an auto light does while
    // the chooser tries its candidates.
    const std::array<double, kAutoLitTerms> truth{0.5, 0.1, 1.0, 3.0};
    const std::array<double, kAutoLitTerms> model{6.0, 1.0, 0.0, 4.0};  // ms at scale 1
    AutoCostModel costs;
    for (int f = 0; f < 600; ++f) {
        const bool pcss = (f / 10) % 2 == 1;
        std::array<double, kAutoLitTerms> predicted{};
        double measured = 0.0;
        for (std::size_t t = 0; t < kAutoLitTerms; ++t) {
            const bool runs = t == 0 || (pcss ? t == 3 : t == 1);
            predicted[t] = runs ? model[t] * costs.litScale[t] : 0.0;
            measured += runs ? model[t] * truth[t] : 0.0;
        }
        costs.observeLitPass(predicted, measured);
    }
    // Each mix's total is what was measured, and so is the difference between the families
    // (what the chooser compares); the split between shading and lookups is not in the data.
    const double hardFrame = model[0] * costs.litScale[0] + model[1] * costs.litScale[1];
    const double pcssFrame = model[0] * costs.litScale[0] + model[3] * costs.litScale[3];
    EXPECT_NEAR(hardFrame, model[0] * truth[0] + model[1] * truth[1], 0.01 * hardFrame);
    EXPECT_NEAR(pcssFrame, model[0] * truth[0] + model[3] * truth[3], 0.01 * pcssFrame);
    EXPECT_NEAR(model[3] * costs.litScale[3] - model[1] * costs.litScale[1], model[3] * truth[3] - model[1] * truth[1],
                0.02 * model[3] * truth[3]);
    EXPECT_NEAR(costs.litScale[0], truth[0], 0.1 * truth[0]) << "the shading, held firmer, stays near the truth";
    EXPECT_EQ(costs.litScale[2], 1.0) << "a family that never ran keeps its scale";
}

TEST(AutoTechnique, EachAutoLightLearnsItsOwnShadowPassScale) {
    // Two auto lights with the same inputs whose passes measure 3x and 0.5x the prediction (a
    // light whose casters are mostly culled, one with heavy overdraw): each prediction converges
    // to its own light's measurement.
    AutoTechniqueState state;
    AutoLightInput in;
    in.pixels = 10000;
    in.casterTriangles = 50000;
    in.penumbraTexels1024 = 10;
    const std::array<std::uint64_t, 2> ids{11, 12};
    const std::array<AutoLightInput, 2> inputs{in, in};
    const std::array<double, 2> truth{3.0, 0.5};
    const std::array<std::string_view, 2> names{"heavy", "culled"};
    std::vector<AutoLightChoice> out(2);
    for (int f = 0; f < 80; ++f) {
        state.choose(ids, inputs, 0.0, f / 30.0, out);
        FrameStats stats;
        std::array<double, 2> predicted{};
        for (std::size_t i = 0; i < 2; ++i) {
            const AutoCandidate& c = autoCandidates()[static_cast<std::size_t>(out[i].candidate)];
            predicted[i] = state.costs().shadowPassMs(in, c);  // the common scale only
            stats.passes.push_back(
                {"Shadow/" + std::string(names[i]) + "/layer0", predicted[i] / state.costs().shadowScale * truth[i]});
        }
        const std::array<double, kAutoLitTerms> lit{};
        state.calibrate(names, ids, predicted, lit, stats);
    }
    state.choose(ids, inputs, 0.0, 80 / 30.0, out);
    for (std::size_t i = 0; i < 2; ++i) {
        const AutoCandidate& c = autoCandidates()[static_cast<std::size_t>(out[i].candidate)];
        AutoLightInput unscaled = in;
        const double model = state.costs().shadowPassMs(unscaled, c) / state.costs().shadowScale;
        EXPECT_NEAR(out[i].predictedShadowPassMs, truth[i] * model, 0.02 * truth[i] * model) << names[i];
    }
}

/// An auto spot named "spot" over a box, and the camera's view at 320x240.
CameraView autoSpotOverABox(test::TestScene& t, Entity* light = nullptr) {
    Light spot = test::lightOf(LightType::Spot);
    spot.radius = 0.2f;
    Shadow s;
    s.autoTechnique = true;
    s.technique = ShadowTechnique::Pcss;
    const Entity e = addLight(t.scene, "spot", spot, s, {0, 6, 0}, {0, -1, 0});
    if (light != nullptr) *light = e;
    addMeshInstance(t.scene.world, "box under the spot", makeBoxMesh(glm::vec3(0.4f)), test::at({0, 2, 0}));
    CameraView view = t.update();
    view.pixelWidth = 320;
    view.pixelHeight = 240;
    return view;
}

TEST(AutoTechnique, PlannerResolvesAutoLightsToConcreteSettingsWithinTheBudget) {
    test::TestScene t;
    Entity light;
    const CameraView view = autoSpotOverABox(t, &light);
    ShadowPlanner planner;
    ShadowLimits limits = planner.limits();
    limits.shadowBudgetMs = 1e-6;  // below every candidate: the cheapest
    planner.setLimits(limits);
    planner.setSceneTime(0.0);
    const ShadowFrame& first = planner.prepare(t.scene.world, view, t.scene.lights);
    ASSERT_EQ(first.lights.size(), 1u);
    EXPECT_TRUE(first.lights[0].automatic);
    EXPECT_EQ(first.lights[0].autoChoice.candidate, -1) << "nothing known yet: the defaults";
    EXPECT_EQ(first.lights[0].settings.technique, ShadowTechnique::Pcss);
    EXPECT_EQ(first.lights[0].mapSize, 1024);
    // Without timings (nothing calls observe) the defaults are held kAutoWarmUpFramesUntimed
    // frames, then the planner chooses from its built-in coefficients.
    for (int f = 1; f < kAutoWarmUpFramesUntimed; ++f) {
        planner.setSceneTime(f / 30.0);
        const ShadowFrame& warming = planner.prepare(t.scene.world, view, t.scene.lights);
        EXPECT_EQ(warming.lights[0].autoChoice.candidate, -1) << "frame " << f << ": still the defaults";
        EXPECT_EQ(warming.lights[0].mapSize, 1024);
    }
    planner.setSceneTime(kAutoWarmUpFramesUntimed / 30.0);
    const ShadowFrame& second = planner.prepare(t.scene.world, view, t.scene.lights);
    const ShadowLightPlan& plan = second.lights[0];
    EXPECT_EQ(plan.entity, light);
    ASSERT_GE(plan.autoChoice.candidate, 0);
    EXPECT_EQ(plan.settings.technique, ShadowTechnique::Hard);
    EXPECT_EQ(plan.mapSize, 512);
    EXPECT_GT(plan.autoChoice.input.penumbraTexels1024, 0.0);
    EXPECT_EQ(second.techniquesInUse & techniqueBit(ShadowTechnique::Pcss), 0u);
    // A bad budget: one warning, treated as none.
    limits.shadowBudgetMs = -3.0;
    planner.setLimits(limits);
    const ShadowFrame& bad = planner.prepare(t.scene.world, view, t.scene.lights);
    int clamped = 0;
    for (const Warning& w : bad.warnings) clamped += w.element == "shadowBudgetMs" ? 1 : 0;
    EXPECT_EQ(clamped, 1);
}

TEST(AutoTechnique, TheFrameAfterAProgramBuildTeachesTheCostModelNothing) {
    // The first frame after the programs were built runs slower than the steady state; its
    // timing is not learnt, so the defaults are held for the settle frame and the warm-up's
    // timed frames, and a settle frame 50 times slower than the rest leaves the prediction at
    // the steady timings.
    test::TestScene t;
    const CameraView view = autoSpotOverABox(t);
    const double steadyMs = 2.0;
    const auto run = [&](double settleMs) {
        ShadowPlanner planner;
        planner.setCaching(false);  // the layer drawn, and timed, every frame
        std::vector<int> candidates;
        double predicted = 0.0;
        for (int f = 0; f < 2 + kAutoSettleFrames + kAutoWarmUpFrames; ++f) {
            planner.setSceneTime(f / 30.0);
            const ShadowFrame& frame = planner.prepare(t.scene.world, view, t.scene.lights);
            candidates.push_back(frame.lights.at(0).autoChoice.candidate);
            predicted = frame.lights[0].autoChoice.predictedShadowPassMs + frame.lights[0].autoChoice.predictedLookupMs;
            FrameStats stats;
            stats.programsCompiled = f == 0 ? 3 : 0;
            const bool settle = f >= 1 && f <= kAutoSettleFrames;
            stats.passes.push_back({"Shadow/spot/layer0", settle ? settleMs : steadyMs});
            stats.passes.push_back({"Main/Lit", settle ? settleMs : steadyMs});
            planner.observe(stats);
        }
        return std::make_pair(candidates, predicted);
    };
    const auto [held, steadyPrediction] = run(steadyMs);
    // Frame 0 builds, frames 1..kAutoSettleFrames settle, then kAutoWarmUpFrames are learnt:
    // the first choice is made on the frame after them.
    const std::size_t first = 1 + kAutoSettleFrames + kAutoWarmUpFrames;
    for (std::size_t f = 0; f < first; ++f) EXPECT_EQ(held[f], -1) << "frame " << f << ": the defaults";
    EXPECT_GE(held[first], 0) << "the first choice";
    ASSERT_GT(steadyPrediction, 0.0);
    const auto [slowHeld, slowPrediction] = run(50.0 * steadyMs);
    EXPECT_GE(slowHeld[first], 0);
    EXPECT_NEAR(slowPrediction, steadyPrediction, 1e-6 * steadyPrediction) << "the settle frame's timing was learnt";
}

}  // namespace
}  // namespace shadow
