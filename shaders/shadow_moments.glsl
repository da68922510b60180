// What every moment technique shares: region moments from a prefiltered chain, Chebyshev's
// one-sided bound, the variance floor and the receiver's reference depth in stored units.
//
// The moments chain (shadow_moments.frag.glsl; level 0 is read from the depth map, sg_texelMoments) holds the means of powers of the stored depth
// over every tile of the map, so one trilinear fetch gives a filter region's moments, whatever
// its width. Chebyshev's one-sided inequality bounds the fraction of the region at least as far
// as the receiver, P(z >= t) <= var / (var + (t - mean)^2) for t > mean.
//
// Reference: W. Donnelly, A. Lauritzen, "Variance Shadow Maps", I3D 2006; A. Lauritzen,
// "Summed-Area Variance Shadow Maps", GPU Gems 3, 2007 (light-bleeding reduction).
#ifndef SG_SHADOW_MOMENTS
#define SG_SHADOW_MOMENTS
#include "shadow_taps.glsl"

// Relative float error of a stored second moment, in units of its value: a few ulps of the mean
// of squares, which E[z^2] - E[z]^2 cancels down to.
const float sg_kVsmMomentUlps = 4.0 * 1.1920929e-7;

// Chebyshev's bound for a receiver at `reference` (stored units) and a region of moments `m`,
// with the variance at least `minVariance`, of which `planeVariance` is the receiver's own plane
// spread over the region (sg_planeVariance) rather than evidence of blockers.
//
// Chebyshev's bound reads all of a region's variance as depths split between the receiver and
// something in front of it. Over a wide region a sloped receiver's own texels spread by
// slope x radius around its depth, and the bound then calls a region half lit that is mostly
// blockers (VSSM's and MSM-soft's searches took blockers at the light and spread their
// penumbrae). Taking the lit part p of the region as the receiver's plane, whose own variance is
// a, the region's variance holds p a of it; the bound on the rest, p = (var - p a) /
// (var - p a + d^2), is the smaller root of a p^2 - (var + d^2 + a) p + var = 0, written so that
// a = 0 is Chebyshev's bound exactly. The plane's share is at most the region's variance (a flat
// region under a steep receiver is not the receiver's plane).
float sg_chebyshevUpperBound(vec2 m, float reference, float minVariance, float planeVariance) {
    float variance = max(m.y - m.x * m.x, minVariance);
    float d = reference - m.x;
    float a = min(planeVariance, variance);
    float b = variance + d * d + a;
    return d <= 0.0 ? 1.0 : 2.0 * variance / (b + sqrt(max(b * b - 4.0 * a * variance, 0.0)));
}

// The variance of the receiver plane's stored depths over a region of radius `radius` (m) whose
// per-axis variance is radius^2 / 4 (the chain's trilinear fetch and the summed-area square both
// are, sg_regionMoments): the plane's depth changes by r.depthSlope per lateral metre.
float sg_planeVariance(sg_Receiver r, float radius) {
    float spread = r.depthSlope * radius / r.depthScale;
    return 0.25 * spread * spread;
}

// The chain level whose texels are as wide as a region of radius `radius` (m) at the receiver.
float sg_regionLevel(sg_Receiver r, float radius) {
    return log2(max(radius / max(r.texelMetres, 1e-30), 1.0));
}

// The four power moments around `uv` in `layer` over one texel: the 2x2 stored depths around it
// from one gather of the depth map, raised to their powers and blended by lerps, exact where the
// four agree as the filtering unit's blend is (a region of cleared texels keeps a mean of exactly
// 1, which the bound reads as lit), edge clamped: a moment chain's level 0 fetched with
// GL_LINEAR, without the level. Hard-edged MSM reads its one-texel region so; VSM and MSM-soft
// their regions finer than level 1 (sg_chainMoments).
vec4 sg_texelMoments(int slot, sg_GpuLight L, vec2 uv, int layer) {
    float size = float(L.mapSize);
    vec2 f;
    vec2 quadUv = sg_quadAt(clamp(uv * size - 0.5, vec2(0.0), vec2(size - 1.0)), size, f);
    vec4 z = clamp(textureGather(sg_shadowDepth[slot], vec3(quadUv, float(layer))), 0.0, 1.0);
    vec4 z2 = z * z;
    return vec4(sg_bilinearQuad(z, f), sg_bilinearQuad(z2, f), sg_bilinearQuad(z2 * z, f), sg_bilinearQuad(z2 * z2, f));
}

