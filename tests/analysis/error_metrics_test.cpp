// Tests for engine/src/analysis/error_metrics.cpp: visibility error statistics on images with
// hand-computed errors, masks, NaN/Inf, size errors, heat-map colours, and folder comparison.
#include <gtest/gtest.h>

#include <memory>

#include "test_support.h"
#include <shadow/image_io.h>
#include <shadow/metrics.h>
#include <stb/stb_image.h>  // decoder only; its implementation comes from libstb
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace shadow {
namespace {

namespace fs = std::filesystem;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

using test::imageOf;

/// A position-like RGBA mask: A from `coverage`, RGB deliberately NaN so that a reader of the
/// wrong channel would notice.
ImageF rgbaMask(int width, int height, const std::vector<float>& coverage) {
    ImageF mask = makeImage(width, height, 4);
    for (std::size_t i = 0; i < coverage.size(); ++i) {
        mask.pixels[4 * i + 0] = kNaN;
        mask.pixels[4 * i + 1] = kNaN;
        mask.pixels[4 * i + 2] = kNaN;
        mask.pixels[4 * i + 3] = coverage[i];
    }
    return mask;
}

// The 4x4 case. Pixels 0-5 are truly lit, 6-10 in the umbra, 11-15 in the penumbra; the
// errors e = estimate - truth are
//   lit       0, 0, 0, -0.25, -0.75 (acne), -1 (acne)
//   umbra     0, 0, +0.125, +0.75 (leak), +1 (leak)
//   penumbra  0, -0.25, +0.25, 0, +0.5
// so (N = 16): sum e = 0.375, sum |e| = 4.875, sum e² = 1.625 + 1.578125 + 0.375 = 3.578125,
// nine |e| > 0.1, penumbra sum e² = 0.375 over 5.
// One image row per line:
// clang-format off
const std::vector<float> kTruth4x4 = {
    1,     1,     1,     1,
    1,     1,     0,     0,
    0,     0,     0,     0.5f,
    0.5f,  0.25f, 0.75f, 0.5f};
const std::vector<float> kEstimate4x4 = {
    1,      1,     1,     0.75f,
    0.25f,  0,     0,     0,
    0.125f, 0.75f, 1,     0.5f,
    0.25f,  0.5f,  0.75f, 1};
// clang-format on

TEST(ErrorMetrics, HandComputedStatisticsOn4x4) {
    const Result<VisibilityErrors> r = compareVisibility(imageOf(4, 4, kEstimate4x4), imageOf(4, 4, kTruth4x4));
    ASSERT_TRUE(r.ok()) << r.error().message;
    const VisibilityErrors& e = *r;
    EXPECT_EQ(e.receiverPixels, 16);
    EXPECT_EQ(e.validPixels, 16);
    EXPECT_EQ(e.nonFinite, 0);
    EXPECT_EQ(e.litPixels, 6);
    EXPECT_EQ(e.umbraPixels, 5);
    EXPECT_EQ(e.penumbraPixels, 5);
    EXPECT_EQ(e.over0_1Pixels, 9);
    EXPECT_EQ(e.acnePixels, 2);
    EXPECT_EQ(e.leakPixels, 2);
    EXPECT_EQ(e.faintLeakPixels, 3);  // 0.125, 0.75 and 1 in the umbra: above 0.1

    EXPECT_DOUBLE_EQ(e.rmse, std::sqrt(3.578125 / 16.0));
    EXPECT_DOUBLE_EQ(e.mae, 4.875 / 16.0);
    EXPECT_DOUBLE_EQ(e.meanError, 0.375 / 16.0);
    EXPECT_DOUBLE_EQ(e.maxAbsError, 1.0);
    EXPECT_DOUBLE_EQ(e.p99, 1.0);  // nearest rank ceil(0.99 * 16) = 16: the largest
    EXPECT_DOUBLE_EQ(e.fractionOver0_1, 9.0 / 16.0);
    EXPECT_DOUBLE_EQ(e.penumbraRmse, std::sqrt(0.375 / 5.0));
    EXPECT_DOUBLE_EQ(e.acneFraction, 2.0 / 6.0);
    EXPECT_DOUBLE_EQ(e.acneMeanDarkening, (0.25 + 0.75 + 1.0) / 6.0);
    EXPECT_DOUBLE_EQ(e.leakFraction, 2.0 / 5.0);
    EXPECT_DOUBLE_EQ(e.faintLeakFraction, 3.0 / 5.0);
    EXPECT_DOUBLE_EQ(e.leakMeanLightening, (0.125 + 0.75 + 1.0) / 5.0);
}

TEST(ErrorMetrics, P99IsNearestRank) {
    // |e| = k/256 for k = 1..150 (exact in float), shuffled by a stride. Nearest rank:
    // ceil(0.99 * 150) = 149, so p99 = 149/256; interpolating definitions give other values.
    constexpr int kN = 150;
    std::vector<float> truth(kN, 0.0f);
    std::vector<float> estimate(kN);
    for (int i = 0; i < kN; ++i) estimate[static_cast<std::size_t>(i)] = static_cast<float>((i * 7) % kN + 1) / 256.0f;
    const Result<VisibilityErrors> r = compareVisibility(imageOf(kN, 1, estimate), imageOf(kN, 1, truth));
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_DOUBLE_EQ(r->p99, 149.0 / 256.0);
    EXPECT_DOUBLE_EQ(r->maxAbsError, 150.0 / 256.0);

    // N = 100: rank 99, not the maximum.
    std::vector<float> est100(100);
    for (int i = 0; i < 100; ++i) est100[static_cast<std::size_t>(i)] = static_cast<float>(100 - i) / 128.0f;
    const Result<VisibilityErrors> r100 =
        compareVisibility(imageOf(100, 1, est100), imageOf(100, 1, std::vector<float>(100, 0.0f)));
    ASSERT_TRUE(r100.ok());
    EXPECT_DOUBLE_EQ(r100->p99, 99.0 / 128.0);
}

TEST(ErrorMetrics, MaskRestrictsToReceiversUsingItsLastChannel) {
    // Only the six lit pixels are receivers.
    std::vector<float> coverage(16, 0.0f);
    for (int i = 0; i < 6; ++i) coverage[static_cast<std::size_t>(i)] = 1.0f;
    const ImageF mask = rgbaMask(4, 4, coverage);
    const Result<VisibilityErrors> r = compareVisibility(imageOf(4, 4, kEstimate4x4), imageOf(4, 4, kTruth4x4), &mask);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->receiverPixels, 6);
    EXPECT_EQ(r->validPixels, 6);
    EXPECT_EQ(r->litPixels, 6);
    EXPECT_EQ(r->umbraPixels, 0);
    EXPECT_EQ(r->penumbraPixels, 0);
    EXPECT_DOUBLE_EQ(r->rmse, std::sqrt(1.625 / 6.0));
    EXPECT_DOUBLE_EQ(r->mae, 2.0 / 6.0);
    EXPECT_DOUBLE_EQ(r->acneFraction, 2.0 / 6.0);
    // Empty classes report 0, not NaN.
    EXPECT_EQ(r->leakFraction, 0.0);
    EXPECT_EQ(r->leakMeanLightening, 0.0);
    EXPECT_EQ(r->penumbraRmse, 0.0);
}

TEST(ErrorMetrics, NonFiniteMaskedOutPixelsAreIgnoredAndEmptyMaskGivesZeros) {
    std::vector<float> estimate = kEstimate4x4;
    estimate[15] = kNaN;  // outside the mask below: neither an error nor a bad pixel
    std::vector<float> coverage(16, 1.0f);
    coverage[15] = 0.0f;
    coverage[14] = kNaN;  // a NaN mask value is not a receiver
    const ImageF mask = rgbaMask(4, 4, coverage);
    const Result<VisibilityErrors> r = compareVisibility(imageOf(4, 4, estimate), imageOf(4, 4, kTruth4x4), &mask);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->receiverPixels, 14);
    EXPECT_EQ(r->nonFinite, 0);
    EXPECT_EQ(r->penumbraPixels, 3);
    // Pixel 15 (e = 0.5) and 14 (e = 0) gone: sum e² = 3.578125 - 0.25.
    EXPECT_DOUBLE_EQ(r->rmse, std::sqrt(3.328125 / 14.0));

    const ImageF none = rgbaMask(4, 4, std::vector<float>(16, 0.0f));
    const Result<VisibilityErrors> empty = compareVisibility(imageOf(4, 4, estimate), imageOf(4, 4, kTruth4x4), &none);
    ASSERT_TRUE(empty.ok());
    EXPECT_EQ(empty->receiverPixels, 0);
    EXPECT_EQ(empty->rmse, 0.0);
    EXPECT_EQ(empty->p99, 0.0);
    EXPECT_EQ(empty->acneFraction, 0.0);
}

