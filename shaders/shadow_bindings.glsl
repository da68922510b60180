// The resources shadow sampling reads: the pass's light and layer records (uniform blocks, one
// slot per light of the pass) and each slot's depth array through two samplers, plus its filter
// chain.
//
// A uniform block indexed by a compile-time slot is read as scalars; a storage buffer indexed
// per pixel is gathered lane by lane on a CPU rasteriser (BENCHMARKS.md, fragment costs).
// Samplers a program does not read are inactive and take no unit.
#ifndef SG_SHADOW_BINDINGS
#define SG_SHADOW_BINDINGS
#include "shadow_types.glsl"

layout(std140, binding = SG_BINDING_LIGHTS) uniform sg_LightBlock {
    sg_GpuLight sg_lights[SG_MAX_LIGHTS_PER_PASS];
};
// Layer k of slot s is sg_layers[s * SG_MAX_LAYERS_PER_LIGHT + k] (sg_GpuLight::firstLayer).
layout(std140, binding = SG_BINDING_LAYERS) uniform sg_LayerBlock {
    sg_GpuShadowLayer sg_layers[SG_MAX_LIGHTS_PER_PASS * SG_MAX_LAYERS_PER_LIGHT];
};

layout(binding = SG_UNIT_SHADOW_COMPARE) uniform sampler2DArrayShadow sg_shadowCompare[SG_MAX_LIGHTS_PER_PASS];
layout(binding = SG_UNIT_SHADOW_DEPTH) uniform sampler2DArray sg_shadowDepth[SG_MAX_LIGHTS_PER_PASS];
// Each slot's filter chain: the min/max depth pyramid, the depth moments (two or four) or the
// summed-area table of two, as the slot's technique reads (ShadowSystem::minMaxOf).
layout(binding = SG_UNIT_SHADOW_MINMAX) uniform sampler2DArray sg_shadowChain[SG_MAX_LIGHTS_PER_PASS];

// 0, read from a record so that the compiler cannot fold it: a loop bound plus this stays a loop
// (lit.frag.glsl's groups of lights alike).
int sg_runtimeZero() { return min(sg_lights[0].layerCount, 0); }

#endif
