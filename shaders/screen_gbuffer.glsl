// The surface targets of the screen-space visibility stage, as its passes write and read them
// (render/screen_visibility.h): two RGBA32UI texels a pixel, and a third with normal maps or
// emission, packed so that a pass reads what it needs in as few fetches as it can (on a CPU
// rasteriser each fetch of a full-screen target costs about as much as the arithmetic of a light).
//   surface  (SG_UNIT_GBUFFER_SURFACE): x the depth along the view (float bits; negative on a
//            surface that does not receive shadows, 0 where nothing was drawn), y z the
//            triangle's normal, octahedral (float bits: the lookups compare depths on its
//            plane), w the interpolated normal the lookups take (octahedral, 2 x snorm16). The
//            camera-relative position is the pixel's ray times the depth (sg_gbufferPosition).
//   material (SG_UNIT_GBUFFER_MATERIAL): half floats albedo rgb, shininess, specular rgb, occlusion.
//   extra    (SG_UNIT_GBUFFER_EXTRA, SG_GBUFFER_MATERIAL): half floats emission rgb, and the
//            lighting normal (octahedral, 2 x snorm16).
#ifndef SG_SCREEN_GBUFFER
#define SG_SCREEN_GBUFFER
#include "shared_constants.h"

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

// The surface texel of a surface at depth `viewDepth` (> 0) along the view.
uvec4 sg_packSurface(float viewDepth, bool receives, vec3 geoNormal, vec3 normal) {
    vec2 geo = sg_octEncode(geoNormal);
    return uvec4(floatBitsToUint(receives ? viewDepth : -viewDepth), floatBitsToUint(geo.x), floatBitsToUint(geo.y),
                 packSnorm2x16(sg_octEncode(normal)));
}

uvec4 sg_packMaterial(vec3 albedo, float shininess, vec3 specular, float occlusion) {
    return uvec4(packHalf2x16(albedo.rg), packHalf2x16(vec2(albedo.b, shininess)), packHalf2x16(specular.rg),
                 packHalf2x16(vec2(specular.b, occlusion)));
}

uvec4 sg_packExtra(vec3 emission, vec3 lightingNormal) {
    return uvec4(packHalf2x16(emission.rg), packHalf2x16(vec2(emission.b, 0.0)), packSnorm2x16(sg_octEncode(lightingNormal)),
                 0u);
}

// The surface texel's signed depth: 0 where nothing was drawn, negative where it receives no shadow.
float sg_gbufferDepth(uvec4 surface) { return uintBitsToFloat(surface.x); }
bool sg_gbufferCovered(uvec4 surface) { return sg_gbufferDepth(surface) != 0.0; }
bool sg_gbufferReceives(uvec4 surface) { return sg_gbufferDepth(surface) > 0.0; }
// The triangle's normal as stored, octahedral (sg_octEncode), and decoded.
vec2 sg_gbufferGeoOct(uvec4 surface) { return vec2(uintBitsToFloat(surface.y), uintBitsToFloat(surface.z)); }
vec3 sg_gbufferGeoNormal(uvec4 surface) { return sg_octDecode(sg_gbufferGeoOct(surface)); }
vec3 sg_gbufferNormal(uvec4 surface) { return sg_octDecode(unpackSnorm2x16(surface.w)); }

#ifdef SG_READS_GBUFFER
layout(binding = SG_UNIT_GBUFFER_SURFACE) uniform usampler2D sg_gbufferSurface;
// The camera-relative ray through pixel centre p, scaled to unit depth along the view:
// uRay00 + (p.x + 0.5) uRayDx + (p.y + 0.5) uRayDy.
uniform vec3 uRay00, uRayDx, uRayDy;

// The camera-relative position of the surface drawn at pixel `p`, its surface texel `surface`.
vec3 sg_gbufferPosition(ivec2 p, uvec4 surface) {
    vec3 ray = uRay00 + (float(p.x) + 0.5) * uRayDx + (float(p.y) + 0.5) * uRayDy;
    return ray * abs(sg_gbufferDepth(surface));
}
#endif
#endif
