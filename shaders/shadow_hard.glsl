// Hard shadows: one bilinear comparison tap at the receiver (2x2 PCF from the sampler).
#ifndef SG_SHADOW_HARD
#define SG_SHADOW_HARD
#include "shadow_receiver.glsl"

float hardVisibility(int slot, GpuLight L, Receiver r) {
    return compareTap(slot, L, r, lateralTap(L, r, vec2(0.0)));
}

#endif
