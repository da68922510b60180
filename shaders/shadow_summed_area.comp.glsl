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
// Two passes of one invocation per line: rows from the depth map (SG_CHAIN_FROM_DEPTH), two
// rows per invocation from one gather of each 2x2 texels (a texel fetch costs more than the sums
// of the four), then columns in place.
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

#ifdef SG_CHAIN_FROM_DEPTH
// The quantised moments (q(w), q(w^2)) of stored depth z.
uvec2 sg_satQuantised(float z) {
    float w = clamp(z * uMomentScale, 0.0, 1.0);
    return uvec2(vec2(w, w * w) * sg_kSatUnit + 0.5);  // at most 2^24, carried by sg_satAdd
}
#endif

void main() {
    ivec2 size = imageSize(uTable);
    int line = int(gl_GlobalInvocationID.x);
#ifdef SG_CHAIN_FROM_DEPTH
    // Rows 2 line and 2 line + 1 (the second past the table when its height is odd).
    int row = 2 * line;
    if (row >= size.y) return;
    bool second = row + 1 < size.y;
    vec2 texelSize = 1.0 / vec2(size);
    uvec4 sum0 = uvec4(0u), sum1 = uvec4(0u);
    for (int i = 0; i < size.x; i += 2) {
        // Texels (i, row) w, (i + 1, row) z, (i, row + 1) x, (i + 1, row + 1) y; those past the
        // table read its edge or wrap, and are left out.
        vec4 z = textureGather(uDepth, vec3(vec2(i + 1, row + 1) * texelSize, float(uLayer)));
        uvec2 a = sg_satQuantised(z.w), b = sg_satQuantised(z.x);
        sum0 = sg_satAdd(sum0, uvec4(a.x, 0u, a.y, 0u));
        sum1 = sg_satAdd(sum1, uvec4(b.x, 0u, b.y, 0u));
        imageStore(uTable, ivec2(i, row), vec4(sum0));
        if (second) imageStore(uTable, ivec2(i, row + 1), vec4(sum1));
        if (i + 1 < size.x) {
            a = sg_satQuantised(z.z);
            b = sg_satQuantised(z.y);
            sum0 = sg_satAdd(sum0, uvec4(a.x, 0u, a.y, 0u));
            sum1 = sg_satAdd(sum1, uvec4(b.x, 0u, b.y, 0u));
            imageStore(uTable, ivec2(i + 1, row), vec4(sum0));
            if (second) imageStore(uTable, ivec2(i + 1, row + 1), vec4(sum1));
        }
    }
#else
    if (line >= size.x) return;
    uvec4 sum = uvec4(0u);
    for (int i = 0; i < size.y; ++i) {
        ivec2 texel = ivec2(line, i);
        sum = sg_satAdd(sum, uvec4(imageLoad(uTable, texel)));
        imageStore(uTable, texel, vec4(sum));
    }
#endif
}
