#include "scene/gltf_material.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

/// Largest emitted radiance a material may have (its factor times its strength), so that no
/// shading overflows a half float target (65504) with a few lights added.
constexpr float kMaxEmission = 1e4f;

/// What a textureInfo names: the texture, the TEXCOORD set it reads and its transform.
struct TextureRef {
    std::shared_ptr<const Texture> texture;
    int set = 0;
    glm::mat3x2 transform{1.0f};
};

Result<glm::vec2> readPair(const tinygltf::Value& v, const std::string& where) {
    if (!v.IsArray() || v.ArrayLen() != 2) return elementError(where, "must be an array of 2 numbers");
    glm::vec2 out;
    for (int i = 0; i < 2; ++i) {
        auto d = readFiniteNumber(v.Get(i), where);
        if (!d) return d.error();
        out[i] = static_cast<float>(*d);
    }
    return out;
}

/// KHR_texture_transform of a textureInfo (absent: identity), updating `set` by its texCoord.
Result<glm::mat3x2> readTransform(const tinygltf::ExtensionMap& extensions, const std::string& where, int& set) {
    const auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end()) return glm::mat3x2(1.0f);
    const std::string w = where + ".extensions.KHR_texture_transform";
    glm::vec2 offset(0.0f), scale(1.0f);
    double rotation = 0.0;
    if (const tinygltf::Value* v = member(it->second, "offset")) {
        auto p = readPair(*v, w + ".offset");
        if (!p) return p.error();
        offset = *p;
    }
    if (const tinygltf::Value* v = member(it->second, "scale")) {
        auto p = readPair(*v, w + ".scale");
        if (!p) return p.error();
        scale = *p;
    }
    if (const tinygltf::Value* v = member(it->second, "rotation")) {
        auto r = readFiniteNumber(*v, w + ".rotation");
        if (!r) return r.error();
        rotation = *r;
    }
    if (const tinygltf::Value* v = member(it->second, "texCoord")) {
        auto i = readIndex(*v, w + ".texCoord");
        if (!i) return i.error();
        set = *i;
    }
    if (set > 7) return elementError(w + ".texCoord", "must be in [0, 7]");
    return textureTransform(offset, static_cast<float>(rotation), scale);
}

/// The textureInfo `info` of member `where` (any of glTF's textureInfo types); nullopt when it
/// names no texture.
template <typename Info>
Result<std::optional<TextureRef>> readTextureRef(const Info& info, const std::string& where,
                                                 TextureImporter& textures) {
    if (info.index < 0) return std::optional<TextureRef>{};
    if (info.texCoord < 0 || info.texCoord > 7) return elementError(where + ".texCoord", "must be in [0, 7]");
    TextureRef ref;
    ref.set = info.texCoord;
    auto transform = readTransform(info.extensions, where, ref.set);
    if (!transform) return transform.error();
    ref.transform = *transform;
    auto texture = textures.get(info.index, where);
    if (!texture) return texture.error();
    ref.texture = *texture;
    return std::optional<TextureRef>{ref};
}

/// The affine 3x3 form of a texture transform, to compose and invert.
glm::dmat3 affine(const glm::mat3x2& m) {
    return {glm::dvec3(m[0], 0.0), glm::dvec3(m[1], 0.0), glm::dvec3(m[2], 1.0)};
}

glm::mat3x2 reduced(const glm::dmat3& m) {
    return {glm::vec2(glm::dvec2(m[0])), glm::vec2(glm::dvec2(m[1])), glm::vec2(glm::dvec2(m[2]))};
}

