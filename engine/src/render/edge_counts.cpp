// Technique auto's edge counts: the lit passes' counters and their read-back (edge_counts.h).
#include "render/edge_counts.h"

#include "gl/gl_api.h"

namespace shadow::render {

const ShadowLightPlan* slotPlan(const ShadowFrame& frame, const PassLights& pass, std::size_t slot) {
    const int light = slot < pass.sceneLight.size() ? pass.sceneLight[slot] : -1;
    if (light < 0 || static_cast<std::size_t>(light) >= frame.lights.size()) return nullptr;
    return &frame.lights[static_cast<std::size_t>(light)];
}

EdgeCounts::~EdgeCounts() {
    if (done_ != nullptr) gl.DeleteSync(done_);
}

void EdgeCounts::collect(std::vector<AutoEdgeCounts>& out, bool wait) {
    if (done_ == nullptr) return;
    const GLenum state = gl.ClientWaitSync(done_, wait ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, wait ? GL_TIMEOUT_IGNORED : 0);
    if (state == GL_TIMEOUT_EXPIRED) return;
    gl.DeleteSync(done_);
    done_ = nullptr;
    if (state == GL_WAIT_FAILED) {
        pending_.clear();
        return;
    }
    gl.GetNamedBufferSubData(buffer_.get(), 0, static_cast<GLsizeiptr>(values_.size() * sizeof(std::uint32_t)),
                             values_.data());
    for (Pending& p : pending_) {
        p.counts.sampled = values_[p.counter];
        p.counts.edge = values_[p.counter + 1];
        p.counts.soft = values_[p.counter + 2];
        out.push_back(p.counts);
    }
    pending_.clear();
}

bool EdgeCounts::prepare(const ShadowFrame& frame, std::span<const PassLights> passes,
                         std::vector<AutoEdgeCounts>& out) {
    slots_.assign(passes.size(), 0);
    bool any = false;
    for (std::size_t p = 0; p < passes.size(); ++p) {
        if (!passes[p].variant.countEdges) continue;
        for (std::size_t slot = 0; slot < SG_MAX_LIGHTS_PER_PASS; ++slot) {
            const ShadowLightPlan* plan = slotPlan(frame, passes[p], slot);
            if (plan == nullptr || !plan->countEdges) continue;
            slots_[p] |= 1 << slot;
            any = true;
        }
    }
    if (!any) return false;
    collect(out, true);  // the storage is about to be zeroed
    pending_.clear();    // what is left never reached `submitted` (its frame threw)
    for (std::size_t p = 0; p < passes.size(); ++p) {
        for (std::size_t slot = 0; slot < SG_MAX_LIGHTS_PER_PASS; ++slot) {
            if ((slots_[p] & (1 << slot)) == 0) continue;
            const ShadowLightPlan& plan = *slotPlan(frame, passes[p], slot);
            AutoEdgeCounts c;
            c.light = plan.entity.bits();
            c.mapSize = plan.mapSize;
            c.technique = plan.settings.technique;
            pending_.push_back({firstCounter(p) + slot * kCountersPerSlot, c});
        }
    }
    values_.assign(firstCounter(passes.size()), 0u);
    const std::size_t bytes = values_.size() * sizeof(std::uint32_t);
    if (bytes > bytes_) {
        buffer_ = gpu::makeBuffer("Main/edgeCounts", static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
        bytes_ = bytes;
    }
    gl.NamedBufferSubData(buffer_.get(), 0, static_cast<GLsizeiptr>(bytes), values_.data());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SG_BINDING_EDGE_COUNTS, buffer_.get());
    return true;
}

void EdgeCounts::submitted() {
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    done_ = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

}  // namespace shadow::render
