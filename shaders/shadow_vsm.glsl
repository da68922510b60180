// Variance shadow maps: the moments chain (shadow_moments.comp.glsl) holds the mean stored depth
// and mean squared stored depth of every tile of the map, so one trilinear fetch gives a filter
// region's mean and variance, whatever its width. Chebyshev's one-sided inequality bounds the
// fraction of the region at least as far as the receiver, P(z >= t) <= var / (var + (t - mean)^2)
// for t > mean, and the bound is taken as the visibility. Where casters overlap at different
// depths the bound is loose and light leaks (the seeds' VSSM notes): bounds below
// `lightBleedReduction` read as shadow and the rest is stretched back to [0, 1].
//
// Reference: W. Donnelly, A. Lauritzen, "Variance Shadow Maps", I3D 2006; A. Lauritzen,
// "Summed-Area Variance Shadow Maps", GPU Gems 3, 2007 (light-bleeding reduction).
#ifndef SG_SHADOW_VSM
#define SG_SHADOW_VSM
#include "shadow_receiver.glsl"

// Relative float error of a stored second moment, in units of its value: a few ulps of the mean
// of squares, which E[z^2] - E[z]^2 cancels down to.
const float kVsmMomentUlps = 4.0 * 1.1920929e-7;

// Chebyshev's bound for a receiver at `reference` (stored units) and a region of moments `m`,
// with the variance at least `minVariance`.
float chebyshevUpperBound(vec2 m, float reference, float minVariance) {
    float variance = max(m.y - m.x * m.x, minVariance);
    float d = reference - m.x;
    return d <= 0.0 ? 1.0 : variance / (variance + d * d);
}

float vsmVisibility(int slot, GpuLight L, Receiver r) {
    Tap center = lateralTap(L, r, vec2(0.0));
    // A square about 2 * pcfRadius wide at the receiver, as PCF's disk, in this layer's texels:
    // mip level log2(width) averages tiles of that width (trilinear between two levels).
    float radiusTexels = min(L.pcfRadius / max(r.texelMetres, 1e-30), L.maxFilterTexels);
    float level = log2(max(2.0 * radiusTexels, 1.0));
    vec2 m = textureLod(uShadowMinMax[slot], vec3(center.uv, float(center.layer)), level).rg;
    float reference = (center.depth - r.depthBias) / r.depthScale;
    // The least variance is the spread of depths within one texel of the receiver's own plane
    // (a plane's texels are not one depth), and never below the moments' float resolution.
    float texelSpread = r.depthSlope * r.texelMetres / r.depthScale;
    float minVariance = max(texelSpread * texelSpread / 12.0, kVsmMomentUlps * m.y);
    float p = chebyshevUpperBound(m, reference, minVariance);
    float cut = clamp(L.lightBleedReduction, 0.0, 0.95);
    return clamp((p - cut) / (1.0 - cut), 0.0, 1.0);
}

#endif
