// The Hamburger 4MSM bound of moment shadow maps: the four-moment chain (shadow_moments.frag.glsl, an RGBA32F chain) holds
// the means of z, z^2, z^3 and z^4 over every tile of the map, so one trilinear fetch gives a
// filter region's first four power moments. Of all depth distributions with those moments, the
// Hamburger 4MSM reconstruction takes the one that puts the most weight in front of the
// receiver (three depths: the receiver's and two more, the roots of a quadratic), and reads its
// weight in front as the shadowed fraction: a sharp bound where VSM's two moments are loose, so
// much less light leaks where casters overlap at different depths.
//
// The moments are pulled towards those of a fixed distribution by `sg_kMsmMomentBias` (alpha)
// before the reconstruction, which keeps the Hankel matrix of the moments positive definite
// whatever their float rounding; the depth bias is the receiver's own (r.depthBias).
//
// Reference: C. Peters, R. Klein, "Moment Shadow Mapping", I3D 2015 (Hamburger 4MSM); the seeds'
// notes on real-time shadows (MSM as the better estimate than VSM's Chebyshev bound).
#ifndef SG_SHADOW_HAMBURGER
#define SG_SHADOW_HAMBURGER
#include "shadow_moments.glsl"

// Moment bias alpha for single-precision moments: the least that leaves no acne; less puts acne
// on lit surfaces, more lets light into umbrae (docs/tuning.md).
const float sg_kMsmMomentBias = 3e-6;

// The fraction of a region's depths in front of `z` (stored units), bounded from the region's
// power moments `b` = (E[z], E[z^2], E[z^3], E[z^4]).
float sg_msmShadowFraction(vec4 b, float z) {
    // Stored depths are at most 1 (the far plane, a cleared texel): a mean of 1 is a region of
    // cleared texels only, with nothing in front of anything. (The biased moments would read a
    // trace of shadow there.)
    if (b.x >= 1.0) return 0.0;
    // The bias below and the floors of the factorisation are sized for depths spread over [0, 1]:
    // a receiver near the light of a long range (z ~ 10^-6 under a 10^6 m range) would drown in
    // them. Below 1/4, the receiver and the moments are scaled by the power of two (exact) that
    // brings it to [1/4, 1/2): the bound is scale-invariant, the bias and floors are not.
    float scale = exp2(max(-floor(log2(max(z, 1e-30))) - 2.0, 0.0));
    b *= vec4(scale, scale * scale, scale * scale * scale, (scale * scale) * (scale * scale));
    z *= scale;
    b = mix(b, vec4(0.5), sg_kMsmMomentBias);
    // B = L D L^T for the Hankel matrix B = [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]], L unit
    // lower triangular; then B c = (1, z, z^2) by forward and back substitution.
    float d2 = max(b.y - b.x * b.x, 1e-12);
    float l32 = (b.z - b.x * b.y) / d2;
    float d3 = max(b.w - b.y * b.y - l32 * l32 * d2, 1e-12);
    float y2 = (z - b.x) / d2;
    float y3 = (z * z - b.y - l32 * (z - b.x)) / d3;
    float c3 = y3;
    float c2 = y2 - l32 * c3;
    float c1 = 1.0 - b.x * c2 - b.y * c3;
    // The other two support points: the roots of c3 x^2 + c2 x + c1.
    float root = sqrt(max(c2 * c2 - 4.0 * c3 * c1, 0.0));
    float inv = 0.5 / (abs(c3) > 1e-30 ? c3 : 1e-30);
    float za = (-c2 - root) * inv, zb = (-c2 + root) * inv;
    float z2 = min(za, zb), z3 = max(za, zb);
    if (z <= z2) return 0.0;
    if (z <= z3) return clamp((z * z3 - b.x * (z + z3) + b.y) / max((z3 - z2) * (z - z2), 1e-30), 0.0, 1.0);
    return clamp(1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / max((z - z2) * (z - z3), 1e-30), 0.0, 1.0);
}

// Where the filter region of radius `radius` (m) spans, the receiver's own plane holds depths
// from t - slope x reach to t + slope x reach, and the 4MSM bound, sharp as it is, reads the
// near half of them as occluders (acne at grazing light). VSM escapes this through Chebyshev's
// one-sided rule (a mean at or beyond the receiver is lit); MSM compares the plane's nearest
// depth in the region instead, this many radii away: the least reach that clears acne down to
// 0.5 degrees (tests/stability/grazing_light_test.cpp holds it there). The price is light in
// umbrae on curved receivers, where the plane's spread is not the surface's, and contact only as
// wide as the region (msm: one texel; msm-soft: the penumbra, which closes at contact); figures
// in docs/tuning.md.
const float sg_kMsmPlaneReach = 1.0;

float sg_msmReference(sg_Receiver r, sg_Tap center, float radius) {
    return sg_momentsReference(r, center) - sg_kMsmPlaneReach * r.depthSlope * radius / r.depthScale;
}

#endif
