// Main pass: sum over this pass's lights of Blinn-Phong shading times the light's visibility.
// Further passes (more than SG_MAX_LIGHTS_PER_PASS lights) add with blending and write only
// colour and their own visibility outputs.
#include "shadow_sampling.glsl"
#include "lighting.glsl"

in vec3 vCsPosition;
in vec3 vWsNormal;

uniform int uFirstLight;     // index in the light buffer of pass slot 0
uniform int uLightCount;     // lights in this pass
uniform int uReceiveShadows;
uniform vec3 uAlbedo;
uniform vec3 uSpecular;
uniform float uShininess;
uniform vec3 uAmbient;       // added by the first pass only
uniform vec3 uCameraForward; // unit, world space
uniform int uDebugView;      // SG_DEBUG_*
uniform int uDebugLight;     // pass slot the debug view shows

layout(location = SG_OUT_COLOR) out vec4 outColor;
#ifdef SG_WRITE_AOVS
layout(location = SG_OUT_POSITION) out vec4 outPosition;  // camera-relative xyz, coverage
layout(location = SG_OUT_DEPTH) out float outDepth;       // distance from the camera (m)
layout(location = SG_OUT_VISIBILITY0) out vec4 outVisibility0;
layout(location = SG_OUT_VISIBILITY1) out vec4 outVisibility1;
#endif

void main() {
    Surface s;
    s.csPosition = vCsPosition;
    s.toViewer = normalize(-vCsPosition);  // never zero: the near plane clips the camera's point
    // A zero normal (a file's, or opposite normals interpolated) takes the triangle's own.
    vec3 n = safeNormalize(vWsNormal, safeNormalize(cross(dFdx(vCsPosition), dFdy(vCsPosition)), s.toViewer));
    // Two-sided: shade the side facing the camera.
    s.normal = dot(n, s.toViewer) < 0.0 ? -n : n;
    s.albedo = uAlbedo;
    s.specular = uSpecular;
    s.shininess = uShininess;

    float viewDistance = dot(vCsPosition, uCameraForward);
    vec3 color = uAmbient * uAlbedo;
    float visibility[SG_MAX_LIGHTS_PER_PASS];
    vec3 debugColor = vec3(0.0);
    for (int i = 0; i < SG_MAX_LIGHTS_PER_PASS; ++i) {
        visibility[i] = 1.0;
        if (i >= uLightCount) continue;
        GpuLight L = uLights[uFirstLight + i];
        vec3 shading = shadeBlinnPhong(L, s);
        if (uReceiveShadows != 0) visibility[i] = shadowVisibility(i, L, s.csPosition, s.normal, viewDistance);
        color += visibility[i] * shading;
        if (i == uDebugLight) {
            if (uDebugView == SG_DEBUG_CASCADE) debugColor = vec3(gDebugCascade == 0, gDebugCascade == 1, gDebugCascade >= 2) * 0.8 + 0.2 * visibility[i];
            if (uDebugView == SG_DEBUG_BLOCKER_DEPTH) debugColor = vec3(gDebugBlockerDepth);
            if (uDebugView == SG_DEBUG_PENUMBRA) debugColor = vec3(gDebugPenumbra);
            if (uDebugView == SG_DEBUG_VISIBILITY) debugColor = vec3(visibility[i]);
        }
    }
    outColor = vec4(uDebugView == SG_DEBUG_NONE ? color : debugColor, 1.0);
#ifdef SG_WRITE_AOVS
    outPosition = vec4(vCsPosition, 1.0);
    outDepth = length(vCsPosition);
    outVisibility0 = vec4(visibility[0], visibility[1], visibility[2], visibility[3]);
    outVisibility1 = vec4(visibility[4], visibility[5], visibility[6], visibility[7]);
#endif
}
