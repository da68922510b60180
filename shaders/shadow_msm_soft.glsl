// Moment soft shadows (msm-soft): VSSM's blocker search and penumbra (shadow_soft_moments.glsl)
// on the four-moment mip chain, one trilinear fetch for the search and four for the penumbra,
// and the Hamburger 4MSM bound (shadow_hamburger.glsl) over the penumbra. The chain is made from
// level 1 up: a fetch finer than level 1 takes its level-0 half from a gather of the depth map
// (sg_chainMoments), as VSM's does, so no pass writes RGBA32F moments at the map's resolution.
#ifndef SG_SHADOW_MSM_SOFT
#define SG_SHADOW_MSM_SOFT
#include "shadow_soft_moments.glsl"
#include "shadow_hamburger.glsl"

sg_ReceiverPolicy sg_msmSoftPolicy() { return sg_planePolicy(); }

// MSM-soft's penumbra region from the mip chain: the square VSSM reads from its table
// (half-width h = r sqrt(3) / 2) as four trilinear fetches at the centres of its quadrants, each
// half a level finer than a quadrant's width (log2(h) - 1/2), instead of one fetch at log2(r),
// whose box-and-tent has tails half again as long as the disk: the level and the positions of
// least penumbra error against the ray-traced truth. The blocker search keeps one fetch: it only
// estimates the blockers' mean depth, and four there measured more error (docs/tuning.md).
vec4 sg_quadrantMoments(int slot, sg_GpuLight L, sg_Receiver r, sg_Tap center, float radius) {
    float h = 0.8660254 * radius / max(r.texelMetres, 1e-30);
    float level = max(log2(max(h, 1e-30)) - 0.5, 0.0);
    vec2 offset = vec2(0.5 * h / L.mapSize);  // map texels (the chain holds no level 0)
    vec4 m = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        vec2 quadrant = vec2((k & 1) == 1 ? 1.0 : -1.0, (k & 2) == 2 ? 1.0 : -1.0);
        m += sg_chainMoments(slot, L, center.uv + quadrant * offset, center.layer, level);
    }
    return 0.25 * m;
}

float sg_msmSoftVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_receiverTap(r);
    if (sg_outsideMap(center)) return 1.0;
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    float dReceiver = center.depth;
    float reference = sg_momentsReference(r, center);
    float size = sg_apparentEmitterSize(L, r.toLight);
    float penumbra = 0.0;
    float dBlocker = 0.0;
    if (size > 0.0) {
        float searchRadius = sg_softMomentsSearchRadius(L, r, dReceiver, size, maxRadius);
        vec2 m = sg_chainMoments(slot, L, center.uv, center.layer, sg_regionLevel(r, searchRadius)).xy;
        penumbra = sg_softMomentsPenumbra(L, r, m, reference, sg_varianceFloor(r, m), searchRadius, dReceiver, size,
                                          maxRadius, dBlocker);
        if (penumbra < 0.0) return 1.0;  // no blocker: lit
        if (sg_refinesSearch(penumbra, searchRadius)) {
            // The search again over the cone to the blockers found (sg_refinesSearch).
            vec2 m2 = sg_chainMoments(slot, L, center.uv, center.layer, sg_regionLevel(r, penumbra)).xy;
            float dBlocker2;
            float refined = sg_softMomentsPenumbra(L, r, m2, reference, sg_varianceFloor(r, m2), penumbra, dReceiver,
                                                   size, maxRadius, dBlocker2);
            if (sg_refinedPenumbra(penumbra, refined) != penumbra) {
                penumbra = refined;
                dBlocker = dBlocker2;
            }
        }
    }
    SG_DEBUG_STORE(sg_debugPenumbra, penumbra);
    vec4 b = sg_quadrantMoments(slot, L, r, center, penumbra);
    // The bound compares the receiver plane's nearest depth in the region (sg_msmReference), but
    // never nearer than halfway to the blockers the search found: over a wide penumbra under a
    // steep light the plane's near edge passes the blockers themselves, and the whole shadow read
    // as lit (builtin:plates-boxes' top box, 0.31 of penumbra RMSE).
    float planeNearest = sg_msmReference(r, center, penumbra);
    float halfway = 0.5 * (reference + dBlocker / r.depthScale);
    return 1.0 - sg_msmShadowFraction(b, max(planeNearest, halfway));
}

#endif
