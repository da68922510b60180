// One level of a shadow layer's moment chain, drawn as one full-screen triangle over the level:
// each texel holds the means of the powers of the stored depth over its tile of the map, 2^level
// texels wide: z and z^2 (VSM), or z, z^2, z^3 and z^4 (MSM-soft; the chain's format keeps what
// it holds), so a trilinear fetch at level log2(w) gives the moments of a region about w texels
// wide. The first level a layer's lookups read (ShadowLayerPlan::chainFirstLevel: 1, or above
// for a VSM layer whose filter is wider wherever a receiver can be; their level-0 fetches come
// from the depth map itself, sg_texelMoments) is drawn straight from the depth map
// (SG_CHAIN_FROM_DEPTH): each texel the mean over its 2^k x 2^k tile of depth texels, by gathers
// of 2x2 (the same means as k halvings, which leave the same texels out of a level of odd size).
// Every level above averages the 2x2 texels of the level below (of a level of odd size, the last
// row and column are left to the level's floor, as GL's own mipmaps round). The levels below the
// first are never made, and the depth pass writes no moments: the chain costs a read of the map.
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
uniform int uLevel;  // the level drawn: tiles of 2^uLevel texels
#else
// The layer's view, its base level the level below the one drawn (the only level it shows).
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2D uBelow;
#endif

layout(location = 0) out vec4 oMoments;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    // One program per case, no `if` between them: llvmpipe runs both sides of an `if`, even on a
    // uniform, and the first from-depth level of an MSM-soft chain cost a third more for it.
#ifdef SG_CHAIN_FROM_DEPTH
    // Gathers at the corner each 2x2 block of the tile shares: exactly those four texels; one
    // for a tile of 2 (SG_CHAIN_TILE 2, level 1), a loop over the tile's blocks for wider tiles
    // (SG_CHAIN_TILE 0, the tile 2^uLevel).
    vec2 texelSize = 1.0 / vec2(textureSize(uDepth, 0).xy);
#if SG_CHAIN_TILE == 2
    const int tile = 2;
#else
    int tile = 1 << uLevel;
#endif
    vec4 sum = vec4(0.0);
    for (int y = 0; y < tile; y += 2) {
        for (int x = 0; x < tile; x += 2) {
            vec4 d = textureGather(uDepth, vec3((vec2(texel * tile + ivec2(x, y)) + 1.0) * texelSize, float(uLayer)));
            sum += sg_depthMoments(d.x) + sg_depthMoments(d.y) + sg_depthMoments(d.z) + sg_depthMoments(d.w);
        }
    }
    oMoments = sum / float(tile * tile);
#else
    // One bilinear fetch at the corner the 2x2 texels share: their mean, weights 1/2 and 1/2
    // exactly.
    oMoments = textureLod(uBelow, (2.0 * vec2(texel) + 1.0) / vec2(textureSize(uBelow, 0)), 0.0);
#endif
}
