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

sg_ReceiverPolicy sg_msmPolicy() { return sg_planePolicy(); }

// The four power moments of the stored depths around `center`, bilinearly weighted as a
// GL_LINEAR fetch of a moment chain's level 0 with its edge clamped weights them: the 2x2
// texels around the tap from one textureGather, each raised to its powers (sg_depthMoments).
vec4 sg_texelMoments(int slot, sg_GpuLight L, sg_Tap center) {
    float size = float(L.mapSize);
    // Clamped as the chain's edge clamps: at the map's edge the texels beyond carry no weight.
    vec2 st = clamp(center.uv * size - 0.5, vec2(0.0), vec2(size - 1.0));
    vec2 base = floor(st);
    vec2 f = st - base;
    vec4 z = textureGather(sg_shadowDepth[slot], vec3((base + 1.0) / size, float(center.layer)));
    // textureGather's order: (0,1), (1,1), (1,0), (0,0) from the lower-left texel.
    vec4 w = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
    mat4 powers = mat4(sg_depthMoments(z.x), sg_depthMoments(z.y), sg_depthMoments(z.z), sg_depthMoments(z.w));
    return powers * w;
}

float sg_msmVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_lateralTap(L, r, vec2(0.0));
    if (sg_outsideMap(center)) return 1.0;
    vec4 b = sg_texelMoments(slot, L, center);
    return 1.0 - sg_msmShadowFraction(b, sg_msmReference(r, center, r.texelMetres));
}

#endif
