// glTF bytes to a tinygltf::Model, with the engine's callbacks: images are accepted without
// being decoded (the engine uses no textures), URIs are file names taken literally (not shell
// words), and in-memory input reads no file at all. tinygltf's messages become one-line
// errors that start with the file (or in-memory) name. The scene file and every external buffer
// or image must be regular files (a FIFO, directory or device is refused before it is opened).
#pragma once

#include <shadow/result.h>
#include <tiny_gltf.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace shadow::gltf {

/// Deepest nesting of JSON arrays and objects read (a glTF needs about 10; `extras` may hold a
/// game's own data). tinygltf converts JSON recursively, so deeper input could exhaust the
/// stack: it is refused before tinygltf sees it.
inline constexpr std::size_t kMaxJsonDepth = 64;

/// Longest message quoted from tinygltf (bytes, then "…"); data: URIs in it are never quoted.
inline constexpr std::size_t kMaxQuotedMessage = 300;

/// Parses the file: binary when it starts with the GLB magic, JSON otherwise. A `.glb`
/// without the magic is an error rather than a JSON parse.
[[nodiscard]] Result<tinygltf::Model> readModel(const std::string& path);

/// Parses `bytes`: GLB when they start with the magic "glTF", JSON otherwise. An external
/// buffer URI is an error, never a file access. `name` starts every error.
[[nodiscard]] Result<tinygltf::Model> readModelFromMemory(std::string_view bytes, const std::string& name);

}  // namespace shadow::gltf
