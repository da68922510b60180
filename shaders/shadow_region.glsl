// What a whole filter region holds, from the min/max depth pyramid (shadow_minmax.comp.glsl):
// no blocker (fully lit), only blockers (umbra), or maybe a penumbra. PCF and PCSS run their
// taps only in the last case. The answer is exact, not a guess: lit or umbra is returned only
// when every tap the full filter would take is sure to compare that way.
//
// Both branches of an `if` run on a CPU rasteriser; a loop stops once no pixel of the SIMD
// group needs another trip (BENCHMARKS.md, fragment costs). So callers turn this answer into a
// tap count of 0 rather than branching around their loops.
#ifndef SG_SHADOW_REGION
#define SG_SHADOW_REGION
#include "shadow_receiver.glsl"

// The least and greatest stored depth (x, y; in stored units) of the square of map texels of
// half-width `radiusTexels` centred on `uv` in `layer`: four texels of the pyramid level whose
// tiles are at least as wide as the square. Map texels outside the map count as the far plane.
vec2 sg_regionDepthRange(int slot, sg_GpuLight L, vec2 uv, int layer, float radiusTexels) {
    int levels = textureQueryLevels(sg_shadowChain[slot]);
    int level = clamp(int(ceil(log2(max(2.0 * radiusTexels / float(SG_MINMAX_TILE), 1.0)))), 0, levels - 1);
    // Level sizes from level 0 (uniform across pixels): llvmpipe answers a per-pixel level with
    // one pixel's level for the whole SIMD group.
    ivec2 size = max(textureSize(sg_shadowChain[slot], 0).xy >> level, ivec2(1));
    float tile = float(SG_MINMAX_TILE) * exp2(float(level));  // map texels per texel of the level
    ivec2 first = ivec2(floor(uv * L.mapSize / tile - 0.5));
    // Without a pyramid this frame (L.regionTest 0) nothing is known: no fetch, a loop of no trip.
    vec2 range = L.regionTest != 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    for (int k = 0; k < 4 * L.regionTest; ++k) {
        ivec2 texel = clamp(first + ivec2(k & 1, k >> 1), ivec2(0), size - 1);
        // textureLod at the texel's centre, not texelFetch, for the same reason.
        vec2 mm = textureLod(sg_shadowChain[slot], vec3((vec2(texel) + 0.5) / vec2(size), float(layer)), float(level)).rg;
        range = vec2(min(range.x, mm.x), max(range.y, mm.y));
    }
    vec2 reach = vec2(radiusTexels / L.mapSize);
    if (any(lessThan(uv - reach, vec2(0.0))) || any(greaterThan(uv + reach, vec2(1.0)))) range.y = 1.0;
    // A square that does not fit in its level's tiles (beyond the largest level) knows nothing.
    if (2.0 * radiusTexels > tile * float(size)) range = vec2(0.0, 1.0);
    return range;
}

// 1 when no texel within `radius` lateral metres of the receiver can shadow a tap on its tangent
// plane, 0 when every texel does, -1 otherwise. `center` is the receiver's own tap.
float sg_regionVisibility(int slot, sg_GpuLight L, sg_Receiver r, sg_Tap center, float radius) {
    // A tap compares the 2x2 texels around it: one more texel and a half of reach.
    float radiusTexels = radius / max(r.texelMetres, 1e-30) + 1.5;
    vec2 uvReach = vec2(radiusTexels / L.mapSize);
    // A point light's region that leaves its face continues on another face: not known here.
    bool crossesFace = L.type == SG_LIGHT_POINT &&
                       (any(lessThan(center.uv - uvReach, vec2(0.0))) || any(greaterThan(center.uv + uvReach, vec2(1.0))));
    vec2 range = sg_regionDepthRange(slot, L, center.uv, center.layer, radiusTexels) * r.depthScale;
    // The taps' reference depths: the tangent plane's depth over the region, less the bias, with
    // two texels of margin for the normal offset's growth with distance.
    float spread = radius * r.depthSlope + 2.0 * r.texelMetres * (1.0 + r.depthSlope);
    float referenceLow = center.depth - r.depthBias - spread;
    float referenceHigh = center.depth - r.depthBias + spread;
    if (crossesFace || radius <= 0.0) return -1.0;
    if (range.x >= referenceHigh) return 1.0;
    if (range.y < referenceLow) return 0.0;
    return -1.0;
}

#endif
