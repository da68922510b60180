// A mesh's material at a fragment (`Material`, engine/include/shadow/components.h): glTF 2.0's
// metallic-roughness model. One function for the forward lit pass and the screen-space stage's
// surface pass, so that both paths shade the same surfaces.
//
// Two variants. Without SG_MATERIAL_MAPS (every material without maps: the built-in scenes')
// the material is its uniforms and the base-colour texture, read by every pixel and selected
// where there is one: straight-line code, where a loop of 0 or 1 trips on the uniform, which a
// CPU rasteriser skips when no pixel enters it, cost the bunny spot's lit pass more than the
// fetch it saved (1920x1080 on llvmpipe: 3 ms of 34). A frame none of whose materials has a
// base-colour texture compiles no fetch (SG_BASE_COLOR_TEXTURE undefined). With it, glTF's
// parameters per pixel: metallic and roughness from the metallic-roughness map (B, G), the normal
// map in the tangent frame of MikkTSpace, occlusion (R) and emission, each map read through its
// own texture-coordinate set and KHR_texture_transform, each in a loop of its own.
#ifndef SG_MATERIAL_GLSL
#define SG_MATERIAL_GLSL
#include "shared_constants.h"
#include "shadow_common.glsl"
#include "alpha_test.glsl"

uniform vec3 uAlbedo;
uniform vec3 uSpecular;
uniform float uShininess;
uniform float uMetallic;
uniform int uTextured;  // 1 with a base-colour texture; an untextured material's read is not used
uniform vec3 uEmissive;  // emitted radiance

#ifdef SG_MATERIAL_MAPS
#define SG_MAP_METALLIC_ROUGHNESS 0
#define SG_MAP_NORMAL 1
#define SG_MAP_OCCLUSION 2
#define SG_MAP_EMISSIVE 3
uniform vec3 uBaseFactor;
uniform float uRoughness;
uniform float uNormalScale;
uniform float uOcclusionStrength;
// Per map (SG_MAP_*): 1 when read, its texture-coordinate set (0 or 1) and transform.
uniform int uMapUsed[4];
uniform int uMapSet[4];
uniform mat3x2 uMapTransform[4];
layout(binding = SG_UNIT_METALLIC_ROUGHNESS) uniform sampler2D uMetallicRoughnessMap;
layout(binding = SG_UNIT_NORMAL_MAP) uniform sampler2D uNormalMap;
layout(binding = SG_UNIT_OCCLUSION) uniform sampler2D uOcclusionMap;
layout(binding = SG_UNIT_EMISSIVE) uniform sampler2D uEmissiveMap;
#endif

// What the material reads of the fragment.
struct MaterialInput {
    vec2 uv0;           // the mesh's first texture-coordinate set (the base colour's)
    vec2 uv1;           // its second (maps only)
    vec4 tangent;       // world tangent and handedness, interpolated (maps only)
    vec3 normal;        // unit shading normal turned to the viewer (sg_surface)
    vec3 interpolated;  // the interpolated normal, not turned
};

// The material at the fragment: what lighting.glsl's Surface takes, and the ambient occlusion
// and emitted radiance.
struct MaterialSample {
    vec3 albedo;
    vec3 specular;
    float shininess;
    vec3 normal;  // the lighting normal: `normal`, or the normal map's, turned to the viewer alike
    float occlusion;
    vec3 emission;
};

// The Blinn-Phong exponent of perceptual roughness r (GGX alpha = r^2): n = 2 / alpha^2 - 2,
// as the glTF loader derives `Material::shininess` (scene/gltf_material.cpp).
float sg_shininessOfRoughness(float r) {
    float a2 = max(r * r * r * r, 1e-4);
    return clamp(2.0 / a2 - 2.0, 1.0, 4096.0);
}

#ifdef SG_MATERIAL_MAPS
vec2 sg_mapUv(int map, MaterialInput m) { return uMapTransform[map] * vec3(uMapSet[map] == 1 ? m.uv1 : m.uv0, 1.0); }

// The normal map's normal: tangent space (+x along the tangent, +y along w * cross(n, t)) to
// world, from the interpolated tangent as MikkTSpace's pixel shader rebuilds it; turned to the
// viewer exactly when the shading normal was.
vec3 sg_mappedNormal(MaterialInput m) {
    vec3 t = texture(uNormalMap, sg_mapUv(SG_MAP_NORMAL, m)).rgb * 2.0 - 1.0;
    t.xy *= uNormalScale;
    float side = dot(m.normal, m.interpolated) < 0.0 ? -1.0 : 1.0;
    vec3 n = m.normal * side;
    vec3 bitangent = m.tangent.w * cross(n, m.tangent.xyz);
    return side * sg_safeNormalize(t.x * m.tangent.xyz + t.y * bitangent + t.z * n, n);
}
#endif

// Takes derivatives (texture lookups): call it in uniform control flow.
MaterialSample sg_material(MaterialInput m) {
    MaterialSample s;
#ifdef SG_BASE_COLOR_TEXTURE
    vec3 base = uTextured != 0 ? texture(uBaseColor, m.uv0).rgb : vec3(1.0);
#else
    vec3 base = vec3(1.0);  // no material of the frame has a base-colour texture
#endif
    s.normal = m.normal;
    s.occlusion = 1.0;
    s.emission = uEmissive;
#ifdef SG_MATERIAL_MAPS
    vec4 mr = vec4(1.0);
    for (int i = 0; i < uMapUsed[SG_MAP_METALLIC_ROUGHNESS]; ++i)
        mr = texture(uMetallicRoughnessMap, sg_mapUv(SG_MAP_METALLIC_ROUGHNESS, m));
    float metallic = clamp(uMetallic * mr.b, 0.0, 1.0);
    vec3 color = uBaseFactor * base;
    s.albedo = color * (1.0 - metallic);
    s.specular = mix(vec3(0.04), color, metallic);
    s.shininess = sg_shininessOfRoughness(clamp(uRoughness * mr.g, 0.0, 1.0));
    for (int i = 0; i < uMapUsed[SG_MAP_NORMAL]; ++i) s.normal = sg_mappedNormal(m);
    for (int i = 0; i < uMapUsed[SG_MAP_OCCLUSION]; ++i)
        s.occlusion = 1.0 + uOcclusionStrength * (texture(uOcclusionMap, sg_mapUv(SG_MAP_OCCLUSION, m)).r - 1.0);
    for (int i = 0; i < uMapUsed[SG_MAP_EMISSIVE]; ++i)
        s.emission *= texture(uEmissiveMap, sg_mapUv(SG_MAP_EMISSIVE, m)).rgb;
#else
    s.albedo = uAlbedo * base;
    s.specular = uSpecular * mix(vec3(1.0), base, uMetallic);
    s.shininess = uShininess;
#endif
    return s;
}
#endif
