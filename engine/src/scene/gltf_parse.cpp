#include "scene/gltf_parse.h"

#include <shadow/image_io.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/gltf_schema.h"
#include "scene/gltf_support.h"

namespace shadow::gltf {
namespace {

/// Keeps every image encoded (its bytes, no larger than the file): a material decodes the ones
/// it uses (gltf_textures.cpp), and an image no material uses costs no decoding.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    if (bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
    image->width = 0;
    image->height = 0;
    return true;
}

/// tinygltf's default expands URIs with wordexp(3), a shell-like expansion; URIs are file
/// names, not shell words, so take them literally.
std::string literalPath(const std::string& path, void*) { return path; }

/// tinygltf quotes the element at fault, and that may be a whole data: URI (megabytes of
/// base64): each one becomes `data:… (N bytes)`.
std::string withoutDataUris(const std::string& text) {
    std::string out;
    std::size_t at = 0;
    for (std::size_t found = text.find("data:"); found != std::string::npos; found = text.find("data:", at)) {
        std::size_t end = found;
        while (end < text.size() && text[end] != '"' && text[end] != '\'' && text[end] != '\n' &&
               !std::isspace(static_cast<unsigned char>(text[end]))) {
            ++end;
        }
        out.append(text, at, found - at);
        out += "data:\u2026 (" + std::to_string(end - found) + " bytes)";
        at = end;
    }
    out.append(text, at, std::string::npos);
    return out;
}

/// tinygltf messages end in newlines and may hold several lines, and may quote input at any
/// length: make them one line of at most kMaxQuotedMessage bytes, data: URIs never quoted.
std::string oneLine(const std::string& raw) {
    std::string text = withoutDataUris(raw);
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    if (text.size() > kMaxQuotedMessage) {
        std::size_t cut = kMaxQuotedMessage;
        while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) --cut;  // whole UTF-8 only
        text.resize(cut);
        text += "\u2026";
    }
    return text.empty() ? "could not be parsed" : text;
}

/// The file's bytes; errors name it. Checked to be a regular file first.
Result<std::string> readWholeFile(const std::string& path) {
    if (std::optional<std::string> what = notRegularFile(path))
        return Error{ErrorCode::FileUnreadable, path + ": " + *what};
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    const std::streamoff size = file ? static_cast<std::streamoff>(file.tellg()) : -1;
    if (size < 0) return Error{ErrorCode::FileUnreadable, path + ": cannot be read"};
    std::string bytes(static_cast<std::size_t>(size), '\0');
    file.seekg(0);
    if (!file.read(bytes.data(), size)) return Error{ErrorCode::FileUnreadable, path + ": cannot be read"};
    return bytes;
}

/// The deepest nesting of arrays and objects in `json` (brackets inside strings skipped).
std::size_t jsonNestingDepth(std::string_view json) {
    std::size_t depth = 0;
    std::size_t deepest = 0;
    bool inString = false;
    bool escaped = false;
    for (const char c : json) {
        if (inString) {
            if (escaped) {
                escaped = false;
            } else if (c == '\\') {
                escaped = true;
            } else if (c == '"') {
                inString = false;
            }
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

/// The JSON text of `bytes`: all of it, or a GLB's JSON chunk (as much of it as is there; a
/// malformed header is tinygltf's to report).
std::string_view jsonText(std::string_view bytes, bool binary) {
    if (!binary) return bytes;
    constexpr std::size_t kHeader = 12;
    constexpr std::size_t kChunkHeader = 8;
    if (bytes.size() < kHeader + kChunkHeader) return {};
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + kHeader, sizeof(length));  // GLB is little-endian, as is every target
    return bytes.substr(kHeader + kChunkHeader, length);
}

/// tinygltf converts JSON recursively, a stack frame per level: refuse deep nesting up front.
Status checkJsonDepth(std::string_view bytes, bool binary, const std::string& name) {
    const std::size_t depth = jsonNestingDepth(jsonText(bytes, binary));
    if (depth > kMaxJsonDepth) {
        return Error{ErrorCode::MalformedFile, name + ": JSON nested " + std::to_string(depth) +
                                                   " levels deep; at most " + std::to_string(kMaxJsonDepth) +
                                                   " are read"};
    }
    return Ok{};
}

bool hasBinaryMagic(std::string_view bytes) { return bytes.size() >= 4 && bytes.substr(0, 4) == "glTF"; }

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

/// External buffers and images: a path that names something (so that tinygltf reads it and
/// tells what it is) without opening it, as opening a FIFO blocks.
bool pathExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}
bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    if (std::optional<std::string> what = notRegularFile(path)) {
        if (err != nullptr) *err += *what;
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

/// In-memory input reads no file: an external buffer URI is an error, not a disk access.
bool noFileExists(const std::string&, void*) { return false; }
bool noFileRead(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
    if (err != nullptr) *err += "external file \"" + path + "\" is not read when loading from memory\n";
    return false;
}

/// Runs one tinygltf load (`load(loader, model, err, warn)`) with the engine's callbacks:
/// images kept encoded, URIs literal, and, for in-memory input, no file access at all. Errors start
/// with `name`.
template <typename Load>
Result<tinygltf::Model> parseModel(const std::string& name, bool filesAllowed, Load load) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&keepEncodedImage, nullptr);
    if (filesAllowed) {
        loader.SetFsCallbacks({&pathExists, &literalPath, &readRegularFile, &tinygltf::WriteWholeFile, nullptr});
    } else {
        loader.SetFsCallbacks({&noFileExists, &literalPath, &noFileRead, &tinygltf::WriteWholeFile, nullptr});
    }
    tinygltf::Model model;
    std::string err;
    std::string warn;
    bool ok = false;
    try {
        ok = load(loader, model, err, warn);
    } catch (const std::exception& e) {  // tinygltf throws on some malformed input
        err = e.what();
    }
    if (!ok) return Error{ErrorCode::MalformedFile, name + ": " + oneLine(err)};
    return model;
}

