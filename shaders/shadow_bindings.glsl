// The resources shadow sampling reads: the pass's light and layer records (uniform blocks, one
// slot per light of the pass) and each slot's depth array through two samplers.
//
// A uniform block indexed by a compile-time slot is read as scalars; a storage buffer indexed
// per pixel is gathered lane by lane on a CPU rasteriser (BENCHMARKS.md, fragment costs).
#ifndef SG_SHADOW_BINDINGS
#define SG_SHADOW_BINDINGS
#include "glsl_types.glsl"

layout(std140, binding = SG_BINDING_LIGHTS) uniform LightBlock {
    GpuLight uLights[SG_MAX_LIGHTS_PER_PASS];
};
// Layer k of slot s is uLayers[s * SG_MAX_LAYERS_PER_LIGHT + k] (GpuLight::firstLayer).
layout(std140, binding = SG_BINDING_LAYERS) uniform LayerBlock {
    GpuShadowLayer uLayers[SG_MAX_LIGHTS_PER_PASS * SG_MAX_LAYERS_PER_LIGHT];
};

layout(binding = SG_UNIT_SHADOW_COMPARE) uniform sampler2DArrayShadow uShadowCompare[SG_MAX_LIGHTS_PER_PASS];
layout(binding = SG_UNIT_SHADOW_DEPTH) uniform sampler2DArray uShadowDepth[SG_MAX_LIGHTS_PER_PASS];
#if defined(SG_TECH_PCF_ENABLED) || defined(SG_TECH_PCSS_ENABLED) || defined(SG_TECH_VSM_ENABLED) || \
    defined(SG_TECH_VSSM_ENABLED) || defined(SG_TECH_MSM_ENABLED) || defined(SG_TECH_MSM_SOFT_ENABLED)
// Each slot's filter chain: the min/max depth pyramid (PCF, PCSS), the depth moments (VSM: two; MSM, MSM-soft: four)
// or the summed-area table of two (VSSM).
layout(binding = SG_UNIT_SHADOW_MINMAX) uniform sampler2DArray uShadowMinMax[SG_MAX_LIGHTS_PER_PASS];
#endif

#endif
