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

// 0, read from a record so that the compiler cannot fold it: a loop bound plus this stays a loop.
int sg_runtimeZero() { return min(sg_lights[0].layerCount, 0); }

// Put before every loop whose trip count is known only at run time (a filter's taps). With
// SG_ISOLATE_LOOPS defined it is one trip around that loop: llvmpipe counts the trips of all of a
// shader's loops on one counter, and LLVM's analysis of loops in sequence on that counter grows
// exponentially with their number (12 loops in a row took 0.9 s to compile, 16 took 44 s; three
// cascaded suns with PCF, 170 s), while a loop in a loop of its own starts no chain. The engine
// defines it where a program would have more loops in sequence than kMaxLoopsInSequence
// (gl/technique_glsl.h), and always in a game's shader, whose calls it cannot count: the guard
// costs PCF and PCSS 5-8 % of their lit pass on llvmpipe. Only the loop is wrapped: code in a loop
// runs under a mask, which costs a CPU rasteriser straight-line code's speed (a whole light
// wrapped ran 25 % slower).
#ifdef SG_ISOLATE_LOOPS
#define SG_ISOLATED for (int sg_isolated = 0; sg_isolated < 1 + sg_runtimeZero(); ++sg_isolated)
#else
#define SG_ISOLATED
#endif

#endif
