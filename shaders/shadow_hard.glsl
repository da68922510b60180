// Hard shadows: one bilinear comparison tap at the receiver (2x2 PCF from the gathered texels).
#ifndef SG_SHADOW_HARD
#define SG_SHADOW_HARD
#include "shadow_taps.glsl"

sg_ReceiverPolicy sg_hardPolicy() { return sg_planePolicy(); }

float sg_hardVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    return sg_compareTap(slot, L, r, sg_receiverTap(r));
}

#endif
