#include "render/present.h"

#include "gl/gl_state.h"
#include "gl/program.h"

#include <shadow/shared_constants.h>

#include <algorithm>
#include <string>

namespace shadow::render {
namespace {

/// Pixels along each edge of the tile one invocation of the meter counts, and of a work group's
/// 8 x 8 tiles (exposure_histogram.comp.glsl).
constexpr int kMeterTile = 8;
constexpr int kMeterGroup = 8 * kMeterTile;

}  // namespace

Presenter::Presenter()
    : toneMapProgram_(gpu::buildProgram({"Present/ToneMap", "fullscreen.vert.glsl", "tone_map.frag.glsl", {}, 0})),
      meterProgram_(gpu::buildComputeProgram("Present/Meter", "exposure_histogram.comp.glsl",
                                             {"SG_METER_TILE " + std::to_string(kMeterTile)})),
      bins_(gpu::makeBuffer("Present/exposureBins", sizeof(LuminanceHistogram), nullptr, GL_DYNAMIC_STORAGE_BIT)) {
    exposureLocation_ = gl.GetUniformLocation(toneMapProgram_.get(), "sg_exposure");
    empty_ = gpu::makeVertexArray("Present/empty vertex array");
}

LuminanceHistogram Presenter::meter(GLuint color, int width, int height) {
    LuminanceHistogram counts{};
    gl.NamedBufferSubData(bins_.get(), 0, sizeof(counts), counts.data());
    gl.UseProgram(meterProgram_.get());
    gl.BindTextureUnit(0, color);
    gl.BindSampler(0, 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SG_BINDING_JOINTS, bins_.get());
    gl.DispatchCompute(static_cast<GLuint>((width + kMeterGroup - 1) / kMeterGroup),
                       static_cast<GLuint>((height + kMeterGroup - 1) / kMeterGroup), 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.GetNamedBufferSubData(bins_.get(), 0, sizeof(counts), counts.data());
    return counts;
}

GLuint Presenter::toneMap(GLuint color, int width, int height, float exposure) {
    if (width != width_ || height != height_ || !display_) {
        display_ = gpu::makeTexture("Present/display", GL_TEXTURE_2D);
        gl.TextureStorage2D(display_.get(), 1, GL_RGBA8, width, height);
        gl.TextureParameteri(display_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.TextureParameteri(display_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TextureParameteri(display_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TextureParameteri(display_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        framebuffer_ = gpu::makeFramebuffer("Present/display");
        gl.NamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, display_.get(), 0);
        gl.NamedFramebufferDrawBuffer(framebuffer_.get(), GL_COLOR_ATTACHMENT0);
        gl.NamedFramebufferReadBuffer(framebuffer_.get(), GL_COLOR_ATTACHMENT0);
        width_ = width;
        height_ = height;
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    gl.Viewport(0, 0, width, height);
    gpu::setPassDefaults();
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.UseProgram(toneMapProgram_.get());
    gl.ProgramUniform1f(toneMapProgram_.get(), exposureLocation_, exposure);
    gl.BindTextureUnit(0, color);
    gl.BindSampler(0, 0);
    gl.BindVertexArray(empty_.get());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    return display_.get();
}

std::vector<std::uint8_t> Presenter::readDisplay() const {
    if (!display_) return {};
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3U);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.get());
    gpu::setReadbackDefaults();
    // Row 0 of the display texture is the image's top row already.
    gl.ReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    return rgb;
}

}  // namespace shadow::render
