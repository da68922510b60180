// Definitions shared by the shadow pass and the shadow sampling code.
#ifndef SG_SHADOW_COMMON
#define SG_SHADOW_COMMON

// Linear depth of a light-view position (m): along the axis for orthographic layers, from the
// light for perspective ones. The one definition both writer and reader use.
float sg_lightSpaceDepth(vec3 lsPosition, bool orthographic) {
    return orthographic ? -lsPosition.z : length(lsPosition);
}

// The powers z, z^2, z^3 and z^4 of a stored depth, clamped to [0, 1] as the depth buffer
// clamps it: a texel of level 0 of a moment chain (a two-moment chain keeps the first two).
vec4 sg_depthMoments(float depth) {
    float z = clamp(depth, 0.0, 1.0);
    float z2 = z * z;
    return vec4(z, z2, z2 * z, z2 * z2);
}

// Unit vector along `v`, or `fallback` when `v` is too short to have a direction (a receiver at
// the light's own position, a zero normal from a file): normalize(0) is NaN in GLSL.
vec3 sg_safeNormalize(vec3 v, vec3 fallback) {
    float len = length(v);
    return len > 1e-20 ? v / len : fallback;
}

// Two unit vectors perpendicular to unit `axis` and to each other (a frame across a ray or a
// plane), built from the coordinate axis least aligned with it.
void sg_perpendicularBasis(vec3 axis, out vec3 t1, out vec3 t2) {
    vec3 a = abs(axis);
    vec3 helper = (a.x <= a.y && a.x <= a.z) ? vec3(1, 0, 0) : (a.y <= a.z ? vec3(0, 1, 0) : vec3(0, 0, 1));
    t1 = normalize(cross(axis, helper));
    t2 = cross(axis, t1);
}

// The screen-space stage's samples (SG_STAGE_FEATURES, screen_resolve.glsl explains): each
// technique lowers sg_stageFeature to the narrowest feature (m) its visibility may have nearby.
#ifdef SG_STAGE_FEATURES
float sg_stageBlock = 0.0;  // the sample's block at its receiver (m), set by the stage
float sg_stageFeature = 3.0e38;
#define SG_STAGE_FEATURE(radius) sg_stageFeature = min(sg_stageFeature, (radius))
#else
#define SG_STAGE_FEATURE(radius)
#endif

#endif
