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

/// TEXCOORD_`set` into `out` (left empty without it: the textures are sampled at (0, 0)).
Status readTexcoordSet(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int set,
                       const std::string& where, std::size_t vertexCount, std::vector<glm::vec2>& out) {
    if (set < 0) return Ok{};
    const std::string semantic = "TEXCOORD_" + std::to_string(set);
    const auto it = primitive.attributes.find(semantic);
    if (it == primitive.attributes.end()) return Ok{};  // the caller warns and drops the textures
    const std::string uvWhere = where + ".attributes." + semantic;
    auto uv = readTexcoords(model, it->second, uvWhere);
    if (!uv) return uv.error();
    if (uv->size() != vertexCount) {
        return elementError(
            uvWhere, "has " + std::to_string(uv->size()) + " elements, POSITION has " + std::to_string(vertexCount));
    }
    out = std::move(*uv);
    return Ok{};
}

/// The texture-coordinate sets `material` reads and a normal map's tangents: the file's TANGENT
/// where the primitive has normals of its own, else computed by the caller (`computeTangents`,
/// after flat normals for a primitive without).
Status readMaterialInputs(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                          const MaterialImport& material, MeshData& mesh) {
    const std::size_t n = mesh.positions.size();
    const auto& sets = material.texcoordSets;
    if (auto st = readTexcoordSet(model, primitive, sets[0], where, n, mesh.texcoords); !st) return st;
    if (auto st = readTexcoordSet(model, primitive, sets[1], where, n, mesh.texcoords1); !st) return st;
    const auto tangent = primitive.attributes.find("TANGENT");
    if (material.material.normalMap.texture == nullptr || tangent == primitive.attributes.end()) return Ok{};
    const std::string tangentWhere = where + ".attributes.TANGENT";
    auto tangents = readTangents(model, tangent->second, tangentWhere);
    if (!tangents) return tangents.error();
    if (tangents->size() != n) {
        return elementError(tangentWhere,
                            "has " + std::to_string(tangents->size()) + " elements, POSITION has " + std::to_string(n));
    }
    for (glm::vec4& t : *tangents) {
        const glm::vec3 xyz(t);
        const float length = glm::length(xyz);
        t = glm::vec4(length > 0.0f ? xyz / length : xyz, t.w < 0.0f ? -1.0f : 1.0f);
    }
    mesh.tangents = std::move(*tangents);
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

/// Target `k`'s displacements of `attribute` into block k of `out` (n per target; zeros without
/// them, `out` stays empty when no target has them). Each must be a float VEC3 of one element
/// per POSITION.
Status readMorphAttribute(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const char* attribute,
                          const std::string& where, std::size_t n, std::vector<glm::vec3>& out) {
    const std::size_t targets = primitive.targets.size();
    for (std::size_t k = 0; k < targets; ++k) {
        const auto it = primitive.targets[k].find(attribute);
        if (it == primitive.targets[k].end()) continue;
        const std::string targetWhere = where + "." + indexed("targets", k) + "." + attribute;
        auto deltas = readVec3(model, it->second, targetWhere);
        if (!deltas) return deltas.error();
        if (deltas->size() != n) {
            return elementError(
                targetWhere, "has " + std::to_string(deltas->size()) + " elements, POSITION has " + std::to_string(n));
        }
        out.resize(targets * n, glm::vec3(0.0f));
        std::copy(deltas->begin(), deltas->end(), out.begin() + static_cast<std::ptrdiff_t>(k * n));
    }
    return Ok{};
}

/// The primitive's morph targets: POSITION, NORMAL (where the primitive has normals) and TANGENT
/// (where it has the file's tangents) displacements; other attributes of a target are not read.
Status readMorphTargets(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                        MeshData& mesh) {
    if (primitive.targets.empty()) return Ok{};
    const std::size_t n = mesh.positions.size();
    mesh.morphTargets = primitive.targets.size();
    if (auto st = readMorphAttribute(model, primitive, "POSITION", where, n, mesh.morphPositions); !st) return st;
    if (!mesh.normals.empty()) {
        if (auto st = readMorphAttribute(model, primitive, "NORMAL", where, n, mesh.morphNormals); !st) return st;
    }
    if (!mesh.tangents.empty()) {
        if (auto st = readMorphAttribute(model, primitive, "TANGENT", where, n, mesh.morphTangents); !st) return st;
    }
    if (mesh.morphPositions.empty()) mesh.morphPositions.assign(mesh.morphTargets * n, glm::vec3(0.0f));
    return Ok{};
}

/// The warning for a texture that reads `TEXCOORD_<set>`, which the primitive at `where` lacks.
Warning missingTexcoord(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int set,
                        const std::string& where, const char* texture) {
    const auto m = static_cast<std::size_t>(primitive.material);
    const std::string& name = model.materials[m].name;
    return {WarningCode::MissingTexcoord, where,
            where + " has no TEXCOORD_" + std::to_string(set) + ", which " + indexed("materials", m) +
                (name.empty() ? "" : " (\"" + name + "\")") + "." + texture +
                " reads: the primitive is drawn without that texture"};
}

/// Every texture of `material` whose TEXCOORD set the primitive lacks is dropped, each with a
/// `MissingTexcoord` warning (rather than sampling texel (0, 0) everywhere).
void dropMapsWithoutTexcoords(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                              const std::string& where, MaterialImport& material, const MeshData& mesh,
                              std::vector<Warning>& warnings) {
    const auto lacks = [&](int set) { return (set == 0 ? mesh.texcoords : mesh.texcoords1).empty(); };
    const auto fileSet = [&](int set) { return material.texcoordSets[static_cast<std::size_t>(set)]; };
    Material& m = material.material;
    if (m.baseColorTexture != nullptr && lacks(0)) {
        warnings.push_back(
            missingTexcoord(model, primitive, fileSet(0), where, "pbrMetallicRoughness.baseColorTexture"));
        m.baseColorTexture = nullptr;
    }
    const std::pair<MaterialMap*, const char*> maps[] = {
        {&m.metallicRoughnessMap, "pbrMetallicRoughness.metallicRoughnessTexture"},
        {&m.normalMap, "normalTexture"},
        {&m.occlusionMap, "occlusionTexture"},
        {&m.emissiveMap, "emissiveTexture"}};
    for (const auto& [map, texture] : maps) {
        if (map->texture == nullptr || !lacks(map->texcoordSet)) continue;
        warnings.push_back(missingTexcoord(model, primitive, fileSet(map->texcoordSet), where, texture));
        map->texture = nullptr;
    }
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

    auto material = importMaterial(model, primitive.material, where + ".material", textures);
    if (!material) return material.error();
    if (auto st = readMaterialInputs(model, primitive, where, *material, *mesh); !st) return st.error();
    dropMapsWithoutTexcoords(model, primitive, where, *material, *mesh, warnings);
    if (auto st = readSkinning(model, primitive, where, *mesh); !st) return st.error();
    if (auto st = readMorphTargets(model, primitive, where, *mesh); !st) return st.error();
    if (mesh->normals.empty()) {
        makeFlatNormals(*mesh);
    } else {
        computeBounds(*mesh);
    }
    const MaterialMap& normalMap = material->material.normalMap;
    if (normalMap.texture != nullptr && mesh->tangents.empty()) computeTangents(*mesh, normalMap.texcoordSet);
    // The base colour's transform baked into set 0 (the other maps of that set carry its
    // inverse), after the tangents, which follow the file's coordinates.
    if (material->baseTransform != glm::mat3x2(1.0f)) {
        for (glm::vec2& uv : mesh->texcoords) uv = material->baseTransform * glm::vec3(uv, 1.0f);
    }
    computeClosed(*mesh);
    computeJointBounds(*mesh);
    computeMorphBounds(*mesh);
    return std::optional<MeshPart>{MeshPart{std::move(mesh), material->material}};
}

}  // namespace

