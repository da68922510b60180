// The upsample of visibility computed at reduced resolution, shared by the renderer's
// screen-space stage (screen_visibility.frag.glsl) and the game-facing mask
// (shadow_mask.frag.glsl): one sample per d x d block of the screen, at the block's centre pixel
// q * d + d / 2; each full-resolution pixel blends the four samples around it with bilinear
// weights, keeping only those on its own surface (on its triangle's plane and facing as it
// does), and is sent to a refine pass (its visibility recomputed at full resolution) for every
// light when none is kept, and for a light whose kept samples disagree, or whose kept sample
// nearest it holds a feature narrower than its block: each light's technique reports at the
// samples the narrowest feature its visibility may have nearby (SG_STAGE_FEATURE,
// shadow_common.glsl: PCSS's penumbra where its search found blockers within a block and texels
// that do not block, the moment methods' where their search region holds both, sdf's penumbra
// at a caster its cone passed within a block of, PCF's radius where a search of the block finds
// both), since a shadow that narrow can fall between the samples, which then agree.
// A thin shadow between two samples is near both, so refining the pixels nearest each covers
// it (tests/render/screen_visibility_test.cpp: of thin posts' shadows at quarter resolution,
// 22-29 % of the pixels read lit without the reports and the normals, under 1 % with them for
// PCSS, PCF and sdf).
#ifndef SG_SCREEN_RESOLVE
#define SG_SCREEN_RESOLVE
#include "screen_gbuffer.glsl"

// Kept samples differing by more than this send a pixel to the refine pass (0.25 let the
// upsample add 5-7 % to sdf's and PCSS's error on builtin:default at 320x240; 0.1 costs the
// refine 0.4 ms more on the bunny spot at 1280x720).
#define SG_VIS_REFINE_SPREAD 0.1
// A sample whose lights' narrowest feature (a radius) is under this many of its blocks sends the
// pixels nearest it to the refine pass (a radius of a quarter block: a shadow half a block wide).
#define SG_VIS_FEATURE_BLOCKS 0.25

#ifdef SG_STAGE_FEATURES
// The stage's samples, before the lights are evaluated: the block around the sample, `divisor`
// pixels of `pixelMetres` each on its surface (a lateral width across the light is at most
// that), for the filters' searches (sg_stageBlock, shadow_common.glsl).
void sg_beginStageSample(float pixelMetres, int divisor) {
    sg_stageBlock = float(divisor) * pixelMetres;
}
// After each light: its bit of the sample's code (1 << `channel`) when its visibility may hold a
// feature narrower than SG_VIS_FEATURE_BLOCKS of the block, and the report cleared for the next.
uint sg_stageLightSharp(int channel) {
    bool sharp = sg_stageFeature < SG_VIS_FEATURE_BLOCKS * sg_stageBlock;
    sg_stageFeature = 3.0e38;
    return sharp ? 1u << uint(channel) : 0u;
}
#endif

// A kept sample's triangle faces about as the pixel's: their normals' octahedral coordinates
// (sg_octEncode) differ by at most this on each axis (about 30-45 degrees; a pixel whose
// normal lies across the octahedron's seam from its samples' goes to the refine pass). A sample
// on the extension of the pixel's plane but on another surface (the ground at the foot of a
// post, seen at a silhouette) is not blended in.
#define SG_VIS_SAME_NORMAL 0.5

// A sample's code, 16 bits: its triangle's normal (octahedral, 6 bits a coordinate, bits 0-11:
// steps of 0.03, a sixteenth of SG_VIS_SAME_NORMAL) and, per light of its group (bits 12-15),
// whether that light's visibility holds a feature narrower than its block.
// `octNormal`: the normal's octahedral coordinates (sg_octEncode); `sharpLights`: a bit per light.
uint sg_stageCode(vec2 octNormal, uint sharpLights) {
    uvec2 q = uvec2(round((octNormal * 0.5 + 0.5) * 63.0));
    return q.x | (q.y << 6) | ((sharpLights & 15u) << 12);
}
uint sg_stageCodeSharp(uint code) { return (code >> 12) & 15u; }
// Whether the sample of `code` faces as the pixel whose triangle's normal has the octahedral
// coordinates `octNormal`: compared in those coordinates, with no decode.
bool sg_stageCodeFaces(uint code, vec2 octNormal) {
    vec2 p = vec2(uvec2(code, code >> 6) & 63u) * (2.0 / 63.0) - 1.0;
    vec2 d = abs(p - octNormal);
    return max(d.x, d.y) <= SG_VIS_SAME_NORMAL;
}

