// One level of a shadow layer's min/max depth pyramid: each texel holds the least and the
// greatest stored depth of its tile of the map. Level 0 reads SG_MINMAX_TILE^2 depth texels,
// every further level the 2x2 texels of the level below. PCF and PCSS read it to find, in a few
// fetches, regions with no blocker (fully lit) or only blockers (umbra), and skip their taps.
//
// Compute dispatches, not draws into each level: on llvmpipe, a draw into the pyramid's
// framebuffer doubled the next frame's depth pass of a 70k-triangle caster (`shadow_render
// builtin:bunny-spot --size 1280x720 --no-cache --technique pcf`, its stats.json: depth layer
// 39 ms with draws, 17 ms with dispatches). One level per dispatch: a work group that reduced
// 8x8 texels to four levels through shared memory measured 2.2x slower (barriers are costly on a
// CPU rasteriser), and one that wrote three levels from registers, a 4x4 block of level 0 per
// invocation, no faster (builtin:default, `--technique pcf --no-cache`, 320x240, 5 runs in turn:
// 20-25 ms for the 9 layers either way): the cost is level 0's reading of every depth texel, about
// 2 ns a texel through gathers (4 ns through texelFetch).
//
// Only the tiles that hold a texel the layer's casters drew are dispatched (uOrigin, the
// dispatch's size); filter_chain.cpp clears the others to the far depth's range, which is what
// they would hold: on builtin:bunny-spot the bunny covers a small part of the spot's map.
//
// Reference: the hierarchical min/max shadow map of G. Guennebaud, L. Barthe, M. Paulin,
// "Real-time soft shadow mapping by backprojection", EGSR 2006, and of Z. Dong, B. Yang,
// "Variance soft shadow mapping", 2010 (the seeds' VSSM notes).
#include "shadow_chain_level.glsl"

layout(binding = SG_IMAGE_MINMAX, rg32f) writeonly uniform image2D uTarget;  // level uLevel of the layer

vec2 merge(vec2 a, vec2 b) { return vec2(min(a.x, b.x), max(a.y, b.y)); }

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy) + uOrigin;
    if (any(greaterThanEqual(texel, imageSize(uTarget)))) return;
    vec2 range = vec2(1.0, 0.0);
#ifdef SG_CHAIN_FROM_DEPTH
    // Gathers of 2x2 texels; coordinates past the map's edge clamp to it (the sampler's own).
    vec2 texelSize = 1.0 / vec2(textureSize(uDepth, 0).xy);
    for (int y = 0; y < SG_MINMAX_TILE; y += 2) {
        for (int x = 0; x < SG_MINMAX_TILE; x += 2) {
            vec2 uv = (vec2(texel * SG_MINMAX_TILE + ivec2(x, y)) + 1.0) * texelSize;
            vec4 d = textureGather(uDepth, vec3(uv, float(uLayer)));
            range = merge(range, vec2(min(min(d.x, d.y), min(d.z, d.w)), max(max(d.x, d.y), max(d.z, d.w))));
        }
    }
#else
    ivec2 size = textureSize(uBelow, uLevel - 1).xy;
    for (int k = 0; k < 4; ++k) {
        ivec3 below = ivec3(min(texel * 2 + ivec2(k & 1, k >> 1), size - 1), uLayer);
        range = merge(range, texelFetch(uBelow, below, uLevel - 1).rg);
    }
#endif
    imageStore(uTarget, texel, vec4(range, 0.0, 0.0));
}
