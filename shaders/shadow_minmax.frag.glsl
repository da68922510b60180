// One level of a shadow layer's min/max depth pyramid: each texel holds the least and the
// greatest stored depth of its tile of the map. Level 0 reads SG_MINMAX_TILE^2 depth texels,
// every further level the 2x2 texels of the level below. PCF and PCSS read it to find, in two
// fetches, regions with no blocker (fully lit) or only blockers (umbra), and skip their taps.
//
// Reference: the hierarchical min/max shadow map of G. Guennebaud, L. Barthe, M. Paulin,
// "Real-time soft shadow mapping by backprojection", EGSR 2006, and of Z. Dong, B. Yang,
// "Variance soft shadow mapping", 2010 (the seeds' VSSM notes).
#include "shared_constants.h"

#ifdef SG_MINMAX_FROM_DEPTH
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uDepth;  // the layer's depth map
#else
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uBelow;  // level below, its only level sampled
#endif
uniform int uLayer;

layout(location = 0) out vec2 outMinMax;

void main() {
    ivec2 tile = ivec2(gl_FragCoord.xy);
    vec2 range = vec2(1.0, 0.0);
#ifdef SG_MINMAX_FROM_DEPTH
    // Gathers of 2x2 texels; coordinates past the map's edge clamp to it (the sampler's own).
    vec2 texelSize = 1.0 / vec2(textureSize(uDepth, 0).xy);
    for (int y = 0; y < SG_MINMAX_TILE; y += 2) {
        for (int x = 0; x < SG_MINMAX_TILE; x += 2) {
            vec2 uv = (vec2(tile * SG_MINMAX_TILE + ivec2(x, y)) + 1.0) * texelSize;
            vec4 d = textureGather(uDepth, vec3(uv, float(uLayer)));
            range = vec2(min(range.x, min(min(d.x, d.y), min(d.z, d.w))), max(range.y, max(max(d.x, d.y), max(d.z, d.w))));
        }
    }
#else
    ivec2 size = textureSize(uBelow, 0).xy;
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 2; ++x) {
            vec2 below = texelFetch(uBelow, ivec3(min(tile * 2 + ivec2(x, y), size - 1), uLayer), 0).rg;
            range = vec2(min(range.x, below.x), max(range.y, below.y));
        }
    }
#endif
    outMinMax = range;
}
