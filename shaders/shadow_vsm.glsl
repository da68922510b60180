// Variance shadow maps: Chebyshev's bound over the two moments of a region of the light's
// `pcfRadius`, one trilinear fetch of the moments chain whatever its width (below level 1, with
// a gather of the depth map for level 0), taken as the visibility. Where casters overlap at different depths the bound is loose and light leaks (the
// seeds' VSSM notes): bounds below `lightBleedReduction` read as shadow and the rest is
// stretched back to [0, 1].
#ifndef SG_SHADOW_VSM
#define SG_SHADOW_VSM
#include "shadow_moments.glsl"

sg_ReceiverPolicy sg_vsmPolicy() { return sg_planePolicy(); }

float sg_vsmVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_receiverTap(r);
    if (sg_outsideMap(center)) return 1.0;
    // PCF's disk of pcfRadius at the receiver, at most maxFilterTexels.
    // Chebyshev's bound as it is (no plane share, sg_chebyshevUpperBound): over PCF's few texels the
    // receiver's plane spreads little, and taking it out put false shadow on curved receivers.
    vec2 m = sg_regionMoments(slot, L, r, center, sg_pcfRadius(L, r)).xy;
    return sg_momentsVisibility(L, m, sg_momentsReference(r, center), sg_varianceFloor(r, m), 0.0);
}

#endif
