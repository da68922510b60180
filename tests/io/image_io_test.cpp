// Tests for engine/src/io/image_io.cpp: EXR and PNG writing/reading, atomic writes, tone map.

#include <gtest/gtest.h>

#include <memory>

#include "test_support.h"
#include <shadow/image_io.h>
#include <stb/stb_image.h>  // decoder only; its implementation comes from libstb
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace shadow::image_io_test {
namespace {

namespace fs = std::filesystem;

/// A fresh directory per test under $SHADOW_TEST_TMP (or the system temp dir), removed after.
class TempDirTest : public ::testing::Test {
protected:
    void SetUp() override {
        tmp_ = std::make_unique<test::TempDir>("image_io_test");
        dir_ = tmp_->path();
    }
    void TearDown() override { tmp_.reset(); }

    [[nodiscard]] std::string path(const std::string& name) const { return (dir_ / name).string(); }

    /// Names of every entry left in the test directory.
    [[nodiscard]] std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir_)) {
            names.push_back(entry.path().filename().string());
        }
        return names;
    }

    [[nodiscard]] bool anyTempLeft() const {
        for (const std::string& name : entries()) {
            if (name.find(".tmp-") != std::string::npos) return true;
        }
        return false;
    }

    std::unique_ptr<test::TempDir> tmp_;  // removes the folder
    fs::path dir_;
};

class Exr : public TempDirTest {};
class Png : public TempDirTest {};
class ImageIo : public TempDirTest {};

std::vector<std::uint8_t> readBytes(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// An image whose every sample differs, with signs, fractions and a wide range of magnitudes.
ImageF patternImage(int width, int height, int channels) {
    ImageF image = makeImage(width, height, channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < channels; ++c) {
                const float sign = (x + y + c) % 3 == 0 ? -1.0f : 1.0f;
                image.at(x, y, c) =
                    sign * (0.1f + x + 10.0f * y + 0.25f * c) * std::pow(4.0f, static_cast<float>((x + c) % 5 - 2));
            }
        }
    }
    return image;
}

std::vector<std::string> namesFor(int channels) {
    return channels == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B", "A"};
}

// ---- EXR ------------------------------------------------------------------------------------

TEST_F(Exr, FloatRoundTripIsExact) {
    for (int channels : {1, 4}) {
        SCOPED_TRACE(channels);
        const ImageF image = patternImage(7, 5, channels);
        const std::string file = path("float.exr");
        ASSERT_TRUE(writeExr(file, image, namesFor(channels), ExrPixelType::Float).ok());
        const Result<ImageF> read = readExr(file, namesFor(channels));
        ASSERT_TRUE(read.ok()) << read.error().message;
        EXPECT_EQ(read->width, 7);
        EXPECT_EQ(read->height, 5);
        EXPECT_EQ(read->channels, channels);
        EXPECT_EQ(read->pixels, image.pixels);
    }
}

TEST_F(Exr, HalfRoundTripIsWithinHalfPrecision) {
    for (int channels : {1, 4}) {
        SCOPED_TRACE(channels);
        const ImageF image = patternImage(7, 5, channels);
        const std::string file = path("half.exr");
        ASSERT_TRUE(writeExr(file, image, namesFor(channels), ExrPixelType::Half).ok());
        const Result<ImageF> read = readExr(file, namesFor(channels));
        ASSERT_TRUE(read.ok()) << read.error().message;
        ASSERT_EQ(read->pixels.size(), image.pixels.size());
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            // Half has an 11-bit significand: round-to-nearest errs by at most 2^-11 relative
            // (all pattern values are normal halves).
            EXPECT_NEAR(read->pixels[i], image.pixels[i], std::abs(image.pixels[i]) / 2048.0f) << "sample " << i;
        }
    }
}

TEST_F(Exr, HalfClampsValuesBeyondHalfRangeInsteadOfWritingInf) {
    ImageF image = makeImage(2, 1, 1);
    image.at(0, 0, 0) = 1.0e6f;
    image.at(1, 0, 0) = -1.0e6f;
    const std::string file = path("clamp.exr");
    ASSERT_TRUE(writeExr(file, image, {"Y"}, ExrPixelType::Half).ok());
    const Result<ImageF> read = readExr(file, {"Y"});
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->at(0, 0, 0), 65504.0f);
    EXPECT_EQ(read->at(1, 0, 0), -65504.0f);
}

