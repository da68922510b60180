// The emitter's geometry shared by every soft-shadow technique (PCSS, VSSM), in the physical
// units of docs/output_contract.md: `emitterSize` is a disk or sphere radius (m) for spot and point lights, an
// angular radius (rad) for directional ones; all widths are lateral metres at the receiver.
#ifndef SG_SHADOW_PENUMBRA
#define SG_SHADOW_PENUMBRA
#include "shadow_receiver.glsl"

// Blocker search region: the cone from the receiver to the emitter, widest at the nearest depth
// a blocker can have (`blockerNear`: a spot's or point light's nearest caster, or a fixed near
// plane beyond it; a cascade's highest caster below its top).
float sg_blockerSearchRadius(sg_GpuLight L, sg_Receiver r, float dReceiver, float size) {
    float blockerNear = sg_layers[L.firstLayer + r.layer].blockerNear;
    if (L.type == SG_LIGHT_DIRECTIONAL) return max(dReceiver - blockerNear, 0.0) * tan(size);
    float near = max(blockerNear, 1e-6);
    return size * max(dReceiver - near, 0.0) / near;
}

// Penumbra half-width at a receiver `dReceiver` from the light behind a blocker at `dBlocker`
// (both metres along the light's depth), by similar triangles.
float sg_penumbraRadius(sg_GpuLight L, float dReceiver, float dBlocker, float size) {
    return L.type == SG_LIGHT_DIRECTIONAL ? (dReceiver - dBlocker) * tan(size)
                                          : (dReceiver - dBlocker) * size / max(dBlocker, 1e-6);
}

#endif