TEST(ErrorMetrics, NonFiniteEstimateScoresTheWorstErrorAndIsCounted) {
    std::vector<float> estimate = kEstimate4x4;
    estimate[3] = kNaN;   // lit: e = -0.25 becomes -1 (acne)
    estimate[9] = -kInf;  // umbra: e = +0.75 becomes +1 (a leak either way)
    const Result<VisibilityErrors> r = compareVisibility(imageOf(4, 4, estimate), imageOf(4, 4, kTruth4x4));
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->receiverPixels, 16);
    EXPECT_EQ(r->nonFinite, 2);
    EXPECT_EQ(r->validPixels, 16);
    EXPECT_EQ(r->litPixels, 6);
    EXPECT_EQ(r->umbraPixels, 5);
    EXPECT_EQ(r->acnePixels, 3);
    EXPECT_EQ(r->leakPixels, 2);
    const double sumSq = 3.578125 - 0.0625 + 1.0 - 0.5625 + 1.0;
    EXPECT_DOUBLE_EQ(r->rmse, std::sqrt(sumSq / 16.0));
    EXPECT_DOUBLE_EQ(r->mae, (4.875 - 0.25 + 1.0 - 0.75 + 1.0) / 16.0);
    EXPECT_DOUBLE_EQ(r->maxAbsError, 1.0);

    // An estimate that is NaN everywhere is the worst there is, not a perfect score.
    const Result<VisibilityErrors> allNaN =
        compareVisibility(imageOf(4, 4, std::vector<float>(16, kNaN)), imageOf(4, 4, kTruth4x4));
    ASSERT_TRUE(allNaN.ok()) << allNaN.error().message;
    EXPECT_EQ(allNaN->nonFinite, 16);
    EXPECT_DOUBLE_EQ(allNaN->rmse, 1.0);
    EXPECT_DOUBLE_EQ(allNaN->mae, 1.0);
}

