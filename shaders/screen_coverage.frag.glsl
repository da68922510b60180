// The screen-space visibility stage's coverage at a reduced resolution (SG_VIS_DIVISOR d): depth
// 0 where the sample of a d x d block (its centre pixel) is a surface that receives shadows, 1
// elsewhere. The stage at that resolution is then depth-tested against it (its triangle at the
// far plane, GREATER), so a CPU rasteriser skips the blocks of samples with nothing to shade
// before they run the lights' filters, which then run straight-line (no loop to skip them).
// With SG_COVERAGE_MARKS, at full resolution, the same for the correction of a deferred lit pass
// that resolved the stage itself (lit.frag.glsl): depth 0 where the lit pass marked a light of
// the group corrected.
#include "screen_gbuffer.glsl"

#ifdef SG_COVERAGE_MARKS
layout(binding = SG_UNIT_LIT_STAGE) uniform usampler2D uMarks;  // lit.frag.glsl's SG_OUT_MARKS
uniform int uMarkBits;  // the slots of the group to correct, a bit each

void main() { gl_FragDepth = (texelFetch(uMarks, ivec2(gl_FragCoord.xy), 0).r & uint(uMarkBits)) != 0u ? 0.0 : 1.0; }
#else
void main() {
    ivec2 src = min(ivec2(gl_FragCoord.xy) * SG_VIS_DIVISOR + SG_VIS_DIVISOR / 2,
                    textureSize(sg_gbufferSurface, 0) - 1);
    gl_FragDepth = sg_gbufferReceives(texelFetch(sg_gbufferSurface, src, 0)) ? 0.0 : 1.0;
}
#endif
