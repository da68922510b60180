// The public shader contract: a game's own shader (forward or deferred) evaluates the same shadow
// visibility as the module's renderer, from the same GLSL function and the same inputs.
//
// In the game's fragment shader, after `#version 450 core`:
//
//     <the text of shadowShaderSource(points, techniques)>
//     ...
//     sg_Surface s = sg_surface(csPosition, wsNormal);   // uniform control flow
//     float v = sg_lightVisibility(slot, csPosition, s, viewDistance);
//
// where `csPosition` is the shaded point minus the camera's world position (the `wsCamera` given
// to `ShadowShaderContract::inputs`), `wsNormal` its interpolated world normal and `viewDistance`
// its distance along the camera's forward axis (the cascades' split measure). `slot` indexes the
// lights handed to `inputs`; it must be dynamically uniform (a loop counter or constant).
// Each frame, after the shadow maps' `render`, the game calls `ShadowShaderContract::inputs`
// (shadow/shader_contract.h; `ShadowSystem::shaderInputs` on the facade) and binds what it
// returns (`bind`, or the names itself at the binding points).
//
// The same files stand under share/shadow_engine/shaders/ of an installed package for a game
// that expands `#include`s itself: `shadow.glsl` is the entry point, and the `SG_BINDING_*` and
// `SG_UNIT_SHADOW_*` macros of shared_constants.h may be defined before it.
#pragma once

#include <shadow/components.h>
#include <shadow/gl_handles.h>
#include <shadow/result.h>
#include <shadow/scene.h>
#include <shadow/shared_constants.h>

#include <array>

#include <glm/glm.hpp>
#include <string>

namespace shadow {

/// Where the shadow GLSL reads its inputs: uniform-buffer binding points of its three blocks and
/// the first texture unit of each of its three sampler arrays (slot i at unit + i). The defaults
/// are the engine's own.
struct ShadowBindingPoints {
    int lightBlock = SG_BINDING_LIGHTS;        ///< GpuLight[SG_MAX_LIGHTS_PER_PASS]
    int layerBlock = SG_BINDING_LAYERS;        ///< GpuShadowLayer[slot * SG_MAX_LAYERS_PER_LIGHT + k]
    int kernelBlock = SG_BINDING_KERNELS;      ///< the filters' Poisson disk
    int compareUnit = SG_UNIT_SHADOW_COMPARE;  ///< depth arrays with the comparison sampler
    int depthUnit = SG_UNIT_SHADOW_DEPTH;      ///< the same arrays with the raw-depth sampler
    /// Filter chains: min/max pyramids (PCF, PCSS), moments (VSM, MSM-soft), summed-area tables (VSSM).
    int minMaxUnit = SG_UNIT_SHADOW_MINMAX;
    int sdfAtlasUnit = SG_UNIT_SDF_ATLAS;         ///< technique sdf: the distance-field atlas (3D)
    int sdfInstanceUnit = SG_UNIT_SDF_INSTANCES;  ///< technique sdf: the field casters (buffer texture)
};

/// The public shadow GLSL as one text for a game's fragment shader, to stand after its
/// `#version 450 core` line: the `#define`s of `points` and of the techniques whose bits are set
/// in `techniques` (code of the others is left out; a light whose technique is left out reads as
/// lit), then shaders/shadow.glsl with its `#include`s expanded. Its `#line` directives number
/// the files in include order from 1, so a compiler message names a line of the module's file; a
/// game that wants its own line numbers after the text adds its own `#line`.
/// Throws `std::invalid_argument` naming the problem when a binding point or unit is negative,
/// two blocks share a binding point, or two sampler arrays' units overlap.
std::string shadowShaderSource(const ShadowBindingPoints& points = {}, unsigned techniques = kAllShadowTechniques);
/// `shadowShaderSource` for a game built without exceptions: the text, or the error it would throw.
[[nodiscard]] Result<std::string> tryShadowShaderSource(const ShadowBindingPoints& points = {},
                                                        unsigned techniques = kAllShadowTechniques) noexcept;

/// What a game's shader reads for up to SG_MAX_LIGHTS_PER_PASS lights (slots), from
/// `ShadowShaderContract::inputs` (or `ShadowSystem::shaderInputs`). Names are GL object names,
/// valid until the next `inputs` or shadow-map `render` call (a light's arrays can be
/// reallocated when its map size changes).
struct ShadowShaderInputs {
    int lights = 0;                                              ///< slots in use, [0, SG_MAX_LIGHTS_PER_PASS]
    std::array<int, SG_MAX_LIGHTS_PER_PASS> sceneLight{};        ///< scene light of each slot, -1 none
    GlBuffer lightBuffer;                                        ///< uniform buffer: the light block (bind whole)
    GlBuffer layerBuffer;                                        ///< uniform buffer: the layer block
    GlBuffer kernelBuffer;                                       ///< uniform buffer: the kernel block
    std::array<GlTexture, SG_MAX_LIGHTS_PER_PASS> depthArray{};  ///< per slot, none without a map
    std::array<GlTexture, SG_MAX_LIGHTS_PER_PASS> minMax{};      ///< per slot: its filter chain, none without one
    GlTexture fieldAtlas;      ///< technique sdf: the distance-field atlas, none before a light uses sdf
    GlTexture fieldInstances;  ///< technique sdf: the frame's field casters, relative to the inputs' camera
    GlSampler compareSampler;  ///< for the compare units (hardware comparison)
    GlSampler depthSampler;    ///< for the raw-depth units
    unsigned techniques = 0;   ///< `techniqueBit`s of the slots' techniques
    /// Per slot: the light's SG_LIGHT_*, SG_TECH_* and SG_KERNEL_*, for a shader specialised per
    /// light configuration (`sg_shadowVisibility(slot, sg_slotLight(slot, type, technique,
    /// kernel), csPosition, s.normal, s.geoNormal, s.curvature, viewDistance)` with compile-time
    /// constants, as the module's own passes do).
    std::array<int, SG_MAX_LIGHTS_PER_PASS> type{}, technique{}, kernel{};
};

}  // namespace shadow