TEST_F(Exr, ReadsChannelsInRequestedOrder) {
    ImageF image = makeImage(3, 2, 4);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 3; ++x) {
            for (int c = 0; c < 4; ++c) image.at(x, y, c) = static_cast<float>(c + 1);  // R=1..A=4
        }
    }
    const std::string file = path("order.exr");
    ASSERT_TRUE(writeExr(file, image, {"R", "G", "B", "A"}).ok());
    const Result<ImageF> read = readExr(file, {"A", "R", "B"});
    ASSERT_TRUE(read.ok()) << read.error().message;
    ASSERT_EQ(read->channels, 3);
    EXPECT_EQ(read->at(2, 1, 0), 4.0f);
    EXPECT_EQ(read->at(2, 1, 1), 1.0f);
    EXPECT_EQ(read->at(2, 1, 2), 3.0f);
}

TEST_F(Exr, PixelZeroZeroWrittenIsPixelZeroZeroRead) {
    ImageF image = makeImage(7, 5, 1);
    image.at(0, 0, 0) = 1.0f;  // top-left
    image.at(6, 0, 0) = 2.0f;  // top-right
    image.at(0, 4, 0) = 3.0f;  // bottom-left
    const std::string file = path("corner.exr");
    ASSERT_TRUE(writeExr(file, image, {"Y"}).ok());
    const Result<ImageF> read = readExr(file, {"Y"});
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->at(0, 0, 0), 1.0f);
    EXPECT_EQ(read->at(6, 0, 0), 2.0f);
    EXPECT_EQ(read->at(0, 4, 0), 3.0f);
    EXPECT_EQ(read->at(6, 4, 0), 0.0f);
}

/// Little-endian byte sink for hand-made EXR files.
struct Bytes {
    std::vector<std::uint8_t> data;
    void u8(std::uint8_t v) { data.push_back(v); }
    void i32(std::int32_t v) {
        for (int i = 0; i < 4; ++i) u8(static_cast<std::uint8_t>(static_cast<std::uint32_t>(v) >> (8 * i)));
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) u8(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    void f32(float v) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &v, 4);
        i32(static_cast<std::int32_t>(bits));
    }
    void str(const std::string& s) {
        data.insert(data.end(), s.begin(), s.end());
        u8(0);
    }
    void attribute(const std::string& name, const std::string& type, std::int32_t size) {
        str(name);
        str(type);
        i32(size);
    }
    void box(int x0, int y0, int x1, int y1) {
        for (int v : {x0, y0, x1, y1}) i32(v);
    }
};

/// An uncompressed single-channel ("Y", float) EXR whose data window starts at (x0, y0), not at
/// the origin, written byte by byte from the OpenEXR file layout so the reader is tested
/// against a file our writer did not make. Pixel (x, y) of the window holds 100 y + x.
std::vector<std::uint8_t> offsetWindowExr(int x0, int y0, int width, int height) {
    Bytes b;
    for (std::uint8_t m : {0x76, 0x2f, 0x31, 0x01}) b.u8(m);
    b.i32(2);  // version 2, single-part scanline
    b.attribute("channels", "chlist", 19);
    b.str("Y");
    b.i32(2);                             // FLOAT
    for (int i = 0; i < 4; ++i) b.u8(0);  // pLinear + reserved
    b.i32(1);
    b.i32(1);
    b.u8(0);
    b.attribute("compression", "compression", 1);
    b.u8(0);  // NO_COMPRESSION: one scanline per chunk
    b.attribute("dataWindow", "box2i", 16);
    b.box(x0, y0, x0 + width - 1, y0 + height - 1);
    b.attribute("displayWindow", "box2i", 16);
    b.box(0, 0, 15, 15);
    b.attribute("lineOrder", "lineOrder", 1);
    b.u8(0);
    b.attribute("pixelAspectRatio", "float", 4);
    b.f32(1.0f);
    b.attribute("screenWindowCenter", "v2f", 8);
    b.f32(0.0f);
    b.f32(0.0f);
    b.attribute("screenWindowWidth", "float", 4);
    b.f32(1.0f);
    b.u8(0);  // end of header
    const std::size_t chunkSize = 8 + 4 * static_cast<std::size_t>(width);
    const std::size_t firstChunk = b.data.size() + 8 * static_cast<std::size_t>(height);
    for (int y = 0; y < height; ++y) b.u64(firstChunk + y * chunkSize);
    for (int y = 0; y < height; ++y) {
        b.i32(y0 + y);
        b.i32(4 * width);
        for (int x = 0; x < width; ++x) b.f32(static_cast<float>(100 * y + x));
    }
    return b.data;
}

