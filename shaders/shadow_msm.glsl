// Moment shadow maps, hard-edged: the Hamburger 4MSM bound (shadow_hamburger.glsl) over a region
// of one texel, for edges antialiased by the moments rather than by taps.
#ifndef SG_SHADOW_MSM
#define SG_SHADOW_MSM
#include "shadow_hamburger.glsl"

sg_ReceiverPolicy sg_msmPolicy() { return sg_planePolicy(); }

// Hard-edged MSM: the bound over a region of one texel (level 0's bilinear blend), for edges
// antialiased by the moments rather than by taps.
float sg_msmVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_lateralTap(L, r, vec2(0.0));
    if (sg_outsideMap(center)) return 1.0;
    float radius = r.texelMetres;
    vec4 b = sg_regionMoments(slot, r, center, radius);
    return 1.0 - sg_msmShadowFraction(b, sg_msmReference(r, center, radius));
}

#endif
