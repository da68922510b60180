// Main pass: the sum over this pass's lights of Lambert + GGX shading times the light's visibility.
//
// The renderer compiles one variant per light configuration of a pass (render/lit_programs.h):
// SG_PASS_LIGHTS lights, its slots grouped by equal configuration (SG_PASS_GROUPS; per group g
// the SG_GROUP<g>_* constants of gl/technique_glsl.h). A light's type, technique and kernel are
// known when compiling: no branch for a type or technique the light does not have, and a light
// unlike the others of its pass is straight-line code with no per-pixel index into the sampler
// array or the light records (the fragment-cost table in BENCHMARKS.md measures what each of
// those costs).
// Depth comes from the depth pre-pass (depth test EQUAL), so each visible pixel is shaded once;
// further passes (more lights) add with blending.
//
// With SG_DEFERRED the pass is the screen-space visibility stage's last (RenderOptions::
// screenVisibility): one full-screen triangle that reads each pixel's surface from the surface
// pass's targets (SG_READS_GBUFFER) and each light's visibility from the stage. A group of four
// slots (k = 0 for slots 0-3, 1 for 4-7) whose stage ran at a reduced resolution d, without
// contact shadows, is resolved here (SG_LAYER<k>_RESOLVE d, sg_resolveStage); the others'
// visibility is read from the stage's full-resolution target (SG_LAYER<k>_RESOLVE 0), written
// by its passes. A light the resolve marks (SG_LAYER<k>_PER_LIGHT 0: every light of its group
// where one is marked, as the stage's own refine) adds nothing here: the pass writes the marks
// (a bit per slot, SG_OUT_MARKS), and with SG_LIT_CORRECTION the same program is the pass that
// adds those lights, their technique run at full resolution, at the marked pixels alone
// (depth-tested against the marks, render/screen_visibility.h): a CPU rasteriser then skips
// whole blocks without one, where a loop here would run the technique under the mask of every
// block an edge crosses (twice to four times the refine pass's time, measured on the bunny spot).
#include "shadow_visibility.glsl"
#include "shadow_surface.glsl"
#include "lighting.glsl"
#include "screen_gbuffer.glsl"
#include "screen_resolve.glsl"
#ifndef SG_DEFERRED
#include "material.glsl"
#endif

#if SG_MAX_LIGHTS_PER_PASS != 8
#error "main() below shades groups 0-7: one SG_SHADE_ONE/SG_SHADE_MANY choice per possible group"
#endif

#ifdef SG_DEFERRED
layout(binding = SG_UNIT_GBUFFER_MATERIAL) uniform usampler2D sg_gbufferMaterial;
// Slots 0-3 of the pass in layer 0, 4-7 in layer 1 (screen_visibility.frag.glsl).
layout(binding = SG_UNIT_SCREEN_VISIBILITY) uniform sampler2DArray sg_screenVisibility;
#ifndef SG_LAYER0_RESOLVE
#define SG_LAYER0_RESOLVE 0
#endif
#ifndef SG_LAYER1_RESOLVE
#define SG_LAYER1_RESOLVE 0
#endif
#ifndef SG_LAYER0_PER_LIGHT
#define SG_LAYER0_PER_LIGHT 0
#endif
#ifndef SG_LAYER1_PER_LIGHT
#define SG_LAYER1_PER_LIGHT 0
#endif
#define SG_LIT_RESOLVES (SG_LAYER0_RESOLVE > 1 || SG_LAYER1_RESOLVE > 1)
#ifdef SG_LIT_CORRECTION
// The marks the lit pass wrote (SG_OUT_MARKS): bit s, slot s's visibility to add.
layout(binding = SG_UNIT_LIT_STAGE) uniform usampler2D sg_litMarks;
#else
// The groups resolved here: the stage at their divisor (one for both), its layers as the groups'.
layout(binding = SG_UNIT_LIT_STAGE) uniform sampler2DArray sg_litStage;
layout(binding = SG_UNIT_SCREEN_DEPTH) uniform usampler2DArray sg_litStageDepth;
uniform float uPixelAngle;  // 2 tan(fov / 2) / height: a pixel's footprint per metre of depth
#if SG_LIT_RESOLVES
layout(location = SG_OUT_MARKS) out uint outMarks;
#endif
#endif
#ifdef SG_GBUFFER_MATERIAL
// A frame with normal maps or emission: the emitted radiance and the lighting normal.
layout(binding = SG_UNIT_GBUFFER_EXTRA) uniform usampler2D sg_gbufferExtra;
#endif
#else
in vec4 vCsPositionU;  // lit.vert.glsl: position and texture u
in vec4 vWsNormalV;    // normal and texture v
#ifdef SG_MATERIAL_MAPS
in vec4 vWsTangent;
in vec2 vTexcoord1;
#endif
#endif

