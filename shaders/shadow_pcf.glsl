// Percentage-closer filtering over a disk of lateral metres at the receiver, with as many taps
// as the disk's area in texels asks for, and none where the min/max pyramid shows the whole disk
// lit or in umbra.
//
// Reference: W. Reeves, D. Salesin, R. Cook, "Rendering Antialiased Shadows with Depth Maps",
// SIGGRAPH 1987.
#ifndef SG_SHADOW_PCF
#define SG_SHADOW_PCF
#include "shadow_hard.glsl"
#include "shadow_kernels.glsl"
#include "shadow_region.glsl"

// Taps a disk of `radiusTexels` texels needs: about one per texel of its area (each tap is a 2x2
// bilinear filter itself), at least one, at most `samples`.
int tapsFor(float radiusTexels, int samples) {
    return clamp(int(ceil(radiusTexels * radiusTexels)), 1, max(samples, 1));
}

// The four comparisons of the 2x2 texels around the tap (textureGather with a reference): four
// samples of the filter for one fetch.
float gatherTap(int slot, GpuLight L, Receiver r, Tap t) {
    return dot(compareQuad(slot, L, r, t).lit, vec4(0.25));
}

// The mean of `taps` samples over a disk of `radius` metres; a single sample is one bilinear tap
// at the receiver. With `gathers`, 3 taps / 4 fetches of 2x2 comparisons each (three times the
// samples for three quarters of the fetches; on the bunny scene the same error as bilinear taps
// within 1.2 %, half as many gathers measured up to 2.8 % more). A loop, not a branch: with
// taps = 0 in a whole SIMD group it costs one empty trip.
float pcfTaps(int slot, GpuLight L, Receiver r, float radius, int taps, const bool gathers) {
    int fetches = gathers && taps > 1 ? (taps * 3 + 3) / 4 : taps;
    DiskWalk disk = beginDisk(pixelRotation(), fetches);
    float sum = 0.0;
    for (int i = 0; i < fetches; ++i) {
        Tap t = lateralTap(L, r, nextDiskSample(L.kernel, disk, i) * (taps > 1 ? radius : 0.0));
        sum += gathers && taps > 1 ? gatherTap(slot, L, r, t) : compareTap(slot, L, r, t);
    }
    return sum / float(max(fetches, 1));
}

// PCF of the light's own radius (`pcfRadius`, at most `maxFilterTexels` texels).
float pcfVisibility(int slot, GpuLight L, Receiver r) {
    float radius = min(L.pcfRadius, L.maxFilterTexels * r.texelMetres);
    Tap center = lateralTap(L, r, vec2(0.0));
    float known = regionVisibility(slot, L, r, center, radius);
    int taps = known >= 0.0 ? 0 : tapsFor(radius / r.texelMetres, L.pcfSamples);
    float filtered = pcfTaps(slot, L, r, radius, taps, true);
    return known >= 0.0 ? known : filtered;
}

#endif
