// Writing and reading images: PNG (8-bit sRGB) and OpenEXR (float channels).
//
// Every writer writes to a temporary name beside the target and renames it into place, so a
// killed run never leaves a half-written image. Rows are stored top row first: pixel (0,0) is
// the top-left.
#pragma once

#include <shadow/result.h>

#include <cstdint>
#include <string>
#include <vector>

namespace shadow {

/// A float image of `channels` interleaved channels, top row first.
struct ImageF {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;  ///< size width * height * channels

    [[nodiscard]] float& at(int x, int y, int c) {
        return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c];
    }
    [[nodiscard]] float at(int x, int y, int c) const {
        return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c];
    }
};

/// Makes a zero-filled image.
[[nodiscard]] ImageF makeImage(int width, int height, int channels);

/// Writes 8-bit RGB or RGBA (`channels` 3 or 4) PNG.
[[nodiscard]] Status writePng(const std::string& path, int width, int height, int channels,
                              const std::vector<std::uint8_t>& pixels);

/// Precision of the EXR channels written.
enum class ExrPixelType { Half, Float };

/// Writes an EXR with channel names `names` (one per image channel, e.g. {"R","G","B","A"} or
/// {"Y"}).
[[nodiscard]] Status writeExr(const std::string& path, const ImageF& image, const std::vector<std::string>& names,
                              ExrPixelType type = ExrPixelType::Float);

/// Reads every channel of an EXR, in the order of `names` (each must exist). Rows top first.
[[nodiscard]] Result<ImageF> readExr(const std::string& path, const std::vector<std::string>& names);

/// Linear HDR RGB(A) to 8-bit sRGB, after exposure `exposure` and the Reinhard curve x/(1+x)
/// applied to luminance (Rec. 709), the colour scaled with it so that hue survives; a colour
/// whose brightest channel would pass 1 is scaled down whole. Grey maps exactly as the curve
/// per channel. NaN, negative and -inf channels become 0; +inf is full brightness. Alpha is
/// copied linearly.
[[nodiscard]] std::vector<std::uint8_t> toneMapToSrgb8(const ImageF& rgb, float exposure);

/// The exposure that brings the image's log-average luminance (over pixels with light, so a
/// black background does not count) to `key` (Reinhard et al. 2002, "Photographic tone
/// reproduction"); 1 for an image with no light.
[[nodiscard]] float autoExposure(const ImageF& rgb, float key = 0.18f);

/// Writes `text` to `path` through a temporary file and a rename.
[[nodiscard]] Status writeTextFileAtomic(const std::string& path, const std::string& text);

}  // namespace shadow
