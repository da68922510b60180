// Renderer::presentToTexture: the frame's linear colour, exposed and tone-mapped by the functions
// of tone_map.h, the same ones toneMapToSrgb8 runs on the CPU, into an 8-bit target whose row 0
// is the image's top row (as the CPU's images and a UI's texture coordinates have it).
#include "tone_map.h"

layout(binding = 0) uniform sampler2D sg_frameColor;
uniform float sg_exposure;

layout(location = 0) out vec4 sg_outDisplay;

void main() {
    ivec2 size = textureSize(sg_frameColor, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 c = max(texelFetch(sg_frameColor, ivec2(p.x, size.y - 1 - p.y), 0).rgb * sg_exposure, vec3(0.0));
    float scale = sg_toneScale(sg_luminance(c.r, c.g, c.b), max(c.r, max(c.g, c.b)));
    sg_outDisplay = vec4(sg_srgbEncode(c.r * scale), sg_srgbEncode(c.g * scale), sg_srgbEncode(c.b * scale), 1.0);
}
