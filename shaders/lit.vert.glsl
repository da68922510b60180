// Main pass and depth pre-pass: camera-relative positions keep float precision far from the origin.
#include "mesh_vertex.glsl"

uniform mat4 uCsFromLocal;      // object -> camera-relative world
uniform mat3 uNormalFromLocal;  // inverse transpose of its upper 3x3
uniform mat4 uClipFromCs;       // camera-relative world -> clip

out vec3 vCsPosition;
out vec3 vWsNormal;
out vec2 vTexcoord;
// The depth pre-pass and the lit pass must rasterise the same depths (EQUAL test).
invariant gl_Position;

void main() {
    mat4 skin = sg_skinMatrix();
    vec4 cs = uCsFromLocal * (skin * vec4(inPosition, 1.0));
    vCsPosition = cs.xyz;
    vWsNormal = uNormalFromLocal * (mat3(skin) * inNormal);
    vTexcoord = inTexcoord;
    gl_Position = uClipFromCs * cs;
}
