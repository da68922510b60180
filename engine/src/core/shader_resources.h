// What every shadow lookup reads besides the light and layer records: the comparison and
// raw-depth samplers, the filters' kernel block, and per slot a light's depth array and filter
// chain. Made by the shader contract, the mask and the renderer alike (each its own, a few
// hundred bytes), and bound the same way by all three.
#pragma once

#include <shadow/shadow_maps.h>
#include <shadow/shadow_shaders.h>

#include "gl/objects.h"

#include <span>

namespace shadow::gpu {

/// The samplers and kernel block of the shadow GLSL.
struct ShaderResources {
    Sampler compareSampler;  ///< hardware comparison, bilinear: every tap a 2x2 PCF
    Sampler depthSampler;    ///< raw depth, nearest
    Buffer kernel;           ///< the Poisson disk, two points per vec4 (filled once)

    /// Makes the objects; requires a current context with `loadGl` done. Throws `GlError` when
    /// GL fails (the caller has read the host's errors first).
    ShaderResources();
};

/// Binds at `points` the kernel block of `resources` and, per slot i < SG_MAX_LIGHTS_PER_PASS,
/// the depth array of scene light `sceneLights[i]` in `maps` with the comparison and with the
/// raw-depth sampler, and its filter chain with the texture's own filtering (-1 or a slot beyond
/// the span: nothing bound there).
void bindShadowResources(const ShaderResources& resources, const ShadowMaps& maps, std::span<const int> sceneLights,
                         const ShadowBindingPoints& points);

}  // namespace shadow::gpu
