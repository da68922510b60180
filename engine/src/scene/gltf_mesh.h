// glTF meshes and materials to engine `MeshData` and `Material`s.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <shadow/warnings.h>
#include <tiny_gltf.h>

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
/// TEXCOORD_n is read where the material's base-colour texture uses it (a primitive without
/// that set is drawn without the texture, with a `MissingTexcoord` warning into `warnings`);
/// JOINTS_0 and WEIGHTS_0 where present (weights normalised to sum 1; a vertex without weight
/// follows joint 0).
[[nodiscard]] Result<std::vector<MeshPart>> importMesh(const tinygltf::Model& model, std::size_t meshIndex,
                                                       TextureImporter& textures, std::vector<Warning>& warnings);

/// `materials[index]` with its metallic-roughness factors (diffuse = base colour x
/// (1 - metallic), specular = mix(0.04, base colour, metallic)), with its base-colour texture
/// and alpha mode; the default `Material` for index -1. `where` names the referring element.
/// Factors are clamped to [0, 1]. `texCoord` receives the TEXCOORD set the texture reads.
[[nodiscard]] Result<Material> importMaterial(const tinygltf::Model& model, int index, const std::string& where,
                                              TextureImporter& textures, int& texCoord);

}  // namespace shadow::gltf
