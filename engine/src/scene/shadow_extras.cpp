#include "scene/shadow_extras.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>
#include <vector>

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
    if (const auto t = techniqueFromAnyName(*name)) return *t;
    return elementError(where, "unknown technique \"" + *name + "\" (expected one of " + techniqueNameList() + ", " +
                                   kAutoTechniqueName + ")");
}

Result<FilterKernel> parseKernel(const tinygltf::Value& v, const std::string& where) {
    auto name = readString(v, where);
    if (!name) return name.error();
    if (const auto k = filterKernelFromName(*name)) return *k;
    return elementError(where, "unknown kernel \"" + *name + "\" (expected vogel, poisson or uniform)");
}

Result<DepthMode> parseDepthMode(const tinygltf::Value& v, const std::string& where) {
    auto name = readString(v, where);
    if (!name) return name.error();
    if (const auto m = depthModeFromName(*name)) return *m;
    return elementError(where, "unknown depth mode \"" + *name + "\" (expected nearest, midpoint or second)");
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

constexpr const char* kTechniqueKey = "technique";
constexpr const char* kKernelKey = "kernel";
constexpr const char* kDepthModeKey = "depthMode";

/// A light's numeric knobs: each key of its `extras.shadow` with the field it sets. The one list
/// of them: the parser reads these, and the unknown-key check knows these.
struct LightKnobs {
    std::array<Knob<int>, 5> ints;
    std::array<Knob<float>, 9> floats;
    /// Lengths (and maxFilterTexels) whose default is derived from the scene: a number >= 0 or
    /// "auto" (`kAutomatic`).
    std::array<Knob<float>, 6> lengths;
    std::array<Knob<bool>, 1> bools;
};

/// A length knob: a number >= 0 (metres), or "auto" for the value derived from the scene.
Result<float> readLengthOrAuto(const tinygltf::Value& v, const std::string& where) {
    if (v.IsString()) {
        if (v.Get<std::string>() == "auto") return kAutomatic;
        return elementError(where, "must be a number >= 0 or \"auto\"");
    }
    return readNonNegativeFloat(v, where);
}

LightKnobs lightKnobs(LightShadowExtras& out) {
    Shadow& s = out.shadow;
    return {{{{"mapSize", &s.mapSize},
              {"pcfSamples", &s.pcfSamples},
              {"blockerSamples", &s.blockerSamples},
              {"cascades", &s.cascades},
              {"sdfSteps", &s.sdfSteps}}},
            {{{"radius", &out.radius},
              {"angularRadius", &out.angularRadius},
              {"slopeBias", &s.slopeBias},
              {"normalOffset", &s.normalOffset},
              {"lightBleedReduction", &s.lightBleedReduction},
              {"cascadeSplitLambda", &s.cascadeSplitLambda},
              {"cascadeBlend", &s.cascadeBlend},
              {"shadowDistance", &s.shadowDistance},
              {"nearPlane", &s.nearPlane}}},
            {{{"constantBias", &s.constantBias},
              {"pcfRadius", &s.pcfRadius},
              {"sdfStartOffset", &s.sdfStartOffset},
              {"sdfMinStep", &s.sdfMinStep},
              {"contactLength", &s.contactLength},
              {"maxFilterTexels", &s.maxFilterTexels}}},
            {{{"contactShadows", &s.contactShadows}}}};
}

/// A mesh node's knobs.
std::array<Knob<bool>, 2> meshKnobs(MeshShadowFlags& out) { return {{{"cast", &out.cast}, {"receive", &out.receive}}}; }

/// Every key a light's (`light`) or a mesh node's `extras.shadow` reads.
std::vector<std::string_view> knownKeys(bool light) {
    std::vector<std::string_view> keys;
    const auto add = [&](const auto& knobs) {
        for (const auto& knob : knobs) keys.emplace_back(knob.key);
    };
    if (light) {
        LightShadowExtras scratch;
        const LightKnobs knobs = lightKnobs(scratch);
        keys = {kTechniqueKey, kKernelKey, kDepthModeKey};
        add(knobs.ints);
        add(knobs.floats);
        add(knobs.lengths);
        add(knobs.bools);
    } else {
        MeshShadowFlags scratch;
        add(meshKnobs(scratch));
    }
    return keys;
}

/// Levenshtein distance, case-insensitive (a key differing only in case is a near miss too).
std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                              std::tolower(static_cast<unsigned char>(b[j - 1]));
            const std::size_t next = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
            diagonal = row[j];
            row[j] = next;
        }
    }
    return row[b.size()];
}

}  // namespace

