// Percentage-closer filtering over a disk of lateral metres at the receiver (shared by PCF and
// PCSS): taps on the receiver's tangent plane, each a 2x2 comparison of its own.
//
// Reference: W. Reeves, D. Salesin, R. Cook, "Rendering Antialiased Shadows with Depth Maps",
// SIGGRAPH 1987.
#ifndef SG_SHADOW_FILTER
#define SG_SHADOW_FILTER
#include "shadow_taps.glsl"
#include "shadow_kernels.glsl"

// Taps a disk of `radiusTexels` texels needs: about one per texel of its area (each tap is a 2x2
// bilinear filter itself), at least one, at most `samples`.
int sg_tapsFor(float radiusTexels, int samples) {
    return clamp(int(ceil(radiusTexels * radiusTexels)), 1, max(samples, 1));
}

// The four comparisons of the 2x2 texels around the tap (textureGather with a reference): four
// samples of the filter for one fetch.
float sg_gatherTap(int slot, sg_GpuLight L, sg_Receiver r, sg_Tap t) {
    return dot(sg_compareQuad(slot, L, r, t).lit, vec4(0.25));
}

// The mean of `taps` samples over a disk of `radius` metres; a single sample is one bilinear tap
// at the receiver. With `gathers`, 3 taps / 4 fetches of 2x2 comparisons each: three times the
// samples for three quarters of the fetches, at the error of bilinear taps (docs/tuning.md). A
// loop, not a branch: with taps = 0 in a whole SIMD group it costs one empty trip.
float sg_pcfTaps(int slot, sg_GpuLight L, sg_Receiver r, float radius, int taps, const bool gathers) {
    int fetches = gathers && taps > 1 ? (taps * 3 + 3) / 4 : taps;
    sg_DiskWalk disk = sg_beginDisk(sg_pixelRotation(), fetches);
    float sum = 0.0;
    SG_ISOLATED
    for (int i = 0; i < fetches; ++i) {
        sg_Tap t = sg_lateralTap(L, r, sg_nextDiskSample(L.kernel, disk, i) * (taps > 1 ? radius : 0.0));
        sum += gathers && taps > 1 ? sg_gatherTap(slot, L, r, t) : sg_compareTap(slot, L, r, t);
    }
    return sum / float(max(fetches, 1));
}

#ifdef SG_STAGE_FEATURES
// The stage's samples, for a filter without a blocker search (PCF): a blocker and a texel that
// does not block within the sample's block report the filter's radius as its feature.
const int sg_kStageBlockGathers = 4;
void sg_stageBlockSearch(int slot, sg_GpuLight L, sg_Receiver r, float radius) {
    sg_DiskWalk disk = sg_beginDisk(sg_pixelRotation(), sg_kStageBlockGathers);
    float blocked = 0.0;
    for (int i = 0; i < sg_kStageBlockGathers; ++i) {
        sg_Tap t = sg_lateralTap(L, r, sg_nextDiskSample(L.kernel, disk, i) * max(sg_stageBlock, radius));
        blocked += dot(vec4(1.0) - sg_compareQuad(slot, L, r, t).lit, vec4(1.0));
    }
    if (blocked > 0.0 && blocked < 4.0 * float(sg_kStageBlockGathers)) SG_STAGE_FEATURE(radius);
}
#define SG_STAGE_BLOCK_SEARCH(slot, L, r, radius) sg_stageBlockSearch(slot, L, r, radius)
#else
#define SG_STAGE_BLOCK_SEARCH(slot, L, r, radius)
#endif

#endif
