// One level of a shadow layer's moment chain: each texel holds the means of the powers of the
// stored depth over its tile of the map, 2^level texels wide: z and z^2 (VSM), or z, z^2,
// z^3 and z^4 with SG_FOUR_MOMENTS (MSM). Level 0 reads one depth texel, every further level
// averages the 2x2 texels of the level below, so a trilinear fetch at level log2(w) gives the
// moments of a region about w texels wide. One level per dispatch, as for the min/max pyramid
// (shadow_minmax.comp.glsl).
//
// References: W. Donnelly, A. Lauritzen, "Variance Shadow Maps", I3D 2006 (the seeds' notes on
// VSM/VSSM); C. Peters, R. Klein, "Moment Shadow Mapping", I3D 2015.
#include "shadow_chain_level.glsl"

#ifdef SG_FOUR_MOMENTS
layout(binding = SG_IMAGE_MINMAX, rgba32f) writeonly uniform image2D uTarget;  // level uLevel of the layer
#else
layout(binding = SG_IMAGE_MINMAX, rg32f) writeonly uniform image2D uTarget;  // level uLevel of the layer
#endif

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(uTarget)))) return;
#ifdef SG_CHAIN_FROM_DEPTH
    float z = texelFetch(uDepth, ivec3(texel, uLayer), 0).r;
    float z2 = z * z;
    vec4 moments = vec4(z, z2, z2 * z, z2 * z2);
#else
    // Sizes that are not powers of two repeat the last row or column below.
    ivec2 size = textureSize(uBelow, uLevel - 1).xy;
    vec4 moments = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec3 below = ivec3(min(texel * 2 + ivec2(k & 1, k >> 1), size - 1), uLayer);
        moments += texelFetch(uBelow, below, uLevel - 1);
    }
    moments *= 0.25;
#endif
    imageStore(uTarget, texel, moments);
}
