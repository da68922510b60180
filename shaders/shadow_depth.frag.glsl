// Shadow pass: stores *linear* light-space depth, normalised by the layer's depth scale, so
// every filter works in metres (docs/output_contract.md): distance along the axis for orthographic layers,
// distance from the light for perspective ones. Float32 depth keeps 24 bits of relative
// precision at every distance, where non-linear NDC depth would lose the far range.
//
// With SG_DEPTH_BEHIND_FIRST (the second-depth modes, DepthMode in components.h) this is the
// second of a layer's two passes: uNearest holds the first pass's nearest depth, every fragment
// at or in front of it is discarded, and the depth test keeps the nearest surface behind it.
// SG_DEPTH_MIDPOINT stores the mean of the two, which grows with the second depth, so the same
// depth test keeps the right surface. Where no surface lies behind the first the layer keeps
// its clear value, the far depth.
//
// With SG_DEPTH_BACKGROUND this draws a moment technique's backgrounds (the receivers that do
// not cast, ShadowLayerPlan::backgrounds) into the scratch, tested GREATER against its clear
// value 0, so that it keeps the farthest: only where the layer uCasters, drawn already, holds no
// caster (the far depth). shadow_background.frag.glsl then copies them into the layer.
//
// With SG_ALPHA_TESTED (a cut-out caster, `Material::cutout`) its holes are left out, by the same
// test as the main pass (alpha_test.glsl).
#include "shadow_common.glsl"
#include "shared_constants.h"
// Read with SG_ALPHA_TESTED only (an include may not stand under a condition).
#include "alpha_test.glsl"
in vec2 vTexcoord;

in vec3 vLsPosition;

uniform float uDepthScale;
uniform int uOrthographic;

#ifdef SG_DEPTH_BEHIND_FIRST
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2D uNearest;
// 1 in the first pass, which draws the nearest depth into uNearest's texture with this same
// program: the two passes then compute every surface's depth by the same instructions.
uniform int uFirstPass;

// How far behind the nearest depth a fragment must lie to be another surface: two ulps of the
// depth (the first surface is drawn by the same instructions in both passes, see uFirstPass),
// plus what the rasteriser's sub-texel placement of a steep surface moves its depth: a 1/128
// of the depth's change across a texel. Without the second term a surface seen at 0.5 degrees
// met itself again 0.1-1 mm behind (a row of texels whose midpoint was the surface itself,
// found by tests/stability/second_depth_test.cpp; 1/1024 still left it).
const float SG_BEHIND_ULPS = 2.4e-7;
const float SG_BEHIND_TEXEL_FRACTION = 1.0 / 128.0;
#endif

#ifdef SG_DEPTH_BACKGROUND
layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2DArray uCasters;
uniform int uLayer;
#endif

void main() {
    float depth = sg_lightSpaceDepth(vLsPosition, uOrthographic != 0) / uDepthScale;
#ifdef SG_DEPTH_BEHIND_FIRST
    float slope = fwidth(depth);  // outside the branch: derivatives need every fragment of the quad
#endif
#ifdef SG_ALPHA_TESTED
    if (sg_isHole(vTexcoord)) discard;
#endif
#ifdef SG_DEPTH_BEHIND_FIRST
    if (uFirstPass == 0) {
        float nearest = texelFetch(uNearest, ivec2(gl_FragCoord.xy), 0).r;
        if (depth <= nearest + SG_BEHIND_ULPS * max(1.0, nearest) + SG_BEHIND_TEXEL_FRACTION * slope) discard;
#ifdef SG_DEPTH_MIDPOINT
        depth = 0.5 * (nearest + depth);
#endif
    }
#endif
#ifdef SG_DEPTH_BACKGROUND
    if (texelFetch(uCasters, ivec3(ivec2(gl_FragCoord.xy), uLayer), 0).r < 1.0) discard;
#endif
    gl_FragDepth = depth;
}
