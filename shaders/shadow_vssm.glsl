// Variance soft shadow mapping (the seeds' VSSM; shadow_soft_moments.glsl has the method): both
// regions read from the light's summed-area table (shadow_summed_area.glsl, 16 fetches of exact
// integer sums whatever the width), Chebyshev's bound over the penumbra with the light-bleeding
// reduction as VSM's.
#ifndef SG_SHADOW_VSSM
#define SG_SHADOW_VSSM
#include "shadow_soft_moments.glsl"
#include "shadow_summed_area.glsl"

sg_ReceiverPolicy sg_vssmPolicy() { return sg_planePolicy(); }

float sg_vssmVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_receiverTap(r);
    // A layer without casters has no table (its moment scale 0): lit.
    if (sg_outsideMap(center) || sg_summedMomentScale(L, center) == 0.0) return 1.0;
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    float dReceiver = center.depth;
    float reference = sg_summedReference(L, r, center);
    float size = sg_apparentEmitterSize(L, r.toLight);
    // The blocker search region, its refinement (sg_refinedPenumbra), then the penumbra: one
    // loop body reads all three, so the table's 16 fetches are compiled once, and a SIMD group
    // whose regions hold no blocker stops after the first read. Without an emitter the penumbra
    // is 0 and only it is read.
    int reads = size > 0.0 ? 3 : 1;
    float radius = size > 0.0 ? sg_softMomentsSearchRadius(L, r, dReceiver, size, maxRadius) : 0.0;
    float visibility = 1.0;
    SG_ISOLATED
    for (int k = 0; k < reads; ++k) {
        vec2 m = sg_summedRegionMoments(slot, L, r, center, radius);
        float minVariance = sg_summedVarianceFloor(L, r, center, m);
        if (k + 1 < reads) {
            float dBlocker;
            float penumbra =
                sg_softMomentsPenumbra(L, r, m, reference, minVariance, radius, dReceiver, size, maxRadius, dBlocker);
            if (k == 0) {
                if (penumbra < 0.0) break;  // no blocker: lit
                // Searched again only where under half the first region (sg_refinesSearch).
                if (!sg_refinesSearch(penumbra, radius)) ++k;
                radius = penumbra;
            } else {
                radius = sg_refinedPenumbra(radius, penumbra);
            }
        } else {
            SG_DEBUG_STORE(sg_debugPenumbra, radius);
            visibility = sg_momentsVisibility(L, m, reference, minVariance, sg_planeVariance(r, radius));
        }
    }
    return visibility;
}

#endif
