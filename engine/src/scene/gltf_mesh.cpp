#include "scene/gltf_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>

#include "scene/gltf_accessors.h"
#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

/// Unit normals where the file's are usable; zero-length ones stay zero (they light nothing,
/// and renormalising them would invent a direction).
void normalizeNormals(std::vector<glm::vec3>& normals) {
    for (glm::vec3& n : normals) {
        const float length = glm::length(n);
        if (length > 0.0f && std::isfinite(length)) n /= length;
    }
}

Status readNormals(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                   MeshData& mesh) {
    const auto it = primitive.attributes.find("NORMAL");
    if (it == primitive.attributes.end()) return Ok{};
    const std::string normalWhere = where + ".attributes.NORMAL";
    auto normals = readVec3(model, it->second, normalWhere);
    if (!normals) return normals.error();
    if (normals->size() != mesh.positions.size()) {
        return elementError(normalWhere, "has " + std::to_string(normals->size()) + " elements, POSITION has " +
                                             std::to_string(mesh.positions.size()));
    }
    mesh.normals = std::move(*normals);
    normalizeNormals(mesh.normals);
    return Ok{};
}

Status readTriangleIndices(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                           MeshData& mesh) {
    const std::size_t vertexCount = mesh.positions.size();
    if (primitive.indices >= 0) {
        auto indices = readIndices(model, primitive.indices, vertexCount, where + ".indices");
        if (!indices) return indices.error();
        mesh.indices = std::move(*indices);
    } else {
        // Bounded by the buffer size, so this allocation is no larger than the file.
        mesh.indices.resize(vertexCount);
        std::iota(mesh.indices.begin(), mesh.indices.end(), std::uint32_t{0});
    }
    if (mesh.indices.size() % 3 != 0) {
        return elementError(where, std::to_string(mesh.indices.size()) + " vertices do not make whole triangles");
    }
    return Ok{};
}

Status readTexcoordSet(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int set,
                       const std::string& where, MeshData& mesh) {
    const std::string semantic = "TEXCOORD_" + std::to_string(set);
    const auto it = primitive.attributes.find(semantic);
    if (it == primitive.attributes.end()) return Ok{};  // the caller warns and drops the texture
    const std::string uvWhere = where + ".attributes." + semantic;
    auto uv = readTexcoords(model, it->second, uvWhere);
    if (!uv) return uv.error();
    if (uv->size() != mesh.positions.size()) {
        return elementError(uvWhere, "has " + std::to_string(uv->size()) + " elements, POSITION has " +
                                         std::to_string(mesh.positions.size()));
    }
    mesh.texcoords = std::move(*uv);
    return Ok{};
}

/// JOINTS_0 and WEIGHTS_0 (both or neither); a skin checks the joint indices against its own
/// joints when a node uses the mesh.
Status readSkinning(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                    MeshData& mesh) {
    const auto joints = primitive.attributes.find("JOINTS_0");
    const auto weights = primitive.attributes.find("WEIGHTS_0");
    if (joints == primitive.attributes.end() && weights == primitive.attributes.end()) return Ok{};
    if (joints == primitive.attributes.end() || weights == primitive.attributes.end()) {
        return elementError(where, "has one of JOINTS_0 and WEIGHTS_0 without the other");
    }
    auto j = readJoints(model, joints->second, 65536, where + ".attributes.JOINTS_0");
    if (!j) return j.error();
    auto w = readWeights(model, weights->second, where + ".attributes.WEIGHTS_0");
    if (!w) return w.error();
    if (j->size() != mesh.positions.size() || w->size() != mesh.positions.size()) {
        return elementError(where, "JOINTS_0 and WEIGHTS_0 must have one element per POSITION (" +
                                       std::to_string(mesh.positions.size()) + ")");
    }
    for (glm::vec4& weight : *w) {
        weight = glm::max(weight, glm::vec4(0.0f));
        const float sum = weight.x + weight.y + weight.z + weight.w;
        weight = sum > 0.0f ? weight / sum : glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
    }
    mesh.joints = std::move(*j);
    mesh.weights = std::move(*w);
    return Ok{};
}

/// The warning for a texture that reads `TEXCOORD_<set>`, which the primitive at `where` lacks.
Warning missingTexcoord(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int set,
                        const std::string& where) {
    const auto m = static_cast<std::size_t>(primitive.material);
    const std::string& name = model.materials[m].name;
    return {WarningCode::MissingTexcoord, where,
            where + " has no TEXCOORD_" + std::to_string(set) + ", which " + indexed("materials", m) +
                (name.empty() ? "" : " (\"" + name + "\")") +
                ".pbrMetallicRoughness.baseColorTexture reads: the primitive is drawn without that texture"};
}

/// The mesh of one primitive; nullopt when it draws nothing (another mode, or empty).
Result<std::optional<MeshPart>> importPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                                const std::string& where, std::string name, TextureImporter& textures,
                                                std::vector<Warning>& warnings) {
    // -1 is what tinygltf leaves in a Model built in code; the file default is TRIANGLES.
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
        return std::optional<MeshPart>{};
    }
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) {
        return elementError(where, "has no POSITION attribute");
    }
    auto positions = readVec3(model, position->second, where + ".attributes.POSITION");
    if (!positions) return positions.error();
    if (positions->size() > std::numeric_limits<std::uint32_t>::max()) {
        return elementError(where, "too many vertices for 32-bit indices", ErrorCode::LimitExceeded);
    }
    auto mesh = std::make_shared<MeshData>();
    mesh->name = std::move(name);
    mesh->positions = std::move(*positions);
    if (auto st = readNormals(model, primitive, where, *mesh); !st) return st.error();
    if (auto st = readTriangleIndices(model, primitive, where, *mesh); !st) return st.error();
    if (mesh->indices.empty()) return std::optional<MeshPart>{};

    int texCoord = 0;
    auto material = importMaterial(model, primitive.material, where + ".material", textures, texCoord);
    if (!material) return material.error();
    if (material->baseColorTexture != nullptr) {
        if (auto st = readTexcoordSet(model, primitive, texCoord, where, *mesh); !st) return st.error();
        if (mesh->texcoords.empty()) {
            warnings.push_back(missingTexcoord(model, primitive, texCoord, where));
            material->baseColorTexture = nullptr;
        }
    }
    if (auto st = readSkinning(model, primitive, where, *mesh); !st) return st.error();
    if (mesh->normals.empty()) {
        makeFlatNormals(*mesh);
    } else {
        computeBounds(*mesh);
    }
    computeClosed(*mesh);
    computeJointBounds(*mesh);
    return std::optional<MeshPart>{MeshPart{std::move(mesh), *material}};
}

