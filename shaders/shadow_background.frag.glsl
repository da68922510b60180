// The last step of a moment technique's layer with backgrounds (ShadowLayerPlan::backgrounds):
// the farthest background depth, drawn into the scratch only where the layer holds no caster
// (shadow_depth.frag.glsl with SG_DEPTH_BACKGROUND), written into those texels of the layer.
// The scratch keeps its clear value 0 everywhere else: those fragments are discarded, and the
// layer keeps its casters and, where there is neither, the far depth.
#include "shared_constants.h"

layout(binding = SG_UNIT_MINMAX_SOURCE) uniform sampler2D uBackground;

void main() {
    float depth = texelFetch(uBackground, ivec2(gl_FragCoord.xy), 0).r;
    if (depth <= 0.0) discard;
    gl_FragDepth = depth;
}
