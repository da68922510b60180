// Definitions shared by the shadow pass and the shadow sampling code.
#ifndef SG_SHADOW_COMMON
#define SG_SHADOW_COMMON

// Linear depth of a light-view position (m): along the axis for orthographic layers, from the
// light for perspective ones. The one definition both writer and reader use.
float sg_lightSpaceDepth(vec3 lsPosition, bool orthographic) {
    return orthographic ? -lsPosition.z : length(lsPosition);
}

// Unit vector along `v`, or `fallback` when `v` is too short to have a direction (a receiver at
// the light's own position, a zero normal from a file): normalize(0) is NaN in GLSL.
vec3 sg_safeNormalize(vec3 v, vec3 fallback) {
    float len = length(v);
    return len > 1e-20 ? v / len : fallback;
}

#endif
