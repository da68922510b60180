// glTF meshes and materials to engine `MeshData` and `Material`s.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <shadow/warnings.h>
#include <tiny_gltf.h>

#include "scene/gltf_material.h"
#include "scene/gltf_textures.h"

#include <memory>
#include <string>
#include <vector>

namespace shadow::gltf {

/// One drawable primitive of a glTF mesh: its geometry and its material.
struct MeshPart {
    std::shared_ptr<const MeshData> data;
    Material material;
};

/// The drawable parts of `meshes[meshIndex]`, one per TRIANGLES primitive with at least one
/// triangle; primitives of other modes are skipped (the engine draws triangles only).
/// Primitives without NORMAL get flat normals; those without indices get sequential ones.
/// The TEXCOORD sets the material's textures read (at most two), the base colour's
/// KHR_texture_transform baked into the first (a primitive without a set its textures read is
/// drawn without those textures, each with a `MissingTexcoord` warning into `warnings`); a
/// normal map's TANGENT or computed tangents; JOINTS_0 and WEIGHTS_0 where present (weights
/// normalised to sum 1; a vertex without weight follows joint 0).
[[nodiscard]] Result<std::vector<MeshPart>> importMesh(const tinygltf::Model& model, std::size_t meshIndex,
                                                       TextureImporter& textures, std::vector<Warning>& warnings);

}  // namespace shadow::gltf