TEST(ErrorMetrics, NonFiniteTruthIsBadInputNamingThePixel) {
    std::vector<float> truth = kTruth4x4;
    truth[7] = kInf;  // (3, 1)
    const Result<VisibilityErrors> r = compareVisibility(imageOf(4, 4, kEstimate4x4), imageOf(4, 4, truth));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("(3, 1)"), std::string::npos) << r.error().message;

    // Outside the mask it is not looked at.
    std::vector<float> coverage(16, 1.0f);
    coverage[7] = 0.0f;
    const ImageF mask = rgbaMask(4, 4, coverage);
    EXPECT_TRUE(compareVisibility(imageOf(4, 4, kEstimate4x4), imageOf(4, 4, truth), &mask).ok());
}

TEST(ErrorMetrics, ClassEpsilonAbsorbsNearBinaryTruth) {
    // 0.9995 is lit and 0.0005 umbra (within ε = 1e-3); 0.002 and 0.998 are penumbra.
    const std::vector<float> truth = {0.9995f, 0.0005f, 0.002f, 0.998f};
    const std::vector<float> estimate = {0.4f, 0.6f, 0.002f, 0.998f};
    const Result<VisibilityErrors> r = compareVisibility(imageOf(4, 1, estimate), imageOf(4, 1, truth));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->litPixels, 1);
    EXPECT_EQ(r->umbraPixels, 1);
    EXPECT_EQ(r->penumbraPixels, 2);
    EXPECT_EQ(r->acnePixels, 1);
    EXPECT_EQ(r->leakPixels, 1);
    EXPECT_EQ(r->penumbraRmse, 0.0);
}

TEST(ErrorMetrics, SizeMismatchNamesBothSizes) {
    const ImageF a = makeImage(4, 4, 1);
    const ImageF b = makeImage(4, 3, 1);
    const Result<VisibilityErrors> r = compareVisibility(a, b);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("4x4"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("4x3"), std::string::npos) << r.error().message;

    const ImageF mask = makeImage(2, 2, 4);
    const Result<VisibilityErrors> m = compareVisibility(a, a, &mask);
    ASSERT_FALSE(m.ok());
    EXPECT_NE(m.error().message.find("mask is 2x2"), std::string::npos) << m.error().message;
    EXPECT_NE(m.error().message.find("4x4"), std::string::npos) << m.error().message;

    const Result<VisibilityErrors> c = compareVisibility(makeImage(4, 4, 3), a);
    ASSERT_FALSE(c.ok());
    EXPECT_NE(c.error().message.find("3 channels"), std::string::npos) << c.error().message;
    EXPECT_FALSE(errorHeatMap(a, b).ok());
}

