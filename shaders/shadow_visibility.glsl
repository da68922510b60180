// Shadow visibility of one light at one receiver point: the light's technique and the blend
// between cascades. The techniques come from shadow_techniques.glsl: `sg_techniquePolicy` (the
// technique's share of bias and offset), `sg_techniqueVisibility` and one
// `sg_<technique>LightVisibility` per technique, with the code of the techniques compiled in and
// no other (the engine writes that file for each program from its technique table; the
// installed copy selects them by SG_TECH_*_ENABLED).
#ifndef SG_SHADOW_VISIBILITY
#define SG_SHADOW_VISIBILITY
#include "shadow_receiver.glsl"
#include "shadow_debug.glsl"

// The light of pass slot `slot` with its type, technique and kernel replaced by the
// compile-time constants given, so that the compiler folds every test on them: a shader
// specialised per light configuration (the renderer's lit passes, the shadow mask) runs no code
// for a type or technique the light does not have.
sg_GpuLight sg_slotLight(const int slot, const int type, const int technique, const int kernel) {
    sg_GpuLight L = sg_lights[slot];
    L.type = type;
    L.technique = technique;
    L.kernel = kernel;
    L.firstLayer = slot * SG_MAX_LAYERS_PER_LIGHT;
    return L;
}

// The body of a light's visibility in [0, 1] at a receiver point, for a technique whose receiver
// policy is POLICY and whose visibility is VISIBILITY(slot, L, receiver); the parameters are those
// of sg_shadowVisibility below. Near the far end of a cascade the next cascade is blended in over
// the last `cascadeBlend` fraction of its range, so cascade borders do not show as seams; that
// second evaluation is a loop trip, which a CPU rasteriser skips where no pixel of its SIMD group
// lies in a blend band (it runs both sides of an `if`).
//
// The evaluations, in one of two shapes. Straight-line (the default): the first evaluation
// unmasked at full speed, the blend's second one in a loop of 0 or 1 trips. With
// SG_ISOLATE_LOOPS (a program too large to compile its lights straight-line: a game's shader, or
// a pass of many unlike lights) both are trips of one loop, which compiles the technique once
// for both cascades and keeps the light's code off the chain of loops in sequence, at a quarter
// of the speed of straight-line code lost to the loop's masks on a CPU rasteriser.
#ifdef SG_ISOLATE_LOOPS
#define SG_EVALUATE_CASCADES(VISIBILITY)                                                                      \
    float v = 1.0;                                                                                            \
    for (int e = 0; e < min(L.layerCount, 1) + (blend > 0.0 ? 1 : 0); ++e) {                                  \
        sg_Receiver r = sg_makeReceiver(L, csPosition, wsNormal, geoNormal, curvature, viewDistance,          \
                                        cascade < 0 ? -1 : cascade + e, policy);                              \
        if (e == 0) SG_DEBUG_STORE(sg_debugCascade, r.layer);                                                 \
        float next = VISIBILITY(slot, L, r);                                                                  \
        v = e == 0 ? next : mix(v, next, blend);                                                              \
    }
#else
#define SG_EVALUATE_CASCADES(VISIBILITY)                                                                      \
    sg_Receiver r = sg_makeReceiver(L, csPosition, wsNormal, geoNormal, curvature, viewDistance, cascade, policy); \
    SG_DEBUG_STORE(sg_debugCascade, r.layer);                                                                 \
    float v = VISIBILITY(slot, L, r);                                                                         \
    for (int next = 0; next < int(blend > 0.0); ++next) {                                                     \
        sg_Receiver n = sg_makeReceiver(L, csPosition, wsNormal, geoNormal, curvature, viewDistance,          \
                                        cascade + 1, policy);                                                 \
        v = mix(v, VISIBILITY(slot, L, n), blend);                                                            \
    }
#endif

// A macro, so that the function of each technique (sg_<technique>LightVisibility, written by
// shadow_techniques.glsl) calls its technique directly: a pass whose slots have techniques
// known when compiling need not compile (and then discard) the dispatch over all of them.
#define SG_SHADOW_VISIBILITY_BODY(POLICY, VISIBILITY)                                                         \
    if (L.technique == SG_TECH_NONE) return 1.0;                                                              \
    int cascade = -1; /* the layer of a directional light; the others choose by position */                  \
    float blend = 0.0;                                                                                        \
    if (L.type == SG_LIGHT_DIRECTIONAL) {                                                                     \
        cascade = sg_selectCascade(L, viewDistance);                                                          \
        if (cascade + 1 < L.layerCount && L.cascadeBlend > 0.0) {                                             \
            float end = sg_layers[L.firstLayer + cascade].splitFar;                                           \
            float begin = cascade > 0 ? sg_layers[L.firstLayer + cascade - 1].splitFar : 0.0;                 \
            float band = L.cascadeBlend * (end - begin);                                                      \
            blend = clamp((viewDistance - (end - band)) / max(band, 1e-6), 0.0, 1.0);                         \
        }                                                                                                     \
    }                                                                                                         \
    sg_ReceiverPolicy policy = POLICY;                                                                        \
    SG_EVALUATE_CASCADES(VISIBILITY)                                                                          \
    return clamp(v, 0.0, 1.0);

#include "shadow_techniques.glsl"

// Visibility in [0, 1] of light `L` (bound to pass slot `slot`) at a receiver point at
// `csPosition` (camera-relative) with shading normal `wsNormal`, triangle normal `geoNormal` and
// `curvature` (sg_Surface), `viewDistance` along the camera's axis, by the light's technique.
float sg_shadowVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
                          float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_techniquePolicy(L.technique), sg_techniqueVisibility)
}
#endif
