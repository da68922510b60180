// The levels of a shadow layer's min/max depth pyramid: each texel holds the least and the
// greatest stored depth of its tile of the map. A texel of level 0 covers SG_MINMAX_TILE^2 depth
// texels, every further level the 2x2 texels of the level below. PCF and PCSS read it to find, in
// a few fetches, regions with no blocker (fully lit) or only blockers (umbra), and skip their taps.
// Three levels per dispatch, in blocks (shadow_chain_level.glsl).
//
// Compute dispatches, not draws into each level: on llvmpipe, a draw into the pyramid's
// framebuffer doubled the next frame's depth pass of a 70k-triangle caster (`shadow_render
// builtin:bunny-spot --size 1280x720 --no-cache --technique pcf`, its stats.json: depth layer
// 39 ms with draws, 17 ms with dispatches).
//
// Reference: the hierarchical min/max shadow map of G. Guennebaud, L. Barthe, M. Paulin,
// "Real-time soft shadow mapping by backprojection", EGSR 2006, and of Z. Dong, B. Yang,
// "Variance soft shadow mapping", 2010 (the seeds' VSSM notes).
#define SG_CHAIN_FORMAT rg32f
#include "shadow_chain_level.glsl"

vec4 sg_chainMerge(vec4 a, vec4 b, vec4 c, vec4 d) {
    return vec4(min(min(a.x, b.x), min(c.x, d.x)), max(max(a.y, b.y), max(c.y, d.y)), 0.0, 0.0);
}

#ifdef SG_CHAIN_FROM_DEPTH
vec4 sg_chainFromDepth(ivec2 texel) {
    // Gathers of 2x2 texels; coordinates past the map's edge clamp to it (the sampler's own).
    vec2 texelSize = 1.0 / vec2(textureSize(uDepth, 0).xy);
    vec2 range = vec2(1.0, 0.0);
    for (int y = 0; y < SG_MINMAX_TILE; y += 2) {
        for (int x = 0; x < SG_MINMAX_TILE; x += 2) {
            vec2 uv = (vec2(texel * SG_MINMAX_TILE + ivec2(x, y)) + 1.0) * texelSize;
            vec4 d = textureGather(uDepth, vec3(uv, float(uLayer)));
            range = vec2(min(range.x, min(min(d.x, d.y), min(d.z, d.w))), max(range.y, max(max(d.x, d.y), max(d.z, d.w))));
        }
    }
    return vec4(range, 0.0, 0.0);
}
#endif
