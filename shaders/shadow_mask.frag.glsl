// Screen-space shadow mask (ShadowSystem::renderMask): the visibility of up to four lights at
// every pixel of a game's depth buffer, one light per channel, for a game whose lighting
// multiplies it in without any shader of the module.
//
// The receiver is rebuilt from depth: the camera-relative position by unprojecting the pixel
// centre, the triangle's plane from the neighbour on each axis whose depth is closer (so a
// silhouette does not tilt the plane of the surface in front of it), the shading normal from the
// game's normal texture when it gives one (SG_MASK_NORMALS) and the curvature from its change.
// Slots are specialised and grouped like the lit passes' (SG_MASK_LIGHTS, SG_PASS_GROUPS,
// SG_GROUP<g>_*).
//
// At reduced resolution (ShadowMaskRequest::resolution) three passes, as the renderer's
// screen-space stage runs (screen_resolve.glsl):
// - the samples (uDivisor d > 1): one pixel per d x d block, the visibility at the block's centre
//   pixel, and that receiver's camera-relative position (w 1; 0 without geometry);
// - the resolve (SG_MASK_RESOLVE, with SG_MASK_DIVISOR d): each pixel blends the four samples
//   around it that lie on its own surface (within 1.5 blocks' footprint of its plane), marks
//   in depth the pixels with none or with disagreeing ones, and writes the refine's prior (the
//   lights to recompute there, sg_refinePrior);
// - the refine: the samples' program at full resolution (uDivisor 1, uRefine 1), depth-tested so
//   that only marked pixels run, and there only the lights the prior leaves. One program of the
//   lights' techniques serves every resolution: a mask's lights compile their techniques once.
// (Includes may not stand under a condition: each file is expanded once, where first named.)
#include "shadow_visibility.glsl"
#include "screen_resolve.glsl"
#ifdef SG_MASK_RESOLVE
layout(binding = SG_UNIT_MASK_STAGE) uniform sampler2D uStageMask;
layout(binding = SG_UNIT_MASK_STAGE_POSITION) uniform sampler2D uStagePosition;
#endif

layout(binding = SG_UNIT_MASK_DEPTH) uniform sampler2D uSceneDepth;
#ifdef SG_MASK_NORMALS
layout(binding = SG_UNIT_MASK_NORMAL) uniform sampler2D uSceneNormal;
#endif
uniform mat4 uCsFromClip;      // inverse of the game's camera-relative world -> clip
uniform vec3 uCameraForward;   // unit, world space
uniform int uZeroToOne;        // 1: window depth is NDC z (glClipControl ZERO_TO_ONE)
uniform float uBackgroundDepth;

layout(location = 0) out vec4 outMask;
#ifdef SG_MASK_RESOLVE
#ifdef SG_MASK_REFINE_PER_LIGHT
layout(location = 1) out vec4 outPrior;  // the refine's (sg_refinePrior)
#endif
#else
// The sample's receiver, camera-relative, w: 0 without geometry, else 1 + its code
// (sg_stageCode: an integer below 2^24, exact in a float; at full resolution no buffer takes it).
layout(location = 1) out vec4 outPosition;
uniform int uDivisor;  // the blocks a sample stands for: 1 at full resolution
#ifdef SG_MASK_REFINE_PER_LIGHT
// 1: the refine after a resolve, which computes only the lights the resolve's prior leaves
// (with three or more shadowed lights, kMinPerLightRefineLights: with fewer it is every light).
uniform int uRefine;
layout(binding = SG_UNIT_MASK_STAGE) uniform sampler2D uRefinePrior;
#define SG_MASK_ONLY_WHERE_LEFT(slot) for (int once = 0; once < int(sg_refinesLight(prior, slot)); ++once)
#else
#define SG_MASK_ONLY_WHERE_LEFT(slot)
#endif
#endif

// Camera-relative position of pixel `p` at window depth `d`.
vec3 csAt(ivec2 p, float d) {
    vec2 ndcXy = (vec2(p) + 0.5) / vec2(textureSize(uSceneDepth, 0)) * 2.0 - 1.0;
    float ndcZ = uZeroToOne != 0 ? d : d * 2.0 - 1.0;
    vec4 cs = uCsFromClip * vec4(ndcXy, ndcZ, 1.0);
    return cs.xyz / cs.w;
}

