#include "gl/pass_timer.h"

#include <utility>

namespace shadow::gpu {

PassTimer::PassTimer(bool wallClock) : wallClock_(wallClock) {}

PassTimer::~PassTimer() {
    auto release = [this](const Frame& f) {
        for (std::size_t k = 0; k < f.count; ++k) {
            if (f.passes[k].query != 0) freeQueries_.push_back(f.passes[k].query);
        }
    };
    release(current_);
    for (std::size_t i = 0; i < inFlightCount_; ++i) release(inFlight_[(inFlightFirst_ + i) % kMaxFramesInFlight]);
    if (!freeQueries_.empty()) {
        gl.DeleteQueries(static_cast<GLsizei>(freeQueries_.size()), freeQueries_.data());
    }
}

void PassTimer::begin(std::string_view name) {
    gl.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(name.size()), name.data());
    if (!enabled_) return;
    if (current_.count == current_.passes.size()) current_.passes.emplace_back();
    Pending& p = current_.passes[current_.count++];
    p.name.assign(name);
    p.ms = 0.0;
    p.query = 0;
    if (wallClock_) {
        gl.Finish();  // earlier work must not be billed to this pass
        start_ = std::chrono::steady_clock::now();
    } else {
        if (freeQueries_.empty()) {
            GLuint q = 0;
            gl.CreateQueries(GL_TIME_ELAPSED, 1, &q);
            freeQueries_.push_back(q);
        }
        p.query = freeQueries_.back();
        freeQueries_.pop_back();
        gl.BeginQuery(GL_TIME_ELAPSED, p.query);
    }
}

void PassTimer::end() {
    if (!enabled_) {
        gl.PopDebugGroup();
        return;
    }
    Pending& p = current_.passes[current_.count - 1];
    if (wallClock_) {
        gl.Finish();
        p.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    } else {
        gl.EndQuery(GL_TIME_ELAPSED);
    }
    gl.PopDebugGroup();
}

bool PassTimer::ready(const Frame& f) const {
    // Queries finish in order: the last one's result available means all of the frame's are.
    if (f.count == 0) return true;
    GLuint available = GL_FALSE;
    gl.GetQueryObjectuiv(f.passes[f.count - 1].query, GL_QUERY_RESULT_AVAILABLE, &available);
    return available == GL_TRUE;
}

void PassTimer::report(Frame& f, FrameStats& stats) {
    for (std::size_t k = 0; k < f.count; ++k) {
        Pending& p = f.passes[k];
        if (p.query != 0) {
            GLuint64 ns = 0;
            gl.GetQueryObjectui64v(p.query, GL_QUERY_RESULT, &ns);
            p.ms = static_cast<double>(ns) * 1e-6;
            freeQueries_.push_back(p.query);
            p.query = 0;
        }
        stats.addPass(p.name, p.ms);
    }
    f.count = 0;
}

void PassTimer::collect(FrameStats& stats) {
    stats.timingMethod = method();
    const long long frame = frameNumber_++;
    if (wallClock_ || !enabled_) {
        report(current_, stats);
        stats.timingLagFrames = 0;
        return;
    }
    // The oldest earlier frame, once its results are in; waited for only when the ring is full.
    if (inFlightCount_ > 0) {
        Frame& oldest = inFlight_[inFlightFirst_];
        if (inFlightCount_ == kMaxFramesInFlight || ready(oldest)) {
            stats.timingLagFrames = static_cast<int>(frame - oldest.number);
            report(oldest, stats);
            inFlightFirst_ = (inFlightFirst_ + 1) % kMaxFramesInFlight;
            --inFlightCount_;
        }
    }
    if (current_.count > 0) {
        Frame& slot = inFlight_[(inFlightFirst_ + inFlightCount_) % kMaxFramesInFlight];
        std::swap(slot, current_);  // keeps both frames' storage
        slot.number = frame;
        ++inFlightCount_;
    }
}

}  // namespace shadow::gpu
