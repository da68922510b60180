// Surface pass of the screen-space visibility stage (render/screen_visibility.h): the scene's
// geometry drawn once, through the lit pass's vertex shader, into what the stage and the
// deferred lit pass read back per pixel: the camera-relative position, the shading normal, the
// triangle's own normal and the material. With SG_ALPHA_TESTED (cut-out materials) the holes
// are left out.
#include "shadow_surface.glsl"
#include "screen_gbuffer.glsl"
#include "alpha_test.glsl"

in vec4 vCsPositionU;  // lit.vert.glsl: position and texture u
in vec4 vWsNormalV;    // normal and texture v

uniform int uReceiveShadows;
uniform vec3 uAlbedo;
uniform vec3 uSpecular;
uniform float uShininess;
uniform int uTextured;  // 1 with a texture
uniform float uMetallic;

layout(location = 0) out vec4 outPosition;  // camera-relative xyz, sg_gbufferFlags
layout(location = 1) out vec4 outNormals;   // octahedral shading normal (xy), triangle normal (zw)
layout(location = 2) out vec4 outAlbedo;    // linear albedo, shininess
layout(location = 3) out vec4 outSpecular;  // specular colour

void main() {
    vec2 texcoord = vec2(vCsPositionU.w, vWsNormalV.w);
#ifdef SG_ALPHA_TESTED
    if (sg_isHole(texcoord)) discard;
#endif
    vec3 cs = vCsPositionU.xyz;
    sg_Surface s = sg_surface(cs, vWsNormalV.xyz);
    // A loop, not an if: a CPU rasteriser skips a loop no pixel enters (lit.frag.glsl).
    vec3 base = vec3(1.0);
    for (int i = 0; i < uTextured; ++i) base = texture(uBaseColor, texcoord).rgb;
    outPosition = vec4(cs, sg_gbufferFlags(uReceiveShadows != 0, s.curvature));
    outNormals = vec4(sg_octEncode(s.normal), sg_octEncode(s.geoNormal));
    outAlbedo = vec4(uAlbedo * base, clamp(uShininess, 1.0, 4096.0));
    outSpecular = vec4(uSpecular * mix(vec3(1.0), base, uMetallic), 1.0);
}
