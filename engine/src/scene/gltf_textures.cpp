#include "scene/gltf_textures.h"

#include <stb_image.h>

#include <algorithm>
#include <climits>
#include <cstring>

#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

Texture::Wrap wrapOf(int mode) {
    switch (mode) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Texture::Wrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Texture::Wrap::MirroredRepeat;
        default: return Texture::Wrap::Repeat;
    }
}

/// The encoded bytes of `images[index]`: what the parser kept (a data URI or a file), or its
/// bufferView's range.
Result<std::vector<unsigned char>> encodedImage(const tinygltf::Model& model, std::size_t index,
                                                const std::string& name) {
    const tinygltf::Image& image = model.images[index];
    if (!image.image.empty()) return image.image;
    if (image.bufferView < 0) return elementError(name, "has no data (no uri a file or data URI gave, no bufferView)");
    const auto view = static_cast<std::size_t>(image.bufferView);
    if (view >= model.bufferViews.size()) {
        return elementError(name, "bufferView " + std::to_string(image.bufferView) + " does not exist");
    }
    const tinygltf::BufferView& v = model.bufferViews[view];
    if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= model.buffers.size()) {
        return elementError(name, indexed("bufferViews", view) + " names no buffer");
    }
    const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(v.buffer)].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset) {
        return elementError(name, indexed("bufferViews", view) + " exceeds its buffer");
    }
    const auto first = data.begin() + static_cast<std::ptrdiff_t>(v.byteOffset);
    return std::vector<unsigned char>(first, first + static_cast<std::ptrdiff_t>(v.byteLength));
}

/// Whether `bytes` begin as a PNG or a JPEG file does (its signature), decodable or not.
bool looksLikePngOrJpeg(const std::vector<unsigned char>& bytes) {
    static constexpr unsigned char kPng[] = {0x89, 'P', 'N', 'G'};
    static constexpr unsigned char kJpeg[] = {0xFF, 0xD8, 0xFF};
    const auto startsWith = [&](const auto& magic) {
        return bytes.size() >= sizeof(magic) && std::memcmp(bytes.data(), magic, sizeof(magic)) == 0;
    };
    return startsWith(kPng) || startsWith(kJpeg);
}

/// Decodes `bytes` (PNG or JPEG) to RGBA8, checking the size before decoding.
Result<Texture> decode(const std::vector<unsigned char>& bytes, const std::string& name) {
    if (bytes.size() > static_cast<std::size_t>(INT_MAX)) return elementError(name, "too large");
    const int size = static_cast<int>(bytes.size());
    int width = 0;
    int height = 0;
    int channels = 0;
    if (stbi_info_from_memory(bytes.data(), size, &width, &height, &channels) == 0) {
        return elementError(name,
                            std::string("is not an image the loader decodes (PNG or JPEG): ") + stbi_failure_reason());
    }
    if (width < 1 || height < 1 || width > kMaxTextureEdge || height > kMaxTextureEdge ||
        static_cast<long long>(width) * height > kMaxTexturePixels) {
        return elementError(name,
                            "is " + std::to_string(width) + "x" + std::to_string(height) +
                                " pixels; the loader decodes at most " + std::to_string(kMaxTextureEdge) +
                                " on a side and " + std::to_string(kMaxTexturePixels) + " in all (8192 x 8192)",
                            ErrorCode::LimitExceeded);
    }
    stbi_uc* pixels = stbi_load_from_memory(bytes.data(), size, &width, &height, &channels, 4);
    if (pixels == nullptr) return elementError(name, std::string("could not be decoded: ") + stbi_failure_reason());
    Texture texture;
    texture.width = width;
    texture.height = height;
    texture.rgba.assign(pixels, pixels + static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4U);
    stbi_image_free(pixels);
    return texture;
}

}  // namespace

Result<std::shared_ptr<const Texture>> TextureImporter::get(int index, const std::string& where) {
    if (index < 0 || static_cast<std::size_t>(index) >= textures_.size()) {
        return elementError(where, "texture " + std::to_string(index) + " does not exist");
    }
    const auto t = static_cast<std::size_t>(index);
    if (textures_[t]) return textures_[t];
    const tinygltf::Texture& texture = model_.textures[t];
    const std::string name = indexed("textures", t);
    // Only an extension's image (KTX2, WebP) and no PNG/JPEG fallback: drawn without it, as the
    // extension's UnsupportedFeature warning says.
    if (texture.source < 0 && !texture.extensions.empty()) return std::shared_ptr<const Texture>{};
    if (texture.source < 0 || static_cast<std::size_t>(texture.source) >= model_.images.size()) {
        return elementError(name + ".source", "image " + std::to_string(texture.source) + " does not exist");
    }
    const auto imageIndex = static_cast<std::size_t>(texture.source);
    const std::string imageName = indexed("images", imageIndex);
    auto bytes = encodedImage(model_, imageIndex, imageName);
    if (!bytes) return bytes.error();
    // Not a PNG or a JPEG, nor anything else the decoder reads: a format left out (KTX2, WebP, DDS
    // named as a core image), drawn without, where a PNG or JPEG that does not decode is an error.
    int width = 0;
    int height = 0;
    int channels = 0;
    if (!looksLikePngOrJpeg(*bytes) &&
        stbi_info_from_memory(bytes->data(), static_cast<int>(std::min<std::size_t>(bytes->size(), INT_MAX)), &width,
                              &height, &channels) == 0) {
        if (!dropped_[imageIndex]) {
            dropped_[imageIndex] = true;
            const std::string& uri = model_.images[imageIndex].uri;
            warnings_.push_back({WarningCode::UnsupportedFeature, imageName,
                                 imageName + (uri.empty() || uri.rfind("data:", 0) == 0 ? "" : " (" + uri + ")") +
                                     ": not a PNG or JPEG image, the formats the loader decodes; the materials "
                                     "using it are drawn without this texture"});
        }
        return std::shared_ptr<const Texture>{};
    }
    auto decoded = decode(*bytes, imageName);
    if (!decoded) return decoded.error();
    decoded->name = model_.images[imageIndex].name.empty() ? imageName : model_.images[imageIndex].name;
    if (texture.sampler >= 0) {
        if (static_cast<std::size_t>(texture.sampler) >= model_.samplers.size()) {
            return elementError(name + ".sampler", "sampler " + std::to_string(texture.sampler) + " does not exist");
        }
        const tinygltf::Sampler& sampler = model_.samplers[static_cast<std::size_t>(texture.sampler)];
        decoded->wrapS = wrapOf(sampler.wrapS);
        decoded->wrapT = wrapOf(sampler.wrapT);
    }
    textures_[t] = std::make_shared<const Texture>(std::move(*decoded));
    return textures_[t];
}

}  // namespace shadow::gltf
