// What the module's mesh programs (the main pass's lit.vert.glsl and the shadow pass's
// shadow_depth.vert.glsl) share: the vertex attributes of a `MeshCache` mesh, morph targets
// and skinning.
//
// Deformation is compiled in, not branched on: a program is built for each kind of draw it
// meets (gpu::meshDeform: rigid, SG_SKINNED, SG_MORPHED or both), so a rigid draw runs none of
// it. (As loops on a uniform, skinning's and morphing's code cost a rigid bunny's shadow pass a
// third of its time on llvmpipe, which runs the vertex shader of each vertex in full.)
// A skinned draw binds the pose's joint matrices (frame-from-mesh, `Skin::frameFromMesh`) at
// SG_BINDING_JOINTS; its object transform is then the skin's frame (`Skin::worldFromFrame`). One
// path on the GPU for every pass, so a shadow follows its skin exactly.
#ifndef SG_MESH_VERTEX
#define SG_MESH_VERTEX
#include "shared_constants.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord;
layout(location = 3) in uvec4 inJoints;
layout(location = 4) in vec4 inWeights;
#ifdef SG_MATERIAL_MAPS
// A material with maps (shaders/material.glsl): the mesh's second texture-coordinate set and its
// normal map's tangents (xyz, w the handedness); (0, 0, 0, 1) where the mesh has none.
layout(location = SG_ATTRIB_TEXCOORD1) in vec2 inTexcoord1;
layout(location = SG_ATTRIB_TANGENT) in vec4 inTangent;
#endif

#ifdef SG_SKINNED
layout(std430, binding = SG_BINDING_JOINTS) readonly buffer sg_JointBlock {
    mat4 sg_jointFromMesh[];
};
#endif

// The vertex's blend of its joints' matrices (weights sum to 1); the identity for a rigid draw.
// Normals take its upper 3x3: exact for joints without non-uniform scale.
mat4 sg_skinMatrix() {
#ifdef SG_SKINNED
    uint joints = uint(sg_jointFromMesh.length());
    mat4 m = mat4(0.0);
    for (int k = 0; k < 4; ++k) {
        if (inWeights[k] > 0.0 && inJoints[k] < joints) m += inWeights[k] * sg_jointFromMesh[inJoints[k]];
    }
    return m;
#else
    return mat4(1.0);
#endif
}

// Morph targets (SG_MORPHED: a `Morph` with targets drawn): uMorphCount (<=
// SG_MAX_MORPH_INFLUENCES) influences, each (target, weight), displace the vertex before it is
// skinned (glTF). The mesh's displacements are at SG_BINDING_MORPH_DELTAS, vertex-major: vertex
// v's of target t at (v * uMorphTargets + t) * 3, position, normal and tangent in turn.
#ifdef SG_MORPHED
layout(std430, binding = SG_BINDING_MORPH_DELTAS) readonly buffer sg_MorphBlock {
    vec4 sg_morphDeltas[];
};
uniform int uMorphCount;
uniform int uMorphTargets;
uniform vec2 uMorphInfluences[SG_MAX_MORPH_INFLUENCES];
#endif

// The vertex in the mesh's space, its drawn targets' weighted displacements added: one loop for
// every attribute (a program that reads no normal or tangent, the shadow pass's, compiles their
// sums away). The normal is not renormalised: the fragment stage normalises its interpolated
// normal.
struct sg_MorphedVertex {
    vec3 position;
    vec3 normal;
    vec3 tangent;  // the displacement of the tangent's xyz (the tangent itself is an attribute of
                   // the material programs only)
};

sg_MorphedVertex sg_morphedVertex() {
    sg_MorphedVertex v = sg_MorphedVertex(inPosition, inNormal, vec3(0.0));
#ifdef SG_MORPHED
    for (int i = 0; i < uMorphCount; ++i) {
        int at = (gl_VertexID * uMorphTargets + int(uMorphInfluences[i].x)) * 3;
        float w = uMorphInfluences[i].y;
        v.position += w * sg_morphDeltas[at].xyz;
        v.normal += w * sg_morphDeltas[at + 1].xyz;
        v.tangent += w * sg_morphDeltas[at + 2].xyz;
    }
#endif
    return v;
}
#endif