// The step to the neighbour along `axis` on the same surface: of the two, the one whose depth
// along the view is closer to the centre's (one-sided at the image border). Returns the
// neighbour's pixel in `q`.
vec3 surfaceStep(ivec2 p, vec3 c, ivec2 axis, out ivec2 q) {
    ivec2 size = textureSize(uSceneDepth, 0);
    ivec2 ahead = p + axis, behind = p - axis;
    bool hasAhead = all(lessThan(ahead, size)), hasBehind = all(greaterThanEqual(behind, ivec2(0)));
    vec3 a = hasAhead ? csAt(ahead, texelFetch(uSceneDepth, ahead, 0).r) : c;
    vec3 b = hasBehind ? csAt(behind, texelFetch(uSceneDepth, behind, 0).r) : c;
    float viewC = dot(c, uCameraForward);
    bool useAhead = hasAhead && (!hasBehind || abs(dot(a, uCameraForward) - viewC) <= abs(dot(b, uCameraForward) - viewC));
    q = useAhead ? ahead : behind;
    return useAhead ? a - c : c - b;
}

#ifdef SG_MASK_RESOLVE
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float d = texelFetch(uSceneDepth, p, 0).r;
    vec4 mask = vec4(1.0);
    uint refine = 0u;  // the lights the refine recomputes, a bit each
    if (d != uBackgroundDepth) {
        vec3 c = csAt(p, d);
        ivec2 qx, qy;
        vec3 dx = surfaceStep(p, c, ivec2(1, 0), qx);
        vec3 dy = surfaceStep(p, c, ivec2(0, 1), qy);
        vec3 geoNormal = sg_safeNormalize(cross(dx, dy), normalize(-c));
        // A sample of the same surface lies up to 1.5 blocks away, and a curved surface leaves
        // its tangent plane by about that much.
        float tolerance = 1.5 * float(SG_MASK_DIVISOR) * max(length(dx), length(dy));
        ivec2 last = textureSize(uStageMask, 0) - 1;
        vec2 t;
        ivec2 base = sg_stageBase(p, SG_MASK_DIVISOR, t);
        vec2 octNormal = sg_octEncode(geoNormal);
        vec4 weights;
        uvec4 sharp;
        vec4 samples[4];
        for (int k = 0; k < 4; ++k) {
            ivec2 q = clamp(base + sg_kStageQuad[k], ivec2(0), last);
            vec4 at = texelFetch(uStagePosition, q, 0);
            samples[k] = texelFetch(uStageMask, q, 0);
            uint code = uint(max(at.w - 1.0, 0.0));
            bool same = at.w > 0.5 && abs(dot(at.xyz - c, geoNormal)) <= tolerance && sg_stageCodeFaces(code, octNormal);
            weights[k] = same ? max(sg_stageWeight(k, t), 1e-4) : 0.0;
            sharp[k] = sg_stageCodeSharp(code);
        }
        float weight = weights.x + weights.y + weights.z + weights.w;
        vec4 w = weights / max(weight, 1e-30);
        bvec4 kept = greaterThan(weights, vec4(0.0));
        refine = sg_nearestSharp(sharp, weights);
        for (int l = 0; l < SG_MASK_LIGHTS; ++l) {
            vec4 g = vec4(samples[0][l], samples[1][l], samples[2][l], samples[3][l]);
            mask[l] = sg_blendKept(g, w, kept, 1u << l, refine);
        }
        refine = sg_refinedLights(refine, kept, SG_MASK_LIGHTS);
    }
    // Depth 0 marks the pixel for the refine pass, whose depth test skips the blocks without one.
    gl_FragDepth = refine != 0u ? 0.0 : 1.0;
    outMask = mask;
#ifdef SG_MASK_REFINE_PER_LIGHT
    outPrior = sg_refinePrior(mask, refine);