TEST(ErrorMetrics, PooledLightsArePixelWeighted) {
    // Light 0: the 4x4 case; light 1: 16 exactly estimated lit pixels. Pooled over 32 pixels.
    const std::vector<ImageF> estimates = {imageOf(4, 4, kEstimate4x4), imageOf(4, 4, std::vector<float>(16, 1.0f))};
    const std::vector<ImageF> truths = {imageOf(4, 4, kTruth4x4), imageOf(4, 4, std::vector<float>(16, 1.0f))};
    const Result<VisibilityErrors> all = compareVisibilityPooled(estimates, truths);
    ASSERT_TRUE(all.ok()) << all.error().message;
    EXPECT_EQ(all->validPixels, 32);
    EXPECT_DOUBLE_EQ(all->rmse, std::sqrt(3.578125 / 32.0));
    EXPECT_DOUBLE_EQ(all->mae, 4.875 / 32.0);
    EXPECT_EQ(all->litPixels, 22);
    EXPECT_DOUBLE_EQ(all->acneFraction, 2.0 / 22.0);
    EXPECT_DOUBLE_EQ(all->leakFraction, 2.0 / 5.0);
    // Pooled p99: rank ceil(0.99 * 32) = 32, the largest |e| of either light.
    EXPECT_DOUBLE_EQ(all->p99, 1.0);

    std::vector<float> coverage(16, 0.0f);
    for (int i : {0, 1, 2, 3}) coverage[static_cast<std::size_t>(i)] = 1.0f;
    const ImageF mask = rgbaMask(4, 4, coverage);  // pixels 0-3: e = 0, 0, 0, -0.25 in light 0
    const Result<VisibilityErrors> masked = compareVisibilityPooled(estimates, truths, &mask);
    ASSERT_TRUE(masked.ok());
    EXPECT_EQ(masked->receiverPixels, 8);
    EXPECT_DOUBLE_EQ(masked->rmse, std::sqrt(0.0625 / 8.0));

    const Result<VisibilityErrors> uneven = compareVisibilityPooled(estimates, {truths[0]});
    ASSERT_FALSE(uneven.ok());
    const std::vector<ImageF> wrongSize = {truths[0], makeImage(2, 2, 1)};
    const Result<VisibilityErrors> bad = compareVisibilityPooled(estimates, wrongSize);
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("light 1"), std::string::npos) << bad.error().message;
}

// ---- Heat maps ------------------------------------------------------------------------------

void expectColor(const std::array<float, 3>& got, float r, float g, float b) {
    EXPECT_FLOAT_EQ(got[0], r);
    EXPECT_FLOAT_EQ(got[1], g);
    EXPECT_FLOAT_EQ(got[2], b);
}

TEST(ErrorHeatMap, ColoursAtMinusOneZeroPlusOne) {
    expectColor(errorColor(-1.0), 0, 0, 1);  // too dark: blue
    expectColor(errorColor(0.0), 1, 1, 1);   // exact: white
    expectColor(errorColor(1.0), 1, 0, 0);   // too light: red
    expectColor(errorColor(-0.5), 0.5f, 0.5f, 1);
    expectColor(errorColor(0.25), 1, 0.75f, 0.75f);
    expectColor(errorColor(-3.0), 0, 0, 1);  // saturates
    expectColor(errorColor(7.0), 1, 0, 0);
    expectColor(errorColor(std::nan("")), kHeatMapBadColor[0], kHeatMapBadColor[1], kHeatMapBadColor[2]);
}

TEST(ErrorHeatMap, ImageColoursReceiversAndGreysBackground) {
    // e = -1, 0, +1, (masked out), NaN.
    const ImageF truth = imageOf(5, 1, {1, 0.5f, 0, 0.3f, 1});
    const ImageF estimate = imageOf(5, 1, {0, 0.5f, 1, 0.9f, kNaN});
    const ImageF mask = imageOf(5, 1, {1, 1, 1, 0, 1});
    const Result<ImageF> map = errorHeatMap(estimate, truth, &mask);
    ASSERT_TRUE(map.ok()) << map.error().message;
    ASSERT_EQ(map->channels, 3);
    const std::vector<std::array<float, 3>> expected = {
        {0, 0, 1}, {1, 1, 1}, {1, 0, 0}, kHeatMapBackground, kHeatMapBadColor};
    for (int x = 0; x < 5; ++x) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_FLOAT_EQ(map->at(x, 0, c), expected[static_cast<std::size_t>(x)][static_cast<std::size_t>(c)])
                << "pixel " << x << " channel " << c;
        }
    }
}

