// Main pass: the sum over this pass's lights of Blinn-Phong shading times the light's visibility.
//
// The renderer compiles one variant per light configuration of a pass (render/lit_programs.h):
// SG_PASS_LIGHTS lights, and for every slot i < SG_MAX_LIGHTS_PER_PASS the constants
// SG_SLOT<i>_TYPE (SG_LIGHT_*), SG_SLOT<i>_TECH (SG_TECH_*) and SG_SLOT<i>_KERNEL (SG_KERNEL_*). Each slot's code is straight-line
// with its type, technique and layers known when compiling: no light loop, no per-pixel index
// into the sampler array or the light records, no branch for a type or technique the light does
// not have (the fragment-cost table in BENCHMARKS.md measures what each of those costs).
// Depth comes from the depth pre-pass (depth test EQUAL), so each visible pixel is shaded once;
// further passes (more lights) add with blending.
#include "shadow_visibility.glsl"
#include "shadow_surface.glsl"
#include "lighting.glsl"

#if SG_MAX_LIGHTS_PER_PASS != 8
#error "main() below shades slots 0-7: one SG_SHADE_SLOT line per slot"
#endif

in vec3 vCsPosition;
in vec3 vWsNormal;

uniform int uReceiveShadows;
uniform vec3 uAlbedo;
uniform vec3 uSpecular;
uniform float uShininess;
uniform vec3 uAmbient;        // added by the first pass only
uniform vec3 uCameraForward;  // unit, world space

layout(location = SG_OUT_COLOR) out vec4 outColor;
#ifdef SG_WRITE_AOVS
layout(location = SG_OUT_POSITION) out vec4 outPosition;  // camera-relative xyz, coverage
layout(location = SG_OUT_DEPTH) out float outDepth;       // distance from the camera (m)
layout(location = SG_OUT_VISIBILITY0) out vec4 outVisibility0;
layout(location = SG_OUT_VISIBILITY1) out vec4 outVisibility1;
#endif

// Radiance from pass slot `slot` and its visibility. Without AOVs or debug views the shadow
// lookup is skipped where the light's shading is zero (facing away, outside the cone, beyond
// the range); the visibility AOV keeps its meaning everywhere on geometry.
vec3 shadeSlot(const int slot, const int type, const int technique, const int kernel, Surface s, float viewDistance,
               out float visibility) {
    GpuLight L = shadowSlotLight(slot, type, technique, kernel);
    vec3 shading = shadeBlinnPhong(L, s);
    visibility = 1.0;
#if defined(SG_WRITE_AOVS) || defined(SG_DEBUG_VIEWS)
    bool wanted = true;
#else
    bool wanted = max(shading.r, max(shading.g, shading.b)) > 0.0;
#endif
    if (technique != SG_TECH_NONE && uReceiveShadows != 0 && wanted) {
        visibility = shadowVisibility(slot, L, s.csPosition, s.normal, s.geoNormal, s.curvature, viewDistance);
    }
    return visibility * shading;
}

#ifdef SG_DEBUG_VIEWS
// SG_DEBUG_VIEW (SG_DEBUG_*) of pass slot SG_DEBUG_SLOT, read right after that slot ran.
vec3 debugColor = vec3(0.0);
#define SG_DEBUG_CAPTURE(i, v)                                                                    \
    if (i == SG_DEBUG_SLOT) {                                                                     \
        if (SG_DEBUG_VIEW == SG_DEBUG_CASCADE)                                                    \
            debugColor = vec3(gDebugCascade == 0, gDebugCascade == 1, gDebugCascade >= 2) * 0.8 + 0.2 * v; \
        if (SG_DEBUG_VIEW == SG_DEBUG_BLOCKER_DEPTH) debugColor = vec3(gDebugBlockerDepth);       \
        if (SG_DEBUG_VIEW == SG_DEBUG_PENUMBRA) debugColor = vec3(gDebugPenumbra);                \
        if (SG_DEBUG_VIEW == SG_DEBUG_VISIBILITY) debugColor = vec3(v);                           \
    }
#else
#define SG_DEBUG_CAPTURE(i, v)
#endif

// Slot i of the pass: folded away for i >= SG_PASS_LIGHTS.
#define SG_SHADE_SLOT(i)                                                                          \
    if (i < SG_PASS_LIGHTS) {                                                                     \
        color += shadeSlot(i, SG_SLOT##i##_TYPE, SG_SLOT##i##_TECH, SG_SLOT##i##_KERNEL, s, viewDistance, visibility[i]); \
        SG_DEBUG_CAPTURE(i, visibility[i])                                                        \
    }

void main() {
    Surface s;
    s.csPosition = vCsPosition;
    s.toViewer = normalize(-vCsPosition);  // never zero: the near plane clips the camera's point
    ShadowSurface shadowSide = shadowSurface(vCsPosition, vWsNormal);
    s.geoNormal = shadowSide.geoNormal;
    s.curvature = shadowSide.curvature;
    s.normal = shadowSide.normal;  // two-sided: the side facing the camera
    s.albedo = uAlbedo;
    s.specular = uSpecular;
    s.shininess = uShininess;

    float viewDistance = dot(vCsPosition, uCameraForward);
    vec3 color = uAmbient * uAlbedo;
    float visibility[SG_MAX_LIGHTS_PER_PASS] = float[](1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0);
    SG_SHADE_SLOT(0)
    SG_SHADE_SLOT(1)
    SG_SHADE_SLOT(2)
    SG_SHADE_SLOT(3)
    SG_SHADE_SLOT(4)
    SG_SHADE_SLOT(5)
    SG_SHADE_SLOT(6)
    SG_SHADE_SLOT(7)
#ifdef SG_DEBUG_VIEWS
    outColor = vec4(debugColor, 1.0);
#else
    outColor = vec4(color, 1.0);
#endif
#ifdef SG_WRITE_AOVS
    outPosition = vec4(vCsPosition, 1.0);
    outDepth = length(vCsPosition);
    outVisibility0 = vec4(visibility[0], visibility[1], visibility[2], visibility[3]);
    outVisibility1 = vec4(visibility[4], visibility[5], visibility[6], visibility[7]);
#endif
}