#endif
}
#else
// Light `slot` of the mask, of group g (as lit.frag.glsl's SG_SHADE_LIGHT), where the prior
// leaves it (every light but in the refine), in a loop of one trip or none: a CPU rasteriser
// skips it for a block of pixels where no pixel runs it. The samples note whether it reported a
// feature narrower than their block.
#define SG_MASK_LIGHT(g, slot)                                                                      \
    SG_MASK_ONLY_WHERE_LEFT(slot) {                                                                 \
        sg_GpuLight L = sg_slotLight(slot, SG_GROUP##g##_TYPE, SG_GROUP##g##_TECH, SG_GROUP##g##_KERNEL); \
        if (SG_GROUP##g##_TECH != SG_TECH_NONE)                                                     \
            mask[slot] = SG_GROUP##g##_VISIBILITY(slot, L, c, normal, geoNormal, curvature, viewDistance); \
        sharpLights |= sg_stageLightSharp(slot);                                                    \
    }
#define SG_MASK_ONE(g) \
    if (g < SG_PASS_GROUPS) SG_MASK_LIGHT(g, SG_GROUP##g##_FIRST)
#define SG_MASK_MANY(g)                                                                             \
    if (g < SG_PASS_GROUPS) {                                                                       \
        const int slots[SG_GROUP##g##_COUNT] = SG_GROUP##g##_SLOTS;                                 \
        for (int k = 0; k < SG_GROUP##g##_COUNT + sg_runtimeZero(); ++k) SG_MASK_LIGHT(g, slots[k]) \
    }

void main() {
    // A sample stands for its block's centre pixel (the pixel itself at full resolution).
    ivec2 p = min(ivec2(gl_FragCoord.xy) * uDivisor + uDivisor / 2, textureSize(uSceneDepth, 0) - 1);
    float d = texelFetch(uSceneDepth, p, 0).r;
    // The resolve's prior in the refine: its visibility, -1 for the lights to recompute; every
    // light elsewhere.
#ifdef SG_MASK_REFINE_PER_LIGHT
    vec4 prior = uRefine != 0 ? texelFetch(uRefinePrior, p, 0) : vec4(-1.0);
    vec4 mask = mix(prior, vec4(1.0), lessThan(prior, vec4(0.0)));
#else
    vec4 mask = vec4(1.0);
#endif
    vec4 position = vec4(0.0);
    if (d != uBackgroundDepth) {
        vec3 c = csAt(p, d);
        position = vec4(c, 1.0);
        vec3 toViewer = normalize(-c);
        ivec2 qx, qy;
        vec3 dx = surfaceStep(p, c, ivec2(1, 0), qx);
        vec3 dy = surfaceStep(p, c, ivec2(0, 1), qy);
        vec3 geoNormal = sg_safeNormalize(cross(dx, dy), toViewer);
        float curvature = 0.0;
#ifdef SG_MASK_NORMALS
        vec3 n = sg_safeNormalize(texelFetch(uSceneNormal, p, 0).xyz, geoNormal);
        vec3 nx = sg_safeNormalize(texelFetch(uSceneNormal, qx, 0).xyz, n);
        vec3 ny = sg_safeNormalize(texelFetch(uSceneNormal, qy, 0).xyz, n);
        curvature = max(length(nx - n) / max(length(dx), 1e-20), length(ny - n) / max(length(dy), 1e-20));
#else
        vec3 n = geoNormal;
#endif
        vec3 normal = dot(n, toViewer) < 0.0 ? -n : n;
        float viewDistance = dot(c, uCameraForward);
        // The block's footprint for the lights' reports (screen_resolve.glsl): a pixel's on the
        // surface is the longer step to its neighbours.
        sg_beginStageSample(max(length(dx), length(dy)), uDivisor);
        uint sharpLights = 0u;
#if SG_GROUP0_COUNT == 1
        SG_MASK_ONE(0)
#else
        SG_MASK_MANY(0)
#endif
#if SG_GROUP1_COUNT == 1
        SG_MASK_ONE(1)
#else
        SG_MASK_MANY(1)
#endif
#if SG_GROUP2_COUNT == 1
        SG_MASK_ONE(2)
#else
        SG_MASK_MANY(2)
#endif
#if SG_GROUP3_COUNT == 1
        SG_MASK_ONE(3)
#else
        SG_MASK_MANY(3)
#endif
        // The lights with a feature narrower than its block.
        position.w = 1.0 + float(sg_stageCode(sg_octEncode(geoNormal), uDivisor > 1 ? sharpLights : 0u));
    }
    outMask = mask;
    outPosition = position;
}
#endif
