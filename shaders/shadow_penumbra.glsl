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

// The blocker search (PCSS's, VSSM's, MSM-soft's) is done twice. The first region is the cone
// to the nearest depth a blocker can have, and over a scene of several caster heights it takes
// in blockers of other heights, which pull the mean blocker depth from the one that occludes the
// receiver (the two plates of builtin:plates: the high plate's texels widen the low plate's
// penumbra). The second region is the cone to the mean depth found, which is the first
// penumbra's width (similar triangles): for blockers of one depth the same region again, for
// several the ones that can occlude at that depth. It is searched only where under half the
// first (`sg_refinesSearch`; 0.9 gained 0.0003 of RMSE more at most), and its penumbra is taken
// only where narrower (`sg_refinedPenumbra`): where the narrower region found no blocker, or a
// nearer one, the first estimate stands (taking it either way made the default scene's spot and
// point light worse). Against the truth (docs/tuning.md): VSSM and MSM-soft gain on every light
// of five scenes at both map sizes; PCSS, whose taps already carry each blocker's own depth to
// the receiver, on the bunny, the default scene and the contact sample, the plates unchanged.
bool sg_refinesSearch(float penumbra, float searchRadius) { return penumbra < 0.5 * searchRadius; }

// The penumbra half-width after the second search (`refined`, -1 without a blocker in it).
float sg_refinedPenumbra(float first, float refined) {
    return refined >= 0.0 && refined < first ? refined : first;
}

// Penumbra half-width at a receiver `dReceiver` from the light behind a blocker at `dBlocker`
// (both metres along the light's depth), by similar triangles.
float sg_penumbraRadius(sg_GpuLight L, float dReceiver, float dBlocker, float size) {
    return L.type == SG_LIGHT_DIRECTIONAL ? (dReceiver - dBlocker) * tan(size)
                                          : (dReceiver - dBlocker) * size / max(dBlocker, 1e-6);
}

// A spot's emitter is a disk facing along the spot's axis: seen from a receiver off the axis it
// is an ellipse, narrower towards the axis by the cosine of the angle off it, which this returns
// for a receiver in direction `toLight` (unit, towards the light). A sphere (point light) and the
// sun's disk look round from everywhere: 1.
float sg_emitterForeshortening(sg_GpuLight L, vec3 toLight) {
    return L.type == SG_LIGHT_SPOT ? clamp(dot(-toLight, L.wsDirection), 0.0, 1.0) : 1.0;
}

// The emitter's size (emitterSize's unit) as the disk of the same area as it looks from `r`:
// what a round region stands in for the ellipse with (the soft moment techniques' squares, the
// distance-field march's cone).
float sg_apparentEmitterSize(sg_GpuLight L, vec3 toLight) {
    return max(L.emitterSize, 0.0) * sqrt(sg_emitterForeshortening(L, toLight));
}

// The PCSS search and filter cover the emitter seen through the receiver, so they take the
// ellipse itself: `r` with its lateral axes squeezed towards the spot's axis, so that every
// lateral offset lands where the emitter's shape says (`r` as it is for a round emitter).
sg_Receiver sg_emitterShaped(sg_GpuLight L, sg_Receiver r) {
    vec3 ray = normalize(r.lsPosition);  // from the light, whose axis is -z in its space
    vec3 towardAxis = vec3(0.0, 0.0, -1.0) + ray.z * ray;  // the axis, less its part along the ray
    vec2 e = vec2(dot(r.lsTangent1, towardAxis), dot(r.lsTangent2, towardAxis));
    float len = length(e);
    if (L.type != SG_LIGHT_SPOT || len < 1e-6) return r;
    e /= len;
    // o -> o - (1 - cos) (o.e) e, applied to the axes: axis i gains -(1 - cos) e_i (e.x t1 + e.y t2).
    vec2 k = (1.0 - sg_emitterForeshortening(L, r.toLight)) * e;
    vec3 cs = e.x * r.csTangent1 + e.y * r.csTangent2;
    vec3 ls = e.x * r.lsTangent1 + e.y * r.lsTangent2;
    vec4 clip = e.x * r.clipTangent1 + e.y * r.clipTangent2;
    r.csTangent1 -= k.x * cs;
    r.csTangent2 -= k.y * cs;
    r.lsTangent1 -= k.x * ls;
    r.lsTangent2 -= k.y * ls;
    r.clipTangent1 -= k.x * clip;
    r.clipTangent2 -= k.y * clip;
    return r;
}

#endif
