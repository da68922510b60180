// The JSON types of the glTF core members the importer reads, checked on the file's own JSON.
// tinygltf takes an optional member of the wrong type for absent and keeps its default
// (`"alphaCutoff": "half"` reads as 0.5, `"translation": ["1", 0, 0]` as the origin), so a
// typing mistake in a file would be drawn silently as something else. Here it is an error
// naming the member, as the engine's own reads of `extras` and extension objects are.
#pragma once

#include <shadow/result.h>

#include <nlohmann/json.hpp>

namespace shadow::gltf {

/// Checks every core member the importer reads (scenes, nodes, meshes, materials, textures,
/// samplers, images, accessors, buffer views, buffers, animations, skins, cameras, the
/// extension lists) for its JSON type: a number, an integer (a JSON integer within `int`, as
/// tinygltf reads indices), a string, a boolean, an object, or an array of one of those. The
/// error names the member, e.g. `materials[0].alphaCutoff: must be a number, not a string`.
/// Members it does not list (extensions, extras, names of other kinds) are not looked at.
[[nodiscard]] Status checkMemberTypes(const nlohmann::json& document);

}  // namespace shadow::gltf
