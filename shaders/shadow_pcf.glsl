// PCF: percentage-closer filtering of the light's own radius (`pcfRadius`), with as many taps as
// the disk's area in texels asks for, and none where the min/max pyramid shows the whole disk
// lit or in umbra.
#ifndef SG_SHADOW_PCF
#define SG_SHADOW_PCF
#include "shadow_filter.glsl"
#include "shadow_region.glsl"

// PCF's taps lie on the receiver triangle's plane as every filter's do (sg_planePolicy). A bend
// term (taps following the shading normal's curvature, half of it times the reach squared in
// bias) served the former metre-valued radius; at the default of 1.5 texels it measured more
// error, not less (docs/tuning.md).
sg_ReceiverPolicy sg_pcfPolicy() { return sg_planePolicy(); }

// PCF of the light's own radius (sg_pcfRadius).
float sg_pcfVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    float radius = sg_pcfRadius(L, r);
    sg_Tap center = sg_lateralTap(L, r, vec2(0.0));
    float known = sg_regionVisibility(slot, L, r, center, radius);
    int taps = known >= 0.0 ? 0 : sg_tapsFor(radius / r.texelMetres, L.pcfSamples);
    float filtered = sg_pcfTaps(slot, L, r, radius, taps, true);
    return known >= 0.0 ? known : filtered;
}

#endif