// The renderer's stage keeps a sample in one 32-bit texel: its depth along the view as a half
// float (bits 0-15; 0: no receiver; 2^-11 of the depth, a twentieth of the resolve's
// tolerance at quarter resolution in 720 rows) and its code (bits 16-31).
uint sg_packStageSample(float depth, uint code) { return (packHalf2x16(vec2(depth, 0.0)) & 0xffffu) | (code << 16); }
float sg_stageSampleDepth(uint texel) { return unpackHalf2x16(texel).x; }
uint sg_stageSampleCode(uint texel) { return texel >> 16; }

// The four samples around a pixel in textureGather's order: (0,1), (1,1), (1,0), (0,0) from the
// lower-left one.
const ivec2 sg_kStageQuad[4] = ivec2[](ivec2(0, 1), ivec2(1, 1), ivec2(1, 0), ivec2(0, 0));

// The lower-left of the 2x2 samples around full-resolution pixel `p` of a stage with divisor
// `d`, and p's place between them (`t`, 0 to 1 on each axis).
ivec2 sg_stageBase(ivec2 p, int d, out vec2 t) {
    ivec2 base = ivec2(floor((vec2(p) - float(d / 2)) / float(d)));
    t = (vec2(p) - vec2(base * d + d / 2)) / float(d);
    return base;
}

// Bilinear weight of sample `k` (sg_kStageQuad order) at place `t`.
float sg_stageWeight(int k, vec2 t) {
    return (sg_kStageQuad[k].x == 1 ? t.x : 1.0 - t.x) * (sg_kStageQuad[k].y == 1 ? t.y : 1.0 - t.y);
}

// The lights a pixel must refine for features narrower than the blocks: those the kept sample
// nearest it (the largest of `weights`, 0 where not kept) marks sharp (`sharp`: each sample's
// sg_stageCodeSharp). A shadow that thin between two samples marks both (each found the caster
// near), so refining the pixels nearest each covers the gap.
uint sg_nearestSharp(uvec4 sharp, vec4 weights) {
    float most = max(max(weights.x, weights.y), max(weights.z, weights.w));
    uint lights = 0u;
    for (int k = 0; k < 4; ++k) lights |= weights[k] == most ? sharp[k] : 0u;
    return most > 0.0 ? lights : 0u;
}

// The blend of one light's four samples `g` with the normalised weights `w` of those `kept`;
// the light's bit (`bit`) goes into `refine` when the kept samples differ by more than
// SG_VIS_REFINE_SPREAD (an edge sharper than the blocks: a contact shadow, a hard shadow's edge).
float sg_blendKept(vec4 g, vec4 w, bvec4 kept, uint bit, inout uint refine) {
    vec4 hi = mix(vec4(0.0), g, kept), lo = mix(vec4(1.0), g, kept);
    float spread = max(max(hi.x, hi.y), max(hi.z, hi.w)) - min(min(lo.x, lo.y), min(lo.z, lo.w));
    refine |= spread > SG_VIS_REFINE_SPREAD ? bit : 0u;
    return dot(w, g);
}

// The lights of `lights` a pixel's refine recomputes, of those its resolve marked (`refine`):
// every light where no sample was `kept`, and where some were not (a geometric edge) while the
// refine runs there anyway, since a light whose kept samples agree may still change at the edge
// (the shadow a box casts at its foot, where the ground's samples beyond the box agree on lit):
// recomputing only the marked lights there added 12-24 % to PCSS's and MSM-soft's error on
// builtin:default at 320x240, quarter resolution.
uint sg_refinedLights(uint refine, bvec4 kept, int lights) {
    uint every = (1u << uint(lights)) - 1u;
    bool edge = !all(kept) && refine != 0u;
    return !any(kept) || edge ? every : refine & every;
}

// The refine's input at a pixel the resolve could not upsample for every light: the resolved
// visibility `v` of the lights it keeps, -1 for those (`refine`, a bit per light) the refine
// recomputes. The refine runs only those (sg_refinesLight), at full resolution.
vec4 sg_refinePrior(vec4 v, uint refine) {
    bvec4 again = notEqual(uvec4(refine) & uvec4(1u, 2u, 4u, 8u), uvec4(0u));
    return mix(v, vec4(-1.0), again);
}
// Whether the refine recomputes light `channel`, of the resolve's `prior` (sg_refinePrior).
bool sg_refinesLight(vec4 prior, int channel) { return prior[channel] < 0.0; }

// The lights marked for their visibility at full resolution in a group of `lights` whose resolve
// asks to recompute `refine` (a bit each): those lights, or with whole-group refines (`perLight`
// false: fewer than kMinPerLightRefineLights shadowed lights, core/stage_resolution.h) every
// light of the group where one is.
uint sg_groupMarks(uint refine, int lights, bool perLight) {
    uint every = (1u << uint(lights)) - 1u;
    return perLight ? refine : (refine != 0u ? every : 0u);
}

