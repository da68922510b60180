// The light and layer records of a shader's slots, uploaded into buffers of their owner's: the
// shader contract's (a game's forward pass) and the mask's own, so that neither rewrites what
// the other bound.
#pragma once

#include <shadow/gpu_records.h>
#include <shadow/shadow_maps.h>
#include <shadow/shadow_planner.h>
#include <shadow/shadow_shaders.h>

#include "core/shader_resources.h"
#include "gl/objects.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

namespace shadow::gpu {

/// One owner's record buffers, the records last uploaded and what a shader reads of them.
struct ShaderRecords {
    Buffer lights;  ///< GpuLight[SG_MAX_LIGHTS_PER_PASS]
    Buffer layers;  ///< GpuShadowLayer[SG_MAX_LIGHTS_PER_PASS * SG_MAX_LAYERS_PER_LIGHT]
    std::array<GpuLight, SG_MAX_LIGHTS_PER_PASS> lightRecords{};
    std::array<GpuShadowLayer, std::size_t{SG_MAX_LIGHTS_PER_PASS} * SG_MAX_LAYERS_PER_LIGHT> layerRecords{};
    ShadowShaderInputs inputs;  ///< with the kernel and samplers of the `ShaderResources` given

    /// Makes the buffers, labelled `label`/lights and `label`/layers; requires a current context.
    ShaderRecords(const ShaderResources& resources, std::string_view label);
};

/// Uploads into `records` the records of scene lights `sceneLights` of `frame` (slot i is
/// `sceneLights[i]`) with the maps of `maps`, positions relative to `wsCamera`, and returns
/// `records.inputs`. Throws `std::invalid_argument` naming `call` for more than
/// SG_MAX_LIGHTS_PER_PASS lights or one that is not a scene light; `GlError` for a GL error.
const ShadowShaderInputs& uploadShaderInputs(ShaderRecords& records, const ShadowFrame& frame, const ShadowMaps& maps,
                                             std::span<const int> sceneLights, const glm::dvec3& wsCamera,
                                             std::string_view call);

/// Binds `inputs` at `points`: the light and layer blocks (whole), then `bindShadowResources`
/// of its slots' scene lights.
void bindShaderInputs(const ShaderResources& resources, const ShadowMaps& maps, const ShadowShaderInputs& inputs,
                      const ShadowBindingPoints& points);

}  // namespace shadow::gpu
