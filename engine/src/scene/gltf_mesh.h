// glTF meshes and materials to engine `MeshData` and Blinn-Phong `Material`s.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <tiny_gltf.h>

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
[[nodiscard]] Result<std::vector<MeshPart>> importMesh(const tinygltf::Model& model, std::size_t meshIndex);

/// `materials[index]` mapped from metallic-roughness to Blinn-Phong; the default `Material`
/// for index -1. `where` names the referring element. Factors are clamped to [0, 1].
[[nodiscard]] Result<Material> importMaterial(const tinygltf::Model& model, int index, const std::string& where);

}  // namespace shadow::gltf
