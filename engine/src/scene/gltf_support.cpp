#include "scene/gltf_support.h"

#include <algorithm>
#include <map>
#include <span>
#include <string>

#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

using nlohmann::json;

constexpr const char* kPlainMaterial = "the material is drawn as a plain metallic-roughness one";

constexpr FeatureSupport kFeatures[] = {
    {"KHR_lights_punctual", Support::Read, ""},
    {"KHR_xmp_json_ld", Support::Read, ""},  // metadata: nothing to draw
    {"KHR_materials_unlit", Support::Dropped, "unlit materials are shaded by the lights like the others"},
    {"KHR_texture_transform", Support::Read, ""},
    {"KHR_texture_basisu", Support::Dropped,
     "KTX2 images are not decoded: a texture's PNG or JPEG `source` is used, else the material is drawn "
     "without that texture"},
    {"EXT_texture_webp", Support::Dropped,
     "WebP images are not decoded: a texture's PNG or JPEG `source` is used, else the material is drawn "
     "without that texture"},
    {"KHR_materials_emissive_strength", Support::Read, ""},
    {"KHR_materials_clearcoat", Support::Dropped, kPlainMaterial},
    {"KHR_materials_sheen", Support::Dropped, kPlainMaterial},
    {"KHR_materials_specular", Support::Dropped, kPlainMaterial},
    {"KHR_materials_ior", Support::Dropped, kPlainMaterial},
    {"KHR_materials_transmission", Support::Dropped, kPlainMaterial},
    {"KHR_materials_volume", Support::Dropped, kPlainMaterial},
    {"KHR_materials_iridescence", Support::Dropped, kPlainMaterial},
    {"KHR_materials_anisotropy", Support::Dropped, kPlainMaterial},
    {"KHR_materials_dispersion", Support::Dropped, kPlainMaterial},
    {"KHR_materials_diffuse_transmission", Support::Dropped, kPlainMaterial},
    {"KHR_materials_pbrSpecularGlossiness", Support::Dropped,
     "the material's metallic-roughness values (or their defaults) are drawn"},
    {"KHR_materials_variants", Support::Dropped, "the primitives' default materials are drawn"},
    {"KHR_animation_pointer", Support::Dropped, "only animations of node transforms play"},
    {"EXT_mesh_gpu_instancing", Support::Dropped, "each node is drawn once, at its own transform"},
    {"KHR_draco_mesh_compression", Support::Refused,
     "compressed primitives are not decoded: their uncompressed accessors are drawn"},
    {"EXT_meshopt_compression", Support::Refused,
     "compressed buffer views are not decoded: their fallback buffers are read"},
    {"KHR_mesh_quantization", Support::Refused, "quantized vertex attributes are not read"},
    {"primitive modes other than TRIANGLES", Support::Dropped,
     "points, lines, triangle strips and triangle fans are left out"},
    {"COLOR_0", Support::Dropped, "vertex colours are not drawn"},
    {"JOINTS_1", Support::Dropped, "only a vertex's first four joint influences (JOINTS_0/WEIGHTS_0) pose it"},
    {"magFilter NEAREST", Support::Dropped, "textures are filtered linearly (pixel art is drawn blurred)"},
    {"alphaMode BLEND", Support::Dropped,
     "blended surfaces are not blended: they are drawn, and cast shadows, as cut-outs at alpha 0.5"},
};

/// The uses of one extension or feature: how many, and the first.
struct Use {
    std::size_t count = 0;
    std::string first;
};
using Uses = std::map<std::string, Use>;

void record(Uses& uses, const std::string& name, const std::string& where) {
    Use& use = uses[name];
    if (use.count++ == 0) use.first = where;
}

/// Every object of `document` named `extensions` (outside `extras`, a game's own data): each of
/// its members is a use of that extension. Walked in document order with a stack of its own
/// (children pushed last first): a file's arrays may be long.
void collectExtensions(const json& document, Uses& uses) {
    std::vector<std::pair<const json*, std::string>> stack{{&document, ""}};
    std::vector<std::pair<const json*, std::string>> children;
    while (!stack.empty()) {
        const auto [value, where] = std::move(stack.back());
        stack.pop_back();
        children.clear();
        if (value->is_array()) {
            for (std::size_t i = 0; i < value->size(); ++i) children.emplace_back(&value->at(i), indexed(where, i));
        } else if (value->is_object()) {
            for (const auto& [key, item] : value->items()) {
                if (key == "extras") continue;
                const std::string path = where.empty() ? key : where + "." + key;
                if (key == "extensions" && item.is_object()) {
                    for (const auto& [name, object] : item.items()) {
                        record(uses, name, path + "." + name);
                    }
                }
                children.emplace_back(&item, path);
            }
        }
        stack.insert(stack.end(), std::make_move_iterator(children.rbegin()), std::make_move_iterator(children.rend()));
    }
}

/// `object[key]` when `object` is an object holding `key`, else null. Looked up by value, not
/// through nlohmann's iterators, whose null checks GCC cannot see through at -O3
/// (-Wnull-dereference).
const json* jsonMember(const json& object, const char* key) {
    if (!object.is_object() || !object.contains(key)) return nullptr;
    return &object.at(key);
}

