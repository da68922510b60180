#include "scene/shadow_extras.h"

#include <array>

#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

/// The `shadow` member of `extras` and its element name. Null when there is none; an error
/// when it exists but is not an object (a typo there would otherwise silently do nothing).
struct ShadowObject {
    const tinygltf::Value* value = nullptr;
    std::string where;
};

Result<ShadowObject> findShadowObject(const tinygltf::Value& extras, const std::string& where) {
    ShadowObject found{member(extras, "shadow"), where + ".extras.shadow"};
    if (found.value != nullptr && !found.value->IsObject()) {
        return elementError(found.where, "must be an object");
    }
    return found;
}

Result<ShadowTechnique> parseTechnique(const tinygltf::Value& v, const std::string& where) {
    auto name = readString(v, where);
    if (!name) return name.error();
    if (const auto t = techniqueFromName(*name)) return *t;
    return elementError(where, "unknown technique \"" + *name + "\" (expected one of " + techniqueNameList() + ")");
}

Result<FilterKernel> parseKernel(const tinygltf::Value& v, const std::string& where) {
    auto name = readString(v, where);
    if (!name) return name.error();
    if (const auto k = filterKernelFromName(*name)) return *k;
    return elementError(where, "unknown kernel \"" + *name + "\" (expected vogel, poisson or uniform)");
}

template <typename Field>
struct Knob {
    const char* key;
    Field* field;
};

/// Reads every present knob of `fields` with `read`; absent keys keep their defaults.
template <typename Field, std::size_t N, typename Read>
Status readKnobs(const ShadowObject& object, const std::array<Knob<Field>, N>& knobs, Read read) {
    for (const Knob<Field>& knob : knobs) {
        const tinygltf::Value* v = member(*object.value, knob.key);
        if (v == nullptr) continue;
        auto parsed = read(*v, object.where + "." + knob.key);
        if (!parsed) return parsed.error();
        *knob.field = *parsed;
    }
    return Ok{};
}

}  // namespace

Result<LightShadowExtras> parseShadowExtras(const tinygltf::Value& extras, const std::string& where) {
    auto object = findShadowObject(extras, where);
    if (!object) return object.error();
    LightShadowExtras out;
    if (object->value == nullptr) return out;

    if (const tinygltf::Value* technique = member(*object->value, "technique")) {
        auto parsed = parseTechnique(*technique, object->where + ".technique");
        if (!parsed) return parsed.error();
        out.shadow.technique = *parsed;
    }
    if (const tinygltf::Value* kernel = member(*object->value, "kernel")) {
        auto parsed = parseKernel(*kernel, object->where + ".kernel");
        if (!parsed) return parsed.error();
        out.shadow.kernel = *parsed;
    }
    Shadow& s = out.shadow;
    const std::array<Knob<int>, 4> ints{{{"mapSize", &s.mapSize},
                                         {"pcfSamples", &s.pcfSamples},
                                         {"blockerSamples", &s.blockerSamples},
                                         {"cascades", &s.cascades}}};
    const std::array<Knob<float>, 12> floats{{{"radius", &out.radius},
                                              {"angularRadius", &out.angularRadius},
                                              {"constantBias", &s.constantBias},
                                              {"slopeBias", &s.slopeBias},
                                              {"normalOffset", &s.normalOffset},
                                              {"pcfRadius", &s.pcfRadius},
                                              {"lightBleedReduction", &s.lightBleedReduction},
                                              {"maxFilterTexels", &s.maxFilterTexels},
                                              {"cascadeSplitLambda", &s.cascadeSplitLambda},
                                              {"cascadeBlend", &s.cascadeBlend},
                                              {"shadowDistance", &s.shadowDistance},
                                              {"nearPlane", &s.nearPlane}}};
    if (auto st = readKnobs(*object, ints, readPositiveInt); !st) return st.error();
    if (auto st = readKnobs(*object, floats, readNonNegativeFloat); !st) return st.error();
    return out;
}

Result<MeshShadowFlags> parseMeshShadowExtras(const tinygltf::Value& extras, const std::string& where) {
    auto object = findShadowObject(extras, where);
    if (!object) return object.error();
    MeshShadowFlags out;
    if (object->value == nullptr) return out;
    const std::array<Knob<bool>, 2> flags{{{"cast", &out.cast}, {"receive", &out.receive}}};
    if (auto st = readKnobs(*object, flags, readBool); !st) return st.error();
    return out;
}

}  // namespace shadow::gltf
