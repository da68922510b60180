// Renderer::meterExposure: the exposure meter's histogram of the frame's linear colour (the bins
// of tone_map.h, as luminanceHistogram counts them on the CPU), for exposureFromHistogram.
//
// Each invocation counts a tile of SG_METER_TILE x SG_METER_TILE pixels and adds a run of pixels
// in the same bin with one atomic (neighbours mostly share a bin). Measured on llvmpipe at
// 1280x720 (fastest of 25): 17 ms with one atomic per pixel and 4x4 tiles, 35 ms with 16x16 work
// groups counting in shared memory first (their barriers cost more than the atomics they save).
#include "shared_constants.h"
#include "tone_map.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D sg_frameColor;
// The storage binding the module's passes use (the joint matrices'), which its GL state guard
// puts back for the host.
layout(std430, binding = SG_BINDING_JOINTS) buffer sg_ExposureBins {
    uint sg_exposureBins[SG_EXPOSURE_BINS];
};

void main() {
    ivec2 size = textureSize(sg_frameColor, 0);
    ivec2 base = ivec2(gl_GlobalInvocationID.xy) * SG_METER_TILE;
    int runBin = 0;
    uint run = 0u;
    for (int j = 0; j < SG_METER_TILE; ++j) {
        for (int i = 0; i < SG_METER_TILE; ++i) {
            ivec2 p = base + ivec2(i, j);
            if (p.x >= size.x || p.y >= size.y) continue;
            vec3 c = texelFetch(sg_frameColor, p, 0).rgb;
            float lum = sg_luminance(c.r, c.g, c.b);
            if (!sg_exposureCounted(lum)) continue;
            int bin = sg_exposureBin(lum);
            if (bin != runBin && run > 0u) {
                atomicAdd(sg_exposureBins[runBin], run);
                run = 0u;
            }
            runBin = bin;
            ++run;
        }
    }
    if (run > 0u) atomicAdd(sg_exposureBins[runBin], run);
}
