// Screen-space visibility stage (render/screen_visibility.h): the shadow visibility of up to
// four lights of a lit pass (slots SG_SLOT_BASE + 0..3, one per channel) at the surfaces the
// surface pass drew, read back per pixel instead of recomputed per fragment of the scene.
//
// Two programs per light configuration:
// - the stage (SG_VIS_DIVISOR d): one pixel of the target per d x d block of the screen, the
//   visibility at the block's centre pixel's surface; d = 1 is the visibility at full resolution.
// - the resolve (SG_VIS_RESOLVE, with SG_VIS_DIVISOR d > 1), for a group the deferred lit pass
//   does not resolve itself (contact shadows; render/screen_visibility.h): back to full
//   resolution (sg_resolveStage, screen_resolve.glsl). Each pixel blends the four nearest
//   samples of the stage with bilinear weights, keeping only samples that lie on its own surface (within 1.5 blocks' footprint of its triangle's plane), so a penumbra
//   is never blurred across a geometric edge. A pixel with no such sample (silhouettes, thin
//   parts), or with a light whose kept samples disagree (an edge sharper than the blocks) or
//   report a feature narrower than them, is marked in depth for the refine pass.
// - the refine: the stage at full resolution, depth-tested so that only marked pixels run. With
//   three or more shadowed lights in the group (SG_VIS_REFINE, and SG_VIS_REFINE_PER_LIGHT in the
//   resolve), the resolve also writes a prior (sg_refinePrior) and the refine recomputes only
//   the lights it marks, keeping the resolve's value for the others.
// Slots are specialised and grouped like the lit passes' (SG_VIS_LIGHTS, SG_PASS_GROUPS,
// SG_GROUP<g>_*).
#include "shadow_visibility.glsl"
#include "screen_gbuffer.glsl"
#include "screen_resolve.glsl"

uniform vec3 uCameraForward;  // unit, world space
uniform float uPixelAngle;    // 2 tan(fov / 2) / height: a pixel's footprint per metre of depth

#ifdef SG_VIS_CONTACT
// Per channel: the contact march's length, metres when > 0, automatic when < 0, none when 0 (a
// light without contact shadows).
uniform vec4 uContactLength;
uniform mat4 uClipFromCs;  // camera-relative world -> clip
#ifndef SG_CONTACT_THICKNESS
#define SG_CONTACT_THICKNESS 0.25
#endif
#endif

#ifdef SG_VIS_RESOLVE
// The stage's visibility (a layer per group) and its samples' depths along the view, with
// clamp-to-edge addressing for gathers.
layout(binding = SG_UNIT_SCREEN_VISIBILITY) uniform sampler2DArray uStageVisibility;
// Each sample's depth along the view and code (sg_packStageSample), a layer per group.
layout(binding = SG_UNIT_SCREEN_DEPTH) uniform usampler2DArray uStageDepth;
uniform int uStageLayer;
layout(location = 0) out vec4 outVisibility;
#ifdef SG_VIS_REFINE_PER_LIGHT
// The refine's input (sg_refinePrior): what the resolve kept, -1 for the lights to recompute.
layout(location = 1) out vec4 outPrior;
#endif
#else
layout(location = 0) out vec4 outVisibility;
// The sample's depth along the view and its code (sg_packStageSample).
layout(location = 1) out uint outSample;
#endif
#ifdef SG_VIS_REFINE
// The resolve's output for the refine (sg_refinePrior), at full resolution.
layout(binding = SG_UNIT_SCREEN_VISIBILITY) uniform sampler2D uRefinePrior;
vec4 sg_visPrior = vec4(1.0);  // this pixel's
// The refine computes a light only where the resolve left it: in a loop of one trip or none,
// which a CPU rasteriser skips for a block of pixels where no pixel runs it (an `if` would run
// it under a mask).
#define SG_VIS_ONLY_WHERE_LEFT(slot) for (int once = 0; once < int(sg_refinesLight(sg_visPrior, slot)); ++once)
#else
#define SG_VIS_ONLY_WHERE_LEFT(slot)
#endif
#ifdef SG_STAGE_FEATURES
uint sg_visSharpLights = 0u;  // the sample's lights with a feature narrower than its block
#define SG_VIS_REPORT(slot) sg_visSharpLights |= sg_stageLightSharp(slot);
#else
#define SG_VIS_REPORT(slot)
#endif

