// glTF textures to engine `Texture`s: images decoded (PNG, JPEG: stb_image) on first use by a
// material, and shared by every material that uses them.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <shadow/warnings.h>
#include <tiny_gltf.h>

#include <memory>
#include <string>
#include <vector>

namespace shadow::gltf {

/// Largest image the loader decodes, in pixels (8192 x 8192, each side at most
/// `kMaxTextureEdge`, the largest texture llvmpipe makes): 256 MiB of RGBA decoded, as much
/// again in the GL texture and a third more in its mipmaps.
inline constexpr long long kMaxTexturePixels = 64LL << 20U;
inline constexpr int kMaxTextureEdge = 16384;

/// The textures of one import. The parser keeps images encoded (see gltf_parse.cpp); `get`
/// decodes one when a material first uses it.
class TextureImporter {
public:
    /// `warnings` receives one UnsupportedFeature warning per image left out (see `get`).
    TextureImporter(const tinygltf::Model& model, std::vector<Warning>& warnings)
        : model_(model), warnings_(warnings), textures_(model.textures.size()) {}

    /// `textures[index]`, decoded to RGBA8 with its sampler's wrap modes; `where` names the
    /// referring element. An image that is missing, a PNG or JPEG that does not decode, or one
    /// larger than the limits is an error naming it. Null, and the material drawn without it, for a
    /// texture whose only image is an extension's (KHR_texture_basisu, EXT_texture_webp without a
    /// `source`), and for an image in a format the loader does not decode at all (KTX2, WebP,
    /// DDS named as a core image, as some exporters write them): one warning naming the image.
    [[nodiscard]] Result<std::shared_ptr<const Texture>> get(int index, const std::string& where);

private:
    const tinygltf::Model& model_;
    std::vector<Warning>& warnings_;
    std::vector<std::shared_ptr<const Texture>> textures_;                        ///< by texture index, once decoded
    std::vector<bool> dropped_ = std::vector<bool>(model_.images.size(), false);  ///< by image: warned
};

}  // namespace shadow::gltf