/// A fresh directory per test under $SHADOW_TEST_TMP (or the system temp dir), removed after.
class MetricsDirTest : public ::testing::Test {
protected:
    void SetUp() override {
        tmp_ = std::make_unique<test::TempDir>("error_metrics_test");
        dir_ = tmp_->path();
    }
    void TearDown() override { tmp_.reset(); }

    /// `dir_/name`, created as a folder when `folder`.
    [[nodiscard]] std::string path(const std::string& name, bool folder = false) const {
        const fs::path p = dir_ / name;
        if (folder) fs::create_directories(p);
        return p.string();
    }

    static void writeVisibility(const std::string& dir, int index, const ImageF& image) {
        const std::string file = dir + "/visibility_" + std::to_string(index) + ".exr";
        ASSERT_TRUE(writeExr(file, image, {"Y"}).ok()) << file;
    }
    static void writePosition(const std::string& dir, const ImageF& rgba) {
        ASSERT_TRUE(writeExr(dir + "/position.exr", rgba, {"R", "G", "B", "A"}).ok());
    }

    std::unique_ptr<test::TempDir> tmp_;  // removes the folder
    fs::path dir_;
};

TEST_F(MetricsDirTest, HeatMapPngHasTheExpectedBytes) {
    const ImageF truth = imageOf(5, 1, {1, 0.5f, 0, 0.3f, 1});
    const ImageF estimate = imageOf(5, 1, {0, 0.5f, 1, 0.9f, kNaN});
    const ImageF mask = imageOf(5, 1, {1, 1, 1, 0, 1});
    const std::string file = path("error_0.png");
    ASSERT_TRUE(writeHeatMapPng(file, *errorHeatMap(estimate, truth, &mask)).ok());
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(file.c_str(), &w, &h, &n, 3);
    ASSERT_NE(data, nullptr);
    const std::vector<unsigned char> bytes(data, data + 15);
    stbi_image_free(data);
    EXPECT_EQ(w, 5);
    EXPECT_EQ(h, 1);
    const std::vector<unsigned char> expected = {0, 0, 255, 255, 255, 255, 255, 0, 0, 128, 128, 128, 0, 0, 0};
    EXPECT_EQ(bytes, expected);
}

