// One level of a shadow layer's moment chain, drawn as one full-screen triangle over the level
// (level 0 only when the depth pass did not write it, SG_DEPTH_MOMENTS in shadow_depth.frag.glsl):
// each texel holds the means of the powers of the stored depth over its tile of the map, 2^level
// texels wide: z and z^2 (VSM), or z, z^2, z^3 and z^4 (MSM and MSM-soft; the chain's format
// keeps what it holds). Level 0 (SG_CHAIN_FROM_DEPTH) reads one depth texel, every further level
// averages the 2x2 texels of the level below (of a level of odd size, the last row and column
// are left to the level's floor, as GL's own mipmaps round), so a trilinear fetch at level log2(w) gives the moments of a region about w texels wide.
//
// Draws, not compute dispatches: on llvmpipe an image store costs about 27 ns per texel, more
// than the fragment pipeline's whole write of it (builtin:default, `--technique vsm --no-cache`:
// the chain of 9 layers, 1024^2 and 512^2, 196 ms by dispatches, see stats.json's
// `Shadow/<light>/moments<k>`). Not the driver's mipmap generation either: llvmpipe's maps the
// whole texture, every layer, for each layer's call.
//
// References: W. Donnelly, A. Lauritzen, "Variance Shadow Maps", I3D 2006 (the seeds' notes on
// VSM/VSSM); C. Peters, R. Klein, "Moment Shadow Mapping", I3D 2015.
#include "shadow_common.glsl"
#include "shared_constants.h"

#ifdef SG_CHAIN_FROM_DEPTH
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uDepth;  // the layer's depth map
uniform int uLayer;
#else
// The layer's view, its base level the level below the one drawn (the only level it shows).
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2D uBelow;
#endif

layout(location = 0) out vec4 oMoments;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
#ifdef SG_CHAIN_FROM_DEPTH
    oMoments = sg_depthMoments(texelFetch(uDepth, ivec3(texel, uLayer), 0).r);
#else
    // One bilinear fetch at the corner the 2x2 texels share: their mean, weights 1/2 and 1/2
    // exactly.
    oMoments = textureLod(uBelow, (2.0 * vec2(texel) + 1.0) / vec2(textureSize(uBelow, 0)), 0.0);
#endif
}
