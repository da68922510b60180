#include "scene/gltf_lights.h"

#include <glm/gtc/constants.hpp>

#include "scene/gltf_values.h"
#include "scene/shadow_extras.h"

namespace shadow::gltf {
namespace {

const char* const kExtension = "KHR_lights_punctual";

/// The light's type; nullopt for a type this engine does not know (a later version of the
/// extension may add types, so such a light is skipped rather than the file refused).
Result<std::optional<LightType>> parseType(const tinygltf::Value& light, const std::string& where,
                                           std::vector<Warning>& warnings) {
    const tinygltf::Value* type = member(light, "type");
    if (type == nullptr) return elementError(where + ".type", "missing");
    auto name = readString(*type, where + ".type");
    if (!name) return name.error();
    if (*name == "directional") return std::optional(LightType::Directional);
    if (*name == "point") return std::optional(LightType::Point);
    if (*name == "spot") return std::optional(LightType::Spot);
    warnings.push_back({WarningCode::UnsupportedLight, where,
                        where + ": unknown light type \"" + *name +
                            "\" (known: directional, point, spot); the light and the nodes' references to it "
                            "are ignored"});
    return std::optional<LightType>{};
}

Result<glm::vec3> parseColor(const tinygltf::Value& color, const std::string& where) {
    if (!color.IsArray() || color.ArrayLen() != 3) {
        return elementError(where, "must be an array of 3 numbers");
    }
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c) {
        auto v = readNonNegativeFloat(color.Get(c), indexed(where, static_cast<std::size_t>(c)));
        if (!v) return v.error();
        rgb[c] = *v;
    }
    return rgb;
}

/// Reads `key` of `object` into `out` when present; absent keys keep the default.
Status readOptionalFloat(const tinygltf::Value& object, const char* key, const std::string& where, float& out) {
    const tinygltf::Value* v = member(object, key);
    if (v == nullptr) return Ok{};
    auto parsed = readNonNegativeFloat(*v, where + "." + key);
    if (!parsed) return parsed.error();
    out = *parsed;
    return Ok{};
}

/// Cone angles as the extension requires: 0 <= inner < outer <= pi/2.
Status parseSpot(const tinygltf::Value& light, const std::string& where, Light& out) {
    const tinygltf::Value* spot = member(light, "spot");
    if (spot == nullptr) return Ok{};
    const std::string spotWhere = where + ".spot";
    if (!spot->IsObject()) return elementError(spotWhere, "must be an object");
    if (auto st = readOptionalFloat(*spot, "innerConeAngle", spotWhere, out.innerConeAngle); !st) {
        return st;
    }
    if (auto st = readOptionalFloat(*spot, "outerConeAngle", spotWhere, out.outerConeAngle); !st) {
        return st;
    }
    if (!(out.outerConeAngle > 0.0f) || out.outerConeAngle > glm::half_pi<float>() + 1e-6f) {
        return elementError(spotWhere + ".outerConeAngle", "must be in (0, pi/2]");
    }
    if (!(out.innerConeAngle < out.outerConeAngle)) {
        return elementError(spotWhere + ".innerConeAngle", "must be less than outerConeAngle");
    }
    return Ok{};
}

Result<LightDefinition> parseLight(const tinygltf::Value& value, const std::string& where, bool strict,
                                   std::vector<Warning>& warnings) {
    if (!value.IsObject()) return elementError(where, "must be an object");
    LightDefinition def;
    auto type = parseType(value, where, warnings);
    if (!type) return type.error();
    if (!*type) {
        def.supported = false;
        return def;
    }
    def.light.type = **type;
    if (const tinygltf::Value* name = member(value, "name")) {
        auto parsed = readString(*name, where + ".name");
        if (!parsed) return parsed.error();
        def.name = *parsed;
    }
    if (const tinygltf::Value* color = member(value, "color")) {
        auto parsed = parseColor(*color, where + ".color");
        if (!parsed) return parsed.error();
        def.light.color = *parsed;
    }
    if (auto st = readOptionalFloat(value, "intensity", where, def.light.intensity); !st) {
        return st.error();
    }
    if (auto st = readOptionalFloat(value, "range", where, def.light.range); !st) return st.error();
    if (def.light.type == LightType::Spot) {
        if (auto st = parseSpot(value, where, def.light); !st) return st.error();
    }
    const tinygltf::Value* extras = member(value, "extras");
    auto settings =
        orDefaults(parseShadowExtras(extras != nullptr ? *extras : tinygltf::Value(), where), strict, where, warnings);
    if (!settings) return settings.error();
    if (extras != nullptr) warnUnknownShadowKeys(*extras, where, /*light=*/true, warnings);
    def.light.radius = settings->radius;
    def.light.angularRadius = settings->angularRadius;
    if (settings->shadow.technique != ShadowTechnique::None) def.shadow = settings->shadow;
    return def;
}

}  // namespace

Result<std::vector<LightDefinition>> importLights(const tinygltf::Model& model, bool strictShadowSettings,
                                                  std::vector<Warning>& warnings) {
    std::vector<LightDefinition> out;
    const auto extension = model.extensions.find(kExtension);
    if (extension == model.extensions.end()) return out;
    const tinygltf::Value* lights = member(extension->second, "lights");
    if (lights == nullptr) return out;
    const std::string where = std::string(kExtension) + ".lights";
    if (!lights->IsArray()) return elementError(where, "must be an array");
    for (std::size_t i = 0; i < lights->ArrayLen(); ++i) {
        auto light = parseLight(lights->Get(static_cast<int>(i)), indexed(where, i), strictShadowSettings, warnings);
        if (!light) return light.error();
        out.push_back(std::move(*light));
    }
    return out;
}

Result<std::optional<std::size_t>> nodeLight(const tinygltf::Node& node, std::size_t nodeIndex,
                                             std::size_t lightCount) {
    const auto extension = node.extensions.find(kExtension);
    if (extension == node.extensions.end()) return std::optional<std::size_t>{};
    const std::string where = "nodes[" + std::to_string(nodeIndex) + "].extensions." + kExtension + ".light";
    const tinygltf::Value* light = member(extension->second, "light");
    if (light == nullptr) return elementError(where, "missing");
    auto index = readIndex(*light, where);
    if (!index) return index.error();
    if (static_cast<std::size_t>(*index) >= lightCount) {
        return elementError(where, "light " + std::to_string(*index) + " does not exist");
    }
    return std::optional<std::size_t>{static_cast<std::size_t>(*index)};
}

}  // namespace shadow::gltf
