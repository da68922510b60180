// Technique auto's edge counts (docs/auto_technique.md, "Edge counts"): the storage the forward lit
// passes count into (shaders/lit.frag.glsl, SG_COUNT_EDGES; three counters per pass slot), which
// slots each pass counts this frame, and the read-back of finished counts without waiting for the
// GPU (a fence, polled each frame).
#pragma once

#include "gl/objects.h"
#include "render/light_packing.h"

#include <shadow/shadow_planner.h>
#include <shadow/shared_constants.h>
#include <shadow/stats.h>

#include <cstdint>
#include <span>
#include <vector>

namespace shadow::render {

/// The plan of the light in `pass`'s slot `slot`, null for an empty slot.
[[nodiscard]] const ShadowLightPlan* slotPlan(const ShadowFrame& frame, const PassLights& pass, std::size_t slot);

class EdgeCounts {
public:
    EdgeCounts() = default;
    ~EdgeCounts();
    EdgeCounts(const EdgeCounts&) = delete;
    EdgeCounts& operator=(const EdgeCounts&) = delete;

    /// The counts of an earlier frame the GPU has finished into `out` (with `wait`, waiting for
    /// them); nothing when none are pending or they are not done.
    void collect(std::vector<AutoEdgeCounts>& out, bool wait);
    /// This frame's counted slots (`ShadowLightPlan::countEdges` in a pass whose variant counts):
    /// their counters zeroed and bound at SG_BINDING_EDGE_COUNTS. Counts still pending are
    /// collected first, waiting for them (the storage is reused). False when nothing is counted.
    bool prepare(const ShadowFrame& frame, std::span<const PassLights> passes, std::vector<AutoEdgeCounts>& out);
    /// Counters per pass slot (lit.frag.glsl: sampled, edge, soft), and the first of pass `pass`'s.
    static constexpr std::size_t kCountersPerSlot = 3;
    [[nodiscard]] static std::size_t firstCounter(std::size_t pass) {
        return pass * SG_MAX_LIGHTS_PER_PASS * kCountersPerSlot;
    }
    /// The slots pass `pass` counts this frame (bit per slot).
    [[nodiscard]] int slots(std::size_t pass) const { return pass < slots_.size() ? slots_[pass] : 0; }
    /// After the lit passes of a frame `prepare` returned true for: the counts become pending.
    void submitted();

private:
    struct Pending {
        std::size_t counter = 0;  ///< first of its three counters
        AutoEdgeCounts counts;    ///< the light, map and technique; the counts when read
    };
    gpu::Buffer buffer_;
    std::size_t bytes_ = 0;
    std::vector<int> slots_;
    std::vector<Pending> pending_;
    std::vector<std::uint32_t> values_;
    GLsync done_ = nullptr;  ///< set by `submitted`, until collected
};

}  // namespace shadow::render
