// What the module's mesh programs (the main pass's lit.vert.glsl and the shadow pass's
// shadow_depth.vert.glsl) share: the vertex attributes of a `MeshCache` mesh, morph targets
// and skinning.
//
// A skinned draw (a `Skin` on the instance) sets uSkinned = 1 and binds the pose's joint matrices
// (frame-from-mesh, `Skin::frameFromMesh`) at SG_BINDING_JOINTS; its object transform is then the
// skin's frame (`Skin::worldFromFrame`); uSkinned is 0 or 1. One path on the GPU for every pass, so a shadow follows
// its skin exactly. A rigid draw sets uSkinned = 0 and reads no joint.
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

layout(std430, binding = SG_BINDING_JOINTS) readonly buffer sg_JointBlock {
    mat4 sg_jointFromMesh[];
};
uniform int uSkinned;

// The vertex's blend of its joints' matrices (weights sum to 1); the identity for a rigid draw.
// Normals take its upper 3x3: exact for joints without non-uniform scale.
mat4 sg_skinMatrix() {
    // Loops, not ifs (a CPU rasteriser runs both sides of an if): a rigid draw takes no trip.
    mat4 m = mat4(1.0);
    for (int rigid = 0; rigid < uSkinned; ++rigid) {
        uint joints = uint(sg_jointFromMesh.length());
        m = mat4(0.0);
        for (int k = 0; k < 4; ++k) {
            if (inWeights[k] > 0.0 && inJoints[k] < joints) m += inWeights[k] * sg_jointFromMesh[inJoints[k]];
        }
    }
    return m;
}

// Morph targets (a `Morph` with targets drawn): uMorphCount (<= SG_MAX_MORPH_INFLUENCES)
// influences, each (target, weight), displace the vertex before it is skinned (glTF). The mesh's
// displacements are at SG_BINDING_MORPH_DELTAS, vertex-major: vertex v's of target t at
// (v * uMorphTargets + t) * 3, position, normal and tangent in turn. uMorphCount = 0 (a rigid
// draw, or every weight 0) reads none, in the same loop-not-if shape as skinning.
layout(std430, binding = SG_BINDING_MORPH_DELTAS) readonly buffer sg_MorphBlock {
    vec4 sg_morphDeltas[];
};
uniform int uMorphCount;
uniform int uMorphTargets;
uniform vec2 uMorphInfluences[SG_MAX_MORPH_INFLUENCES];

// The weighted displacement of attribute `a` (0 position, 1 normal, 2 tangent).
vec3 sg_morphDelta(int a) {
    vec3 d = vec3(0.0);
    for (int i = 0; i < uMorphCount; ++i) {
        int at = (gl_VertexID * uMorphTargets + int(uMorphInfluences[i].x)) * 3 + a;
        d += uMorphInfluences[i].y * sg_morphDeltas[at].xyz;
    }
    return d;
}
// The vertex's position and normal in the mesh's space, morphed (the normal not renormalised:
// the fragment stage normalises its interpolated normal).
vec3 sg_position() { return inPosition + sg_morphDelta(0); }
vec3 sg_normal() { return inNormal + sg_morphDelta(1); }
#endif
