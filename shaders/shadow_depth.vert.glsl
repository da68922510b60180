// Shadow pass: one layer of a light's shadow-map array, depth only.
#include "mesh_vertex.glsl"

uniform mat4 uLightFromLocal;  // object -> light view (m)
uniform mat4 uClipFromLight;

out vec3 vLsPosition;
out vec2 vTexcoord;

void main() {
    vec4 ls = uLightFromLocal * (sg_skinMatrix() * vec4(sg_morphedVertex().position, 1.0));
    vLsPosition = ls.xyz;
    vTexcoord = inTexcoord;
    gl_Position = uClipFromLight * ls;
}