TEST_F(Exr, ReadsFromTheDataWindowWhateverItsOrigin) {
    const std::string file = path("window.exr");
    const std::vector<std::uint8_t> bytes = offsetWindowExr(-3, 2, 4, 3);
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    const Result<ImageF> read = readExr(file, {"Y"});
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->width, 4);
    EXPECT_EQ(read->height, 3);
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 4; ++x) EXPECT_EQ(read->at(x, y, 0), 100.0f * y + x) << x << "," << y;
    }
}

TEST_F(Exr, MissingChannelIsAnErrorNamingChannelAndPath) {
    const std::string file = path("rgb.exr");
    ASSERT_TRUE(writeExr(file, makeImage(2, 2, 3), {"R", "G", "B"}).ok());
    const Result<ImageF> read = readExr(file, {"R", "Zdepth"});
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().message.find("Zdepth"), std::string::npos) << read.error().message;
    EXPECT_NE(read.error().message.find(file), std::string::npos) << read.error().message;
}

TEST_F(Exr, UnreadableFileIsAnErrorNamingPath) {
    const std::string missing = path("missing.exr");
    const Result<ImageF> notThere = readExr(missing, {"Y"});
    ASSERT_FALSE(notThere.ok());
    EXPECT_NE(notThere.error().message.find(missing), std::string::npos);

    const std::string garbage = path("garbage.exr");
    std::ofstream(garbage) << "this is not an OpenEXR file";
    const Result<ImageF> notExr = readExr(garbage, {"Y"});
    ASSERT_FALSE(notExr.ok());
    EXPECT_NE(notExr.error().message.find(garbage), std::string::npos);
}

TEST_F(Exr, TruncatedFileIsAnError) {
    const std::string file = path("truncated.exr");
    ASSERT_TRUE(writeExr(file, patternImage(7, 5, 4), namesFor(4)).ok());
    fs::resize_file(file, fs::file_size(file) / 2);
    EXPECT_FALSE(readExr(file, namesFor(4)).ok());
}

TEST_F(Exr, WriteIntoMissingDirectoryFailsAndLeavesNoFile) {
    const std::string file = path("no/such/dir/out.exr");
    const Status status = writeExr(file, makeImage(2, 2, 1), {"Y"});
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(file), std::string::npos) << status.error().message;
    EXPECT_FALSE(fs::exists(file));
    EXPECT_TRUE(entries().empty());
}

TEST_F(Exr, BadArgumentsAreErrorsAndWriteNothing) {
    const std::string file = path("bad.exr");
    EXPECT_FALSE(writeExr(file, makeImage(2, 2, 3), {"R", "G"}).ok());  // too few names
    EXPECT_FALSE(writeExr(file, makeImage(2, 2, 2), {"R", "R"}).ok());  // duplicate
    EXPECT_FALSE(writeExr(file, makeImage(0, 2, 1), {"Y"}).ok());       // empty
    ImageF shortBuffer = makeImage(2, 2, 1);
    shortBuffer.pixels.pop_back();
    const Status status = writeExr(file, shortBuffer, {"Y"});
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(file), std::string::npos);
    EXPECT_TRUE(entries().empty());
}

TEST_F(Exr, LeavesNoTemporaryFileAfterSuccessOrFailure) {
    ASSERT_TRUE(writeExr(path("ok.exr"), makeImage(3, 3, 1), {"Y"}).ok());
    ASSERT_FALSE(writeExr(path("ok.exr/inside.exr"), makeImage(3, 3, 1), {"Y"}).ok());
    fs::create_directory(path("taken"));  // rename onto a directory fails after the write
    ASSERT_FALSE(writeExr(path("taken"), makeImage(3, 3, 1), {"Y"}).ok());
    EXPECT_FALSE(anyTempLeft());
    EXPECT_TRUE(fs::is_directory(path("taken")));
}

