// The shader contract's objects (shadow_shaders.h has the GLSL text and what it reads): the
// records of the lights a game's shader evaluates, uploaded into buffers this object owns, and
// the samplers and kernel every shadow lookup reads, bound at the game's binding points.
#pragma once

#include <shadow/result.h>
#include <shadow/shadow_maps.h>
#include <shadow/shadow_planner.h>
#include <shadow/shadow_shaders.h>
#include <shadow/warnings.h>

#include <glm/glm.hpp>

#include <memory>
#include <span>
#include <vector>

namespace shadow {

/// What a game's own shader reads, from a planned and rendered frame. Requires a current OpenGL
/// 4.5 context with `loadGl` done.
class ShadowShaderContract {
public:
    /// Throws `GlError` when `loadGl` has not run.
    ShadowShaderContract();
    /// For a game built without exceptions: the contract, or the error the constructor would throw.
    [[nodiscard]] static Result<std::unique_ptr<ShadowShaderContract>> create() noexcept;
    ~ShadowShaderContract();
    ShadowShaderContract(const ShadowShaderContract&) = delete;
    ShadowShaderContract& operator=(const ShadowShaderContract&) = delete;

    /// Uploads the records of scene lights `sceneLights` of `frame` (slot i is `sceneLights[i]`),
    /// positions relative to `wsCamera`, with the maps of `maps` (rendered from `frame`), into
    /// buffers this object owns, and returns what a game's shader reads. A light without a map
    /// this frame reads as lit. The buffers are rewritten by the next call (and by nothing else).
    /// Throws `std::invalid_argument` for more than SG_MAX_LIGHTS_PER_PASS lights or an index
    /// that is not a scene light; `GlError` for an error of its own.
    const ShadowShaderInputs& inputs(const ShadowFrame& frame, const ShadowMaps& maps, std::span<const int> sceneLights,
                                     const glm::dvec3& wsCamera);
    /// `inputs` for a game built without exceptions.
    [[nodiscard]] Result<const ShadowShaderInputs*> tryInputs(const ShadowFrame& frame, const ShadowMaps& maps,
                                                              std::span<const int> sceneLights,
                                                              const glm::dvec3& wsCamera) noexcept;
    /// Binds `inputs` at `points`: the three uniform buffers (whole), and per slot the depth
    /// array with the comparison sampler and with the raw-depth sampler, and the filter chain.
    /// These bindings are the host's draw state: they stay after the call (nothing else changes).
    void bind(const ShadowShaderInputs& inputs, const ShadowBindingPoints& points = {});
    /// What `bind` binds besides the light and layer blocks: the kernel block, and per slot
    /// i < SG_MAX_LIGHTS_PER_PASS the maps in `maps` of scene light `sceneLights[i]` (-1 or a
    /// slot beyond the span: none). For a renderer that keeps its own light and layer records.
    void bindResources(const ShadowMaps& maps, std::span<const int> sceneLights,
                       const ShadowBindingPoints& points = {});

    /// `HostGlError` warnings of its calls (none has a `FrameStats`): an error the host left
    /// pending before one is read, cleared and kept here (at most 16 until cleared), never thrown.
    [[nodiscard]] const std::vector<Warning>& warnings() const;
    /// Forgets the warnings read.
    void clearWarnings();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
