// The cut-out test of a material with alpha mode MASK or BLEND (`Material::cutout`), one rule for
// every pass that draws it (shadow depth, depth pre-pass) and for the reference tracer
// (reference/ray_scene.cpp): a surface is a hole where base alpha x texture alpha < cutoff.
#ifndef SG_ALPHA_TEST
#define SG_ALPHA_TEST
#include "shared_constants.h"

layout(binding = SG_UNIT_BASE_COLOR) uniform sampler2D uBaseColor;
uniform float uAlpha;        // Material::alpha
uniform float uAlphaCutoff;  // Material::alphaCutoff

bool sg_isHole(vec2 texcoord) { return uAlpha * texture(uBaseColor, texcoord).a < uAlphaCutoff; }
#endif
