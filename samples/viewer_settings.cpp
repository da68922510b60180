#include "viewer_settings.h"

#include <array>
#include <charconv>
#include <cmath>

namespace shadow::viewer {
namespace {

constexpr unsigned kAllTypes = 7u;
constexpr unsigned kDirectional = 1u << static_cast<unsigned>(LightType::Directional);
constexpr unsigned kLocal =
    (1u << static_cast<unsigned>(LightType::Spot)) | (1u << static_cast<unsigned>(LightType::Point));
constexpr unsigned kAllTechniques = ~0u;
constexpr unsigned kMapped = ~(techniqueBit(ShadowTechnique::None));
constexpr unsigned kSoft = techniqueBit(ShadowTechnique::Pcss) | techniqueBit(ShadowTechnique::PcssTextbook) |
                           techniqueBit(ShadowTechnique::Vssm) | techniqueBit(ShadowTechnique::MsmSoft) |
                           techniqueBit(ShadowTechnique::Sdf);
constexpr unsigned kFiltered = techniqueBit(ShadowTechnique::Pcf) | techniqueBit(ShadowTechnique::Vsm);
constexpr unsigned kTaps = techniqueBit(ShadowTechnique::Pcf) | techniqueBit(ShadowTechnique::Pcss);

using Kind = LightSetting::Kind;

// The rows, in panel order; ranges as components.h documents them.
const std::array<LightSetting, 16> kSettings = {{
    {"technique", "technique", Kind::Technique, 0, 0, false, kAllTypes, kAllTechniques},
    {"radius", "emitter radius (m)", Kind::Float, 0.0f, 2.0f, false, kLocal, kSoft, &Light::radius},
    {"angularRadius", "emitter half-angle (rad)", Kind::Float, 0.0f, 0.2f, false, kDirectional, kSoft,
     &Light::angularRadius},
    {"mapSize", "map size (texels)", Kind::Int, 16, 4096, true, kAllTypes, kMapped, nullptr, nullptr, &Shadow::mapSize},
    {"pcfSamples", "PCF taps", Kind::Int, 1, 64, false, kAllTypes, kTaps, nullptr, nullptr, &Shadow::pcfSamples},
    {"blockerSamples", "PCSS blocker taps", Kind::Int, 1, 64, false, kAllTypes, techniqueBit(ShadowTechnique::Pcss),
     nullptr, nullptr, &Shadow::blockerSamples},
    {"pcfRadius", "filter radius (m)", Kind::Float, 0.0f, 0.5f, false, kAllTypes, kFiltered, nullptr,
     &Shadow::pcfRadius},
    {"maxFilterTexels", "max filter (texels)", Kind::Float, 1.0f, 256.0f, true, kAllTypes,
     techniqueBit(ShadowTechnique::Pcss), nullptr, &Shadow::maxFilterTexels},
    {"constantBias", "constant bias (m)", Kind::Float, 0.0f, 0.05f, false, kAllTypes, kMapped, nullptr,
     &Shadow::constantBias},
    {"slopeBias", "slope bias (texels)", Kind::Float, 0.0f, 16.0f, false, kAllTypes, kMapped, nullptr,
     &Shadow::slopeBias},
    {"normalOffset", "normal offset (texels)", Kind::Float, 0.0f, 16.0f, false, kAllTypes, kMapped, nullptr,
     &Shadow::normalOffset},
    {"cascades", "cascades", Kind::Int, 1, 4, false, kDirectional, kMapped, nullptr, nullptr, &Shadow::cascades},
    {"cascadeSplitLambda", "split lambda", Kind::Float, 0.0f, 1.0f, false, kDirectional, kMapped, nullptr,
     &Shadow::cascadeSplitLambda},
    {"depthMode", "depth mode", Kind::DepthMode, 0, 0, false, kAllTypes, kMapped & ~techniqueBit(ShadowTechnique::Sdf)},
    {"sdfSteps", "sdf steps", Kind::Int, 4, 256, true, kAllTypes, techniqueBit(ShadowTechnique::Sdf), nullptr, nullptr,
     &Shadow::sdfSteps},
    {"lightBleedReduction", "light bleed reduction", Kind::Float, 0.0f, 0.95f, false, kAllTypes,
     techniqueBit(ShadowTechnique::Vsm) | techniqueBit(ShadowTechnique::Vssm), nullptr, &Shadow::lightBleedReduction},
}};

}  // namespace

std::span<const LightSetting> lightSettings() { return kSettings; }

const LightSetting* findLightSetting(std::string_view key) {
    for (const LightSetting& s : kSettings) {
        if (key == s.key) return &s;
    }
    return nullptr;
}

std::string lightSettingKeys() {
    std::string keys;
    for (const LightSetting& s : kSettings) keys += (keys.empty() ? "" : ", ") + std::string(s.key);
    return keys;
}

bool settingApplies(const LightSetting& setting, LightType type, ShadowTechnique technique) {
    return (setting.lightTypes & (1u << static_cast<unsigned>(type))) != 0 &&
           (setting.techniques & techniqueBit(technique)) != 0;
}

double readSetting(const World& world, Entity light, const LightSetting& setting) {
    if (setting.lightFloat != nullptr) {
        const Light* l = world.tryGet<Light>(light);
        return l != nullptr ? l->*setting.lightFloat : Light{}.*setting.lightFloat;
    }
    const Shadow* found = world.tryGet<Shadow>(light);
    const Shadow s = found != nullptr ? *found : Shadow{.technique = ShadowTechnique::None};
    switch (setting.kind) {
        case Kind::Technique: return static_cast<double>(s.technique);
        case Kind::DepthMode: return static_cast<double>(s.depthMode);
        case Kind::Int: return s.*setting.shadowInt;
        case Kind::Float: return s.*setting.shadowFloat;
    }
    return 0.0;
}

void writeSetting(World& world, Entity light, const LightSetting& setting, double value) {
    if (setting.lightFloat != nullptr) {
        if (Light* l = world.tryGet<Light>(light)) l->*setting.lightFloat = static_cast<float>(value);
        return;
    }
    Shadow* s = world.tryGet<Shadow>(light);
    if (s == nullptr) s = &world.emplace<Shadow>(light);
    switch (setting.kind) {
        case Kind::Technique: s->technique = static_cast<ShadowTechnique>(value); break;
        case Kind::DepthMode: s->depthMode = static_cast<DepthMode>(value); break;
        case Kind::Int: s->*setting.shadowInt = static_cast<int>(value); break;
        case Kind::Float: s->*setting.shadowFloat = static_cast<float>(value); break;
    }
}

Result<double> parseSettingValue(const LightSetting& setting, std::string_view text) {
    switch (setting.kind) {
        case Kind::Technique: {
            if (auto t = techniqueFromName(text)) return static_cast<double>(*t);
            return Error{ErrorCode::InvalidArgument,
                         "unknown technique '" + std::string(text) + "' (known: " + techniqueNameList() + ")"};
        }
        case Kind::DepthMode: {
            if (auto m = depthModeFromName(text)) return static_cast<double>(*m);
            return Error{ErrorCode::InvalidArgument,
                         "unknown depth mode '" + std::string(text) + "' (known: nearest, midpoint, second)"};
        }
        case Kind::Int: {
            int v = 0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc{} || end != text.data() + text.size()) {
                return Error{ErrorCode::InvalidArgument,
                             std::string(setting.key) + " '" + std::string(text) + "': expected an integer"};
            }
            return static_cast<double>(v);
        }
        case Kind::Float: {
            if (text == "auto" && setting.shadowFloat != nullptr && isAutomatic(Shadow{}.*setting.shadowFloat)) {
                return static_cast<double>(kAutomatic);  // a length whose default is derived from the scene
            }
            double v = 0.0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(v)) {
                return Error{ErrorCode::InvalidArgument,
                             std::string(setting.key) + " '" + std::string(text) + "': expected a finite number"};
            }
            return v;
        }
    }
    return Error{ErrorCode::InvalidArgument, "unreadable value"};
}

}  // namespace shadow::viewer