Result<std::vector<MeshPart>> importMesh(const tinygltf::Model& model, std::size_t meshIndex, TextureImporter& textures,
                                         std::vector<Warning>& warnings) {
    const tinygltf::Mesh& mesh = model.meshes[meshIndex];
    const std::string meshWhere = indexed("meshes", meshIndex);
    const std::string baseName = mesh.name.empty() ? "mesh" + std::to_string(meshIndex) : mesh.name;
    std::vector<MeshPart> parts;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        if (mesh.primitives[p].targets.size() != mesh.primitives[0].targets.size()) {
            return elementError(meshWhere + "." + indexed("primitives", p) + ".targets",
                                "has " + std::to_string(mesh.primitives[p].targets.size()) + " morph targets, " +
                                    indexed("primitives", 0) + " has " +
                                    std::to_string(mesh.primitives[0].targets.size()) + " (glTF asks for as many)");
        }
        std::string name = mesh.primitives.size() == 1 ? baseName : baseName + "/primitive" + std::to_string(p);
        auto part = importPrimitive(model, mesh.primitives[p], meshWhere + "." + indexed("primitives", p),
                                    std::move(name), textures, warnings);
        if (!part) return part.error();
        if (part->has_value()) parts.push_back(std::move(**part));
    }
    return parts;
}

}  // namespace shadow::gltf