// The material (material.glsl) comes from its uniforms and textures, or from the surface
// targets; a cut-out's holes never reach this pass (the depth pre-pass leaves them out,
// depth_prepass.frag.glsl).
uniform int uReceiveShadows;
// With SG_LIT_AMBIENT (the first pass) the hemisphere ambient (lighting.glsl) and the emission
// are added; the other passes add their lights alone.
uniform vec3 uAmbientSky, uAmbientGround;
uniform vec3 uCameraForward;  // unit, world space

layout(location = SG_OUT_COLOR) out vec4 outColor;
#ifdef SG_WRITE_AOVS
layout(location = SG_OUT_POSITION) out vec4 outPosition;  // camera-relative xyz, coverage
layout(location = SG_OUT_DEPTH) out float outDepth;       // distance from the camera (m)
layout(location = SG_OUT_VISIBILITY0) out vec4 outVisibility0;
layout(location = SG_OUT_VISIBILITY1) out vec4 outVisibility1;
#endif

// Whether pass slot `technique`'s shadow lookup is needed where its shading is `shading`. Without
// AOVs or debug views it is skipped where the light's shading is zero (facing away, outside the
// cone, beyond the range); the visibility AOV keeps its meaning everywhere on geometry.
bool shadowWanted(const int technique, vec3 shading) {
#if defined(SG_WRITE_AOVS) || defined(SG_DEBUG_VIEWS)
    bool wanted = true;
#else
    bool wanted = max(shading.r, max(shading.g, shading.b)) > 0.0;
#endif
    return technique != SG_TECH_NONE && uReceiveShadows != 0 && wanted;
}

#ifdef SG_DEBUG_VIEWS
// SG_DEBUG_VIEW (SG_DEBUG_*) of pass slot SG_DEBUG_SLOT, read right after that slot ran.
vec3 debugColor = vec3(0.0);
#define SG_DEBUG_CAPTURE(i, v)                                                                    \
    if (i == SG_DEBUG_SLOT) {                                                                     \
        if (SG_DEBUG_VIEW == SG_DEBUG_CASCADE)                                                    \
            debugColor = vec3(sg_debugCascade == 0 || sg_debugCascade == 3, sg_debugCascade == 1 || sg_debugCascade == 3, sg_debugCascade == 2) * 0.8 + 0.2 * v; \
        if (SG_DEBUG_VIEW == SG_DEBUG_BLOCKER_DEPTH) debugColor = vec3(sg_debugBlockerDepth);       \
        if (SG_DEBUG_VIEW == SG_DEBUG_PENUMBRA) debugColor = vec3(sg_debugPenumbra);                \
        if (SG_DEBUG_VIEW == SG_DEBUG_VISIBILITY) debugColor = vec3(v);                           \
        if (SG_DEBUG_VIEW == SG_DEBUG_MARCH_STEPS) debugColor = vec3(sg_debugMarchSteps / float(max(L.sdfSteps, 1))); \
        if (SG_DEBUG_VIEW == SG_DEBUG_CLOSEST) debugColor = vec3(0.5 + 0.5 * sg_debugClosest);     \
    }
#else
#define SG_DEBUG_CAPTURE(i, v)
#endif

// The program's slots are the pass's from this one on: 0, but for a correction of the pass's
// second group of four (slots 4-7), which compiles that group alone.
#ifndef SG_SLOT_BASE
#define SG_SLOT_BASE 0
#endif

