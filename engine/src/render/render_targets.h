// The offscreen targets of the main pass: linear colour, the depth buffer the pre-pass fills,
// and, when AOVs are asked for, world position, camera distance and per-light visibility.
#pragma once

#include "gl/objects.h"

#include <vector>

namespace shadow::render {

class RenderTargets {
public:
    /// Makes the targets fit `width` x `height`, with AOV targets for `passes` main passes when
    /// `aovs`; keeps the current ones when they already fit. Throws `GlError` when the
    /// framebuffer is incomplete.
    void ensure(int width, int height, bool aovs, int passes);
    /// Attaches what main pass `pass` writes and sets its draw buffers.
    void bindPass(int pass);
    /// Clears colour (0), depth (far), and the AOVs (position and depth 0, visibility 1).
    void clear();

    [[nodiscard]] GLuint framebuffer() const { return framebuffer_.get(); }
    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }
    [[nodiscard]] bool aovs() const { return aovs_; }
    /// The visibility texture holding slots 4*(k%2) .. 4*(k%2)+3 of pass k/2.
    [[nodiscard]] GLuint visibility(int pass, int slot) const;

private:
    int width_ = 0, height_ = 0, passes_ = 0;
    bool aovs_ = false;
    gpu::Framebuffer framebuffer_;
    gpu::Texture color_, position_, depthAov_, depthBuffer_;
    std::vector<gpu::Texture> visibility_;  // two RGBA per pass: slots 0-3 and 4-7
};

}  // namespace shadow::render
