#include "gl/pass_timer.h"

namespace shadow::gpu {

PassTimer::PassTimer(bool wallClock) : wallClock_(wallClock) {}

PassTimer::~PassTimer() {
    for (std::size_t k = 0; k < pendingCount_; ++k) {
        if (pending_[k].query != 0) freeQueries_.push_back(pending_[k].query);
    }
    if (!freeQueries_.empty()) {
        gl.DeleteQueries(static_cast<GLsizei>(freeQueries_.size()), freeQueries_.data());
    }
}

void PassTimer::begin(std::string_view name) {
    gl.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(name.size()), name.data());
    if (!enabled_) return;
    if (pendingCount_ == pending_.size()) pending_.emplace_back();
    Pending& p = pending_[pendingCount_++];
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
    Pending& p = pending_[pendingCount_ - 1];
    if (wallClock_) {
        gl.Finish();
        p.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    } else {
        gl.EndQuery(GL_TIME_ELAPSED);
    }
    gl.PopDebugGroup();
}

void PassTimer::collect(FrameStats& stats) {
    for (std::size_t k = 0; k < pendingCount_; ++k) {
        Pending& p = pending_[k];
        if (p.query != 0) {
            GLuint64 ns = 0;
            gl.GetQueryObjectui64v(p.query, GL_QUERY_RESULT, &ns);
            p.ms = static_cast<double>(ns) * 1e-6;
            freeQueries_.push_back(p.query);
            p.query = 0;
        }
        stats.addPass(p.name, p.ms);
    }
    pendingCount_ = 0;
    stats.timingMethod = method();
}

}  // namespace shadow::gpu