Result<glm::vec3> readBaseColor(const tinygltf::PbrMetallicRoughness& pbr, const std::string& where) {
    const std::vector<double>& f = pbr.baseColorFactor;
    if (f.size() != 4) return elementError(where, "must have 4 numbers");
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(f[static_cast<std::size_t>(c)])) return elementError(where, "not finite");
        rgb[c] = static_cast<float>(std::clamp(f[static_cast<std::size_t>(c)], 0.0, 1.0));
    }
    return rgb;
}

Result<float> readUnitFactor(double value, const std::string& where) {
    if (!std::isfinite(value)) return elementError(where, "not finite");
    return static_cast<float>(std::clamp(value, 0.0, 1.0));
}

}  // namespace

Result<std::vector<MeshPart>> importMesh(const tinygltf::Model& model, std::size_t meshIndex, TextureImporter& textures,
                                         std::vector<Warning>& warnings) {
    const tinygltf::Mesh& mesh = model.meshes[meshIndex];
    const std::string meshWhere = indexed("meshes", meshIndex);
    const std::string baseName = mesh.name.empty() ? "mesh" + std::to_string(meshIndex) : mesh.name;
    std::vector<MeshPart> parts;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        std::string name = mesh.primitives.size() == 1 ? baseName : baseName + "/primitive" + std::to_string(p);
        auto part = importPrimitive(model, mesh.primitives[p], meshWhere + "." + indexed("primitives", p),
                                    std::move(name), textures, warnings);
        if (!part) return part.error();
        if (part->has_value()) parts.push_back(std::move(**part));
    }
    return parts;
}

Result<Material> importMaterial(const tinygltf::Model& model, int index, const std::string& where,
                                TextureImporter& textures, int& texCoord) {
    texCoord = 0;
    if (index < 0) return Material{};
    if (static_cast<std::size_t>(index) >= model.materials.size()) {
        return elementError(where, "material " + std::to_string(index) + " does not exist");
    }
    const std::string materialWhere = indexed("materials", static_cast<std::size_t>(index));
    const std::string pbrWhere = materialWhere + ".pbrMetallicRoughness";
    const tinygltf::Material& material = model.materials[static_cast<std::size_t>(index)];
    const tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
    auto base = readBaseColor(pbr, pbrWhere + ".baseColorFactor");
    if (!base) return base.error();
    auto alpha =
        readUnitFactor(pbr.baseColorFactor.size() == 4 ? pbr.baseColorFactor[3] : 1.0, pbrWhere + ".baseColorFactor");
    if (!alpha) return alpha.error();
    auto metallic = readUnitFactor(pbr.metallicFactor, pbrWhere + ".metallicFactor");
    if (!metallic) return metallic.error();
    auto roughness = readUnitFactor(pbr.roughnessFactor, pbrWhere + ".roughnessFactor");
    if (!roughness) return roughness.error();
    auto cutoff = readUnitFactor(material.alphaCutoff, materialWhere + ".alphaCutoff");
    if (!cutoff) return cutoff.error();

    Material out;
    out.albedo = *base * (1.0f - *metallic);
    out.specular = glm::mix(glm::vec3(0.04f), *base, *metallic);
    out.metallic = *metallic;
    out.alpha = *alpha;
    out.alphaCutoff = material.alphaMode == "BLEND" ? 0.5f : *cutoff;
    if (material.alphaMode == "MASK") {
        out.alphaMode = AlphaMode::Mask;
    } else if (material.alphaMode == "BLEND") {
        out.alphaMode = AlphaMode::Blend;
    } else if (!material.alphaMode.empty() && material.alphaMode != "OPAQUE") {
        return elementError(materialWhere + ".alphaMode",
                            "must be OPAQUE, MASK or BLEND, not \"" + material.alphaMode + "\"");
    }
    if (pbr.baseColorTexture.index >= 0) {
        const std::string textureWhere = pbrWhere + ".baseColorTexture";
        if (pbr.baseColorTexture.texCoord < 0 || pbr.baseColorTexture.texCoord > 7) {
            return elementError(textureWhere + ".texCoord", "must be in [0, 7]");
        }
        auto texture = textures.get(pbr.baseColorTexture.index, textureWhere);
        if (!texture) return texture.error();
        out.baseColorTexture = *texture;
        texCoord = pbr.baseColorTexture.texCoord;
    }
    // Blinn-Phong exponent whose lobe matches a GGX lobe of roughness r (alpha = r^2):
    // n = 2 / alpha^2 - 2 (Walter et al. 2007, section 5.2).
    const float alpha2 = std::max(std::pow(*roughness, 4.0f), 1e-4f);
    out.shininess = std::clamp(2.0f / alpha2 - 2.0f, 1.0f, 4096.0f);
    return out;
}

}  // namespace shadow::gltf
