// Shadow pass: stores *linear* light-space depth, normalised by the layer's depth scale, so
// every filter works in metres (docs/output_contract.md): distance along the axis for orthographic layers,
// distance from the light for perspective ones. Float32 depth keeps 24 bits of relative
// precision at every distance, where non-linear NDC depth would lose the far range.
#include "shadow_common.glsl"

in vec3 vLsPosition;

uniform float uDepthScale;
uniform int uOrthographic;

void main() {
    gl_FragDepth = sg_lightSpaceDepth(vLsPosition, uOrthographic != 0) / uDepthScale;
}
