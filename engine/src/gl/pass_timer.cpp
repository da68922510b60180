#include "gl/pass_timer.h"

namespace shadow::gpu {

PassTimer::PassTimer(bool wallClock) : wallClock_(wallClock) {}

PassTimer::~PassTimer() {
    for (const Pending& p : pending_) {
        if (p.query != 0) freeQueries_.push_back(p.query);
    }
    if (!freeQueries_.empty()) {
        gl.DeleteQueries(static_cast<GLsizei>(freeQueries_.size()), freeQueries_.data());
    }
}

void PassTimer::begin(const std::string& name) {
    gl.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(name.size()), name.c_str());
    Pending p;
    p.name = name;
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
    pending_.push_back(std::move(p));
}

void PassTimer::end() {
    Pending& p = pending_.back();
    if (wallClock_) {
        gl.Finish();
        p.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    } else {
        gl.EndQuery(GL_TIME_ELAPSED);
    }
    gl.PopDebugGroup();
}

void PassTimer::collect(FrameStats& stats) {
    for (Pending& p : pending_) {
        if (p.query != 0) {
            GLuint64 ns = 0;
            gl.GetQueryObjectui64v(p.query, GL_QUERY_RESULT, &ns);
            p.ms = static_cast<double>(ns) * 1e-6;
            freeQueries_.push_back(p.query);
        }
        stats.passes.push_back({p.name, p.ms});
    }
    pending_.clear();
    stats.timingMethod = method();
}

}  // namespace shadow::gpu
