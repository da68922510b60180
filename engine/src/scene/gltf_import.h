// The glTF importer's entry point for bytes already in memory (the fuzzer's; loadGltf in
// scene.h reads files).
#pragma once

#include <shadow/scene.h>

#include <string>
#include <string_view>

namespace shadow::gltf {

/// Loads glTF 2.0 from `bytes`: GLB when they start with the magic "glTF", JSON otherwise.
/// Only embedded data (`data:` URIs, the GLB's own chunk) is read: an external buffer URI is an
/// error, never a file access. `name` names the scene and starts every error and warning.
[[nodiscard]] Result<Scene> loadGltfFromMemory(std::string_view bytes, const std::string& name,
                                               const GltfLoadOptions& options = {});

}  // namespace shadow::gltf