TEST_F(Exr, OverwritesAnExistingFile) {
    const std::string file = path("again.exr");
    ImageF image = makeImage(1, 1, 1);
    image.at(0, 0, 0) = 1.0f;
    ASSERT_TRUE(writeExr(file, image, {"Y"}).ok());
    image.at(0, 0, 0) = 2.0f;
    ASSERT_TRUE(writeExr(file, image, {"Y"}).ok());
    const Result<ImageF> read = readExr(file, {"Y"});
    ASSERT_TRUE(read.ok());
    EXPECT_EQ(read->at(0, 0, 0), 2.0f);
}

// ---- PNG ------------------------------------------------------------------------------------

std::uint32_t bigEndian32(const std::vector<std::uint8_t>& b, std::size_t at) {
    return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) | (std::uint32_t{b[at + 2]} << 8) |
           std::uint32_t{b[at + 3]};
}

std::vector<std::uint8_t> bytePattern(int width, int height, int channels) {
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height * channels);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<std::uint8_t>(i * 37);
    return pixels;
}

TEST_F(Png, HasSignatureAndIhdrWithSizeAndColourType) {
    for (int channels : {3, 4}) {
        SCOPED_TRACE(channels);
        const std::string file = path("image.png");
        ASSERT_TRUE(writePng(file, 7, 5, channels, bytePattern(7, 5, channels)).ok());
        const std::vector<std::uint8_t> b = readBytes(file);
        ASSERT_GE(b.size(), 33u);
        const std::vector<std::uint8_t> signature = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
        EXPECT_TRUE(std::equal(signature.begin(), signature.end(), b.begin()));
        EXPECT_EQ(bigEndian32(b, 8), 13u);  // IHDR length
        EXPECT_EQ(std::string(b.begin() + 12, b.begin() + 16), "IHDR");
        EXPECT_EQ(bigEndian32(b, 16), 7u);
        EXPECT_EQ(bigEndian32(b, 20), 5u);
        EXPECT_EQ(b[24], 8);                      // bit depth
        EXPECT_EQ(b[25], channels == 3 ? 2 : 6);  // colour type RGB / RGBA
    }
}

TEST_F(Png, DecodesToTheWrittenPixelsTopRowFirst) {
    const std::vector<std::uint8_t> pixels = bytePattern(7, 5, 4);
    const std::string file = path("image.png");
    ASSERT_TRUE(writePng(file, 7, 5, 4, pixels).ok());
    const std::vector<std::uint8_t> b = readBytes(file);
    int w = 0, h = 0, n = 0;
    stbi_uc* decoded = stbi_load_from_memory(b.data(), static_cast<int>(b.size()), &w, &h, &n, 4);
    ASSERT_NE(decoded, nullptr);
    const std::vector<std::uint8_t> got(decoded, decoded + pixels.size());
    stbi_image_free(decoded);
    EXPECT_EQ(w, 7);
    EXPECT_EQ(h, 5);
    EXPECT_EQ(got, pixels);
}

TEST_F(Png, BadArgumentsAreErrorsNamingPathAndWriteNothing) {
    const std::string file = path("bad.png");
    const Status shortBuffer = writePng(file, 7, 5, 3, std::vector<std::uint8_t>(7 * 5 * 3 - 1));
    ASSERT_FALSE(shortBuffer.ok());
    EXPECT_NE(shortBuffer.error().message.find(file), std::string::npos);
    EXPECT_FALSE(writePng(file, 2, 2, 2, std::vector<std::uint8_t>(8)).ok());  // grey+alpha
    EXPECT_FALSE(writePng(file, 0, 2, 3, {}).ok());
    EXPECT_FALSE(writePng(file, -1, 2, 3, {}).ok());
    EXPECT_TRUE(entries().empty());
}

TEST_F(Png, WriteIntoMissingDirectoryFailsAndLeavesNoFile) {
    const std::string file = path("missing/out.png");
    const Status status = writePng(file, 2, 2, 3, bytePattern(2, 2, 3));
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(file), std::string::npos);
    EXPECT_NE(status.error().message.find("No such file or directory"), std::string::npos) << status.error().message;
    EXPECT_TRUE(entries().empty());
}

// ---- Text files and images ------------------------------------------------------------------

