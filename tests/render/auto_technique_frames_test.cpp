// Technique auto over an animated scene's frames (FrameRunner, which times the passes and feeds
// the planner's calibration): with a steady camera no light switches its technique, map or taps
// more than once a second of scene time once the first second has calibrated the costs, at any
// budget.
#include <gtest/gtest.h>
#include <shadow/auto_technique.h>
#include <shadow/frame_runner.h>
#include <shadow/scene.h>

#include <stdexcept>
#include <vector>

#include "render/render_test_support.h"

namespace shadow::auto_technique_frames_test {
namespace {

struct AutoRun {
    std::vector<std::vector<double>> switches;  ///< per light, the scene time of each switch
    double predictedMs = 0.0;                   ///< the last frame's choices, predicted
};

/// Every switch of each auto light's choice over `frames` frames 1/30 s apart.
AutoRun switchTimes(double budgetMs, int frames) {
    test::glContext();
    Result<Scene> made = makeBuiltinScene("default");  // a moving caster under three lights of each type
    if (!made) throw std::runtime_error(made.error().message);
    Scene scene = std::move(*made);
    scene.world.view<Shadow>().each([](Entity, Shadow& s) { s.autoTechnique = true; });
    FrameRunner runner;
    runner.shadows().planner().setCaching(false);  // the layers redrawn every frame, as a game's moving sun
    ShadowLimits limits = runner.shadows().planner().limits();
    limits.shadowBudgetMs = budgetMs;
    runner.shadows().planner().setLimits(limits);
    RenderOptions options;
    options.width = 160;
    options.height = 90;
    AutoRun run;
    std::vector<std::vector<double>>& switches = run.switches;
    std::vector<int> last;
    for (int f = 0; f < frames; ++f) {
        const double t = f / 30.0;
        runner.runFrame(scene, t, scene.cameras.at(0), options);
        const ShadowFrame& frame = runner.shadows().frame();
        switches.resize(frame.lights.size());
        last.resize(frame.lights.size(), -1);
        for (std::size_t i = 0; i < frame.lights.size(); ++i) {
            const int now = frame.lights[i].autoChoice.candidate;
            if (now >= 0 && last[i] >= 0 && now != last[i]) switches[i].push_back(t);
            if (now >= 0) last[i] = now;
        }
    }
    run.predictedMs = 0.0;
    for (const ShadowLightPlan& plan : runner.shadows().frame().lights) {
        run.predictedMs += plan.autoChoice.predictedShadowPassMs + plan.autoChoice.predictedLookupMs;
    }
    return run;
}

TEST(AutoTechniqueFrames, NoLightSwitchesMoreThanOnceASecondWithASteadyCamera) {
    // No budget (least predicted error), then half of what that choice is predicted to take: the
    // choices sit against the budget, where the calibration's noise and the moving caster's
    // changing penumbrae would make a chooser without hysteresis flip.
    const AutoRun unlimited = switchTimes(0.0, 45);
    ASSERT_GT(unlimited.predictedMs, 0.0);
    for (const double budget : {0.0, 0.5 * unlimited.predictedMs}) {
        const AutoRun run = budget == 0.0 ? unlimited : switchTimes(budget, 75);
        ASSERT_EQ(run.switches.size(), 3u);
        for (std::size_t i = 0; i < run.switches.size(); ++i) {
            double previous = -1.0;
            for (double t : run.switches[i]) {
                // A light's first second after its warm-up is its calibration's: moves to cheaper
                // candidates need not wait then.
                const double settled = kAutoHoldSeconds + kAutoWarmUpFramesUntimed / 30.0;
                if (previous >= settled) {
                    EXPECT_GE(t - previous, 1.0 - 1e-9) << "budget " << budget << " ms, light " << i << ": switches at "
                                                        << previous << " and " << t << " s";
                }
                previous = t;
            }
        }
    }
}

}  // namespace
}  // namespace shadow::auto_technique_frames_test
