// The engine's glTF `extras.shadow` objects, parsed from tinygltf values. Kept apart from the
// importer so a fuzzer can feed arbitrary JSON values to them directly.
//
// Light extras (`KHR_lights_punctual.lights[i].extras.shadow`):
//   technique        a name of the technique table (techniques.h)  (default "hard")
//   kernel           "vogel" | "poisson" | "uniform"; depthMode "nearest" | "midpoint" | "second"
//   mapSize, pcfSamples, blockerSamples, cascades, sdfSteps   positive integers
//   radius, angularRadius, slopeBias, normalOffset, lightBleedReduction,
//   cascadeSplitLambda, shadowDistance, nearPlane             finite numbers >= 0
//   constantBias, pcfRadius, sdfStartOffset, sdfMinStep,      finite numbers >= 0 (m; maxFilterTexels
//   contactLength, maxFilterTexels                            texels), or "auto" (the default:
//                                                             derived from the scene)
// Mesh node extras (`nodes[i].extras.shadow`):
//   cast, receive                                             booleans (default true)
//
// Only type, sign and finiteness are checked here: ranges are clamped (and reported) by the
// shadow system. Unknown keys are ignored so files can carry settings of newer engines, each
// with an `UnknownSetting` warning (warnUnknownShadowKeys) so that a misspelling is seen.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <shadow/warnings.h>
#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace shadow::gltf {

/// What a light's `extras.shadow` says. `radius`/`angularRadius` describe the emitter and go
/// to `Light`; the rest goes to the `Shadow` component, which a light gets only when
/// `shadow.technique != None`.
struct LightShadowExtras {
    Shadow shadow;
    float radius = 0.0f;         ///< m, to `Light::radius`
    float angularRadius = 0.0f;  ///< rad, to `Light::angularRadius`
};

/// Parses the `shadow` member of a light's `extras`. `extras` is the light's whole `extras`
/// value (null, or not an object, means "no settings": the defaults, technique Hard);
/// `where` names the light (`KHR_lights_punctual.lights[1]`) and errors read
/// `<where>.extras.shadow.<key>: <problem>`.
[[nodiscard]] Result<LightShadowExtras> parseShadowExtras(const tinygltf::Value& extras, const std::string& where);

/// What a mesh node's `extras.shadow` says.
struct MeshShadowFlags {
    bool cast = true;
    bool receive = true;
};

/// Parses the `shadow` member of a mesh node's `extras`, as `parseShadowExtras` does.
[[nodiscard]] Result<MeshShadowFlags> parseMeshShadowExtras(const tinygltf::Value& extras, const std::string& where);

/// Appends one `UnknownSetting` warning for every key of `extras.shadow` (an object) that a
/// light's (`light`) or a mesh node's object does not know, suggesting the closest known key
/// when it is at most two edits away. `where` names the light or node, as for the parsers.
void warnUnknownShadowKeys(const tinygltf::Value& extras, const std::string& where, bool light,
                           std::vector<Warning>& warnings);

/// `parsed` itself when it holds a value or `strict` is set; otherwise the defaults `T{}`, with
/// the error appended to `warnings` as `ShadowSettingsIgnored` (the lenient `GltfLoadOptions`).
/// `where` names the element whose `extras.shadow` was parsed (`nodes[0]`).
template <typename T>
[[nodiscard]] Result<T> orDefaults(Result<T> parsed, bool strict, const std::string& where,
                                   std::vector<Warning>& warnings) {
    if (parsed.ok() || strict) return parsed;
    warnings.push_back({WarningCode::ShadowSettingsIgnored, where + ".extras.shadow",
                        parsed.error().message + " (ignored: the defaults are used)"});
    return T{};
}

}  // namespace shadow::gltf
