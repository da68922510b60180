// A compute build of a mip chain's levels (filter_chain.cpp; the min/max pyramid): one dispatch
// writes up to SG_CHAIN_LEVELS_PER_DISPATCH levels of one layer, uLevel and the next ones. Each
// invocation owns a 4x4 block of level uLevel, a 2x2 block of the next level and one texel of the
// one after: it computes the 16 texels of its first level (sg_chainLeaf: from the layer's depth
// map for level 0, SG_CHAIN_FROM_DEPTH, else from level uLevel - 1) and merges them in registers
// for the two levels above (sg_chainMerge), so those cost no fetch and no dispatch of their own.
//
// Why blocks: on llvmpipe a dispatch costs per invocation more than per fetch. One invocation per
// texel and one dispatch per level built the pyramids of builtin:default's 9 layers (1024^2 and
// 512^2, `--technique pcf --no-cache`) in 23-30 ms, blocks in 12-16 ms (stats.json,
// `Shadow/<light>/minmax<k>`). An 8x8 work group that merged levels through shared memory was
// 2.2x slower than one level per dispatch (barriers are costly on a CPU rasteriser); registers
// need no barrier.
//
// A level's texel x merges the texels 2x and 2x + 1 of the level below (of a level of odd size,
// the last row and column are left to the levels' floor).
//
// The chain's file defines SG_CHAIN_FORMAT (its image format) before including this file, and
// after it sg_chainMerge and, for level 0, sg_chainFromDepth.
#ifndef SG_SHADOW_CHAIN_LEVEL
#define SG_SHADOW_CHAIN_LEVEL
#include "shared_constants.h"

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef SG_CHAIN_FROM_DEPTH
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uDepth;  // the layer's depth map
#else
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uBelow;  // the chain, level uLevel - 1 read
#endif

// Levels uLevel, uLevel + 1 and uLevel + 2 of the layer; units past the last level written
// (uLevelsWritten) repeat the last one and are not written.
layout(binding = SG_IMAGE_MINMAX, SG_CHAIN_FORMAT) writeonly uniform image2D uTarget0;
layout(binding = SG_IMAGE_MINMAX + 1, SG_CHAIN_FORMAT) writeonly uniform image2D uTarget1;
layout(binding = SG_IMAGE_MINMAX + 2, SG_CHAIN_FORMAT) writeonly uniform image2D uTarget2;

uniform int uLayer;
uniform int uLevel;          // the first level written
uniform int uLevelsWritten;  // 1 to SG_CHAIN_LEVELS_PER_DISPATCH

// The texel of the level above that covers texels a, b (x + 1), c (y + 1) and d (both).
vec4 sg_chainMerge(vec4 a, vec4 b, vec4 c, vec4 d);

#ifdef SG_CHAIN_FROM_DEPTH
// Texel `texel` of level 0 (inside the level), from the depth map.
vec4 sg_chainFromDepth(ivec2 texel);
vec4 sg_chainLeaf(ivec2 texel) { return sg_chainFromDepth(texel); }
#else
// Texel `texel` of level uLevel (inside the level), from the 2x2 texels of the level below.
vec4 sg_chainLeaf(ivec2 texel) {
    ivec2 size = textureSize(uBelow, uLevel - 1).xy;
    vec4 t[4];
    for (int k = 0; k < 4; ++k) {
        t[k] = texelFetch(uBelow, ivec3(min(texel * 2 + ivec2(k & 1, k >> 1), size - 1), uLayer), uLevel - 1);
    }
    return sg_chainMerge(t[0], t[1], t[2], t[3]);
}
#endif

void sg_chainStore(int target, ivec2 size, ivec2 texel, vec4 value) {
    if (any(greaterThanEqual(texel, size))) return;
    if (target == 0) imageStore(uTarget0, texel, value);
    if (target == 1) imageStore(uTarget1, texel, value);
    if (target == 2) imageStore(uTarget2, texel, value);
}

// The 2x2 block of a level at `base` (texels a, b, c, d as sg_chainMerge takes them) merged into
// the texel above; a block that passes the level's edge repeats its last row or column.
vec4 sg_chainMergeClamped(ivec2 base, ivec2 size, vec4 a, vec4 b, vec4 c, vec4 d) {
    bvec2 inside = lessThan(base + 1, size);
    vec4 right = inside.x ? b : a;
    vec4 below = inside.y ? c : a;
    vec4 diagonal = inside.x ? (inside.y ? d : b) : below;
    return sg_chainMerge(a, right, below, diagonal);
}

void main() {
    ivec2 size0 = imageSize(uTarget0);
    ivec2 base0 = ivec2(gl_GlobalInvocationID.xy) * 4;
    if (any(greaterThanEqual(base0, size0))) return;
    // The block of level uLevel, clamped to the level (an edge block repeats its last texels).
    vec4 v[16];
    for (int i = 0; i < 16; ++i) {
        ivec2 texel = base0 + ivec2(i & 3, i >> 2);
        v[i] = sg_chainLeaf(min(texel, size0 - 1));
        sg_chainStore(0, size0, texel, v[i]);
    }
    if (uLevelsWritten < 2) return;
    ivec2 size1 = imageSize(uTarget1);
    ivec2 base1 = base0 / 2;
    vec4 w[4];
    for (int j = 0; j < 4; ++j) {
        int k = (j & 1) * 2 + (j >> 1) * 8;  // the first of the 2x2 texels of v under w[j]
        w[j] = sg_chainMerge(v[k], v[k + 1], v[k + 4], v[k + 5]);
        sg_chainStore(1, size1, base1 + ivec2(j & 1, j >> 1), w[j]);
    }
    if (uLevelsWritten < 3) return;
    sg_chainStore(2, imageSize(uTarget2), base0 / 4, sg_chainMergeClamped(base1, size1, w[0], w[1], w[2], w[3]));
}

#endif
