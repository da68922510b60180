// The screen-space visibility stage's coverage at a reduced resolution (SG_VIS_DIVISOR d): depth
// 0 where the sample of a d x d block (its centre pixel) is a surface that receives shadows, 1
// elsewhere. The stage at that resolution is then depth-tested against it (its triangle at the
// far plane, GREATER), so a CPU rasteriser skips the blocks of samples with nothing to shade
// before they run the lights' filters, which then run straight-line (no loop to skip them).
#include "screen_gbuffer.glsl"

void main() {
    ivec2 src = min(ivec2(gl_FragCoord.xy) * SG_VIS_DIVISOR + SG_VIS_DIVISOR / 2,
                    textureSize(sg_gbufferSurface, 0) - 1);
    gl_FragDepth = sg_gbufferReceives(texelFetch(sg_gbufferSurface, src, 0)) ? 0.0 : 1.0;
}
