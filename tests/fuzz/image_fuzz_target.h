// What the image fuzzer does with one input: the bytes become the one image of a small GLB (a
// triangle whose material reads that image as each of its five maps, from a bufferView, as an
// exported GLB holds its textures), which is loaded from memory; on what
// loads, every texture must be a whole decoded image inside the loader's limits, and the CPU
// half of a few frames runs (gltf_fuzz_target.h). The image decoder is reached through the same
// path a file's images take. Shared by tests/fuzz/image_fuzzer.cpp and the GoogleTest that
// checks decoded pixels and replays the seeds (image_fuzz_test.cpp).
#pragma once

#include <shadow/scene.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "fuzz/gltf_fuzz_target.h"
#include "scene/glb_bytes.h"
#include "scene/gltf_textures.h"

namespace shadow::fuzz {

/// A GLB whose only image is `image`, read by a triangle's material as its base colour (alpha
/// mode MASK, so the cut-out path reads the alpha too), metallic-roughness, normal, occlusion and
/// emissive maps.
inline std::string glbAroundImage(std::string_view image) {
    // Binary chunk: three positions (36 bytes), three texture coordinates (24), the image.
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float texcoords[6] = {0, 0, 1, 0, 0, 1};
    std::string bin(reinterpret_cast<const char*>(positions), sizeof(positions));
    bin.append(reinterpret_cast<const char*>(texcoords), sizeof(texcoords));
    bin.append(image);
    using nlohmann::json;
    const json map = {{"index", 0}};
    const json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
        {"materials",
         {{{"alphaMode", "MASK"},
           {"pbrMetallicRoughness", {{"baseColorTexture", map}, {"metallicRoughnessTexture", map}}},
           {"normalTexture", map},
           {"occlusionTexture", map},
           {"emissiveTexture", map},
           {"emissiveFactor", {1, 1, 1}}}}},
        {"textures", {{{"source", 0}}}},
        {"images", {{{"bufferView", 2}, {"mimeType", "image/png"}}}},
        {"buffers", {{{"byteLength", bin.size()}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}},
          {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", image.size()}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 3},
           {"type", "VEC3"},
           {"min", {0, 0, 0}},
           {"max", {1, 1, 0}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}}};
    return gltf_test::glbOf(doc.dump(), std::move(bin));
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

/// One fuzz input: `data` as the image of `glbAroundImage`, loaded once (the document has no
/// `extras.shadow`, so a strict and a lenient load read it alike). Returns the load (for the
/// tests); never throws, aborts only on a broken invariant (or a sanitizer report).
inline Result<Scene> runImageInput(const std::uint8_t* data, std::size_t size) {
    const std::string glb = glbAroundImage(std::string_view(reinterpret_cast<const char*>(data), size));
    Result<Scene> scene = gltf::loadGltfFromMemory(glb, "image.glb");
    if (scene.ok()) {
        scene->world.view<Material>().each([](Entity, const Material& m) {
            checkTexture(m.baseColorTexture);
            for (const MaterialMap* map : {&m.metallicRoughnessMap, &m.normalMap, &m.occlusionMap, &m.emissiveMap}) {
                checkTexture(map->texture);
            }
        });
        runCpuFrames(*scene);
    }
    return scene;
}

}  // namespace shadow::fuzz
