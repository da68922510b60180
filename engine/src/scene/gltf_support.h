// What the importer does with each glTF extension and core feature a file may use, in one
// table (gltf_support.cpp, `kFeatures`): read, or left out with one `UnsupportedFeature`
// warning per kind, or, for an extension the file requires and no drawing can do without,
// refused. When the module learns a feature, its row changes to `Read` (or goes), and nothing
// else here does.
#pragma once

#include <shadow/result.h>
#include <shadow/warnings.h>

#include <nlohmann/json.hpp>

#include <span>
#include <vector>

namespace shadow::gltf {

/// What the module does with one extension or feature.
enum class Support {
    Read,     ///< drawn (or, like metadata, has nothing to draw): no warning
    Dropped,  ///< left out, the rest drawn: one warning; a file may require it
    Refused,  ///< left out when merely used (the file carries a fallback); required: the load fails
};

/// One row of the table.
struct FeatureSupport {
    const char* name;     ///< an extension's name, or a core feature's (`morph targets`)
    Support support;      ///< see `Support`
    const char* instead;  ///< Dropped and Refused: what the module draws without it
};

/// Every extension and core feature the module knows, in the order warnings are given.
[[nodiscard]] std::span<const FeatureSupport> featureTable();

/// Checks the file's `extensionsRequired` against the table (an extension it does not know, or
/// one it refuses, fails with one error naming it), then returns one warning per extension or
/// feature the file uses that the module leaves out, its element the first use (`materials[0].
/// pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform`, `meshes[1].
/// primitives[0].targets`), its message the count of uses and what is drawn instead. An
/// extension the table knows is used where an object names it (files list extensions no
/// object uses; `KHR_mesh_quantization`, which has no objects, where it is listed); one it does
/// not know, used but not required, is one warning too, at `extensionsUsed` when no object
/// names it. `KHR_texture_transform` objects that transform nothing (offset 0, rotation 0,
/// scale 1, the texture reference's own texCoord) are not counted.
[[nodiscard]] Result<std::vector<Warning>> checkSupport(const nlohmann::json& document);

}  // namespace shadow::gltf