/// Places a map's TEXCOORD set on one of the mesh's two sets (the base colour's is set 0); a
/// map of set 0 takes the inverse of the base colour's transform first, which the primitive
/// bakes into that set.
Result<MaterialMap> placeMap(const TextureRef& ref, const std::string& where, MaterialImport& out) {
    MaterialMap map;
    map.texture = ref.texture;
    map.uvTransform = ref.transform;
    auto& sets = out.texcoordSets;
    if (sets[0] < 0 || sets[0] == ref.set) {
        sets[0] = ref.set;
        map.texcoordSet = 0;
        const glm::dmat3 base = affine(out.baseTransform);
        if (std::abs(glm::determinant(base)) > 1e-12)
            map.uvTransform = reduced(affine(ref.transform) * glm::inverse(base));
        return map;
    }
    if (sets[1] < 0 || sets[1] == ref.set) {
        sets[1] = ref.set;
        map.texcoordSet = 1;
        return map;
    }
    return elementError(
        where,
        "reads a third TEXCOORD set (TEXCOORD_" + std::to_string(ref.set) + "); the loader reads two per material",
        ErrorCode::Unsupported);
}

Result<float> readUnitFactor(double value, const std::string& where) {
    if (!std::isfinite(value)) return elementError(where, "not finite");
    return static_cast<float>(std::clamp(value, 0.0, 1.0));
}

Result<glm::vec3> readColor(const std::vector<double>& f, std::size_t size, const std::string& where) {
    if (f.size() != size) return elementError(where, "must have " + std::to_string(size) + " numbers");
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c) {
        auto v = readUnitFactor(f[static_cast<std::size_t>(c)], where);
        if (!v) return v.error();
        rgb[c] = *v;
    }
    return rgb;
}

/// The metallic-roughness block's factors and base colour texture.
Status readPbr(const tinygltf::Material& material, const std::string& where, TextureImporter& textures,
               MaterialImport& out) {
    const tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
    const std::string pbrWhere = where + ".pbrMetallicRoughness";
    Material& m = out.material;
    auto base = readColor(pbr.baseColorFactor, 4, pbrWhere + ".baseColorFactor");
    if (!base) return base.error();
    auto alpha = readUnitFactor(pbr.baseColorFactor[3], pbrWhere + ".baseColorFactor");
    if (!alpha) return alpha.error();
    auto metallic = readUnitFactor(pbr.metallicFactor, pbrWhere + ".metallicFactor");
    if (!metallic) return metallic.error();
    auto roughness = readUnitFactor(pbr.roughnessFactor, pbrWhere + ".roughnessFactor");
    if (!roughness) return roughness.error();
    m.baseColor = *base;
    m.alpha = *alpha;
    m.metallic = *metallic;
    m.roughness = *roughness;
    m.albedo = *base * (1.0f - *metallic);
    m.specular = glm::mix(glm::vec3(0.04f), *base, *metallic);
    // Blinn-Phong exponent whose lobe matches a GGX lobe of roughness r (alpha = r^2):
    // n = 2 / alpha^2 - 2 (Walter et al. 2007, section 5.2); shaders/material.glsl does the same.
    const float alpha2 = std::max(std::pow(*roughness, 4.0f), 1e-4f);
    m.shininess = std::clamp(2.0f / alpha2 - 2.0f, 1.0f, 4096.0f);
    auto baseRef = readTextureRef(pbr.baseColorTexture, pbrWhere + ".baseColorTexture", textures);
    if (!baseRef) return baseRef.error();
    if (*baseRef) {
        m.baseColorTexture = (*baseRef)->texture;
        out.texcoordSets[0] = (*baseRef)->set;
        out.baseTransform = (*baseRef)->transform;
    }
    auto mr = readTextureRef(pbr.metallicRoughnessTexture, pbrWhere + ".metallicRoughnessTexture", textures);
    if (!mr) return mr.error();
    if (*mr) {
        auto map = placeMap(**mr, pbrWhere + ".metallicRoughnessTexture", out);
        if (!map) return map.error();
        m.metallicRoughnessMap = *map;
    }
    return Ok{};
}

