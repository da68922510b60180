#include "scene/gltf_parse.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

namespace shadow::gltf {
namespace {

/// The engine uses no textures: accept every image without decoding it.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

/// tinygltf's default expands URIs with wordexp(3), a shell-like expansion; URIs are file
/// names, not shell words, so take them literally.
std::string literalPath(const std::string& path, void*) { return path; }

/// tinygltf messages end in newlines and may hold several lines; make them one line.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    return text.empty() ? "could not be parsed" : text;
}

bool hasBinaryMagic(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    char magic[4] = {};
    return file.read(magic, 4) && std::string(magic, 4) == "glTF";
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

/// In-memory input reads no file: an external buffer URI is an error, not a disk access.
bool noFileExists(const std::string&, void*) { return false; }
bool noFileRead(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
    if (err != nullptr) *err += "external file \"" + path + "\" is not read when loading from memory\n";
    return false;
}

/// Runs one tinygltf load (`load(loader, model, err, warn)`) with the engine's callbacks:
/// images skipped, URIs literal, and, for in-memory input, no file access at all. Errors start
/// with `name`.
template <typename Load>
Result<tinygltf::Model> parseModel(const std::string& name, bool filesAllowed, Load load) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skipImage, nullptr);
    if (filesAllowed) {
        loader.SetFsCallbacks(
            {&tinygltf::FileExists, &literalPath, &tinygltf::ReadWholeFile, &tinygltf::WriteWholeFile, nullptr});
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
    if (!ok) return Error{name + ": " + oneLine(err)};
    return model;
}

}  // namespace

Result<tinygltf::Model> readModel(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        return Error{path + ": no such file"};
    }
    const bool binary = hasBinaryMagic(path);
    if (!binary && lowerExtension(path) == ".glb") {
        return Error{path + ": not a binary glTF file (the header magic is not \"glTF\")"};
    }
    return parseModel(path, true,
                      [&](tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& err, std::string& warn) {
                          return binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                                        : loader.LoadASCIIFromFile(&model, &err, &warn, path);
                      });
}

Result<tinygltf::Model> readModelFromMemory(std::string_view bytes, const std::string& name) {
    const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
    // tinygltf takes the length as unsigned int.
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) return Error{name + ": too large"};
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto size = static_cast<unsigned int>(bytes.size());
    return parseModel(name, false,
                      [&](tinygltf::TinyGLTF& loader, tinygltf::Model& m, std::string& err, std::string& warn) {
                          return binary ? loader.LoadBinaryFromMemory(&m, &err, &warn, data, size, "")
                                        : loader.LoadASCIIFromString(&m, &err, &warn, bytes.data(), size, "");
                      });
}

}  // namespace shadow::gltf
