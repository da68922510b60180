// Percentage-closer filtering over a disk of lateral metres at the receiver.
//
// Reference: W. Reeves, D. Salesin, R. Cook, "Rendering Antialiased Shadows with Depth Maps",
// SIGGRAPH 1987.
#ifndef SG_SHADOW_PCF
#define SG_SHADOW_PCF
#include "shadow_hard.glsl"
#include "shadow_kernels.glsl"

// Percentage-closer filtering over a disk of `radius` metres (lateral, at the receiver).
float pcfVisibility(int slot, GpuLight L, Receiver r, float radius, int samples) {
    if (radius <= 0.0 || samples <= 1) return hardVisibility(slot, L, r);
    DiskWalk disk = beginDisk(pixelRotation(), samples);
    float sum = 0.0;
    for (int i = 0; i < samples; ++i) {
        sum += compareTap(slot, L, r, lateralTap(L, r, nextDiskSample(L.kernel, disk, i) * radius));
    }
    return sum / float(samples);
}

#endif