#ifdef SG_READS_GBUFFER
// The full-resolution pixel whose surface the sample `q` of a stage at divisor `d` holds.
ivec2 sg_stageSource(ivec2 q, int d) { return min(q * d + d / 2, textureSize(sg_gbufferSurface, 0) - 1); }

// The renderer's resolve (the upsample above) at full-resolution pixel `p`, whose surface texel
// is `surface`: the blend of channels 0 to `lights` - 1 of layer `layer` of a stage at divisor
// `d` (`stage` its visibility, clamped at the border; `stageDepth` its samples,
// sg_packStageSample), `pixelAngle` a pixel's footprint per metre of depth. `refine` is set to
// the lights (a bit each) to recompute at this pixel (sg_refinedLights). A surface that receives
// no shadow reads 1 with none to recompute. One function for the stage's resolve pass
// (screen_visibility.frag.glsl) and the deferred lit pass that resolves the stage itself
// (lit.frag.glsl, SG_LAYER<k>_RESOLVE).
vec4 sg_resolveStage(ivec2 p, uvec4 surface, int d, sampler2DArray stage, usampler2DArray stageDepth, int layer,
                     int lights, float pixelAngle, out uint refine) {
    vec3 position = sg_gbufferPosition(p, surface);
    vec3 geoNormal = sg_gbufferGeoNormal(surface);
    // How far off this pixel's plane a sample of the same surface may lie: a stage sample is up
    // to 1.5 blocks away, and a curved surface leaves its tangent plane by about that much.
    float footprint = max(sg_gbufferDepth(surface), 0.0) * pixelAngle;
    float tolerance = 1.5 * float(d) * footprint;
    float planeOffset = dot(position, geoNormal);
    vec2 stageSize = vec2(textureSize(stageDepth, 0).xy);
    // The four samples around p and p's place between them, their 2x2 gathered at the corner
    // they share (texels (base + 1) / size).
    vec2 t;
    ivec2 base = sg_stageBase(p, d, t);
    vec3 corner = vec3(vec2(base + 1) / stageSize, float(layer));
    uvec4 samples = textureGather(stageDepth, corner, 0);
    vec2 octNormal = sg_gbufferGeoOct(surface);  // as stored: no encode of the decoded normal
    vec4 weights;
    uvec4 sharp;
    for (int k = 0; k < 4; ++k) {
        // The sample's point from its depth along its pixel's ray; kept when on p's plane and
        // facing as p's triangle does.
        ivec2 src = sg_stageSource(clamp(base + sg_kStageQuad[k], ivec2(0), ivec2(stageSize) - 1), d);
        vec3 ray = uRay00 + (float(src.x) + 0.5) * uRayDx + (float(src.y) + 0.5) * uRayDy;
        float depth = sg_stageSampleDepth(samples[k]);
        uint code = sg_stageSampleCode(samples[k]);
        bool same = depth > 0.0 && abs(depth * dot(ray, geoNormal) - planeOffset) <= tolerance &&
                    sg_stageCodeFaces(code, octNormal);
        weights[k] = same ? max(sg_stageWeight(k, t), 1e-4) : 0.0;
        sharp[k] = sg_stageCodeSharp(code);
    }
    float weight = weights.x + weights.y + weights.z + weights.w;
    vec4 v = vec4(1.0);
    vec4 w = weights / max(weight, 1e-30);
    bvec4 kept = greaterThan(weights, vec4(0.0));
    // The lights to recompute (a bit each): those with a feature narrower than the blocks at
    // the nearest kept sample, and those whose kept samples disagree.
    uint marked = sg_nearestSharp(sharp, weights);
    // textureGather takes its channel as a constant: one line per channel, those past `lights`
    // folded away.
#define SG_RESOLVE_CHANNEL(c) \
    if (c < lights) v[c] = sg_blendKept(textureGather(stage, corner, c), w, kept, 1u << c, marked);
    SG_RESOLVE_CHANNEL(0)
    SG_RESOLVE_CHANNEL(1)
    SG_RESOLVE_CHANNEL(2)
    SG_RESOLVE_CHANNEL(3)
#undef SG_RESOLVE_CHANNEL
    bool receives = sg_gbufferReceives(surface);
    // Every light at a geometric edge where the refine runs (sg_refinedLights).
    refine = receives ? sg_refinedLights(marked, kept, lights) : 0u;
    return receives ? v : vec4(1.0);
}
#endif

#endif
