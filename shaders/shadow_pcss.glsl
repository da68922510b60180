// Percentage-closer soft shadows: blocker search, penumbra width from similar triangles in the
// emitter's physical size (design.md, emitter conventions), then PCF over that width.
//
// Reference: R. Fernando, "Percentage-Closer Soft Shadows", SIGGRAPH 2005 sketch.
#ifndef SG_SHADOW_PCSS
#define SG_SHADOW_PCSS
#include "shadow_pcf.glsl"
#include "shadow_debug.glsl"

// Percentage-closer soft shadows: blocker search, penumbra from similar triangles, PCF.
float pcssVisibility(int slot, GpuLight L, Receiver r) {
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    Tap center = lateralTap(L, r, vec2(0.0));
    float dReceiver = center.depth;
    float size = max(L.emitterSize, 0.0);
    if (size <= 0.0 || maxRadius <= 0.0) return compareTap(slot, L, r, center);

    // Blocker search region, lateral metres at the receiver: the cone from the receiver to
    // the emitter, widest at the nearest depth a blocker can have.
    GpuShadowLayer S = uLayers[L.firstLayer + r.layer];
    float searchRadius;
    if (L.type == SG_LIGHT_DIRECTIONAL) {
        searchRadius = dReceiver * tan(size);
    } else {
        float near = max(S.depthNear, 1e-6);
        searchRadius = size * max(dReceiver - near, 0.0) / near;
    }
    searchRadius = clamp(searchRadius, r.texelMetres, maxRadius);

    DiskWalk disk = beginDisk(pixelRotation(), L.blockerSamples);
    float blockerSum = 0.0;
    int blockers = 0;
    for (int i = 0; i < L.blockerSamples; ++i) {
        Tap t = lateralTap(L, r, nextDiskSample(L.kernel, disk, i) * searchRadius);
        float stored = texture(uShadowDepth[slot], vec3(t.uv, float(t.layer))).r *
                       (t.layer == r.layer ? r.depthScale : uLayers[L.firstLayer + t.layer].depthScale);
        if (stored < t.depth - r.depthBias) {
            // Blocker depth expressed at the center's lateral position: the tap's own shift
            // along the tangent plane is removed so a sloped receiver does not bias it.
            blockerSum += stored + (dReceiver - t.depth);
            ++blockers;
        }
    }
    if (blockers == 0) {
        SG_DEBUG_STORE(gDebugBlockerDepth, 0.0);
        SG_DEBUG_STORE(gDebugPenumbra, 0.0);
        return 1.0;
    }
    float dBlocker = clamp(blockerSum / float(blockers), 0.0, dReceiver);
    // Penumbra half-width at the receiver (m), by similar triangles.
    float penumbra;
    if (L.type == SG_LIGHT_DIRECTIONAL) {
        penumbra = (dReceiver - dBlocker) * tan(size);
    } else {
        penumbra = (dReceiver - dBlocker) * size / max(dBlocker, 1e-6);
    }
    penumbra = min(penumbra, maxRadius);
    SG_DEBUG_STORE(gDebugBlockerDepth, dBlocker);
    SG_DEBUG_STORE(gDebugPenumbra, penumbra);
    return pcfVisibility(slot, L, r, penumbra, L.pcfSamples);
}
#endif
