// Main pass and depth pre-pass: camera-relative positions keep float precision far from the origin.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;

uniform mat4 uCsFromLocal;      // object -> camera-relative world
uniform mat3 uNormalFromLocal;  // inverse transpose of its upper 3x3
uniform mat4 uClipFromCs;       // camera-relative world -> clip

out vec3 vCsPosition;
out vec3 vWsNormal;
// The depth pre-pass and the lit pass must rasterise the same depths (EQUAL test).
invariant gl_Position;

void main() {
    vec4 cs = uCsFromLocal * vec4(inPosition, 1.0);
    vCsPosition = cs.xyz;
    vWsNormal = uNormalFromLocal * inNormal;
    gl_Position = uClipFromCs * cs;
}
