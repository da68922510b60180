// Moment shadow maps, hard-edged: the Hamburger 4MSM bound (shadow_hamburger.glsl) over a region
// of one texel, for edges antialiased by the moments rather than by taps.
//
// A one-texel region is the bilinear blend of the 2x2 texels around the receiver, whose four
// moments come from one gather of the depth map itself: msm keeps no chain, and its shadow pass
// is hard's (a stored chain cost the depth pass an RGBA32F colour write per fragment, 2.6-3x
// hard's layer; BENCHMARKS.md's error against time).
#ifndef SG_SHADOW_MSM
#define SG_SHADOW_MSM
#include "shadow_hamburger.glsl"
#include "shadow_taps.glsl"

sg_ReceiverPolicy sg_msmPolicy() { return sg_planePolicy(); }

// The four power moments of the stored depths around `center`, bilinearly weighted as a
// GL_LINEAR fetch of a moment chain's level 0 with its edge clamped weights them: the 2x2
// texels around the tap from one textureGather, each raised to its powers.
vec4 sg_texelMoments(int slot, sg_GpuLight L, sg_Tap center) {
    float size = float(L.mapSize);
    // Clamped as the chain's edge clamps: at the map's edge the texels beyond carry no weight.
    vec2 st = clamp(center.uv * size - 0.5, vec2(0.0), vec2(size - 1.0));
    vec2 base = floor(st);
    vec2 f = st - base;
    vec4 z = clamp(textureGather(sg_shadowDepth[slot], vec3((base + 1.0) / size, float(center.layer))), 0.0, 1.0);
    vec4 z2 = z * z;
    // Blended by lerps, exact where the four agree (as the filtering unit blends): a region of
    // cleared texels keeps a mean of exactly 1, which the bound reads as lit.
    return vec4(sg_bilinearQuad(z, f), sg_bilinearQuad(z2, f), sg_bilinearQuad(z2 * z, f), sg_bilinearQuad(z2 * z2, f));
}

float sg_msmVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_lateralTap(L, r, vec2(0.0));
    if (sg_outsideMap(center)) return 1.0;
    vec4 b = sg_texelMoments(slot, L, center);
    return 1.0 - sg_msmShadowFraction(b, sg_msmReference(r, center, r.texelMetres));
}

#endif
