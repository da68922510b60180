// Variance soft shadow mapping, as the seeds' notes describe it: the blocker search and the
// filter both read region moments from the VSM moments chain (shadow_moments.comp.glsl), so
// each costs one trilinear fetch whatever the penumbra's width.
//   1. Moments (mean, mean square) of the blocker search region, the same cone as PCSS's.
//   2. Chebyshev's bound gives the fraction p of the region at least as far as the receiver;
//      taking those texels to lie on the receiver (the planar-receiver assumption,
//      z_unoccluded = t), the mean splits as mean = p t + (1 - p) z_blocker, which gives the
//      average blocker depth without a search loop.
//   3. Penumbra width by similar triangles in the emitter's physical size (as PCSS), and VSM's
//      Chebyshev over a region of that width.
// Where the bound is loose (casters overlapping at different depths) both steps leak light; the
// light-bleeding reduction applies to step 3 as for VSM.
//
// References: Z. Dong, B. Yang, "Variance Soft Shadow Mapping", Pacific Graphics 2010; the
// seeds' notes on real-time shadows (VSSM).
#ifndef SG_SHADOW_VSSM
#define SG_SHADOW_VSSM
#include "shadow_vsm.glsl"
#include "shadow_penumbra.glsl"
#include "shadow_debug.glsl"

// Below this fraction of blockers in the search region the receiver is taken as lit: the
// blocker depth (mean - p t) / (1 - p) is 0/0 there.
const float kVssmLeastBlockers = 1e-3;

float vssmVisibility(int slot, GpuLight L, Receiver r) {
    Tap center = lateralTap(L, r, vec2(0.0));
    if (outsideMap(center)) return 1.0;
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    float dReceiver = center.depth;
    float reference = momentsReference(r, center);
    float size = max(L.emitterSize, 0.0);
    float penumbra = 0.0;
    if (size > 0.0) {
        float searchRadius = clamp(blockerSearchRadius(L, r, dReceiver, size), r.texelMetres, maxRadius);
        vec2 m = regionMoments(slot, r, center, searchRadius);
        float lit = chebyshevUpperBound(m, reference, varianceFloor(r, m));
        if (1.0 - lit < kVssmLeastBlockers) return 1.0;
        float zBlocker = (m.x - lit * reference) / (1.0 - lit);
        float dBlocker = clamp(zBlocker * r.depthScale, 0.0, dReceiver);
        penumbra = min(penumbraRadius(L, dReceiver, dBlocker, size), maxRadius);
        SG_DEBUG_STORE(gDebugBlockerDepth, dBlocker);
    }
    SG_DEBUG_STORE(gDebugPenumbra, penumbra);
    return momentsVisibility(L, r, regionMoments(slot, r, center, penumbra), reference);
}

#endif