/// One of the material's own maps (normal, occlusion, emissive) into `map`.
template <typename Info>
Status readMap(const Info& info, const std::string& where, TextureImporter& textures, MaterialImport& out,
               MaterialMap& map) {
    auto ref = readTextureRef(info, where, textures);
    if (!ref) return ref.error();
    if (!*ref) return Ok{};
    auto placed = placeMap(**ref, where, out);
    if (!placed) return placed.error();
    map = *placed;
    return Ok{};
}

/// The normal, occlusion and emissive maps, their scale and strength, and the emission.
Status readSurfaceMaps(const tinygltf::Material& material, const std::string& where, TextureImporter& textures,
                       MaterialImport& out) {
    Material& m = out.material;
    if (auto st = readMap(material.normalTexture, where + ".normalTexture", textures, out, m.normalMap); !st) return st;
    if (!std::isfinite(material.normalTexture.scale)) return elementError(where + ".normalTexture.scale", "not finite");
    m.normalScale = static_cast<float>(std::clamp(material.normalTexture.scale, -1e3, 1e3));
    if (auto st = readMap(material.occlusionTexture, where + ".occlusionTexture", textures, out, m.occlusionMap); !st) {
        return st;
    }
    auto strength = readUnitFactor(material.occlusionTexture.strength, where + ".occlusionTexture.strength");
    if (!strength) return strength.error();
    m.occlusionStrength = *strength;
    if (auto st = readMap(material.emissiveTexture, where + ".emissiveTexture", textures, out, m.emissiveMap); !st) {
        return st;
    }
    auto emissive = readColor(material.emissiveFactor, 3, where + ".emissiveFactor");
    if (!emissive) return emissive.error();
    float intensity = 1.0f;
    if (const auto it = material.extensions.find("KHR_materials_emissive_strength"); it != material.extensions.end()) {
        const std::string w = where + ".extensions.KHR_materials_emissive_strength.emissiveStrength";
        if (const tinygltf::Value* v = member(it->second, "emissiveStrength")) {
            auto s = readNonNegativeFloat(*v, w);
            if (!s) return s.error();
            intensity = std::min(*s, kMaxEmission);
        }
    }
    m.emissive = glm::min(*emissive * intensity, glm::vec3(kMaxEmission));
    return Ok{};
}

Status readAlphaMode(const tinygltf::Material& material, const std::string& where, Material& m) {
    auto cutoff = readUnitFactor(material.alphaCutoff, where + ".alphaCutoff");
    if (!cutoff) return cutoff.error();
    m.alphaCutoff = material.alphaMode == "BLEND" ? 0.5f : *cutoff;
    if (material.alphaMode == "MASK") {
        m.alphaMode = AlphaMode::Mask;
    } else if (material.alphaMode == "BLEND") {
        m.alphaMode = AlphaMode::Blend;
    } else if (!material.alphaMode.empty() && material.alphaMode != "OPAQUE") {
        return elementError(where + ".alphaMode", "must be OPAQUE, MASK or BLEND, not \"" + material.alphaMode + "\"");
    }
    return Ok{};
}

}  // namespace

Result<MaterialImport> importMaterial(const tinygltf::Model& model, int index, const std::string& where,
                                      TextureImporter& textures) {
    MaterialImport out;
    if (index < 0) return out;
    if (static_cast<std::size_t>(index) >= model.materials.size()) {
        return elementError(where, "material " + std::to_string(index) + " does not exist");
    }
    const std::string materialWhere = indexed("materials", static_cast<std::size_t>(index));
    const tinygltf::Material& material = model.materials[static_cast<std::size_t>(index)];
    if (auto st = readPbr(material, materialWhere, textures, out); !st) return st.error();
    if (auto st = readSurfaceMaps(material, materialWhere, textures, out); !st) return st.error();
    if (auto st = readAlphaMode(material, materialWhere, out.material); !st) return st.error();
    out.material.doubleSided = material.doubleSided;
    return out;
}

}  // namespace shadow::gltf