// A moment chain's trilinear fetch at `level` around `uv`, for a chain made from level 1 up (VSM,
// MSM-soft; sg_GpuShadowLayer::chainFirstLevel), whose texture holds no level 0 (its level k is
// the chain's level k + 1):
// below level 1, the fetch's level-0 half comes from the depth map (sg_texelMoments) and is
// mixed with level 1 by the level's fraction, as the trilinear filter mixes the two levels. A
// loop, not an `if` (a CPU rasteriser runs both sides of an `if`): a group of pixels none of
// which reads below level 1 takes no gather.
vec4 sg_chainMoments(int slot, sg_GpuLight L, vec2 uv, int layer, float level) {
    vec4 m = textureLod(sg_shadowChain[slot], vec3(uv, float(layer)), max(level, 1.0) - 1.0);
    SG_ISOLATED
    for (int k = 0; k < int(level < 1.0); ++k) m = mix(sg_texelMoments(slot, L, uv, layer), m, max(level, 0.0));
    return m;
}

// The moments of the stored depths (two or four, as the chain holds) over a region of radius
// `radius` metres around `center`, one fetch whatever the radius: the trilinear fetch at mip level L = log2(radius in
// texels) filters with a box of 2^L texels convolved with a tent of half-width 2^L, whose
// variance along each axis, 4^L / 4, is that of a disk of the same radius, r^2 / 4 (PCF's).
// One level up, a box as wide as the disk, has tails twice as long (tests/shadow/vsm_test.cpp
// compares VSM with PCF of the same radius). Within the layer's first and last levels
// (sg_GpuShadowLayer::chainFirstLevel and chainLastLevel: the levels beyond are not built), which
// the planner sets around every level a receiver of the layer asks for (VSM; MSM-soft reads
// sg_chainMoments).
vec4 sg_regionMoments(int slot, sg_GpuLight L, sg_Receiver r, sg_Tap center, float radius) {
    sg_GpuShadowLayer S = sg_layers[L.firstLayer + center.layer];
    // A chain built from level 1 serves the levels below it too (sg_chainMoments).
    float lowest = S.chainFirstLevel > 1 ? float(S.chainFirstLevel) : 0.0;
    float level = clamp(sg_regionLevel(r, radius), lowest, float(S.chainLastLevel));
    return sg_chainMoments(slot, L, center.uv, center.layer, level);
}

// The least variance a region's moments are given: the spread of depths within one texel of the
// receiver's own plane (a plane's texels are not one depth), and never below the moments' float
// resolution.
float sg_varianceFloor(sg_Receiver r, vec2 m) {
    float texelSpread = r.depthSlope * r.texelMetres / r.depthScale;
    return max(texelSpread * texelSpread / 12.0, sg_kVsmMomentUlps * m.y);
}

// The receiver's depth in stored units, the bias taken off. Clamped to the far plane as the
// comparing taps clamp theirs (sg_compareQuad): a receiver beyond it, where only cleared texels (1)
// lie, is lit.
float sg_momentsReference(sg_Receiver r, sg_Tap center) {
    return min((center.depth - r.depthBias) / r.depthScale, 1.0);
}

// Visibility of the receiver at `reference` (stored units) behind a region of moments `m`:
// Chebyshev's bound with the variance at least `minVariance` (`planeVariance` of it the
// receiver's plane), then the light-bleeding reduction.
float sg_momentsVisibility(sg_GpuLight L, vec2 m, float reference, float minVariance, float planeVariance) {
    float p = sg_chebyshevUpperBound(m, reference, minVariance, planeVariance);
    float cut = clamp(L.lightBleedReduction, 0.0, 0.95);
    return clamp((p - cut) / (1.0 - cut), 0.0, 1.0);
}

// Whether a receiver lies outside its layer's map: lit, as the comparing taps read outside
// texels (their sampler's border is the far plane). The chain itself clamps to its edge, so that
// a region reaching past a cube face's edge reads the texels along it rather than a far plane.
bool sg_outsideMap(sg_Tap center) {
    return any(lessThan(center.uv, vec2(0.0))) || any(greaterThan(center.uv, vec2(1.0)));
}

#endif
