// The shadow techniques a program compiles and the dispatch on a light's technique, written
// from the engine's technique table (engine/include/shadow/techniques.h).
// A game's shader defines SG_TECH_<NAME>_ENABLED for the techniques it wants (one per
// technique below) before it includes shadow.glsl; the files they share come first, so
// that a loader that expands each file once finds them.
#ifndef SG_SHADOW_TECHNIQUES
#define SG_SHADOW_TECHNIQUES
#include "shadow_receiver.glsl"
#include "shadow_taps.glsl"
#include "shadow_kernels.glsl"
#include "shadow_filter.glsl"
#include "shadow_region.glsl"
#include "shadow_debug.glsl"
#include "shadow_penumbra.glsl"
#include "shadow_pcss_filter.glsl"
#include "shadow_moments.glsl"
#include "shadow_soft_moments.glsl"
#include "shadow_summed_area_format.glsl"
#include "shadow_summed_area.glsl"
#include "shadow_hamburger.glsl"
#ifdef SG_TECH_HARD_ENABLED
#include "shadow_hard.glsl"
#endif
#ifdef SG_TECH_PCF_ENABLED
#include "shadow_pcf.glsl"
#endif
#ifdef SG_TECH_PCSS_ENABLED
#include "shadow_pcss.glsl"
#endif
#ifdef SG_TECH_VSM_ENABLED
#include "shadow_vsm.glsl"
#endif
#ifdef SG_TECH_VSSM_ENABLED
#include "shadow_vssm.glsl"
#endif
#ifdef SG_TECH_MSM_ENABLED
#include "shadow_msm.glsl"
#endif
#ifdef SG_TECH_MSM_SOFT_ENABLED
#include "shadow_msm_soft.glsl"
#endif
#ifdef SG_TECH_SDF_ENABLED
#include "shadow_sdf.glsl"
#endif

// The receiver policy of technique `technique` (its share of bias and normal offset).
sg_ReceiverPolicy sg_techniquePolicy(int technique) {
    sg_ReceiverPolicy policy = sg_planePolicy();
#ifdef SG_TECH_HARD_ENABLED
    if (technique == SG_TECH_HARD) policy = sg_hardPolicy();
#endif
#ifdef SG_TECH_PCF_ENABLED
    if (technique == SG_TECH_PCF) policy = sg_pcfPolicy();
#endif
#ifdef SG_TECH_PCSS_ENABLED
    if (technique == SG_TECH_PCSS) policy = sg_pcssPolicy();
#endif
#ifdef SG_TECH_VSM_ENABLED
    if (technique == SG_TECH_VSM) policy = sg_vsmPolicy();
#endif
#ifdef SG_TECH_VSSM_ENABLED
    if (technique == SG_TECH_VSSM) policy = sg_vssmPolicy();
#endif
#ifdef SG_TECH_MSM_ENABLED
    if (technique == SG_TECH_MSM) policy = sg_msmPolicy();
#endif
#ifdef SG_TECH_MSM_SOFT_ENABLED
    if (technique == SG_TECH_MSM_SOFT) policy = sg_msmSoftPolicy();
#endif
#ifdef SG_TECH_SDF_ENABLED
    if (technique == SG_TECH_SDF) policy = sg_sdfPolicy();
#endif
    return policy;
}

// Visibility of light `L` (pass slot `slot`) at receiver `r` by the light's technique; 1
// for a technique not compiled in.
float sg_techniqueVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    float v = 1.0;
#ifdef SG_TECH_HARD_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_HARD); ++k) v = sg_hardVisibility(slot, L, r);
#endif
#ifdef SG_TECH_PCF_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_PCF); ++k) v = sg_pcfVisibility(slot, L, r);
#endif
#ifdef SG_TECH_PCSS_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_PCSS); ++k) v = sg_pcssVisibility(slot, L, r);
#endif
#ifdef SG_TECH_VSM_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_VSM); ++k) v = sg_vsmVisibility(slot, L, r);
#endif
#ifdef SG_TECH_VSSM_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_VSSM); ++k) v = sg_vssmVisibility(slot, L, r);
#endif
#ifdef SG_TECH_MSM_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_MSM); ++k) v = sg_msmVisibility(slot, L, r);
#endif
#ifdef SG_TECH_MSM_SOFT_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_MSM_SOFT); ++k) v = sg_msmSoftVisibility(slot, L, r);
#endif
#ifdef SG_TECH_SDF_ENABLED
    SG_ISOLATED for (int k = 0; k < int(L.technique == SG_TECH_SDF); ++k) v = sg_sdfVisibility(slot, L, r);
#endif
    return v;
}

// The visibility of a light whose technique is known when compiling (the engine's passes
// name one per slot: SG_SLOT<i>_VISIBILITY), without the dispatch; parameters as
// sg_shadowVisibility's.
float sg_unshadowedLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    return 1.0;
}
#ifdef SG_TECH_HARD_ENABLED
float sg_hardLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_hardPolicy(), sg_hardVisibility)
}
#endif
#ifdef SG_TECH_PCF_ENABLED
float sg_pcfLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_pcfPolicy(), sg_pcfVisibility)
}
#endif
#ifdef SG_TECH_PCSS_ENABLED
float sg_pcssLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_pcssPolicy(), sg_pcssVisibility)
}
#endif
#ifdef SG_TECH_VSM_ENABLED
float sg_vsmLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_vsmPolicy(), sg_vsmVisibility)
}
#endif
#ifdef SG_TECH_VSSM_ENABLED
float sg_vssmLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_vssmPolicy(), sg_vssmVisibility)
}
#endif
#ifdef SG_TECH_MSM_ENABLED
float sg_msmLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_msmPolicy(), sg_msmVisibility)
}
#endif
#ifdef SG_TECH_MSM_SOFT_ENABLED
float sg_msmSoftLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_msmSoftPolicy(), sg_msmSoftVisibility)
}
#endif
#ifdef SG_TECH_SDF_ENABLED
float sg_sdfLightVisibility(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,
    float viewDistance) {
    SG_SHADOW_VISIBILITY_BODY(sg_sdfPolicy(), sg_sdfVisibility)
}
#endif
#endif
