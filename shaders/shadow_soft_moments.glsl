// What the soft moment techniques share (shadow_vssm.glsl, shadow_msm_soft.glsl), soft shadows
// from moments with contact hardening: variance soft shadow mapping as the seeds'
// notes describe it (`vssm`, two moments, Chebyshev's bound) and the same design on four moments
// (`msm-soft`, Hamburger 4MSM). The blocker search and the filter both read region moments whose
// cost does not depend on the region's width: VSSM from the light's summed-area table
// (shadow_summed_area.glsl, 16 fetches of exact integer sums), MSM-soft from its mip chain of
// four moments (shadow_moments.frag.glsl: one trilinear fetch for the search, four for the
// penumbra, sg_quadrantMoments).
//   1. Moments of the blocker search region, the same cone as PCSS's.
//   2. Chebyshev's bound gives the fraction p of the region at least as far as the receiver
//      (for both: the 4MSM bound would need the receiver plane's spread over the whole search
//      region as bias, which detached a thin wall's shadow by 3-13 cm); taking
//      those texels to lie on the receiver (the planar-receiver assumption, z_unoccluded = t),
//      the mean splits as mean = p t + (1 - p) z_blocker, which gives the average blocker depth
//      without a search loop.
//   3. Penumbra width by similar triangles in the emitter's physical size (as PCSS), and the
//      bound (Chebyshev's, or 4MSM's) over a region of that width.
// Where the bound is loose (casters overlapping at different depths) both steps leak light; step
// 3 much less with four moments. The light-bleeding reduction applies to VSSM's step 3 as for VSM.
//
// References: Z. Dong, B. Yang, "Variance Soft Shadow Mapping", Pacific Graphics 2010; the
// seeds' notes on real-time shadows (VSSM); C. Peters, R. Klein, "Moment Shadow Mapping", I3D
// 2015. (C. Peters et al., "Moment Soft Shadow Mapping", 2016, estimates the blocker depth from
// partial moments instead; this is the simpler estimate of step 2 on the four-moment bound.)
#ifndef SG_SHADOW_SOFT_MOMENTS
#define SG_SHADOW_SOFT_MOMENTS
#include "shadow_moments.glsl"
#include "shadow_penumbra.glsl"
#include "shadow_debug.glsl"

// Below this fraction of blockers in the search region the receiver is taken as lit: the
// blocker depth (mean - p t) / (1 - p) is 0/0 there.
const float sg_kVssmLeastBlockers = 1e-3;

// Steps 2 and 3's first half: the penumbra half-width (m) behind a blocker search region of
// moments `m` (E[z], E[z^2], stored units) for a receiver at `reference` (stored units) and
// `dReceiver` (m), the variance at least `minVariance` (the region of radius `searchRadius`);
// -1 when the region holds (almost) no blocker, where the receiver is lit. `dBlocker` is the
// blockers' mean depth (m) it found.
float sg_softMomentsPenumbra(sg_GpuLight L, sg_Receiver r, vec2 m, float reference, float minVariance,
                             float searchRadius, float dReceiver, float size, float maxRadius, out float dBlocker) {
    dBlocker = dReceiver;
    float lit = sg_chebyshevUpperBound(m, reference, minVariance, sg_planeVariance(r, searchRadius));
    if (1.0 - lit < sg_kVssmLeastBlockers) return -1.0;
    float zBlocker = (m.x - lit * reference) / (1.0 - lit);
    dBlocker = clamp(zBlocker * r.depthScale, 0.0, dReceiver);
    SG_DEBUG_STORE(sg_debugBlockerDepth, dBlocker);
    float penumbra = min(sg_penumbraRadius(L, dReceiver, dBlocker, size), maxRadius);
    // A mixed region: the visibility changes over the penumbra nearby (the stage's samples).
    SG_STAGE_FEATURE(lit > sg_kVssmLeastBlockers ? penumbra : 3.0e38);
    return penumbra;
}

// The blocker search region's radius (m): the cone from the receiver to the emitter, at least a
// texel, at most maxFilterTexels.
float sg_softMomentsSearchRadius(sg_GpuLight L, sg_Receiver r, float dReceiver, float size, float maxRadius) {
    return clamp(sg_blockerSearchRadius(L, r, dReceiver, size), r.texelMetres, maxRadius);
}

#endif
