// GL objects of the public shader contract (ShadowSystem::shaderInputs): the samplers and the
// kernel block every shadow lookup reads, and the light and layer blocks uploaded for a game.
#pragma once

#include <shadow/gpu_records.h>
#include <shadow/shadow_system.h>

#include "gl/objects.h"

#include <array>
#include <cstddef>

namespace shadow {

struct ShadowSystem::ShaderInputsGpu {
    gpu::Sampler compareSampler;  ///< hardware comparison, bilinear: every tap a 2x2 PCF
    gpu::Sampler depthSampler;    ///< raw depth, nearest
    gpu::Buffer kernel;           ///< the Poisson disk, two points per vec4 (filled once)
    gpu::Buffer lights;           ///< GpuLight[SG_MAX_LIGHTS_PER_PASS]
    gpu::Buffer layers;           ///< GpuShadowLayer[SG_MAX_LIGHTS_PER_PASS * SG_MAX_LAYERS_PER_LIGHT]
    std::array<gpu::GpuLight, SG_MAX_LIGHTS_PER_PASS> lightRecords{};
    std::array<gpu::GpuShadowLayer, std::size_t{SG_MAX_LIGHTS_PER_PASS} * SG_MAX_LAYERS_PER_LIGHT> layerRecords{};
    ShadowShaderInputs inputs;

    /// Makes the objects; requires a current context with `loadGl` done.
    ShaderInputsGpu();
};

}  // namespace shadow
