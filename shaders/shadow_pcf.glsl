// PCF: percentage-closer filtering of the light's own radius (`pcfRadius`), with as many taps as
// the disk's area in texels asks for, and none where the min/max pyramid shows the whole disk
// lit or in umbra.
#ifndef SG_SHADOW_PCF
#define SG_SHADOW_PCF
#include "shadow_filter.glsl"
#include "shadow_region.glsl"

// PCF's taps lie on the receiver triangle's plane as every filter's do (sg_planePolicy), with
// 0.4 m of depth bias per metre of a tap's reach: a bumpy receiver (the bunny's fur of
// triangles, a crease) rises above its tangent plane within the filter's radius and shadowed its
// own taps. On builtin:bunny (docs/tuning.md) it took PCF's RMSE 0.0402 / 0.0477 / 0.0324 to
// 0.0382 / 0.0455 / 0.0290 (sun / spot / bulb); in PCSS, whose reach is the penumbra's, it
// measured more error (sun 0.0363 -> 0.0376). A curvature-scaled bend (curvature x reach^2)
// measured worse than either on the bunny: it vanishes where the light faces the surface.
sg_ReceiverPolicy sg_pcfPolicy() { return sg_ReceiverPolicy(0.0, sg_kNearSlopeBias, 0.4); }

// At least this many bilinear taps wherever the radius is half a texel or more: the default
// radius of one texel asks for one (radius^2), which is hard's lookup again.
const int sg_kPcfMinTaps = 6;

// PCF of the light's own radius (sg_pcfRadius).
float sg_pcfVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    float radius = sg_pcfRadius(L, r);
    sg_Tap center = sg_receiverTap(r);
    float known = sg_regionVisibility(slot, L, r, center, radius);
    float radiusTexels = radius / r.texelMetres;
    int minTaps = radiusTexels >= 0.5 ? min(sg_kPcfMinTaps, L.pcfSamples) : 1;
    int taps = known >= 0.0 ? 0 : max(sg_tapsFor(radiusTexels, L.pcfSamples), minTaps);
    // Bilinear taps, not gathers of 2x2 box comparisons: at a one-texel radius the boxes' steps
    // are the filter's whole width (sun RMSE 0.0403 with gathers, 0.0382 without).
    float filtered = sg_pcfTaps(slot, L, r, radius, taps, false);
    SG_STAGE_BLOCK_SEARCH(slot, L, r, radius);
    return known >= 0.0 ? known : filtered;
}

#endif
