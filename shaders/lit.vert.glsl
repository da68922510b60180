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
#ifdef SG_MATERIAL_MAPS
// Only materials with maps pay for these (shaders/material.glsl).
out vec4 vWsTangent;  // xyz world tangent, w the handedness (a mirroring transform turns it)
out vec2 vTexcoord1;  // the second texture-coordinate set
#endif
// The depth pre-pass and the lit pass must rasterise the same depths (EQUAL test).
invariant gl_Position;

void main() {
    mat4 skin = sg_skinMatrix();
    sg_MorphedVertex v = sg_morphedVertex();
    vec4 cs = uCsFromLocal * (skin * vec4(v.position, 1.0));
    vCsPositionU = vec4(cs.xyz, inTexcoord.x);
    vWsNormalV = vec4(uNormalFromLocal * (mat3(skin) * v.normal), inTexcoord.y);
#ifdef SG_MATERIAL_MAPS
    // Tangents are directions on the surface: the object's matrix, not the normals' one.
    float mirrored = determinant(uNormalFromLocal) < 0.0 ? -1.0 : 1.0;
    vWsTangent = vec4(mat3(uCsFromLocal) * (mat3(skin) * (inTangent.xyz + v.tangent)), inTangent.w * mirrored);
    vTexcoord1 = inTexcoord1;
#endif
    gl_Position = uClipFromCs * cs;
}