/// A buffer's stand-in for tinygltf's parse: one byte, as it refuses an empty data URI.
constexpr const char* kStandInUri = "data:application/octet-stream;base64,AA==";

/// `text` with a stand-in data URI in every buffer that has no `uri`, and those buffers'
/// indices; nullopt when the JSON does not parse (tinygltf then says why) or has no such buffer.
std::optional<std::pair<std::string, std::vector<std::size_t>>> withStandInBuffers(std::string_view text) {
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded() || !doc.is_object()) return std::nullopt;
    const auto buffers = doc.find("buffers");
    if (buffers == doc.end() || !buffers->is_array()) return std::nullopt;
    std::vector<std::size_t> standIns;
    for (std::size_t i = 0; i < buffers->size(); ++i) {
        nlohmann::json& buffer = (*buffers)[i];
        if (!buffer.is_object() || buffer.contains("uri")) continue;
        buffer["uri"] = kStandInUri;
        buffer["byteLength"] = 1;
        standIns.push_back(i);
    }
    if (standIns.empty()) return std::nullopt;
    return std::pair(doc.dump(), std::move(standIns));
}

/// Parses a .gltf's JSON `text`. glTF allows a buffer without `uri` only as a .glb's BIN chunk,
/// and tinygltf refuses one in a .gltf; but a file whose bufferViews never read it holds a
/// whole scene. So such a buffer is parsed with a stand-in and left empty (no uri, no data),
/// and a read of it fails naming the buffer (gltf_accessors.cpp).
Result<tinygltf::Model> parseAscii(const std::string& name, bool filesAllowed, std::string_view text,
                                   const std::string& baseDir) {
    const auto parse = [&](std::string_view json) {
        return parseModel(name, filesAllowed,
                          [&](tinygltf::TinyGLTF& loader, tinygltf::Model& m, std::string& err, std::string& warn) {
                              return loader.LoadASCIIFromString(&m, &err, &warn, json.data(),
                                                                static_cast<unsigned int>(json.size()), baseDir);
                          });
    };
    Result<tinygltf::Model> model = parse(text);
    if (model || model.error().message.find("'uri' is missing") == std::string::npos) return model;
    auto patched = withStandInBuffers(text);
    if (!patched || patched->first.size() > std::numeric_limits<unsigned int>::max()) return model;
    Result<tinygltf::Model> retried = parse(patched->first);
    if (!retried) return retried;
    for (const std::size_t i : patched->second) {
        retried->buffers[i].uri.clear();
        retried->buffers[i].data.clear();
    }
    return retried;
}

/// The checks of the JSON that tinygltf leaves out, after it parsed `json` into `model`:
/// member types, then the required extensions; errors start with `name`.
Result<ParsedGltf> checkDocument(Result<tinygltf::Model> model, std::string_view json, const std::string& name) {
    if (!model) return model.error();
    const nlohmann::json document = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
    if (Status s = checkMemberTypes(document); !s) return s.error().within(name + ": ");
    auto warnings = checkSupport(document);
    if (!warnings) return warnings.error().within(name + ": ");
    return ParsedGltf{std::move(*model), std::move(*warnings)};
}

}  // namespace

Result<ParsedGltf> readModel(const std::string& path) {
    Result<std::string> bytes = readWholeFile(path);
    if (!bytes) return bytes.error();
    const bool binary = hasBinaryMagic(*bytes);
    if (!binary && lowerExtension(path) == ".glb") {
        return Error{ErrorCode::MalformedFile, path + ": not a binary glTF file (the header magic is not \"glTF\")"};
    }
    if (Status s = checkJsonDepth(*bytes, binary, path); !s) return s.error();
    if (bytes->size() > std::numeric_limits<unsigned int>::max())
        return Error{ErrorCode::LimitExceeded, path + ": too large"};
    // External buffers and images are found beside the file.
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    if (!binary) return checkDocument(parseAscii(path, true, *bytes, baseDir), *bytes, path);
    const auto* data = reinterpret_cast<const unsigned char*>(bytes->data());
    const auto size = static_cast<unsigned int>(bytes->size());
    return checkDocument(
        parseModel(path, true,
                   [&](tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& err, std::string& warn) {
                       return loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, baseDir);
                   }),
        jsonText(*bytes, true), path);
}

Result<ParsedGltf> readModelFromMemory(std::string_view bytes, const std::string& name) {
    const bool binary = hasBinaryMagic(bytes);
    if (Status s = checkJsonDepth(bytes, binary, name); !s) return s.error();
    // tinygltf takes the length as unsigned int.
    if (bytes.size() > std::numeric_limits<unsigned int>::max())
        return Error{ErrorCode::LimitExceeded, name + ": too large"};
    if (!binary) return checkDocument(parseAscii(name, false, bytes, ""), bytes, name);
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto size = static_cast<unsigned int>(bytes.size());
    return checkDocument(
        parseModel(name, false,
                   [&](tinygltf::TinyGLTF& loader, tinygltf::Model& m, std::string& err, std::string& warn) {
                       return loader.LoadBinaryFromMemory(&m, &err, &warn, data, size, "");
                   }),
        jsonText(bytes, true), name);
}

}  // namespace shadow::gltf
