// KHR_lights_punctual lights, with the engine's `extras.shadow` settings.
//
// The light objects are read from the raw extension value
// (`model.extensions["KHR_lights_punctual"]["lights"]`) rather than tinygltf's `model.lights`,
// because tinygltf silently keeps defaults for mistyped members (`"intensity": "bright"`),
// while the engine reports them.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <shadow/warnings.h>
#include <tiny_gltf.h>

#include <optional>
#include <string>
#include <vector>

namespace shadow::gltf {

/// One light of the file, ready to be instanced on the nodes that reference it.
struct LightDefinition {
    std::string name;  ///< may be empty
    Light light;
    /// Absent when `extras.shadow.technique` is "none": such a light gets no `Shadow`.
    std::optional<Shadow> shadow;
    /// False for a light of an unknown `type` (warned as `UnsupportedLight`): nodes that
    /// reference it get no light.
    bool supported = true;
};

/// Every light of the file, in file order; empty when the extension is absent. With
/// `strictShadowSettings` off, a light whose `extras.shadow` does not parse keeps the defaults
/// and a `ShadowSettingsIgnored` warning goes to `warnings`.
[[nodiscard]] Result<std::vector<LightDefinition>> importLights(const tinygltf::Model& model, bool strictShadowSettings,
                                                                std::vector<Warning>& warnings);

/// The light `nodes[nodeIndex]` references through its KHR_lights_punctual extension, or
/// nullopt for none. The index is checked against `lightCount`.
[[nodiscard]] Result<std::optional<std::size_t>> nodeLight(const tinygltf::Node& node, std::size_t nodeIndex,
                                                           std::size_t lightCount);

}  // namespace shadow::gltf
