// What the shadow lookup needs of the shaded surface beyond its position, from screen-space
// derivatives: the triangle's own plane (each shadow-map texel is compared with it), the shading
// normal facing the viewer, and how fast that normal turns (kept in the shading contract's
// signatures for techniques to come; since PCF's reach bias replaced its bend term no technique
// reads it, and the compiler drops it from the forward programs).
#ifndef SG_SHADOW_SURFACE
#define SG_SHADOW_SURFACE
#include "shadow_common.glsl"

struct sg_Surface {
    vec3 normal;      // unit shading normal, turned to face the viewer (two-sided)
    vec3 geoNormal;   // unit normal of the triangle itself (either side)
    float curvature;  // 1/m: how fast the shading normal turns per metre of surface (0 when flat)
};

// The surface at camera-relative position `csPosition` (interpolated) with interpolated normal
// `normal`. Takes derivatives: call it in uniform control flow, once per fragment.
sg_Surface sg_surface(vec3 csPosition, vec3 normal) {
    sg_Surface s;
    vec3 toViewer = normalize(-csPosition);  // never zero: the near plane clips the camera's point
    vec3 dpx = dFdx(csPosition), dpy = dFdy(csPosition);
    // A zero normal (a file's, or opposite normals interpolated) takes the triangle's own.
    s.geoNormal = sg_safeNormalize(cross(dpx, dpy), toViewer);
    vec3 n = sg_safeNormalize(normal, s.geoNormal);
    vec3 dnx = dFdx(n), dny = dFdy(n);
    s.curvature = max(length(dnx) / max(length(dpx), 1e-20), length(dny) / max(length(dpy), 1e-20));
    s.normal = dot(n, toViewer) < 0.0 ? -n : n;
    return s;
}
#endif