// Light `slot` of the group, of group g (as lit.frag.glsl's SG_SHADE_LIGHT), at pass slot
// SG_SLOT_BASE + slot; the stage's samples note whether it reported a feature narrower than
// their block.
#define SG_VIS_LIGHT(g, slot)                                                                          \
    SG_VIS_ONLY_WHERE_LEFT(slot) {                                                                     \
        sg_GpuLight L = sg_slotLight(SG_SLOT_BASE + slot, SG_GROUP##g##_TYPE, SG_GROUP##g##_TECH,       \
                                     SG_GROUP##g##_KERNEL);                                            \
        if (SG_GROUP##g##_TECH != SG_TECH_NONE)                                                        \
            mask[slot] = SG_GROUP##g##_VISIBILITY(SG_SLOT_BASE + slot, L, cs, normal, geoNormal,       \
                                                  curvature, viewDistance);                            \
        SG_VIS_REPORT(slot)                                                                            \
    }
#define SG_VIS_ONE(g) \
    if (g < SG_PASS_GROUPS) SG_VIS_LIGHT(g, SG_GROUP##g##_FIRST)
#define SG_VIS_MANY(g)                                                                                 \
    if (g < SG_PASS_GROUPS) {                                                                          \
        const int slots[SG_GROUP##g##_COUNT] = SG_GROUP##g##_SLOTS;                                    \
        for (int k = 0; k < SG_GROUP##g##_COUNT + sg_runtimeZero(); ++k) SG_VIS_LIGHT(g, slots[k])     \
    }

#ifdef SG_VIS_CONTACT
// Screen-space contact shadow: 0 when a surface on screen stands between the receiver at `cs`
// (triangle normal `geoNormal`, pixel `p`) and its light within `length` metres toward it
// (`toLight`), else 1. SG_CONTACT_STEPS points along the segment (jittered per pixel), each
// projected to the screen: it is occluded when it lies behind the tangent plane of the surface
// drawn there, and past that surface along the view by less than SG_CONTACT_THICKNESS x `length`
// (the depth a surface is assumed to have: a surface far in front hides the point from the
// camera, not from the light). The march starts a pixel's footprint off the receiver's plane, and a point
// above its own plane is never behind it, so flat and gently curved ground casts nothing on
// itself.
float sg_contactVisibility(vec3 cs, vec3 geoNormal, vec3 toLight, float length, ivec2 p) {
    float footprint = max(dot(cs, uCameraForward), 0.0) * uPixelAngle;
    vec3 n = dot(geoNormal, toLight) < 0.0 ? -geoNormal : geoNormal;
    vec3 start = cs + n * footprint;
    vec2 size = vec2(textureSize(sg_gbufferSurface, 0));
    // Interleaved gradient noise: a different start on each pixel of a 4x4 block.
    float jitter = fract(52.9829189 * fract(dot(vec2(p), vec2(0.06711056, 0.00583715))));
    float v = 1.0;
    float thickness = SG_CONTACT_THICKNESS * length;
    for (int k = 0; k < SG_CONTACT_STEPS; ++k) {
        vec3 q = start + toLight * (length * (float(k) + jitter) / float(SG_CONTACT_STEPS));
        vec4 clip = uClipFromCs * vec4(q, 1.0);
        vec2 ndc = clip.xy / max(clip.w, 1e-20);
        ivec2 pixel = ivec2((ndc * 0.5 + 0.5) * size);
        bool onScreen = clip.w > 0.0 && all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, ivec2(size)));
        pixel = clamp(pixel, ivec2(0), ivec2(size) - 1);
        uvec4 surface = texelFetch(sg_gbufferSurface, pixel, 0);
        vec3 there = sg_gbufferPosition(pixel, surface);
        vec3 thereNormal = sg_gbufferGeoNormal(surface);
        // Behind the plane of the surface there, as seen from the camera: its normal turned to face it.
        vec3 facing = dot(thereNormal, there) > 0.0 ? -thereNormal : thereNormal;
        float behind = dot(there - q, facing);
        float deeper = dot(q - there, uCameraForward);  // along the view: how far past it q lies
        // The receiver's own pixel and its neighbours are its own surface at the screen's
        // resolution: a march that stays on them resolves nothing the screen can show.
        bool away = max(abs(pixel.x - p.x), abs(pixel.y - p.y)) > 1;
        if (onScreen && away && sg_gbufferCovered(surface) && behind > 0.0 && deeper < thickness) v = 0.0;
    }
    return v;
}
#endif

// The group's visibility at the surface drawn at full-resolution pixel `p`, whose surface
// texel is `surface`.
vec4 visibilityAt(ivec2 p, uvec4 surface) {
    vec3 cs = sg_gbufferPosition(p, surface);
    float curvature = 0.0;  // the lookups do not read it (sg_makeReceiver)
    vec3 normal = sg_gbufferNormal(surface);
    vec3 geoNormal = sg_gbufferGeoNormal(surface);
    float viewDistance = dot(cs, uCameraForward);
#ifdef SG_VIS_REFINE
    // The lights the resolve kept keep its visibility; the others are computed below.
    vec4 mask = mix(sg_visPrior, vec4(1.0), lessThan(sg_visPrior, vec4(0.0)));
#else
    vec4 mask = vec4(1.0);
#endif
#if SG_GROUP0_COUNT == 1
    SG_VIS_ONE(0)
#else
    SG_VIS_MANY(0)
#endif
#if SG_GROUP1_COUNT == 1
    SG_VIS_ONE(1)
#else
    SG_VIS_MANY(1)
#endif
#if SG_GROUP2_COUNT == 1
    SG_VIS_ONE(2)
#else
    SG_VIS_MANY(2)
#endif
#if SG_GROUP3_COUNT == 1
    SG_VIS_ONE(3)
#else
    SG_VIS_MANY(3)
#endif
#ifdef SG_VIS_CONTACT
    for (int c = 0; c < SG_VIS_LIGHTS; ++c) {
        // A loop of one trip or none: a light without contact shadows runs no march, nor does
        // the refine's for a light the resolve kept.
        bool runs = uContactLength[c] != 0.0;
#ifdef SG_VIS_REFINE
        runs = runs && sg_refinesLight(sg_visPrior, c);
#endif
        for (int i = 0; i < int(runs); ++i) {
            sg_GpuLight L = sg_lights[SG_SLOT_BASE + c];
            vec3 toLight = L.type == SG_LIGHT_DIRECTIONAL ? -L.wsDirection : normalize(L.csPosition - cs);
            // Automatic: the shorter of SG_CONTACT_AUTO_TEXELS of the map's texels here (what its
            // bias and filter lose) and SG_CONTACT_AUTO_PIXELS pixels (what the screen resolves).
            float texel = sg_texelMetresAt(L, sg_selectLayer(L, cs, viewDistance), cs);
            float length = uContactLength[c] > 0.0
                               ? uContactLength[c]
                               : min(SG_CONTACT_AUTO_TEXELS * texel, SG_CONTACT_AUTO_PIXELS * max(viewDistance, 0.0) * uPixelAngle);
            mask[c] = min(mask[c], sg_contactVisibility(cs, geoNormal, toLight, length, p));
        }
    }
#endif
    return mask;
}

#ifndef SG_VIS_RESOLVE
void main() {
    ivec2 src = sg_stageSource(ivec2(gl_FragCoord.xy), SG_VIS_DIVISOR);
    uvec4 surface = texelFetch(sg_gbufferSurface, src, 0);
    bool receives = sg_gbufferReceives(surface);
    // Depth-tested (SG_FULLSCREEN_FAR, GREATER) against the scene's depth at full resolution, or
    // against the coverage at this one (screen_coverage.frag.glsl): blocks without a surface
    // are skipped before they run, the others run straight-line.
    float depth = receives ? sg_gbufferDepth(surface) : 0.0;
#ifdef SG_STAGE_FEATURES
    // The block's footprint for the lights' reports: a pixel's width across the view at this
    // depth, stretched as the surface turns from it.
    vec3 cs = sg_gbufferPosition(src, surface);
    float facing = abs(dot(sg_gbufferGeoNormal(surface), cs)) / max(length(cs), 1e-30);
    sg_beginStageSample(depth * uPixelAngle / max(facing, 0.05), SG_VIS_DIVISOR);
#endif
#ifdef SG_VIS_REFINE
    sg_visPrior = texelFetch(uRefinePrior, src, 0);
#endif
    vec4 v = receives ? visibilityAt(src, surface) : vec4(1.0);
    outVisibility = v;
    uint sharp = 0u;
#ifdef SG_STAGE_FEATURES
    // The lights whose visibility may hold a feature narrower than the block: the resolve
    // refines them at the pixels nearest the sample (screen_resolve.glsl).
    sharp = sg_visSharpLights;
#endif
    outSample = sg_packStageSample(depth, sg_stageCode(sg_gbufferGeoOct(surface), sharp));
}
#else
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint refine;
    vec4 v = sg_resolveStage(p, texelFetch(sg_gbufferSurface, p, 0), SG_VIS_DIVISOR, uStageVisibility, uStageDepth,
                             uStageLayer, SG_VIS_LIGHTS, uPixelAngle, refine);
    // The refine pass recomputes the lights of `refine` at full resolution: depth 0 marks the
    // pixel for that pass's depth test, which skips whole blocks without one (the filters' code
    // then costs nothing where it does not run), and the prior says which lights it runs.
    gl_FragDepth = refine != 0u ? 0.0 : 1.0;
    outVisibility = v;
#ifdef SG_VIS_REFINE_PER_LIGHT
    outPrior = sg_refinePrior(v, refine);
#endif
}
#endif
