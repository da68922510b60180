// Main pass and depth pre-pass: camera-relative positions keep float precision far from the origin.
#include "mesh_vertex.glsl"

uniform mat4 uCsFromLocal;      // object -> camera-relative world
uniform mat3 uNormalFromLocal;  // inverse transpose of its upper 3x3
uniform mat4 uClipFromCs;       // camera-relative world -> clip

// The texture coordinates ride in the w of the position and normal: two varyings, not three, so
// a CPU rasteriser sets up no more per triangle than before textures (measured on the bunny's
// 70 000 triangles at 1280x720: a third varying cost the main pass about 10 %).
out vec4 vCsPositionU;  // xyz camera-relative position, w texture u
out vec4 vWsNormalV;    // xyz world normal, w texture v
// The depth pre-pass and the lit pass must rasterise the same depths (EQUAL test).
invariant gl_Position;

void main() {
    mat4 skin = sg_skinMatrix();
    vec4 cs = uCsFromLocal * (skin * vec4(inPosition, 1.0));
    vCsPositionU = vec4(cs.xyz, inTexcoord.x);
    vWsNormalV = vec4(uNormalFromLocal * (mat3(skin) * inNormal), inTexcoord.y);
    gl_Position = uClipFromCs * cs;
}
