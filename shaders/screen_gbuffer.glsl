// The surface targets of the screen-space visibility stage, as its passes read them: units,
// the coverage flags and the octahedral normal encoding (render/screen_visibility.h).
#ifndef SG_SCREEN_GBUFFER
#define SG_SCREEN_GBUFFER
#include "shared_constants.h"

// The position target's w: 0 where nothing was drawn, 1 + curvature (1/m) on a surface that
// receives shadows, -(1 + curvature) on one that does not.
float sg_gbufferFlags(bool receives, float curvature) { return receives ? 1.0 + curvature : -1.0 - curvature; }
bool sg_gbufferCovered(float w) { return w != 0.0; }
bool sg_gbufferReceives(float w) { return w > 0.0; }
float sg_gbufferCurvature(float w) { return abs(w) - 1.0; }

// A unit vector as two numbers in [-1, 1]: the octahedron's faces unfolded onto a square.
vec2 sg_octEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 p = n.xy;
    if (n.z < 0.0) p = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return p;
}

vec3 sg_octDecode(vec2 p) {
    vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    float t = max(-n.z, 0.0);
    n.x += n.x >= 0.0 ? -t : t;
    n.y += n.y >= 0.0 ? -t : t;
    return normalize(n);
}

#ifdef SG_READS_GBUFFER
layout(binding = SG_UNIT_GBUFFER_POSITION) uniform sampler2D sg_gbufferPosition;
layout(binding = SG_UNIT_GBUFFER_NORMALS) uniform sampler2D sg_gbufferNormals;
#endif
#endif