Result<LightShadowExtras> parseShadowExtras(const tinygltf::Value& extras, const std::string& where) {
    auto object = findShadowObject(extras, where);
    if (!object) return object.error();
    LightShadowExtras out;
    if (object->value == nullptr) return out;

    if (const tinygltf::Value* technique = member(*object->value, kTechniqueKey)) {
        if (technique->IsString() && technique->Get<std::string>() == kAutoTechniqueName) {
            out.shadow.autoTechnique = true;
            out.shadow.technique = ShadowTechnique::Pcss;  // a technique with a map; the planner chooses
        } else {
            auto parsed = parseTechnique(*technique, object->where + "." + kTechniqueKey);
            if (!parsed) return parsed.error();
            out.shadow.technique = *parsed;
        }
    }
    if (const tinygltf::Value* kernel = member(*object->value, kKernelKey)) {
        auto parsed = parseKernel(*kernel, object->where + "." + kKernelKey);
        if (!parsed) return parsed.error();
        out.shadow.kernel = *parsed;
    }
    if (const tinygltf::Value* mode = member(*object->value, kDepthModeKey)) {
        auto parsed = parseDepthMode(*mode, object->where + "." + kDepthModeKey);
        if (!parsed) return parsed.error();
        out.shadow.depthMode = *parsed;
    }
    const LightKnobs knobs = lightKnobs(out);
    if (auto st = readKnobs(*object, knobs.ints, readPositiveInt); !st) return st.error();
    if (auto st = readKnobs(*object, knobs.floats, readNonNegativeFloat); !st) return st.error();
    if (auto st = readKnobs(*object, knobs.lengths, readLengthOrAuto); !st) return st.error();
    if (auto st = readKnobs(*object, knobs.bools, readBool); !st) return st.error();
    return out;
}

void warnUnknownShadowKeys(const tinygltf::Value& extras, const std::string& where, bool light,
                           std::vector<Warning>& warnings) {
    const tinygltf::Value* object = member(extras, "shadow");
    if (object == nullptr || !object->IsObject()) return;
    const std::string objectWhere = where + ".extras.shadow";
    const std::vector<std::string_view> keys = knownKeys(light);
    for (const std::string& key : object->Keys()) {
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
        std::string_view closest;
        std::size_t best = 3;  // suggest only within two edits
        for (const std::string_view k : keys) {
            const std::size_t d = editDistance(key, k);
            if (d < best) {
                best = d;
                closest = k;
            }
        }
        // Keys are quoted at most 64 bytes long: a file may hold any key.
        const std::string shown = key.size() > 64 ? key.substr(0, 64) + "\u2026" : key;
        std::string message = objectWhere + ": unknown key \"" + shown + "\" ignored";
        if (!closest.empty()) message += " (did you mean \"" + std::string(closest) + "\"?)";
        warnings.push_back({WarningCode::UnknownSetting, objectWhere + "." + shown, message});
    }
}

Result<MeshShadowFlags> parseMeshShadowExtras(const tinygltf::Value& extras, const std::string& where) {
    auto object = findShadowObject(extras, where);
    if (!object) return object.error();
    MeshShadowFlags out;
    if (object->value == nullptr) return out;
    if (auto st = readKnobs(*object, meshKnobs(out), readBool); !st) return st.error();
    return out;
}

}  // namespace shadow::gltf
