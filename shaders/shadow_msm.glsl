// Moment shadow maps, hard-edged: the Hamburger 4MSM bound (shadow_hamburger.glsl) over a region
// of one texel, for edges antialiased by the moments rather than by taps.
//
// A one-texel region is the bilinear blend of the 2x2 texels around the receiver, whose four
// moments come from one gather of the depth map itself: msm keeps no chain, and its shadow pass
// is hard's (BENCHMARKS.md's error against time; a stored chain cost the depth pass an RGBA32F
// colour write per fragment: 1.3-3.9x hard's shadow pass at 1024^2 on that chart's scenes).
#ifndef SG_SHADOW_MSM
#define SG_SHADOW_MSM
#include "shadow_hamburger.glsl"

sg_ReceiverPolicy sg_msmPolicy() { return sg_planePolicy(); }

float sg_msmVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_receiverTap(r);
    if (sg_outsideMap(center)) return 1.0;
    vec4 b = sg_texelMoments(slot, L, center.uv, center.layer);
    return 1.0 - sg_msmShadowFraction(b, sg_msmReference(r, center, r.texelMetres));
}

#endif
