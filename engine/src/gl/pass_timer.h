// Timing GPU passes honestly on both kinds of renderer.
//
// On a CPU rasteriser (llvmpipe) GL_TIME_ELAPSED does not cover rasterisation (a 32-tap 720p
// pass read 0.03 ms by query and 11 ms by wall clock), so each pass is bracketed by glFinish
// and timed by the wall clock. On a GPU, timer queries are used, and read a frame or more later:
// `collect` reports the passes of the oldest earlier frame whose queries have all finished (the
// lag is `FrameStats::timingLagFrames`), never waiting for the GPU unless kMaxFramesInFlight
// frames are still pending.
#pragma once

#include "gl/objects.h"

#include <shadow/stats.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace shadow::gpu {

/// Times the passes of a frame. Kept from frame to frame by its owner: the names and queries of
/// one frame's passes are reused by the next, so timing allocates nothing in steady state.
class PassTimer {
public:
    /// `wallClock` true for CPU rasterisers.
    explicit PassTimer(bool wallClock);
    ~PassTimer();
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;

    /// Starts timing a pass named `name` (also pushes a debug group of that name). Passes do
    /// not nest: each ends before the next begins.
    void begin(std::string_view name);
    /// Ends the pass begun last.
    void end();
    /// Wall clock: appends the timings of the passes since the last collect to `stats`. Timer
    /// queries: sets this frame's queries in flight and appends the passes of the oldest earlier
    /// frame whose results are ready (at most one frame per call; none while none is ready), with
    /// `stats.timingLagFrames` saying how many frames ago they ran.
    void collect(FrameStats& stats);
    /// Frames of queries kept in flight before `collect` waits for the oldest.
    static constexpr std::size_t kMaxFramesInFlight = 3;
    [[nodiscard]] const char* method() const {
        if (!enabled_) return "off";
        return wallClock_ ? "wall-clock-fence" : "timer-query";
    }
    /// Off: passes keep their debug groups but are not timed (no glFinish, no query) and
    /// `collect` adds none.
    void setEnabled(bool enabled) { enabled_ = enabled; }
    [[nodiscard]] bool enabled() const { return enabled_; }

private:
    struct Pending {
        std::string name;
        double ms = 0.0;
        GLuint query = 0;
    };
    /// One frame's passes: the first `count` of `passes` (the entries after them are kept for
    /// their storage), and the frame's number.
    struct Frame {
        std::vector<Pending> passes;
        std::size_t count = 0;
        long long number = 0;
    };
    [[nodiscard]] bool ready(const Frame& f) const;
    /// Appends `f`'s passes to `stats` (reading its queries, waiting if need be) and empties it.
    void report(Frame& f, FrameStats& stats);

    bool wallClock_;
    bool enabled_ = true;
    std::chrono::steady_clock::time_point start_{};
    /// The passes since the last collect.
    Frame current_;
    /// Timer queries: frames whose results are not read yet, oldest first, in a ring of
    /// `inFlightCount_` entries starting at `inFlightFirst_`.
    std::array<Frame, kMaxFramesInFlight> inFlight_;
    std::size_t inFlightFirst_ = 0, inFlightCount_ = 0;
    long long frameNumber_ = 0;
    std::vector<GLuint> freeQueries_;
};

/// Times a pass for the duration of a scope.
class ScopedPass {
public:
    ScopedPass(PassTimer& timer, std::string_view name) : timer_(timer) { timer_.begin(name); }
    ~ScopedPass() { timer_.end(); }
    ScopedPass(const ScopedPass&) = delete;
    ScopedPass& operator=(const ScopedPass&) = delete;

private:
    PassTimer& timer_;
};

}  // namespace shadow::gpu
