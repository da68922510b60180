// What the image fuzzer does with one input: the bytes become the one image of a small GLB (a
// triangle whose material reads that image as each of its five maps, from a bufferView, as an
// exported GLB holds its textures), which is loaded from memory, strict and lenient; on what
// loads, every texture must be a whole decoded image inside the loader's limits, and the CPU
// half of a few frames runs (gltf_fuzz_target.h). The image decoder is reached through the same
// path a file's images take. Shared by tests/fuzz/image_fuzzer.cpp and the GoogleTest that
// checks decoded pixels and replays the seeds (image_fuzz_test.cpp).
#pragma once

#include <shadow/scene.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include "fuzz/gltf_fuzz_target.h"
#include "scene/gltf_textures.h"

namespace shadow::fuzz {

/// A GLB whose only image is `image`, read by a triangle's material as its base colour (alpha
/// mode MASK, so the cut-out path reads the alpha too), metallic-roughness, normal, occlusion and
/// emissive maps.
inline std::string glbAroundImage(std::string_view image) {
    // Binary chunk: three positions (36 bytes), three texture coordinates (24), the image.
    std::string bin(60, '\0');
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float texcoords[6] = {0, 0, 1, 0, 0, 1};
    std::memcpy(bin.data(), positions, sizeof(positions));
    std::memcpy(bin.data() + 36, texcoords, sizeof(texcoords));
    bin.append(image);
    while (bin.size() % 4 != 0) bin.push_back('\0');
    const std::string map = R"({"index":0})";
    std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)";
    json.append(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],)");
    json.append(R"("materials":[{"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":)")
        .append(map)
        .append(R"(,"metallicRoughnessTexture":)")
        .append(map)
        .append(R"(},"normalTexture":)")
        .append(map)
        .append(R"(,"occlusionTexture":)")
        .append(map)
        .append(R"(,"emissiveTexture":)")
        .append(map)
        .append(R"(,"emissiveFactor":[1,1,1]}],)");
    json.append(R"("textures":[{"source":0}],"images":[{"bufferView":2,"mimeType":"image/png"}],)");
    json.append(R"("buffers":[{"byteLength":)").append(std::to_string(bin.size())).append("}],");
    json.append(R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},)");
    json.append(R"({"buffer":0,"byteOffset":36,"byteLength":24},)");
    json.append(R"({"buffer":0,"byteOffset":60,"byteLength":)").append(std::to_string(image.size())).append("}],");
    json.append(R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)");
    json.append(R"("min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}]})");
    while (json.size() % 4 != 0) json.push_back(' ');

    std::string glb;
    const auto u32 = [&glb](std::size_t v) {
        const auto x = static_cast<std::uint32_t>(v);
        glb.append(reinterpret_cast<const char*>(&x), 4);  // little-endian hosts only, as the loader
    };
    glb.append("glTF");
    u32(2);
    u32(12 + 8 + json.size() + 8 + bin.size());
    u32(json.size());
    glb.append("JSON");
    glb.append(json);
    u32(bin.size());
    glb.append("BIN\0", 4);
    glb.append(bin);
    return glb;
}

/// Aborts unless `texture` is absent (an image the loader drops with a warning) or a whole
/// decoded image inside the loader's limits.
inline void checkTexture(const std::shared_ptr<const Texture>& texture) {
    if (texture == nullptr) return;
    check(texture->width >= 1 && texture->height >= 1 && texture->width <= gltf::kMaxTextureEdge &&
              texture->height <= gltf::kMaxTextureEdge &&
              static_cast<long long>(texture->width) * texture->height <= gltf::kMaxTexturePixels,
          "texture size inside the loader's limits");
    check(texture->rgba.size() ==
              static_cast<std::size_t>(texture->width) * static_cast<std::size_t>(texture->height) * 4U,
          "texture holds width x height RGBA pixels");
}

/// One fuzz input: `data` as the image of `glbAroundImage`. Returns the strict load (for the
/// tests); never throws, aborts only on a broken invariant (or a sanitizer report).
inline Result<Scene> runImageInput(const std::uint8_t* data, std::size_t size) {
    const std::string glb = glbAroundImage(std::string_view(reinterpret_cast<const char*>(data), size));
    Result<Scene> strict = Error{ErrorCode::InvalidValue, "not loaded"};
    for (bool isStrict : {true, false}) {
        GltfLoadOptions options;
        options.strictShadowSettings = isStrict;
        Result<Scene> scene = gltf::loadGltfFromMemory(glb, "image.glb", options);
        if (scene.ok()) {
            scene->world.view<Material>().each([](Entity, const Material& m) {
                checkTexture(m.baseColorTexture);
                for (const MaterialMap* map :
                     {&m.metallicRoughnessMap, &m.normalMap, &m.occlusionMap, &m.emissiveMap}) {
                    checkTexture(map->texture);
                }
            });
            runCpuFrames(*scene);
        }
        if (isStrict) strict = std::move(scene);
    }
    return strict;
}

}  // namespace shadow::fuzz
