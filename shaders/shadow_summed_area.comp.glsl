// A shadow layer's summed-area table of depth moments (VSSM): texel (x, y) holds the sums of the
// quantised w and w^2 over the map texels [0, x] x [0, y], w = min(z s, 1) the stored depth z
// scaled by the layer's moment scale s (a power of two: exact; ShadowLayerPlan::momentScale puts
// the farthest caster in (1/4, 1/2], whatever the light's range). w is taken to 24-bit fixed
// point, q = floor(w 2^24 + 1/2) (the nearest unit, within half a unit), and
// summed as integers modulo 2^48, each sum two 24-bit limbs (lo, hi) held as floats: the texel
// is (w lo, w hi, w^2 lo, w^2 hi). Integers below 2^24 are exact floats, so nothing is rounded
// however large the table, and a rectangle's sum from its corners is exact whenever the sum
// itself is below 2^47 (any region of under 2^23 texels; the lookups read at most 2^18) - where
// a float table of a 2048^2 layer holds sums near 10^6 with ulps of 0.06, more than a small
// region's whole sum.
// Two passes of one invocation per line: rows from the depth map (SG_CHAIN_FROM_DEPTH), then
// columns in place.
//
// References: F. Crow, "Summed-Area Tables for Texture Mapping", SIGGRAPH 1984; A. Lauritzen,
// "Summed-Area Variance Shadow Maps", GPU Gems 3, 2007 (integer tables for precision).
#include "shared_constants.h"
#include "shadow_summed_area_format.glsl"

layout(local_size_x = 64) in;

layout(binding = SG_IMAGE_MINMAX, rgba32f) uniform image2D uTable;  // the layer's table
#ifdef SG_CHAIN_FROM_DEPTH
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uDepth;  // the layer's depth map
uniform int uLayer;
uniform float uMomentScale;  // s
#endif

void main() {
    ivec2 size = imageSize(uTable);
    int line = int(gl_GlobalInvocationID.x);
#ifdef SG_CHAIN_FROM_DEPTH
    if (line >= size.y) return;
#else
    if (line >= size.x) return;
#endif
    uvec4 sum = uvec4(0u);
    for (int i = 0; i < size.x; ++i) {
#ifdef SG_CHAIN_FROM_DEPTH
        ivec2 texel = ivec2(i, line);
        float w = clamp(texelFetch(uDepth, ivec3(texel, uLayer), 0).r * uMomentScale, 0.0, 1.0);
        uvec2 q = uvec2(vec2(w, w * w) * sg_kSatUnit + 0.5);  // at most 2^24, carried below
        sum = sg_satAdd(sum, uvec4(q.x, 0u, q.y, 0u));
#else
        ivec2 texel = ivec2(line, i);
        sum = sg_satAdd(sum, uvec4(imageLoad(uTable, texel)));
#endif
        imageStore(uTable, texel, vec4(sum));
    }
}
