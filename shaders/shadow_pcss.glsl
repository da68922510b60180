// Percentage-closer soft shadows: the PCSS filter (shadow_pcss_filter.glsl) over the light's map.
//
// Reference: R. Fernando, "Percentage-Closer Soft Shadows", SIGGRAPH 2005 sketch.
#ifndef SG_SHADOW_PCSS
#define SG_SHADOW_PCSS
#include "shadow_pcss_filter.glsl"

sg_ReceiverPolicy sg_pcssPolicy() { return sg_planePolicy(); }

float sg_pcssVisibility(int slot, sg_GpuLight L, sg_Receiver r) { return sg_pcssFilter(slot, L, r); }

#endif