// Two 2x2 lights; position.exr covers pixels 0-2 (pixel 3 is background, where the
// estimates hold garbage that must not count).
//   light 0: truth {1, 1, 0, 0.5}, estimate {1, 0.25, 0.5, 9}: e = 0, -0.75 (acne), +0.5
//   light 1: truth {0, 0, 0.5, 0}, estimate {0, 1, 0.5, NaN}:  e = 0, +1 (leak), 0
TEST_F(MetricsDirTest, CompareFoldersPerLightAndPooled) {
    const std::string est = path("est", true);
    const std::string tru = path("truth", true);
    writeVisibility(tru, 0, imageOf(2, 2, {1, 1, 0, 0.5f}));
    writeVisibility(tru, 1, imageOf(2, 2, {0, 0, 0.5f, 0}));
    writeVisibility(est, 0, imageOf(2, 2, {1, 0.25f, 0.5f, 9}));
    writeVisibility(est, 1, imageOf(2, 2, {0, 1, 0.5f, kNaN}));
    writeVisibility(est, 5, imageOf(2, 2, {0, 0, 0, 0}));  // not in the truth: a warning
    writePosition(tru, rgbaMask(2, 2, {1, 1, 1, 0}));

    const Result<FolderComparison> r = compareFolders(est, tru);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->width, 2);
    EXPECT_EQ(r->height, 2);
    EXPECT_EQ(r->maskSource, tru + "/position.exr");
    ASSERT_EQ(r->lights.size(), 2u);
    ASSERT_EQ(r->warnings.size(), 1u);
    EXPECT_NE(r->warnings[0].find("visibility_5.exr"), std::string::npos);

    const VisibilityErrors& l0 = r->lights[0].errors;
    EXPECT_EQ(r->lights[0].index, 0);
    EXPECT_EQ(l0.validPixels, 3);
    EXPECT_EQ(l0.nonFinite, 0);
    EXPECT_DOUBLE_EQ(l0.rmse, std::sqrt((0.5625 + 0.25) / 3.0));
    EXPECT_DOUBLE_EQ(l0.acneFraction, 0.5);
    EXPECT_EQ(l0.umbraPixels, 1);
    EXPECT_EQ(l0.leakPixels, 0);  // 0.5 is not > 0.5

    const VisibilityErrors& l1 = r->lights[1].errors;
    EXPECT_EQ(r->lights[1].index, 1);
    EXPECT_EQ(l1.validPixels, 3);
    EXPECT_DOUBLE_EQ(l1.rmse, std::sqrt(1.0 / 3.0));
    EXPECT_DOUBLE_EQ(l1.leakFraction, 0.5);
    EXPECT_EQ(l1.penumbraPixels, 1);

    // Pooled over the six receivers of both lights.
    const VisibilityErrors& all = r->allLights;
    EXPECT_EQ(all.receiverPixels, 6);
    EXPECT_EQ(all.validPixels, 6);
    EXPECT_DOUBLE_EQ(all.rmse, std::sqrt((0.5625 + 0.25 + 1.0) / 6.0));
    EXPECT_DOUBLE_EQ(all.mae, (0.75 + 0.5 + 1.0) / 6.0);
    EXPECT_DOUBLE_EQ(all.p99, 1.0);
    EXPECT_EQ(all.litPixels, 2);
    EXPECT_EQ(all.umbraPixels, 3);
    EXPECT_EQ(all.penumbraPixels, 1);
    EXPECT_DOUBLE_EQ(all.acneFraction, 0.5);
    EXPECT_DOUBLE_EQ(all.leakFraction, 1.0 / 3.0);

    // The heat map comes along: pixel 1 of light 0 is e = -0.75, pixel 3 is background.
    const ImageF& map = r->lights[0].heatMap;
    EXPECT_FLOAT_EQ(map.at(1, 0, 0), 0.25f);
    EXPECT_FLOAT_EQ(map.at(1, 0, 2), 1.0f);
    EXPECT_FLOAT_EQ(map.at(1, 1, 0), kHeatMapBackground[0]);
}

TEST_F(MetricsDirTest, CompareFoldersMissingEstimateLightNamesTheFile) {
    const std::string est = path("est", true);
    const std::string tru = path("truth", true);
    writeVisibility(tru, 0, imageOf(2, 2, {1, 1, 1, 1}));
    writeVisibility(tru, 1, imageOf(2, 2, {1, 1, 1, 1}));
    writeVisibility(est, 0, imageOf(2, 2, {1, 1, 1, 1}));
    const Result<FolderComparison> r = compareFolders(est, tru);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find(est + "/visibility_1.exr"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("missing"), std::string::npos) << r.error().message;
}

TEST_F(MetricsDirTest, CompareFoldersBadInputNamesTheProblem) {
    const std::string est = path("est", true);
    const std::string tru = path("truth", true);
    const std::string nowhere = path("nowhere");

    Result<FolderComparison> r = compareFolders(nowhere, tru);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find(nowhere), std::string::npos) << r.error().message;

    r = compareFolders(est, tru);  // truth has no visibility files
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find(tru), std::string::npos) << r.error().message;

    writeVisibility(tru, 0, imageOf(2, 2, {1, 1, 1, 1}));
    writeVisibility(est, 0, imageOf(3, 1, {1, 1, 1}));
    r = compareFolders(est, tru);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("3x1"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("2x2"), std::string::npos) << r.error().message;

    {
        std::ofstream garbage(est + "/visibility_0.exr", std::ios::binary | std::ios::trunc);
        garbage << "not an EXR";
    }
    r = compareFolders(est, tru);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find(est + "/visibility_0.exr"), std::string::npos) << r.error().message;

    writeVisibility(est, 0, imageOf(2, 2, {1, 1, 1, 1}));
    r = compareFolders(est, tru, path("no_mask.exr"));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("no_mask.exr"), std::string::npos) << r.error().message;
}

