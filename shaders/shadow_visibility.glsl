// Shadow visibility of one light at one receiver point: the technique of the light, and the
// blend between cascades. Each technique's code is compiled only when its define is set
// (SG_TECH_HARD_ENABLED, SG_TECH_PCF_ENABLED, SG_TECH_PCSS_ENABLED,
// SG_TECH_PCSS_TEXTBOOK_ENABLED, SG_TECH_VSM_ENABLED, SG_TECH_VSSM_ENABLED, SG_TECH_MSM_ENABLED,
// SG_TECH_MSM_SOFT_ENABLED); the renderer sets exactly the ones its
// lights use.
#ifndef SG_SHADOW_VISIBILITY
#define SG_SHADOW_VISIBILITY
#include "shadow_receiver.glsl"
#include "shadow_debug.glsl"
#if defined(SG_TECH_HARD_ENABLED)
#include "shadow_hard.glsl"
#endif
#if defined(SG_TECH_PCF_ENABLED)
#include "shadow_pcf.glsl"
#endif
#if defined(SG_TECH_PCSS_ENABLED)
#include "shadow_pcss.glsl"
#endif
#if defined(SG_TECH_PCSS_TEXTBOOK_ENABLED)
#include "shadow_pcss_textbook.glsl"
#endif
#if defined(SG_TECH_VSM_ENABLED)
#include "shadow_vsm.glsl"
#endif
#if defined(SG_TECH_MSM_ENABLED)
#include "shadow_msm.glsl"
#endif
#if defined(SG_TECH_VSSM_ENABLED) || defined(SG_TECH_MSM_SOFT_ENABLED)
#include "shadow_vssm.glsl"
#endif

float techniqueVisibility(int slot, GpuLight L, Receiver r) {
    float v = 1.0;
#ifdef SG_TECH_HARD_ENABLED
    if (L.technique == SG_TECH_HARD) v = hardVisibility(slot, L, r);
#endif
#ifdef SG_TECH_PCF_ENABLED
    if (L.technique == SG_TECH_PCF) v = pcfVisibility(slot, L, r);
#endif
#ifdef SG_TECH_PCSS_ENABLED
    if (L.technique == SG_TECH_PCSS) v = pcssVisibility(slot, L, r);
#endif
#ifdef SG_TECH_PCSS_TEXTBOOK_ENABLED
    if (L.technique == SG_TECH_PCSS_TEXTBOOK) v = pcssTextbookVisibility(slot, L, r);
#endif
#ifdef SG_TECH_VSM_ENABLED
    if (L.technique == SG_TECH_VSM) v = vsmVisibility(slot, L, r);
#endif
#ifdef SG_TECH_VSSM_ENABLED
    if (L.technique == SG_TECH_VSSM) v = vssmVisibility(slot, L, r);
#endif
#ifdef SG_TECH_MSM_ENABLED
    if (L.technique == SG_TECH_MSM) v = msmVisibility(slot, L, r);
#endif
#ifdef SG_TECH_MSM_SOFT_ENABLED
    if (L.technique == SG_TECH_MSM_SOFT) v = msmSoftVisibility(slot, L, r);
#endif
    return v;
}

// The light of pass slot `slot` with its type, technique and kernel replaced by the
// compile-time constants given, so that the compiler folds every test on them: a shader
// specialised per light configuration (the renderer's lit passes, the shadow mask) runs no code
// for a type or technique the light does not have.
GpuLight shadowSlotLight(const int slot, const int type, const int technique, const int kernel) {
    GpuLight L = uLights[slot];
    L.type = type;
    L.technique = technique;
    L.kernel = kernel;
    L.firstLayer = slot * SG_MAX_LAYERS_PER_LIGHT;
    return L;
}

// Visibility in [0, 1] of light `L` (bound to pass slot `slot`) at a receiver point. Near the
// far end of a cascade the next cascade is blended in over the last `cascadeBlend` fraction
// of its range, so cascade borders do not show as seams.
float shadowVisibility(int slot, GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature, float viewDistance) {
    if (L.technique == SG_TECH_NONE) return 1.0;
    Receiver r = makeReceiver(L, csPosition, wsNormal, geoNormal, curvature, viewDistance, -1);
    SG_DEBUG_STORE(gDebugCascade, r.layer);
    float v = techniqueVisibility(slot, L, r);
    if (L.type == SG_LIGHT_DIRECTIONAL && r.layer + 1 < L.layerCount && L.cascadeBlend > 0.0) {
        float end = uLayers[L.firstLayer + r.layer].splitFar;
        float begin = r.layer > 0 ? uLayers[L.firstLayer + r.layer - 1].splitFar : 0.0;
        float band = L.cascadeBlend * (end - begin);
        float w = clamp((viewDistance - (end - band)) / max(band, 1e-6), 0.0, 1.0);
        if (w > 0.0) {
            Receiver next = makeReceiver(L, csPosition, wsNormal, geoNormal, curvature, viewDistance, r.layer + 1);
            v = mix(v, techniqueVisibility(slot, L, next), w);
        }
    }
    return clamp(v, 0.0, 1.0);
}
#endif
