// Writing and reading images: PNG (8-bit sRGB) and OpenEXR (float channels).
//
// Every writer writes to a temporary name beside the target and renames it into place, so a
// killed run never leaves a half-written image. Rows are stored top row first: pixel (0,0) is
// the top-left.
#pragma once

#include <shadow/result.h>
#include <shadow/tone_map.h>

#include <array>
#include <cstdint>
#include <optional>
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

/// Linear HDR RGB(A) to 8-bit sRGB by the tone map of shadow/tone_map.h (the one the GPU's
/// `Renderer::presentToTexture` runs): exposure `exposure`, the Reinhard curve x/(1+x) applied to
/// luminance (Rec. 709), the colour scaled with it so that hue survives; a colour whose brightest
/// channel would pass 1 is scaled down whole. Grey maps exactly as the curve per channel. NaN,
/// negative and -inf channels become 0; +inf is full brightness. Alpha is copied linearly.
[[nodiscard]] std::vector<std::uint8_t> toneMapToSrgb8(const ImageF& rgb, float exposure);

/// Pixels counted per bin of the exposure meter (shadow/tone_map.h: 1/8-stop bins of log2
/// luminance; black pixels, the background among them, are not counted).
using LuminanceHistogram = std::array<std::uint32_t, SG_EXPOSURE_BINS>;

/// The exposure meter's counts over linear RGB(A) `rgb` (pixels with a non-finite channel left
/// out): what `Renderer::meterExposure` counts on the GPU.
[[nodiscard]] LuminanceHistogram luminanceHistogram(const ImageF& rgb);

/// How `exposureFromHistogram` meters a frame.
struct ExposureSettings {
    /// The luminance the metered one is brought to (mid-grey), (0, 1e3]. Default 0.18.
    float key = 0.18f;
    /// The highlight the floor is measured from: the luminance that this fraction of the counted
    /// pixels does not exceed, (0, 1]. Default 0.99: the brightest 1 % set it, a few specular
    /// pixels do not.
    float highlightPercentile = 0.99f;
    /// The metered luminance is at least the highlight's over 2^highlightStops, [0, 30]. Default
    /// 4: the highlight lands at no more than 16 x key before the curve (2.9, 0.74 after it).
    float highlightStops = 4.0f;
};

/// The exposure for a frame whose counted pixels are `histogram`: `key` over the metered
/// luminance, which is their log-average (Reinhard et al. 2002, "Photographic tone
/// reproduction"; background and black pixels are not counted) or, when that is darker, a floor
/// `highlightStops` below the `highlightPercentile` luminance. The floor keeps a mostly dark frame
/// dark: a frame 95 % in shadow with a small sunlit patch would have its log-average set by the
/// shadow and be lifted to grey; the floor exposes for the patch instead. Frames whose highlights
/// lie within `highlightStops` of their average are metered by the average alone. Luminances
/// are the bins' centres (1/16 of a stop off at most). 1 for a histogram with no pixel; within
/// [1e-8, 1e8]. Settings out of range are clamped.
[[nodiscard]] float exposureFromHistogram(const LuminanceHistogram& histogram, const ExposureSettings& settings = {});

/// `exposureFromHistogram(luminanceHistogram(rgb), {key})`: the exposure shadow_render gives
/// color.png and the viewer its frames.
[[nodiscard]] float autoExposure(const ImageF& rgb, float key = 0.18f);

/// Writes `text` to `path` through a temporary file and a rename.
[[nodiscard]] Status writeTextFileAtomic(const std::string& path, const std::string& text);

/// What `path` is when it is not a regular file, for a message ("no such file", "not a regular
/// file (a FIFO)", ...); nullopt for a regular file. By `std::filesystem::status`: the file is
/// never opened, so a FIFO or a device cannot block the caller.
[[nodiscard]] std::optional<std::string> notRegularFile(const std::string& path);

}  // namespace shadow
