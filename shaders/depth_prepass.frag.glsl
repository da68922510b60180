// Depth pre-pass: depth only, through the lit pass's own vertex shader (invariant position), so
// the lit pass can test EQUAL and shade each visible pixel once. With SG_ALPHA_TESTED (cut-out
// materials) it leaves the holes out; the lit pass draws no discard of its own: a hole's pixel
// holds the depth of what lies behind, which the cut-out surface's fragment does not equal.
// Read with SG_ALPHA_TESTED only (an include may not stand under a condition).
#include "alpha_test.glsl"
in vec4 vCsPositionU;  // lit.vert.glsl: position and texture u
in vec4 vWsNormalV;    // normal and texture v

void main() {
#ifdef SG_ALPHA_TESTED
    if (sg_isHole(vec2(vCsPositionU.w, vWsNormalV.w))) discard;
#endif
}
