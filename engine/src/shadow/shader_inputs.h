// GL objects of the public shader contract (ShadowSystem::shaderInputs): the samplers and the
// kernel block every shadow lookup reads, the light and layer blocks uploaded for a game, and the
// screen-space mask's programs (ShadowSystem::renderMask).
#pragma once

#include <shadow/gpu_records.h>
#include <shadow/shadow_system.h>

#include "gl/objects.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>

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

/// What a mask program is specialised for: the lights in use, the normal texture, and per slot
/// the light's type, technique and kernel.
using MaskKey = std::array<std::uint8_t, 2 + 3 * SG_MAX_MASK_LIGHTS>;

/// One specialisation of the mask pass and its uniform locations.
struct MaskProgram {
    gpu::Program program;
    GLint csFromClip = -1;
    GLint cameraForward = -1;
    GLint zeroToOne = -1;
    GLint backgroundDepth = -1;
};

struct ShadowSystem::MaskGpu {
    std::map<MaskKey, MaskProgram> programs;
    gpu::VertexArray empty;
    gpu::Framebuffer framebuffer;
    gpu::Sampler point;  ///< nearest, no comparison: the game's textures read as values

    MaskGpu();
};

}  // namespace shadow
