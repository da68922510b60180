// Shading of one light, without visibility: the second factor of the split
// L_o ~ [integral of V / integral of 1] * [integral of L_i f_r cos] (the seeds' approximated
// rendering equation). Lambert diffuse plus a GGX specular lobe (Trowbridge-Reitz distribution,
// the height-correlated Smith visibility, Schlick's Fresnel from the specular colour), glTF's
// metallic-roughness model. The material carries its roughness as the Blinn-Phong exponent n of
// the matching lobe (gltf_mesh.cpp: n = 2 / alpha^2 - 2), so alpha^2 = 2 / (n + 2) here.
// Intensities follow KHR_lights_punctual: candela for point and spot (inverse-square falloff),
// lux for directional. The diffuse term is weighted by 1 - F, as the glTF 2.0 specification's
// appendix B mixes the dielectric's diffuse base with its specular layer.
#ifndef SG_LIGHTING
#define SG_LIGHTING

struct Surface {
    vec3 csPosition;
    vec3 normal;    // unit, facing the viewer
    vec3 geoNormal; // unit normal of the triangle itself (either side)
    float curvature; // 1/m: how fast the shading normal turns across the surface
    vec3 toViewer;  // unit
    vec3 albedo;
    vec3 specular;
    float shininess;  // the matching Blinn-Phong exponent of the GGX roughness
};

// Smooth window that brings a light's influence to 0 at `range` (0 = infinite).
float rangeWindow(float distance, float range) {
    if (range <= 0.0) return 1.0;
    float r2 = distance * distance / (range * range);
    float x = clamp(1.0 - r2 * r2, 0.0, 1.0);
    return x * x;
}

// Radiance reflected towards the viewer from light L (visibility not included).
vec3 shadeSurface(sg_GpuLight L, Surface s) {
    vec3 toLight;
    float attenuation = 1.0;
    if (L.type == SG_LIGHT_DIRECTIONAL) {
        toLight = -L.wsDirection;
    } else {
        vec3 d = L.csPosition - s.csPosition;
        float dist2 = max(dot(d, d), 1e-8);
        float dist = sqrt(dist2);
        toLight = d / dist;
        attenuation = rangeWindow(dist, L.range) / dist2;
        if (L.type == SG_LIGHT_SPOT) {
            float cd = dot(-toLight, L.wsDirection);
            attenuation *= smoothstep(L.cosOuter, max(L.cosInner, L.cosOuter + 1e-4), cd);
        }
    }
    float nDotL = dot(s.normal, toLight);
    if (nDotL <= 0.0 || attenuation <= 0.0) return vec3(0.0);
    vec3 h = normalize(toLight + s.toViewer);
    float nDotV = max(dot(s.normal, s.toViewer), 1e-4);
    float nDotH = max(dot(s.normal, h), 0.0);
    float a2 = 2.0 / (s.shininess + 2.0);
    float q = nDotH * nDotH * (a2 - 1.0) + 1.0;
    float distribution = a2 / (3.14159265 * q * q);
    float visibility = 0.5 / (nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2) + nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2));
    float m = 1.0 - max(dot(s.toViewer, h), 0.0);
    float m2 = m * m;
    float f = m2 * m2 * m;
    vec3 fresnel = s.specular + (1.0 - s.specular) * f;
    vec3 brdf = s.albedo / 3.14159265 * (1.0 - fresnel) + distribution * visibility * fresnel;
    return L.radiance * attenuation * nDotL * brdf;
}

// The split-sum's scale and bias of the specular colour for GGX under uniform light, the
// hemisphere's directional albedo (Karis, "Real Shading in Unreal Engine 4", 2013), in the
// analytic fit of Karis, "Physically Based Shading on Mobile" (2014): no lookup texture.
vec2 environmentBrdf(float roughness, float nDotV) {
    vec4 r = roughness * vec4(-1.0, -0.0275, -0.572, 0.022) + vec4(1.0, 0.0425, 1.04, -0.04);
    float a004 = min(r.x * r.x, exp2(-9.28 * nDotV)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}

// Radiance reflected towards the viewer from a hemisphere ambient: radiance `sky` from every
// direction above the horizon (+y), `ground` from every one below. Diffuse: the irradiance of
// the two halves, exact for Lambert; specular: the halves seen along the lobe's dominant
// direction (the mirror direction bent to the normal as the lobe widens), the fraction of sky
// blended over the lobe's width, times the split-sum's directional albedo, so that a metal in
// shadow keeps its colour. `occlusion` scales both (glTF's occlusion texture).
vec3 ambientShading(Surface s, vec3 sky, vec3 ground, float occlusion) {
    float nDotV = max(dot(s.normal, s.toViewer), 1e-4);
    // GGX alpha = sqrt(2 / (n + 2)) of the Blinn-Phong twin's exponent n.
    float alpha = 1.41421356 * inversesqrt(s.shininess + 2.0);
    vec3 irradiance = mix(ground, sky, 0.5 + 0.5 * s.normal.y);
    // Not normalised (its length lies in [0.7, 1]): a slightly softer horizon, one square root
    // less per pixel.
    vec3 dominant = mix(reflect(-s.toViewer, s.normal), s.normal, alpha);
    vec3 prefiltered = mix(ground, sky, clamp(0.5 + 0.5 * dominant.y / max(alpha, 0.02), 0.0, 1.0));
    vec2 ab = environmentBrdf(sqrt(alpha), nDotV);
    vec3 specular = s.specular * ab.x + ab.y;
    return occlusion * (s.albedo * (1.0 - specular) * irradiance + specular * prefiltered);
}
#endif
