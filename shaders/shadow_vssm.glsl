// Soft shadows from moments, with contact hardening: variance soft shadow mapping as the seeds'
// notes describe it (`vssm`, two moments, Chebyshev's bound) and the same design on four moments
// (`msm-soft`, Hamburger 4MSM). The blocker search and the filter both read region moments whose
// cost does not depend on the region's width: VSSM from the light's summed-area table
// (shadow_summed_area.glsl, 16 fetches of exact integer sums), MSM-soft from its mip chain of
// four moments (shadow_moments.comp.glsl: one trilinear fetch for the search, four for the
// penumbra, quadrantMoments).
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
#ifndef SG_SHADOW_VSSM
#define SG_SHADOW_VSSM
#include "shadow_msm.glsl"
#include "shadow_penumbra.glsl"
#include "shadow_summed_area.glsl"
#include "shadow_debug.glsl"

// Below this fraction of blockers in the search region the receiver is taken as lit: the
// blocker depth (mean - p t) / (1 - p) is 0/0 there.
const float kVssmLeastBlockers = 1e-3;

// MSM-soft's penumbra region from the mip chain: the square VSSM reads from its table
// (half-width h = r sqrt(3) / 2) as four trilinear fetches at the centres of its quadrants, each
// half a level finer than a quadrant's width (log2(h) - 1/2), instead of one fetch at log2(r),
// whose box-and-tent has tails half again as long as the disk. Measured on builtin:plates,
// 320x240, against the ray-traced truth: penumbra RMSE 0.050 with one fetch; with four at level
// log2(h) + {-1.5, -1, -0.5, -0.3, 0}: 0.066, 0.034, 0.025, 0.027, 0.038 (quadrant centres),
// 0.059 and 0.043 with the taps at 0.4 h and 0.6 h. The blocker search keeps the one fetch: it
// only estimates the blockers' mean depth, and the four there cost builtin:bunny and
// builtin:default more (RMSE summed over their six lights and the plates' one: 0.687 with four
// in both regions, 0.677 with one in the search, 0.685 with one in both).
vec4 quadrantMoments(int slot, Receiver r, Tap center, float radius) {
    float h = 0.8660254 * radius / max(r.texelMetres, 1e-30);
    float level = max(log2(max(h, 1e-30)) - 0.5, 0.0);
    vec2 offset = vec2(0.5 * h) / vec2(textureSize(uShadowMinMax[slot], 0).xy);
    vec4 m = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        vec2 quadrant = vec2((k & 1) == 1 ? 1.0 : -1.0, (k & 2) == 2 ? 1.0 : -1.0);
        m += textureLod(uShadowMinMax[slot], vec3(center.uv + quadrant * offset, float(center.layer)), level);
    }
    return 0.25 * m;
}

// A region's moments: VSSM's from its table; MSM-soft's from its mip chain, one fetch for the
// blocker `search`, the quadrants for the penumbra.
vec4 regionMomentsOf(int slot, GpuLight L, Receiver r, Tap center, float radius, const bool fourMoments,
                     const bool search) {
    if (!fourMoments) return vec4(summedRegionMoments(slot, L, r, center, radius), 0.0, 0.0);
    return search ? regionMoments(slot, r, center, radius) : quadrantMoments(slot, r, center, radius);
}

// The least variance of a region's moments: the table's fixed point adds its own.
float regionVarianceFloor(GpuLight L, Receiver r, Tap center, vec2 m, const bool fourMoments) {
    return fourMoments ? varianceFloor(r, m) : summedVarianceFloor(L, r, center, m);
}

float softMomentsVisibility(int slot, GpuLight L, Receiver r, const bool fourMoments) {
    Tap center = lateralTap(L, r, vec2(0.0));
    if (outsideMap(center)) return 1.0;
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    float dReceiver = center.depth;
    float reference = fourMoments ? momentsReference(r, center) : summedReference(L, r, center);
    float size = max(L.emitterSize, 0.0);
    float penumbra = 0.0;
    if (size > 0.0) {
        float searchRadius = clamp(blockerSearchRadius(L, r, dReceiver, size), r.texelMetres, maxRadius);
        vec4 b = regionMomentsOf(slot, L, r, center, searchRadius, fourMoments, true);
        float lit = chebyshevUpperBound(b.xy, reference, regionVarianceFloor(L, r, center, b.xy, fourMoments));
        if (1.0 - lit < kVssmLeastBlockers) return 1.0;
        float zBlocker = (b.x - lit * reference) / (1.0 - lit);
        float dBlocker = clamp(zBlocker * r.depthScale, 0.0, dReceiver);
        penumbra = min(penumbraRadius(L, dReceiver, dBlocker, size), maxRadius);
        SG_DEBUG_STORE(gDebugBlockerDepth, dBlocker);
    }
    SG_DEBUG_STORE(gDebugPenumbra, penumbra);
    vec4 b = regionMomentsOf(slot, L, r, center, penumbra, fourMoments, false);
    return fourMoments ? 1.0 - msmShadowFraction(b, msmReference(r, center, penumbra))
                       : momentsVisibility(L, b.xy, reference, regionVarianceFloor(L, r, center, b.xy, false));
}

float vssmVisibility(int slot, GpuLight L, Receiver r) { return softMomentsVisibility(slot, L, r, false); }
float msmSoftVisibility(int slot, GpuLight L, Receiver r) { return softMomentsVisibility(slot, L, r, true); }

#endif
