// The GPU's present passes (engine/src/render/present.cpp) against the CPU's functions they stand
// in for: the tone map (toneMapToSrgb8) and the exposure meter (luminanceHistogram), both from
// shadow/tone_map.h, on a test image that spans the curve and the hues, and on a rendered frame.
#include <gtest/gtest.h>
#include <shadow/image_io.h>
#include <shadow/renderer.h>

#include "gl/gl_api.h"
#include "render/present.h"
#include "render/render_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace shadow::present_test {
namespace {

/// Linear RGB over 256 x 64 pixels: luminance from 1e-7 to 3e4 along x (log-spaced, so every
/// part of the curve and of the sRGB encoding is met), hue and saturation along y (pure
/// primaries, pastels, grey), with a black column for the background.
ImageF testImage() {
    ImageF image = makeImage(256, 64, 3);
    for (int y = 0; y < image.height; ++y) {
        const float hue = 6.2831853f * static_cast<float>(y % 16) / 16.0f;
        const float saturation = static_cast<float>(y / 16) / 3.0f;
        const glm::vec3 tint = glm::mix(
            glm::vec3(1.0f), 0.5f + 0.5f * glm::vec3(std::cos(hue), std::cos(hue + 2.094f), std::cos(hue + 4.189f)),
            saturation);
        for (int x = 1; x < image.width; ++x) {
            const float level = std::pow(10.0f, -7.0f + 11.5f * static_cast<float>(x) / 255.0f);
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = level * tint[c];
        }
    }
    return image;
}

/// `image` as an RGBA32F texture with GL's rows (bottom first), as the renderer's colour target.
gpu::Texture uploadColor(const ImageF& image) {
    std::vector<float> rgba;
    for (int y = image.height - 1; y >= 0; --y) {
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < 3; ++c) rgba.push_back(image.at(x, y, c));
            rgba.push_back(1.0f);
        }
    }
    gpu::Texture texture = gpu::makeTexture("test/color", GL_TEXTURE_2D);
    gl.TextureStorage2D(texture.get(), 1, GL_RGBA32F, image.width, image.height);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TextureSubImage2D(texture.get(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rgba.data());
    return texture;
}

struct Difference {
    int largest = 0;
    double fraction = 0.0;  ///< of the channels that differ at all
};

Difference compare(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    Difference d;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        const int step = std::abs(static_cast<int>(a[i]) - static_cast<int>(b[i]));
        d.largest = std::max(d.largest, step);
        differing += step > 0 ? 1 : 0;
    }
    d.fraction = static_cast<double>(differing) / static_cast<double>(std::max<std::size_t>(a.size(), 1));
    return d;
}

// Tolerance: one 8-bit step (1/255) on any channel. Fails when the GPU's curve, encoding or row
// order is not the CPU's (a flipped image differs by far more than a step on this gradient).
TEST(Present, GpuToneMapMatchesTheCpuToneMapWithinOneStep) {
    test::glContext();
    const ImageF image = testImage();
    const gpu::Texture color = uploadColor(image);
    render::Presenter presenter;
    for (const float exposure : {0.01f, 1.0f, 37.0f, 2000.0f}) {
        presenter.toneMap(color.get(), image.width, image.height, exposure);
        const std::vector<std::uint8_t> gpu = presenter.readDisplay();
        const std::vector<std::uint8_t> cpu = toneMapToSrgb8(image, exposure);
        ASSERT_EQ(gpu.size(), cpu.size());
        const Difference d = compare(gpu, cpu);
        std::cout << "exposure " << exposure << ": GPU tone map against the CPU's: " << d.fraction * 100.0
                  << " % of channels differ, by at most " << d.largest << " step\n";
        EXPECT_LE(d.largest, 1) << "exposure " << exposure;
    }
}

// Fails when the GPU's meter bins other than the CPU's (a bin shifted moves every pixel; a pixel
// count off by the background or the black column changes the total). A pixel may land in the
// neighbouring bin where the two log2 differ in the last bit: 0.5 % of them, at most one bin.
TEST(Present, GpuMeterCountsAsTheCpuHistogram) {
    test::glContext();
    const ImageF image = testImage();
    const gpu::Texture color = uploadColor(image);
    render::Presenter presenter;
    const LuminanceHistogram gpu = presenter.meter(color.get(), image.width, image.height);
    const LuminanceHistogram cpu = luminanceHistogram(image);
    long gpuTotal = 0, cpuTotal = 0, moved = 0;
    for (std::size_t b = 0; b < gpu.size(); ++b) {
        gpuTotal += gpu[b];
        cpuTotal += cpu[b];
        moved += std::abs(static_cast<long>(gpu[b]) - static_cast<long>(cpu[b]));
    }
    EXPECT_EQ(gpuTotal, cpuTotal);
    EXPECT_GT(cpuTotal, 0);
    EXPECT_LE(moved, cpuTotal / 200) << "pixels in another bin";
    EXPECT_NEAR(exposureFromHistogram(gpu), exposureFromHistogram(cpu), 1e-3 * exposureFromHistogram(cpu));
}

// The renderer's own frame: what the viewer shows (meterExposure, presentToTexture,
// readPresented) is what shadow_render writes from the frame read back (autoExposure,
// toneMapToSrgb8), within one step. Fails when the present passes read another target than the
// frame's colour or flip it.
TEST(Present, RendererPresentsTheFrameAsTheCpuToneMapsItsReadback) {
    test::glContext();
    Result<Scene> scene = makeBuiltinScene("default");
    ASSERT_TRUE(scene.ok());
    FrameRunner runner;
    test::RenderedFrame frame = test::renderFrame(runner, *scene, 160, 90, 1.0);
    Renderer& renderer = runner.renderer();
    const float cpuExposure = autoExposure(frame.images.color);
    const float gpuExposure = exposureFromHistogram(renderer.meterExposure(frame.stats));
    EXPECT_NEAR(gpuExposure, cpuExposure, 1e-3 * cpuExposure);
    EXPECT_TRUE(renderer.presentToTexture(cpuExposure, frame.stats));
    const std::vector<std::uint8_t> shown = renderer.readPresented();
    const Difference d = compare(shown, toneMapToSrgb8(frame.images.color, cpuExposure));
    EXPECT_EQ(shown.size(), std::size_t{160} * 90 * 3);
    EXPECT_LE(d.largest, 1);
    EXPECT_TRUE(renderer.warnings().empty());
}

}  // namespace
}  // namespace shadow::present_test
