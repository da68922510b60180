// Surface pass of the screen-space visibility stage (render/screen_visibility.h): the scene's
// geometry drawn once, through the lit pass's vertex shader, into what the stage and the
// deferred lit pass read back per pixel (packed as screen_gbuffer.glsl says): the depth along
// the view, the interpolated normal, the triangle's own normal and the material (material.glsl,
// as the forward lit pass reads it). With SG_ALPHA_TESTED (cut-out materials) the holes are left
// out. With SG_GBUFFER_MATERIAL (a frame with normal maps or emission) also the lighting normal
// and the emitted radiance.
#include "shadow_surface.glsl"
#include "screen_gbuffer.glsl"
#include "material.glsl"

in vec4 vCsPositionU;  // lit.vert.glsl: position and texture u
in vec4 vWsNormalV;    // normal and texture v
#ifdef SG_MATERIAL_MAPS
in vec4 vWsTangent;
in vec2 vTexcoord1;
#endif

uniform int uReceiveShadows;
uniform vec3 uCameraForward;  // unit, world space

layout(location = 0) out uvec4 outSurface;   // sg_packSurface
layout(location = 1) out uvec4 outMaterial;  // sg_packMaterial
#ifdef SG_GBUFFER_MATERIAL
layout(location = 2) out uvec4 outExtra;     // sg_packExtra: emission, lighting normal
#endif

void main() {
    vec2 texcoord = vec2(vCsPositionU.w, vWsNormalV.w);
#ifdef SG_ALPHA_TESTED
    if (sg_isHole(texcoord)) discard;
#endif
    vec3 cs = vCsPositionU.xyz;
    sg_Surface s = sg_surface(cs, vWsNormalV.xyz);
    MaterialInput mi;
    mi.uv0 = texcoord;
    mi.normal = s.normal;
    mi.interpolated = vWsNormalV.xyz;
#ifdef SG_MATERIAL_MAPS
    mi.uv1 = vTexcoord1;
    mi.tangent = vWsTangent;
#endif
    MaterialSample m = sg_material(mi);
    // At least a trace of depth: 0 is "nothing drawn" (the near plane keeps it far above that).
    outSurface = sg_packSurface(max(dot(cs, uCameraForward), 1e-30), uReceiveShadows != 0, s.geoNormal, s.normal);
    outMaterial = sg_packMaterial(m.albedo, clamp(m.shininess, 1.0, 4096.0), m.specular, m.occlusion);
#ifdef SG_GBUFFER_MATERIAL
    outExtra = sg_packExtra(m.emission, m.normal);
#endif
}