/// `jsonMember(object, key)` when it is an array, else null.
const json* arrayMember(const json& object, const char* key) {
    const json* found = jsonMember(object, key);
    return found != nullptr && found->is_array() ? found : nullptr;
}

/// `document[array][i]` for every i, with its path.
template <typename F>
void eachElement(const json& document, const char* array, F&& f) {
    const json* items = arrayMember(document, array);
    if (items == nullptr) return;
    for (std::size_t i = 0; i < items->size(); ++i) {
        if (items->at(i).is_object()) f(items->at(i), indexed(array, i));
    }
}

void collectPrimitiveFeatures(const json& document, Uses& uses) {
    eachElement(document, "meshes", [&](const json& mesh, const std::string& meshWhere) {
        const json* primitives = arrayMember(mesh, "primitives");
        if (primitives == nullptr) return;
        for (std::size_t p = 0; p < primitives->size(); ++p) {
            const json& primitive = primitives->at(p);
            const std::string where = meshWhere + "." + indexed("primitives", p);
            if (const json* mode = jsonMember(primitive, "mode"); mode != nullptr && *mode != 4) {
                record(uses, "primitive modes other than TRIANGLES", where + ".mode");
            }
            const json* attributes = jsonMember(primitive, "attributes");
            if (attributes == nullptr || !attributes->is_object()) continue;
            if (attributes->contains("COLOR_0")) record(uses, "COLOR_0", where + ".attributes.COLOR_0");
            if (attributes->contains("JOINTS_1")) record(uses, "JOINTS_1", where + ".attributes.JOINTS_1");
        }
    });
}

void collectMaterialFeatures(const json& document, Uses& uses) {
    eachElement(document, "samplers", [&](const json& sampler, const std::string& where) {
        constexpr int kNearest = 9728;
        if (const json* mag = jsonMember(sampler, "magFilter"); mag != nullptr && *mag == kNearest) {
            record(uses, "magFilter NEAREST", where + ".magFilter");
        }
    });
    eachElement(document, "materials", [&](const json& material, const std::string& where) {
        if (const json* mode = jsonMember(material, "alphaMode"); mode != nullptr && *mode == "BLEND") {
            record(uses, "alphaMode BLEND", where + ".alphaMode");
        }
    });
}

/// The extensions of `list` (`extensionsUsed`, `extensionsRequired`); the schema check has
/// made sure it is an array of strings when present.
std::vector<std::string> extensionList(const json& document, const char* list) {
    std::vector<std::string> names;
    if (const json* items = arrayMember(document, list); items != nullptr) {
        for (const json& name : *items) {
            if (name.is_string()) names.push_back(name.get<std::string>());
        }
    }
    return names;
}

const FeatureSupport* rowOf(const std::string& name) {
    const auto* it = std::find_if(std::begin(kFeatures), std::end(kFeatures),
                                  [&](const FeatureSupport& f) { return name == f.name; });
    return it == std::end(kFeatures) ? nullptr : it;
}

Warning warningOf(const std::string& name, const Use& use, const char* instead) {
    std::string message = name + " (" +
                          (use.count == 1 ? "used once" : "used " + std::to_string(use.count) + " times") +
                          ", first at " + use.first + "): " + instead;
    return {WarningCode::UnsupportedFeature, use.first, std::move(message)};
}

}  // namespace

std::span<const FeatureSupport> featureTable() { return kFeatures; }

Result<std::vector<Warning>> checkSupport(const nlohmann::json& document) {
    const std::vector<std::string> required = extensionList(document, "extensionsRequired");
    for (std::size_t i = 0; i < required.size(); ++i) {
        const FeatureSupport* row = rowOf(required[i]);
        if (row == nullptr || row->support == Support::Refused) {
            return elementError(indexed("extensionsRequired", i),
                                "the file requires " + required[i] + ", which the module " +
                                    (row == nullptr ? "does not know" : "does not read") + ": it cannot be drawn",
                                ErrorCode::Unsupported);
        }
    }
    Uses uses;
    if (document.is_object()) {
        collectExtensions(document, uses);
        collectPrimitiveFeatures(document, uses);
        collectMaterialFeatures(document, uses);
    }
    // A known extension is used where an object names it (exporters list extensions that no
    // object uses); one that has no objects, or one the table does not know, where it is listed.
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
        for (const std::string& name : extensionList(document, list)) {
            const bool objectless = name == "KHR_mesh_quantization" || rowOf(name) == nullptr;
            if (objectless && uses.find(name) == uses.end()) record(uses, name, list);
        }
    }
    std::vector<Warning> warnings;
    for (const FeatureSupport& row : featureTable()) {
        const auto use = uses.find(row.name);
        if (use == uses.end()) continue;
        if (row.support != Support::Read) warnings.push_back(warningOf(row.name, use->second, row.instead));
        uses.erase(use);
    }
    for (const auto& [name, use] : uses) {
        warnings.push_back(warningOf(name, use, "an extension the module does not know; it is left out"));
    }
    return warnings;
}

}  // namespace shadow::gltf