TEST_F(MetricsDirTest, CompareFoldersMaskFallsBackToEstimateThenEveryPixel) {
    const std::string est = path("est", true);
    const std::string tru = path("truth", true);
    writeVisibility(tru, 0, imageOf(2, 2, {1, 1, 1, 1}));
    writeVisibility(est, 0, imageOf(2, 2, {0, 1, 1, 1}));

    Result<FolderComparison> r = compareFolders(est, tru);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->allLights.receiverPixels, 4);
    EXPECT_EQ(r->maskSource, "none (every pixel)");

    writePosition(est, rgbaMask(2, 2, {0, 1, 1, 1}));
    r = compareFolders(est, tru);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->maskSource, est + "/position.exr");
    EXPECT_EQ(r->allLights.receiverPixels, 3);
    EXPECT_EQ(r->allLights.rmse, 0.0);

    // A mask file given explicitly wins; a one-channel Y mask works too.
    const std::string maskFile = path("mask.exr");
    ASSERT_TRUE(writeExr(maskFile, imageOf(2, 2, {1, 0, 0, 0}), {"Y"}).ok());
    r = compareFolders(est, tru, maskFile);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->maskSource, maskFile);
    EXPECT_EQ(r->allLights.receiverPixels, 1);
    EXPECT_EQ(r->allLights.rmse, 1.0);
}

TEST(ErrorMetrics, InteriorUmbraKeepsItsMarginFromEveryOtherPixel) {
    // A 7x7 true umbra with one lit pixel at (6, 6): interior pixels are 2 pixels from the
    // image's edge and from that pixel, x and y in [2, 4] except (4, 4), 8 of them.
    std::vector<float> truth(49, 0.0f);
    truth[6 * 7 + 6] = 1.0f;
    std::vector<float> estimate(49, 0.0f);
    estimate[3 * 7 + 3] = 0.2f;  // interior: an interior leak above 0.1
    estimate[4 * 7 + 4] = 0.9f;  // next to the lit pixel's margin: a leak, not interior
    estimate[0] = 0.05f;         // at the edge, below 0.1: no leak at all
    const Result<VisibilityErrors> r = compareVisibility(imageOf(7, 7, estimate), imageOf(7, 7, truth));
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->umbraPixels, 48);
    EXPECT_EQ(r->interiorUmbraPixels, 8);
    EXPECT_EQ(r->interiorLeakPixels, 1);
    EXPECT_DOUBLE_EQ(r->interiorLeakFraction, 1.0 / 8.0);
    EXPECT_EQ(r->faintLeakPixels, 2);
    EXPECT_EQ(r->leakPixels, 1);
}

TEST_F(MetricsDirTest, CompareFoldersLitMasksJudgeEachLightWhereTheTruthSaysItShades) {
    const std::string est = path("est", true);
    const std::string tru = path("truth", true);
    writeVisibility(tru, 0, imageOf(2, 2, {1, 1, 1, 1}));
    writeVisibility(tru, 1, imageOf(2, 2, {1, 1, 1, 1}));
    writeVisibility(est, 0, imageOf(2, 2, {0, 1, 1, 1}));  // wrong at pixel 0
    writeVisibility(est, 1, imageOf(2, 2, {1, 1, 1, 0}));  // wrong at pixel 3
    writePosition(tru, rgbaMask(2, 2, {1, 1, 1, 1}));
    // Light 0 shades pixels 1-3 (its error at pixel 0 is outside), light 1 pixels 2 and 3.
    ASSERT_TRUE(writeExr(tru + "/lit_0.exr", imageOf(2, 2, {0, 1, 1, 1}), {"Y"}).ok());
    ASSERT_TRUE(writeExr(tru + "/lit_1.exr", imageOf(2, 2, {0, 0, 1, 1}), {"Y"}).ok());

    Result<FolderComparison> r = compareFolders(est, tru, kLitMasks);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_EQ(r->lights.size(), 2u);
    EXPECT_EQ(r->lights[0].errors.receiverPixels, 3);
    EXPECT_EQ(r->lights[0].errors.rmse, 0.0);
    EXPECT_EQ(r->lights[1].errors.receiverPixels, 2);
    EXPECT_DOUBLE_EQ(r->lights[1].errors.rmse, std::sqrt(0.5));
    EXPECT_EQ(r->allLights.receiverPixels, 5);
    EXPECT_DOUBLE_EQ(r->allLights.rmse, std::sqrt(1.0 / 5.0));

    // A light whose lit mask is missing: one error naming the file.
    fs::remove(tru + "/lit_1.exr");
    r = compareFolders(est, tru, kLitMasks);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("lit_1.exr"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace shadow
