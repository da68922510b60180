// A region's depth moments from the light's summed-area table (VSSM; the table's format is in
// shadow_summed_area_format.glsl): the mean z and mean z^2 over a square about a tap, for any
// width, from the table's values at the square's four corners.
//
// The table sums piecewise-constant texels, so its integral over [0, X) x [0, Y) is bilinear in
// (X, Y) between lattice points: a square with fractional corners is the weighted sum of the 16
// integer rectangles its corners' lattice neighbours span, each summed exactly in integers
// modulo 2^48 (limb by limb) before it becomes a float. The region's moments are then exact to
// one float rounding per rectangle, whatever the map's size: no cancellation of large sums.
// (Rounding the blocker search's corners to texels, 4 fetches, would save time at the same
// error, for penumbra widths that step from texel to texel; docs/tuning.md.)
#ifndef SG_SHADOW_SUMMED_AREA
#define SG_SHADOW_SUMMED_AREA
#include "shadow_bindings.glsl"
#include "shadow_receiver.glsl"
#include "shadow_summed_area_format.glsl"

// The table's integral over [0, p.x) x [0, p.y) as limbs: its texel p - 1, nothing on the lower
// and left edges.
ivec4 sg_satLattice(int slot, ivec2 p, int layer) {
    if (p.x <= 0 || p.y <= 0) return ivec4(0);
    return ivec4(texelFetch(sg_shadowChain[slot], ivec3(p - 1, layer), 0));
}

// A sum known to lie in [0, 2^47) from its limbs' signed combination (lo, hi): modulo 2^48 the
// sum is hi 2^24 + lo, and the one representative of that class near [0, 2^47) is it.
float sg_satSum(int lo, int hi) {
    return float((hi << 8) >> 8) * sg_kSatUnit + float(lo);  // hi modulo 2^24, in [-2^23, 2^23)
}

// Mean z and z^2 (stored units) over the square of half-width `halfTexels` about `uv` in
// `layer` of slot `slot`'s table, cut to the map: a region reaching past the map's edge (or a
// cube face's) averages the part inside it.
vec2 sg_summedSquareMoments(int slot, int layer, vec2 uv, float halfTexels) {
    ivec2 size = textureSize(sg_shadowChain[slot], 0).xy;
    vec2 centre = uv * vec2(size);
    vec2 lo = clamp(centre - halfTexels, vec2(0.0), vec2(size));
    vec2 hi = clamp(centre + halfTexels, vec2(0.0), vec2(size));
    ivec2 i0 = ivec2(floor(lo));
    ivec2 i1 = ivec2(floor(hi));
    vec2 f0 = lo - vec2(i0);
    vec2 f1 = hi - vec2(i1);
    // Column spans first, y bottom (i0.y + uB) to top (i1.y + uT), at x in {i0.x, i0.x + 1,
    // i1.x, i1.x + 1}; points past the table carry weight 0 and are read at its edge.
    ivec4 span[16];  // index 4 a + 2 uT + uB
    for (int a = 0; a < 4; ++a) {
        int x = min(a < 2 ? i0.x + a : i1.x + a - 2, size.x);
        ivec4 bottom0 = sg_satLattice(slot, ivec2(x, i0.y), layer);
        ivec4 bottom1 = sg_satLattice(slot, ivec2(x, min(i0.y + 1, size.y)), layer);
        ivec4 top0 = sg_satLattice(slot, ivec2(x, i1.y), layer);
        ivec4 top1 = sg_satLattice(slot, ivec2(x, min(i1.y + 1, size.y)), layer);
        span[4 * a + 0] = top0 - bottom0;
        span[4 * a + 1] = top0 - bottom1;
        span[4 * a + 2] = top1 - bottom0;
        span[4 * a + 3] = top1 - bottom1;
    }
    vec2 wx0 = vec2(1.0 - f0.x, f0.x), wx1 = vec2(1.0 - f1.x, f1.x);
    vec4 wy = vec4((1.0 - f0.y) * (1.0 - f1.y), f0.y * (1.0 - f1.y), (1.0 - f0.y) * f1.y, f0.y * f1.y);
    vec2 sum = vec2(0.0);
    for (int k = 0; k < 16; ++k) {
        int pL = k & 1, pR = (k >> 1) & 1, y = k >> 2;
        ivec4 rect = span[4 * (2 + pR) + y] - span[4 * pL + y];  // exact, then one rounding
        sum += (wx0[pL] * wx1[pR] * wy[y]) * vec2(sg_satSum(rect.x, rect.y), sg_satSum(rect.z, rect.w));
    }
    float area = max((hi.x - lo.x) * (hi.y - lo.y), 1e-6);
    return sum / (area * sg_kSatUnit);
}

// The layer's moment scale s: the table holds the moments of w = min(z s, 1).
float sg_summedMomentScale(sg_GpuLight L, sg_Tap center) { return sg_layers[L.firstLayer + center.layer].momentScale; }

// The moments (E[z], E[z^2], stored units) of a region of radius `radius` metres about `center`:
// a square of half-width r sqrt(3) / 2, whose variance along each axis, (2 h)^2 / 12 = r^2 / 4,
// is that of the disk PCF and PCSS filter with; at least one texel. Depths beyond 1 / s read as
// 1 / s (no caster lies there: sg_summedReference compares receivers beyond it there).
vec2 sg_summedRegionMoments(int slot, sg_GpuLight L, sg_Receiver r, sg_Tap center, float radius) {
    float halfTexels = max(0.8660254 * radius / max(r.texelMetres, 1e-30), 0.5);
    float s = sg_summedMomentScale(L, center);
    return sg_summedSquareMoments(slot, center.layer, center.uv, halfTexels) / vec2(s, s * s);  // exact: s = 2^k
}

// The receiver's reference depth against the table's moments: no farther than 1 / s, where the
// table holds every depth beyond (only receivers lie there), and one unit of the fixed point
// nearer: a receiver within rounding of its region's mean is its own plane.
float sg_summedReference(sg_GpuLight L, sg_Receiver r, sg_Tap center) {
    float s = sg_summedMomentScale(L, center);
    return min(sg_momentsReference(r, center), 1.0 / s) - 1.0 / (s * sg_kSatUnit);
}

// The least variance of a region's moments from the table: VSM's (sg_varianceFloor), and never
// below that of a depth rounded to the fixed point, (2^-24 / s)^2 / 12.
float sg_summedVarianceFloor(sg_GpuLight L, sg_Receiver r, sg_Tap center, vec2 m) {
    float unit = 1.0 / (sg_summedMomentScale(L, center) * sg_kSatUnit);
    return max(sg_varianceFloor(r, m), unit * unit / 12.0);
}

#endif
