// Definitions shared by the shadow pass and the shadow sampling code.
#ifndef SG_SHADOW_COMMON
#define SG_SHADOW_COMMON

// Linear depth of a light-view position (m): along the axis for orthographic layers, from the
// light for perspective ones. The one definition both writer and reader use.
float lightSpaceDepth(vec3 lsPosition, bool orthographic) {
    return orthographic ? -lsPosition.z : length(lsPosition);
}

#endif
