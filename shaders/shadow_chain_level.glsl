// What a compute build of a mip chain's level takes (filter_chain.cpp; the min/max pyramid): an
// 8x8 work group per tile of texels of one level of one layer, reading the layer's depth map for
// level 0 (SG_CHAIN_FROM_DEPTH) and the level below for the others. The chain's file declares
// the image it writes, in its own format.
#ifndef SG_SHADOW_CHAIN_LEVEL
#define SG_SHADOW_CHAIN_LEVEL
#include "shared_constants.h"

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef SG_CHAIN_FROM_DEPTH
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uDepth;  // the layer's depth map
#else
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uBelow;  // the chain, level uLevel - 1 read
#endif

uniform int uLayer;
uniform int uLevel;
// The first texel of the level the dispatch covers (the min/max pyramid's tiles that hold a
// drawn texel).
uniform ivec2 uOrigin;

#endif
