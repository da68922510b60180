// The bytes of a GLB container (glTF 2.0's binary form), for tests and fuzz targets that build
// documents in memory. Header-only and free of GoogleTest, so that a libFuzzer program can
// include it too.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace shadow::gltf_test {

/// A GLB holding `json` as its JSON chunk (padded with spaces) and, when `bin` is not empty,
/// `bin` as its BIN chunk (padded with zeros). Little-endian hosts only, as the loader.
inline std::string glbOf(std::string json, std::string bin = {}) {
    while (json.size() % 4 != 0) json.push_back(' ');
    while (bin.size() % 4 != 0) bin.push_back('\0');
    std::string glb;
    const auto u32 = [&glb](std::size_t v) {
        const auto x = static_cast<std::uint32_t>(v);
        glb.append(reinterpret_cast<const char*>(&x), 4);
    };
    const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
    glb.append("glTF");
    u32(2);
    u32(total);
    u32(json.size());
    glb.append("JSON").append(json);
    if (!bin.empty()) {
        u32(bin.size());
        glb.append(std::string_view("BIN\0", 4)).append(bin);
    }
    return glb;
}

}  // namespace shadow::gltf_test
