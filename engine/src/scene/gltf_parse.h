// glTF bytes to a tinygltf::Model, with the engine's callbacks: images are kept encoded (a
// material decodes the ones it uses), URIs are file names taken literally (not shell
// words), and in-memory input reads no file at all. tinygltf's messages become one-line
// errors that start with the file (or in-memory) name. The scene file and every external buffer
// or image must be regular files (a FIFO, directory or device is refused before it is opened).
#pragma once

#include <shadow/result.h>
#include <shadow/warnings.h>
#include <tiny_gltf.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace shadow::gltf {

/// Deepest nesting of JSON arrays and objects read (a glTF needs about 10; `extras` may hold a
/// game's own data). tinygltf converts JSON recursively, so deeper input could exhaust the
/// stack: it is refused before tinygltf sees it.
inline constexpr std::size_t kMaxJsonDepth = 64;

/// Longest message quoted from tinygltf (bytes, then "…"); data: URIs in it are never quoted.
inline constexpr std::size_t kMaxQuotedMessage = 300;

/// A parsed file, and what its JSON uses that the module leaves out.
struct ParsedGltf {
    tinygltf::Model model;
    /// `UnsupportedFeature` warnings (gltf_support.h); messages without the file name.
    std::vector<Warning> warnings;
};

/// Parses the file: binary when it starts with the GLB magic, JSON otherwise. A `.glb`
/// without the magic is an error rather than a JSON parse. Then the JSON itself is checked:
/// the types of the core members (gltf_schema.h) and the extensions it requires
/// (gltf_support.h), and what it uses that the module leaves out becomes `warnings`.
[[nodiscard]] Result<ParsedGltf> readModel(const std::string& path);

/// Parses `bytes` as `readModel` does: GLB when they start with the magic "glTF", JSON
/// otherwise. An external buffer URI is an error, never a file access. `name` starts every error.
[[nodiscard]] Result<ParsedGltf> readModelFromMemory(std::string_view bytes, const std::string& name);

}  // namespace shadow::gltf