// Light `slot` of the pass, of group g: its type, technique and kernel are compile-time constants
// (SG_GROUP<g>_*), SG_GROUP<g>_VISIBILITY its technique's function (shadow_techniques.glsl).
#define SG_SHADE_LIGHT(g, slot)                                                                   \
    {                                                                                             \
        sg_GpuLight L = sg_slotLight(slot, SG_GROUP##g##_TYPE, SG_GROUP##g##_TECH, SG_GROUP##g##_KERNEL); \
        vec3 shading = shadeSurface(L, s);                                                     \
        float v = 1.0;                                                                            \
        SG_LIGHT_VISIBILITY(g, slot)                                                              \
        color += v * shading;                                                                     \
        SG_STORE_VISIBILITY(slot, v)                                                              \
        SG_COUNT_EDGES_OF(g, slot, v, shading)                                                    \
        SG_DEBUG_CAPTURE(slot, v)                                                                 \
    }

// Group g of the pass's slots, a light of its own: straight-line code, constant indices (sampler,
// records). Folded away for g >= SG_PASS_GROUPS.
#define SG_SHADE_ONE(g)                                                                           \
    if (g < SG_PASS_GROUPS) SG_SHADE_LIGHT(g, SG_SLOT_BASE + SG_GROUP##g##_FIRST)

// Group g of several lights alike: its code compiled once, in a loop over its slots
// (sg_runtimeZero keeps the compiler from unrolling it), whose slot indexes the samplers
// dynamically.
#define SG_SHADE_MANY(g)                                                                          \
    if (g < SG_PASS_GROUPS) {                                                                     \
        const int slots[SG_GROUP##g##_COUNT] = SG_GROUP##g##_SLOTS;                               \
        for (int k = 0; k < SG_GROUP##g##_COUNT + sg_runtimeZero(); ++k) SG_SHADE_LIGHT(g, SG_SLOT_BASE + slots[k]) \
    }

#ifdef SG_DEFERRED
// Whether pass slot `slot` is marked for its visibility at full resolution (litMarks).
#define SG_LIT_MARKED(slot) (((litMarks >> uint(slot)) & 1u) != 0u)
#ifdef SG_LIT_CORRECTION
// The correction adds a marked light's shading times its visibility, the others nothing. It
// compiles one group of four of the pass (its slots from SG_SLOT_BASE on; straight-line, as the
// stage's programs: a program of the pass's eight slots ran the technique of each marked pixel
// at a third more time on `courtyard`, its slots grouped and its loops isolated) and runs where
// that group is marked. With SG_LIT_CORRECTION_ALL (whole-group marks) every light of it is
// marked where it runs: straight-line code; else a loop of one trip or none per light.
#ifdef SG_LIT_CORRECTION_ALL
#define SG_LIGHT_VISIBILITY(g, slot) \
    v = 0.0;                         \
    if (SG_GROUP##g##_TECH != SG_TECH_NONE) v = SG_LIT_TECHNIQUE(g, slot);
#else
#define SG_LIGHT_VISIBILITY(g, slot)                                                       \
    v = 0.0;                                                                               \
    if (SG_GROUP##g##_TECH != SG_TECH_NONE)                                               \
        for (int once = 0; once < int(SG_LIT_MARKED(slot)); ++once) v = SG_LIT_TECHNIQUE(g, slot);
#endif
#define SG_LIT_TECHNIQUE(g, slot) \
    SG_GROUP##g##_VISIBILITY(slot, L, s.csPosition, shadowNormal, s.geoNormal, 0.0, viewDistance)
#else
// The stage's visibility (1 where the surface receives no shadow), 0 for a marked light, which
// the correction adds.
#define SG_LIGHT_VISIBILITY(g, slot)                                                          \
    if (SG_GROUP##g##_TECH != SG_TECH_NONE)                                                  \
        v = SG_LIT_MARKED(slot) ? 0.0 : receiveShadows ? screenVisibility[(slot) / 4][(slot) % 4] : 1.0;
#endif
#else
#define SG_LIGHT_VISIBILITY(g, slot)                  \
    if (shadowWanted(SG_GROUP##g##_TECH, shading)) \
        v = SG_GROUP##g##_VISIBILITY(slot, L, s.csPosition, shadowNormal, s.geoNormal, s.curvature, viewDistance);
#endif

#ifdef SG_WRITE_AOVS
#define SG_STORE_VISIBILITY(slot, v) visibility[slot] = v;
#else
#define SG_STORE_VISIBILITY(slot, v)
#endif

#if defined(SG_COUNT_EDGES) && defined(SG_DEFERRED)
#error "the edge counts are the forward passes' (the stage's lit pass runs no lookup)"
#endif
#ifdef SG_COUNT_EDGES
// Technique auto's edge counts (docs/auto_technique.md, "Edge counts"): on the frames the
// planner asks (bit `slot` of uCountSlots), at one pixel in each 2x2 block where the light's
// lookup ran, three counters of the slot: the pixels counted, those whose hard lookup (one
// bilinear comparison: within a texel of a shadow edge) is neither 0 nor 1, and those whose
// technique's visibility is neither (its penumbra and that band). The early tests keep the
// counts to the surfaces that pass the depth test when drawn, as without the buffer writes.
layout(early_fragment_tests) in;
layout(std430, binding = SG_BINDING_EDGE_COUNTS) buffer sg_EdgeCountBlock {
    uint sg_edgeCounts[];
};
uniform int uCountSlots;  // bit s: count pass slot s this frame
uniform int uCountBase;   // this pass's first counter
// Neither lit nor umbra, as the error metrics class a pixel (kVisibilityClassEpsilon).
uint sg_mixed(float v) { return uint(v > SG_VISIBILITY_CLASS_EPSILON && v < 1.0 - SG_VISIBILITY_CLASS_EPSILON); }
#define SG_COUNT_EDGES_OF(g, slot, v, shading)                                                    \
    for (int c = 0; c < int(countsHere && ((uCountSlots >> (slot)) & 1) != 0 && shadowWanted(SG_GROUP##g##_TECH, shading)); ++c) { \
        float hardV = SG_GROUP##g##_TECH == SG_TECH_HARD                                          \
                          ? v                                                                     \
                          : sg_hardLightVisibility(slot, L, s.csPosition, shadowNormal, s.geoNormal, s.curvature, viewDistance); \
        uint at = uint(uCountBase + 3 * (slot));                                                  \
        atomicAdd(sg_edgeCounts[at], 1u);                                                         \
        atomicAdd(sg_edgeCounts[at + 1u], sg_mixed(hardV));                                       \
        atomicAdd(sg_edgeCounts[at + 2u], sg_mixed(v));                                           \
    }
#else
#define SG_COUNT_EDGES_OF(g, slot, v, shading)
#endif

#if defined(SG_DEFERRED) && !defined(SG_LIT_CORRECTION)
// The visibility of group `layer` (slots 4 layer to 4 layer + 3, `lights` of them) at `pixel`,
// whose surface texel is `surface`: resolved here from the stage at divisor `resolve` (> 1), its
// marked lights added to `marks` (sg_groupMarks, a bit per slot); else (0) read from the stage's
// full-resolution target. The arguments are constants: the compiler keeps one branch.
vec4 litGroupVisibility(ivec2 pixel, uvec4 surface, int layer, int resolve, int lights, bool perLight,
                        inout uint marks) {
    if (resolve <= 1) return texelFetch(sg_screenVisibility, ivec3(pixel, layer), 0);
    uint refine;
    vec4 v = sg_resolveStage(pixel, surface, resolve, sg_litStage, sg_litStageDepth, layer, lights, uPixelAngle, refine);
    marks |= sg_groupMarks(refine, lights, perLight) << uint(4 * layer);
    return v;
}
#endif

void main() {
#ifdef SG_DEFERRED
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uvec4 gSurface = texelFetch(sg_gbufferSurface, pixel, 0);
    uvec4 gMaterial = texelFetch(sg_gbufferMaterial, pixel, 0);
    // Only pixels the surface pass drew run (depth-tested at the far plane): the background
    // keeps the targets' clear values, as forward leaves it.
    bool receiveShadows = sg_gbufferReceives(gSurface);
    // Per group of four slots: its visibility; the pass's marked slots (a bit each).
    vec4 screenVisibility[2] = vec4[](vec4(1.0), vec4(1.0));
    uint litMarks = 0u;
#ifdef SG_LIT_CORRECTION
    litMarks = texelFetch(sg_litMarks, pixel, 0).r;
#else
    screenVisibility[0] = litGroupVisibility(pixel, gSurface, 0, SG_LAYER0_RESOLVE, min(SG_PASS_LIGHTS, 4),
                                             SG_LAYER0_PER_LIGHT != 0, litMarks);
    if (SG_PASS_LIGHTS > 4)
        screenVisibility[1] = litGroupVisibility(pixel, gSurface, 1, SG_LAYER1_RESOLVE, max(SG_PASS_LIGHTS - 4, 1),
                                                 SG_LAYER1_PER_LIGHT != 0, litMarks);
#if SG_LIT_RESOLVES
    outMarks = litMarks;
#endif
#endif
    vec3 vCsPosition = sg_gbufferPosition(pixel, gSurface);
    vec2 albedoRg = unpackHalf2x16(gMaterial.x), albedoB = unpackHalf2x16(gMaterial.y);
    vec2 specularRg = unpackHalf2x16(gMaterial.z), specularB = unpackHalf2x16(gMaterial.w);
    Surface s;
    s.csPosition = vCsPosition;
    s.toViewer = normalize(-vCsPosition);
    s.geoNormal = sg_gbufferGeoNormal(gSurface);
    s.curvature = 0.0;  // shading does not read it
    s.normal = sg_gbufferNormal(gSurface);
    // The lookups take the interpolated normal, as the stage's passes do (never the normal map's).
    vec3 shadowNormal = s.normal;
    s.albedo = vec3(albedoRg, albedoB.x);
    s.specular = vec3(specularRg, specularB.x);
    s.shininess = albedoB.y;
    float occlusion = specularB.y;
    vec3 emission = vec3(0.0);
#ifdef SG_GBUFFER_MATERIAL
    uvec4 gExtra = texelFetch(sg_gbufferExtra, pixel, 0);
    emission = vec3(unpackHalf2x16(gExtra.x), unpackHalf2x16(gExtra.y).x);
    s.normal = sg_octDecode(unpackSnorm2x16(gExtra.z));
#endif
#else
    vec3 vCsPosition = vCsPositionU.xyz;
    vec3 vWsNormal = vWsNormalV.xyz;
    vec2 vTexcoord = vec2(vCsPositionU.w, vWsNormalV.w);
    Surface s;
    s.csPosition = vCsPosition;
    s.toViewer = normalize(-vCsPosition);  // never zero: the near plane clips the camera's point
    sg_Surface shadowSide = sg_surface(vCsPosition, vWsNormal);
    s.geoNormal = shadowSide.geoNormal;
    s.curvature = shadowSide.curvature;
    // The lookups take the interpolated normal (two-sided: the side facing the camera), never the
    // normal map's, as the stage's surface targets keep it.
    vec3 shadowNormal = shadowSide.normal;
    MaterialInput mi;
    mi.uv0 = vTexcoord;
    mi.normal = shadowSide.normal;
    mi.interpolated = vWsNormal;
#ifdef SG_MATERIAL_MAPS
    mi.uv1 = vTexcoord1;
    mi.tangent = vWsTangent;
#endif
    MaterialSample m = sg_material(mi);
    s.normal = m.normal;
    s.albedo = m.albedo;
    s.specular = m.specular;
    s.shininess = m.shininess;
    float occlusion = m.occlusion;
    vec3 emission = m.emission;
#endif

    float viewDistance = dot(vCsPosition, uCameraForward);
#ifdef SG_COUNT_EDGES
    bool countsHere = all(equal(ivec2(gl_FragCoord.xy) & 1, ivec2(0)));
#endif
    vec3 color = vec3(0.0);
#ifdef SG_LIT_AMBIENT
    color = ambientShading(s, uAmbientSky, uAmbientGround, occlusion) + emission;
#endif
#ifdef SG_WRITE_AOVS
#ifdef SG_LIT_CORRECTION
    // What the correction adds to each slot's visibility: 0 but for the lights it recomputes.
    float visibility[SG_MAX_LIGHTS_PER_PASS] = float[](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
#else
    float visibility[SG_MAX_LIGHTS_PER_PASS] = float[](1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0);
#endif
#endif
#if SG_GROUP0_COUNT == 1
    SG_SHADE_ONE(0)
#else
    SG_SHADE_MANY(0)
#endif
#if SG_GROUP1_COUNT == 1
    SG_SHADE_ONE(1)
#else
    SG_SHADE_MANY(1)
#endif
#if SG_GROUP2_COUNT == 1
    SG_SHADE_ONE(2)
#else
    SG_SHADE_MANY(2)
#endif
#if SG_GROUP3_COUNT == 1
    SG_SHADE_ONE(3)
#else
    SG_SHADE_MANY(3)
#endif
#if SG_GROUP4_COUNT == 1
    SG_SHADE_ONE(4)
#else
    SG_SHADE_MANY(4)
#endif
#if SG_GROUP5_COUNT == 1
    SG_SHADE_ONE(5)
#else
    SG_SHADE_MANY(5)
#endif
#if SG_GROUP6_COUNT == 1
    SG_SHADE_ONE(6)
#else
    SG_SHADE_MANY(6)
#endif
#if SG_GROUP7_COUNT == 1
    SG_SHADE_ONE(7)
#else
    SG_SHADE_MANY(7)
#endif
#ifdef SG_DEBUG_VIEWS
    outColor = vec4(debugColor, 1.0);
#else
    outColor = vec4(color, 1.0);
#endif
#ifdef SG_WRITE_AOVS
    outPosition = vec4(vCsPosition, 1.0);
    outDepth = length(vCsPosition);
    outVisibility0 = vec4(visibility[0], visibility[1], visibility[2], visibility[3]);
    outVisibility1 = vec4(visibility[4], visibility[5], visibility[6], visibility[7]);
#endif
}
