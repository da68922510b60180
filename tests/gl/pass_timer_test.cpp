// Pass timing (engine/src/gl/pass_timer.h): the wall clock reports a frame's own passes; timer
// queries (the GPU path, driven here on llvmpipe, whose queries work though they miss
// rasterisation) are read a frame later, so that collecting never waits for the GPU.
#include "gl/pass_timer.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "render/render_test_support.h"

namespace shadow {
namespace {

std::vector<std::string> names(const FrameStats& stats) {
    std::vector<std::string> out;
    for (const PassTiming& p : stats.passes) out.push_back(p.name);
    return out;
}

void runPasses(gpu::PassTimer& timer, const std::vector<std::string>& passes) {
    for (const std::string& name : passes) {
        gpu::ScopedPass pass(timer, name);
        gl.Flush();
    }
}

TEST(PassTimer, TimerQueriesAreReadAFrameLater) {
    test::glContext();
    gpu::PassTimer timer(false);
    FrameStats first;
    runPasses(timer, {"frame0/a", "frame0/b"});
    timer.collect(first);
    EXPECT_EQ(first.timingMethod, "timer-query");
    EXPECT_TRUE(first.passes.empty()) << "a frame's own queries are not read in that frame";

    for (int frame = 1; frame <= 5; ++frame) {
        FrameStats stats;
        runPasses(timer, {"frame" + std::to_string(frame) + "/a"});
        gl.Finish();  // the frame before is done: its results are ready
        timer.collect(stats);
        SCOPED_TRACE("frame " + std::to_string(frame));
        ASSERT_FALSE(stats.passes.empty());
        EXPECT_EQ(stats.timingLagFrames, 1);
        if (frame == 1) {
            EXPECT_EQ(names(stats), (std::vector<std::string>{"frame0/a", "frame0/b"}));
        } else {
            EXPECT_EQ(names(stats), std::vector<std::string>{"frame" + std::to_string(frame - 1) + "/a"});
        }
        for (const PassTiming& p : stats.passes) EXPECT_GE(p.ms, 0.0);
    }
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(PassTimer, TimerQueriesFallAtMostTheRingBehindAndEveryFrameIsReportedOnceInOrder) {
    test::glContext();
    gpu::PassTimer timer(false);
    std::vector<std::string> reported;
    constexpr int kFrames = 10;
    for (int frame = 0; frame < kFrames; ++frame) {
        FrameStats stats;
        runPasses(timer, {"frame" + std::to_string(frame)});
        timer.collect(stats);  // no Finish: results arrive when the rasteriser gets to them
        if (stats.passes.empty()) continue;
        EXPECT_GE(stats.timingLagFrames, 1);
        EXPECT_LE(stats.timingLagFrames, static_cast<int>(gpu::PassTimer::kMaxFramesInFlight));
        EXPECT_EQ(names(stats), std::vector<std::string>{"frame" + std::to_string(frame - stats.timingLagFrames)});
        for (const std::string& n : names(stats)) reported.push_back(n);
    }
    ASSERT_GE(reported.size(), static_cast<std::size_t>(kFrames) - gpu::PassTimer::kMaxFramesInFlight);
    for (std::size_t i = 0; i < reported.size(); ++i) EXPECT_EQ(reported[i], "frame" + std::to_string(i));
}

TEST(PassTimer, TheWallClockReportsTheFramesOwnPasses) {
    test::glContext();
    gpu::PassTimer timer(true);
    FrameStats stats;
    runPasses(timer, {"a", "b"});
    timer.collect(stats);
    EXPECT_EQ(stats.timingMethod, "wall-clock-fence");
    EXPECT_EQ(names(stats), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(stats.timingLagFrames, 0);
}

TEST(PassTimer, OffTimesNothing) {
    test::glContext();
    gpu::PassTimer timer(false);
    timer.setEnabled(false);
    FrameStats stats;
    runPasses(timer, {"a"});
    timer.collect(stats);
    runPasses(timer, {"b"});
    timer.collect(stats);
    EXPECT_EQ(stats.timingMethod, "off");
    EXPECT_TRUE(stats.passes.empty());
}

}  // namespace
}  // namespace shadow
