// The image fuzz target (image_fuzz_target.h) in every ordinary build: PNGs of each channel
// count and a JPEG, encoded here, load through it as textures holding their pixels (exactly, or
// within the JPEG's loss); a broken image is one error naming it, bytes in no format the loader
// decodes are dropped with a warning, an image too large is refused before it is decoded. With
// SHADOW_FUZZ_SEED_DIR set, the encoded images are written there: tests/fuzz/run_fuzz.sh seeds
// the image fuzzer with them.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz/image_fuzz_target.h"

namespace shadow::image_fuzz_test {
namespace {

constexpr int kWidth = 3;
constexpr int kHeight = 2;

void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

/// A kWidth x kHeight image of `channels` channels, each pixel's channels distinct.
std::vector<unsigned char> pixels(int channels) {
    std::vector<unsigned char> p(static_cast<std::size_t>(kWidth * kHeight * channels));
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<unsigned char>(20 + (i * 37) % 220);
    return p;
}

/// The RGBA the loader makes of pixel `i` of a `channels`-channel image.
std::array<int, 4> expectedRgba(const std::vector<unsigned char>& p, int channels, int i) {
    const auto at = [&](int c) { return static_cast<int>(p[static_cast<std::size_t>(i * channels + c)]); };
    switch (channels) {
        case 1: return {at(0), at(0), at(0), 255};
        case 2: return {at(0), at(0), at(0), at(1)};
        case 3: return {at(0), at(1), at(2), 255};
        default: return {at(0), at(1), at(2), at(3)};
    }
}

struct Encoded {
    std::string name;
    int channels;
    std::string bytes;
    int tolerance;  ///< largest difference per channel after decoding
};

std::vector<Encoded> encodedImages() {
    std::vector<Encoded> images;
    for (int channels = 1; channels <= 4; ++channels) {
        Encoded e{"png" + std::to_string(channels), channels, {}, 0};
        const std::vector<unsigned char> p = pixels(channels);
        EXPECT_NE(stbi_write_png_to_func(appendBytes, &e.bytes, kWidth, kHeight, channels, p.data(), kWidth * channels),
                  0);
        images.push_back(std::move(e));
    }
    Encoded jpeg{"jpg3", 3, {}, 24};
    const std::vector<unsigned char> p = pixels(3);
    EXPECT_NE(stbi_write_jpg_to_func(appendBytes, &jpeg.bytes, kWidth, kHeight, 3, p.data(), 100), 0);
    images.push_back(std::move(jpeg));
    if (const char* dir = std::getenv("SHADOW_FUZZ_SEED_DIR"); dir != nullptr && *dir != '\0') {
        for (const Encoded& e : images) {
            std::ofstream(std::string(dir) + "/image_" + e.name, std::ios::binary) << e.bytes;
        }
    }
    return images;
}

Result<Scene> load(const std::string& bytes) {
    return fuzz::runImageInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

const Material& onlyMaterial(const Scene& scene) {
    const Material* found = nullptr;
    scene.world.view<Material>().each([&found](Entity, const Material& m) { found = &m; });
    EXPECT_NE(found, nullptr);
    return *found;
}

TEST(ImageFuzz, EncodedImagesLoadAsTexturesHoldingTheirPixels) {
    for (const Encoded& e : encodedImages()) {
        SCOPED_TRACE(e.name);
        const Result<Scene> scene = load(e.bytes);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        const Material& m = onlyMaterial(*scene);
        ASSERT_NE(m.baseColorTexture, nullptr);
        // One image, one decoded texture, whichever maps read it.
        EXPECT_EQ(m.normalMap.texture, m.baseColorTexture);
        const Texture& t = *m.baseColorTexture;
        ASSERT_EQ(t.width, kWidth);
        ASSERT_EQ(t.height, kHeight);
        const std::vector<unsigned char> p = pixels(e.channels);
        int worst = 0;
        for (int i = 0; i < kWidth * kHeight; ++i) {
            const std::array<int, 4> want = expectedRgba(p, e.channels, i);
            for (int c = 0; c < 4; ++c) {
                worst =
                    std::max(worst, std::abs(static_cast<int>(t.rgba[static_cast<std::size_t>(i * 4 + c)]) - want[c]));
            }
        }
        EXPECT_LE(worst, e.tolerance);
    }
}

TEST(ImageFuzz, BrokenOrForeignOrHugeImagesAreReportedNotDecoded) {
    const std::string png = encodedImages().front().bytes;
    // Cut short: a PNG that does not decode is an error naming the image.
    const Result<Scene> cut = load(png.substr(0, png.size() / 2));
    ASSERT_FALSE(cut.ok());
    EXPECT_NE(cut.error().message.find("images[0]"), std::string::npos) << cut.error().message;
    // Not an image format at all: the scene loads, the maps are dropped with one warning.
    const Result<Scene> foreign = load("RIFF....WEBPVP8 not really");
    ASSERT_TRUE(foreign.ok()) << foreign.error().message;
    EXPECT_EQ(onlyMaterial(*foreign).baseColorTexture, nullptr);
    EXPECT_EQ(foreign->warnings.size(), 1U);
    // The header says 20000 pixels wide (IHDR's width, big-endian at byte 16): refused by its
    // size before any pixel is decoded.
    std::string wide = png;
    const unsigned char width[4] = {0, 0, 0x4E, 0x20};
    std::memcpy(wide.data() + 16, width, 4);
    const Result<Scene> huge = load(wide);
    ASSERT_FALSE(huge.ok());
    EXPECT_EQ(huge.error().code, ErrorCode::LimitExceeded) << huge.error().message;
}

}  // namespace
}  // namespace shadow::image_fuzz_test
