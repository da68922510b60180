// The upsample of visibility computed at reduced resolution, shared by the renderer's
// screen-space stage (screen_visibility.frag.glsl) and the game-facing mask
// (shadow_mask.frag.glsl): one sample per d x d block of the screen, at the block's centre pixel
// q * d + d / 2; each full-resolution pixel blends the four samples around it with bilinear
// weights, keeping only those on its own surface, and is sent to a refine pass (its visibility
// recomputed at full resolution) when none is kept or the kept ones disagree.
#ifndef SG_SCREEN_RESOLVE
#define SG_SCREEN_RESOLVE

// Kept samples differing by more than this send a pixel to the refine pass (0.25 let the
// upsample add 5-7 % to sdf's and PCSS's error on builtin:default at 320x240; 0.1 costs the
// refine 0.4 ms more on the bunny spot at 1280x720).
#define SG_VIS_REFINE_SPREAD 0.1

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

// The blend of one light's four samples `g` with the normalised weights `w` of those `kept`;
// `spread` grows to the kept samples' largest disagreement.
float sg_blendKept(vec4 g, vec4 w, bvec4 kept, inout float spread) {
    vec4 hi = mix(vec4(0.0), g, kept), lo = mix(vec4(1.0), g, kept);
    spread = max(spread, max(max(hi.x, hi.y), max(hi.z, hi.w)) - min(min(lo.x, lo.y), min(lo.z, lo.w)));
    return dot(w, g);
}

#endif
