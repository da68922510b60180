// Surface pass of the screen-space visibility stage (render/screen_visibility.h): the scene's
// geometry drawn once, through the lit pass's vertex shader, into what the stage and the
// deferred lit pass read back per pixel: the camera-relative position, the shading normal, the
// triangle's own normal and the material (material.glsl, as the forward lit pass reads it).
// With SG_ALPHA_TESTED (cut-out materials) the holes are left out. With SG_GBUFFER_MATERIAL
// (a frame with normal maps or emission) also the lighting normal and the emitted radiance.
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

layout(location = 0) out vec4 outPosition;  // camera-relative xyz, sg_gbufferFlags
// Octahedral: the interpolated normal the shadow lookups take (xy; the lighting normal too
// without SG_GBUFFER_MATERIAL), the triangle's normal (zw).
layout(location = 1) out vec4 outNormals;
layout(location = 2) out vec4 outAlbedo;    // linear albedo, shininess
layout(location = 3) out vec4 outSpecular;  // specular colour, ambient occlusion
#ifdef SG_GBUFFER_MATERIAL
layout(location = 4) out vec4 outShading;   // octahedral lighting normal (xy)
layout(location = 5) out vec4 outEmission;  // emitted radiance (rgb)
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
    outPosition = vec4(cs, sg_gbufferFlags(uReceiveShadows != 0, s.curvature));
    outNormals = vec4(sg_octEncode(s.normal), sg_octEncode(s.geoNormal));
    outAlbedo = vec4(m.albedo, clamp(m.shininess, 1.0, 4096.0));
    outSpecular = vec4(m.specular, m.occlusion);
#ifdef SG_GBUFFER_MATERIAL
    outShading = vec4(sg_octEncode(m.normal), 0.0, 0.0);
    outEmission = vec4(m.emission, 1.0);
#endif
}