TEST_F(ImageIo, MakeImageIsZeroFilledWithTheGivenShape) {
    const ImageF image = makeImage(7, 5, 3);
    EXPECT_EQ(image.width, 7);
    EXPECT_EQ(image.height, 5);
    EXPECT_EQ(image.channels, 3);
    EXPECT_EQ(image.pixels, std::vector<float>(7 * 5 * 3, 0.0f));
}

TEST_F(ImageIo, TextFileIsReplacedWholeAndNoTemporaryRemains) {
    const std::string file = path("stats.json");
    ASSERT_TRUE(writeTextFileAtomic(file, "{\"first\": 1, \"longer\": true}\n").ok());
    ASSERT_TRUE(writeTextFileAtomic(file, "{}\n").ok());
    const std::vector<std::uint8_t> b = readBytes(file);
    EXPECT_EQ(std::string(b.begin(), b.end()), "{}\n");
    EXPECT_EQ(entries(), std::vector<std::string>{"stats.json"});
}

TEST_F(ImageIo, TextFileIntoMissingDirectoryFailsNamingPathAndCause) {
    const std::string file = path("nope/stats.json");
    const Status status = writeTextFileAtomic(file, "{}");
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(file), std::string::npos);
    EXPECT_NE(status.error().message.find("No such file or directory"), std::string::npos) << status.error().message;
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIo, FailedRenameRemovesTheTemporary) {
    fs::create_directory(path("dir"));
    fs::create_directory(path("dir/child"));  // a non-empty directory cannot be replaced
    const Status status = writeTextFileAtomic(path("dir"), "text");
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(path("dir")), std::string::npos);
    EXPECT_FALSE(anyTempLeft());
}

TEST_F(ImageIo, EmptyPathIsAnError) {
    EXPECT_FALSE(writeTextFileAtomic("", "x").ok());
    EXPECT_FALSE(writePng("", 1, 1, 3, {0, 0, 0}).ok());
}

// ---- Tone mapping ---------------------------------------------------------------------------

/// One RGB pixel with all three channels `v`, tone mapped; returns the red byte.
int toneMapOne(float v, float exposure) {
    ImageF image = makeImage(1, 1, 3);
    image.pixels = {v, v, v};
    return toneMapToSrgb8(image, exposure).at(0);
}

