// glTF materials to engine `Material`s: the metallic-roughness model with every texture of the
// core specification, KHR_texture_transform and KHR_materials_emissive_strength.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <tiny_gltf.h>

#include "scene/gltf_textures.h"

#include <array>
#include <string>

namespace shadow::gltf {

/// A material as imported, with what its primitive must read for it.
struct MaterialImport {
    Material material;
    /// The glTF TEXCOORD_n set behind the mesh's set 0 (`MeshData::texcoords`) and set 1
    /// (`texcoords1`); -1 where no texture reads one. The base colour's set is set 0.
    std::array<int, 2> texcoordSets{-1, -1};
    /// The base colour's KHR_texture_transform, which the primitive bakes into its set 0 (the
    /// other maps of set 0 carry its inverse already).
    glm::mat3x2 baseTransform{1.0f};
};

/// `materials[index]`; the default `Material` for index -1. `where` names the referring
/// element. Factors are clamped to their ranges ([0, 1]; the emissive strength to [0, 1e6]); a
/// texture that does not exist, a texCoord outside [0, 7], a KHR_texture_transform member of the
/// wrong type and a material whose textures read more than two TEXCOORD sets are errors naming
/// the element. `doubleSided` is the file's.
[[nodiscard]] Result<MaterialImport> importMaterial(const tinygltf::Model& model, int index, const std::string& where,
                                                    TextureImporter& textures);

}  // namespace shadow::gltf
