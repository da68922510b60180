// What the renderer does with a finished frame for a screen: the exposure meter's histogram of
// its linear colour (a compute pass) and the tone map into an 8-bit display texture (a
// full-screen pass), both from shadow/tone_map.h, as the CPU's `luminanceHistogram` and
// `toneMapToSrgb8` compute them. A viewer that shows every frame this way reads back 1.5 KB of
// counters instead of the frame's floats.
#pragma once

#include "gl/objects.h"

#include <shadow/image_io.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace shadow::render {

class Presenter {
public:
    Presenter();

    /// The exposure meter's counts over the RGBA32F texture `color` (`width` x `height`). Reads
    /// back the counters (waits for the GPU).
    [[nodiscard]] LuminanceHistogram meter(GLuint color, int width, int height);
    /// Tone-maps `color` (`width` x `height`) with `exposure` into the display texture, made to
    /// fit; returns it. Row 0 of the display texture is the image's top row.
    GLuint toneMap(GLuint color, int width, int height, float exposure);
    /// The display texture as 8-bit RGB, rows top first; empty before the first `toneMap`.
    [[nodiscard]] std::vector<std::uint8_t> readDisplay() const;
    [[nodiscard]] GLuint display() const { return display_.get(); }
    [[nodiscard]] GLuint displayFramebuffer() const { return framebuffer_.get(); }
    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }

private:
    gpu::Program toneMapProgram_, meterProgram_;
    GLint exposureLocation_ = -1;
    gpu::VertexArray empty_;
    gpu::Buffer bins_;
    gpu::Texture display_;
    gpu::Framebuffer framebuffer_;
    int width_ = 0, height_ = 0;
};

}  // namespace shadow::render