double srgbOetf(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

TEST(ToneMap, ZeroMapsToZero) { EXPECT_EQ(toneMapOne(0.0f, 1.0f), 0); }

TEST(ToneMap, IsMonotonic) {
    int previous = 0;
    for (float v = 1e-6f; v < 1e6f; v *= 1.05f) {
        const int out = toneMapOne(v, 1.0f);
        EXPECT_GE(out, previous) << v;
        previous = out;
    }
    EXPECT_EQ(previous, 255);
}

TEST(ToneMap, NonFiniteAndNegativeMapToZero) {
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(toneMapOne(std::numeric_limits<float>::quiet_NaN(), 1.0f), 0);
    EXPECT_EQ(toneMapOne(inf, 1.0f), 0);
    EXPECT_EQ(toneMapOne(-inf, 1.0f), 0);
    EXPECT_EQ(toneMapOne(-1.0f, 1.0f), 0);
    EXPECT_EQ(toneMapOne(1.0f, std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(ToneMap, HugeMapsTo255) {
    EXPECT_EQ(toneMapOne(1e30f, 1.0f), 255);
    EXPECT_EQ(toneMapOne(std::numeric_limits<float>::max(), 4.0f), 255);  // product overflows
}

TEST(ToneMap, MatchesSrgbOfReinhardCurveInClosedForm) {
    // The documented curve is Reinhard y = x / (1 + x); invert it (x = y / (1 - y)) so the
    // curve output is known, then compare with the exact sRGB OETF.
    const float exposure = 2.5f;
    for (double y : {0.001, 0.0031308, 0.01, 0.05, 0.18, 0.3, 0.5, 0.73, 0.9, 0.99}) {
        const double x = y / (1.0 - y);
        const int expected = static_cast<int>(std::lround(255.0 * srgbOetf(y)));
        EXPECT_NEAR(toneMapOne(static_cast<float>(x / exposure), exposure), expected, 1) << y;
    }
}

TEST(ToneMap, KeepsChannelCountAndCopiesAlphaLinearlyClamped) {
    ImageF image = makeImage(4, 1, 4);
    const float alphas[] = {0.5f, 2.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()};
    for (int x = 0; x < 4; ++x) image.at(x, 0, 3) = alphas[x];
    const std::vector<std::uint8_t> out = toneMapToSrgb8(image, 8.0f);  // exposure spares alpha
    ASSERT_EQ(out.size(), image.pixels.size());
    EXPECT_EQ(out[3], 128);  // 127.5 rounds up
    EXPECT_EQ(out[7], 255);
    EXPECT_EQ(out[11], 0);
    EXPECT_EQ(out[15], 0);
}

TEST(ToneMap, ExposureMultipliesTheInput) {
    for (float v : {0.01f, 0.2f, 1.0f, 7.0f}) EXPECT_EQ(toneMapOne(v, 4.0f), toneMapOne(4.0f * v, 1.0f));
}

// ---- Exposure -------------------------------------------------------------------------------

/// A grey image: `fraction` of its pixels (the first ones) at luminance `bright`, the rest at
/// `dark`, and `black` more pixels at 0 (the background).
ImageF twoLevels(int pixels, double fraction, float dark, float bright, int black = 0) {
    ImageF image = makeImage(pixels + black, 1, 3);
    for (int x = 0; x < pixels; ++x) {
        const float v = x < static_cast<int>(fraction * pixels) ? bright : dark;
        for (int c = 0; c < 3; ++c) image.at(x, 0, c) = v;
    }
    return image;
}

// The floor of the metered luminance (4 stops below the 99th percentile) keeps a frame that is
// 95 % shadow (ambient-lit at 0.002) around a 5 % sunlit patch (0.5) dark: its shadow stays
// below a quarter of full brightness (sRGB 64) and the patch is exposed for, bright but not
// clipped. The log-average alone (the rule before the floor) lifted that shadow to sRGB 96, a
// grey. Fails without the floor.
TEST(AutoExposure, KeepsAMostlyDarkFrameDark) {
    const ImageF image = twoLevels(10000, 0.05, 0.002f, 0.5f, 2000);
    const float exposure = autoExposure(image);
    const std::vector<std::uint8_t> out = toneMapToSrgb8(image, exposure);
    const int shadow = out[3 * 9999], patch = out[0];
    std::cout << "exposure " << exposure << ": shadow " << shadow << ", patch " << patch << " (sRGB 0-255)\n";
    EXPECT_LT(shadow, 64);
    EXPECT_GT(patch, 200);
    EXPECT_LT(patch, 255);
    // The rule without the floor, for the record: the log-average brought to 0.18.
    const double logAverage = std::exp(0.95 * std::log(0.002) + 0.05 * std::log(0.5));
    EXPECT_GT(toneMapOne(0.002f, static_cast<float>(0.18 / logAverage)), 90);
}

// A frame whose highlights lie within 4 stops of its average is metered by its log-average
// alone, as before: 0.18 over it, within the bins' 1/16 stop (4.4 %). The black background is
// not counted. Fails when the floor or the background reaches such a frame.
TEST(AutoExposure, MetersAnEvenFrameByItsLogAverage) {
    const ImageF image = twoLevels(1000, 0.3, 0.05f, 0.4f, 5000);
    const double logAverage = std::exp(0.7 * std::log(0.05) + 0.3 * std::log(0.4));
    EXPECT_NEAR(autoExposure(image), 0.18 / logAverage, 0.044 * 0.18 / logAverage);
    EXPECT_EQ(autoExposure(makeImage(8, 8, 3)), 1.0f) << "nothing to meter";
}

// Fails when a non-finite pixel is counted (its bin would be the last) or black is.
TEST(AutoExposure, CountsOnlyFiniteLitPixels) {
    ImageF image = twoLevels(100, 0.0, 0.1f, 0.1f, 10);
    image.at(0, 0, 1) = std::numeric_limits<float>::quiet_NaN();
    image.at(1, 0, 0) = std::numeric_limits<float>::infinity();
    const LuminanceHistogram counts = luminanceHistogram(image);
    long total = 0;
    for (const std::uint32_t c : counts) total += c;
    EXPECT_EQ(total, 98);
    EXPECT_EQ(counts.back(), 0u);
    ExposureSettings settings;
    settings.key = 0.25f;
    EXPECT_NEAR(exposureFromHistogram(counts, settings), 2.5, 2.5 * 0.044);
}

}  // namespace
}  // namespace shadow::image_io_test
