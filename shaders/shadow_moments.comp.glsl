// One level of a shadow layer's moment chain (VSM): each texel holds the mean stored depth and
// the mean squared stored depth of its tile of the map, 2^level texels wide. Level 0 reads one
// depth texel, every further level averages the 2x2 texels of the level below, so a trilinear
// fetch at level log2(w) gives the two moments of a region about w texels wide. One level per
// dispatch, as for the min/max pyramid (shadow_minmax.comp.glsl).
//
// Reference: W. Donnelly, A. Lauritzen, "Variance Shadow Maps", I3D 2006 (the seeds' notes on
// VSM/VSSM).
#include "shadow_chain_level.glsl"

layout(binding = SG_IMAGE_MINMAX, rg32f) writeonly uniform image2D uTarget;  // level uLevel of the layer

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(uTarget)))) return;
#ifdef SG_CHAIN_FROM_DEPTH
    float z = texelFetch(uDepth, ivec3(texel, uLayer), 0).r;
    vec2 moments = vec2(z, z * z);
#else
    // Sizes that are not powers of two repeat the last row or column below.
    ivec2 size = textureSize(uBelow, uLevel - 1).xy;
    vec2 moments = vec2(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec3 below = ivec3(min(texel * 2 + ivec2(k & 1, k >> 1), size - 1), uLayer);
        moments += texelFetch(uBelow, below, uLevel - 1).rg;
    }
    moments *= 0.25;
#endif
    imageStore(uTarget, texel, vec4(moments, 0.0, 0.0));
}
