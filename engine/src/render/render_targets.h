// The offscreen targets of the main pass: linear colour, the depth buffer the pre-pass fills,
// and, when AOVs are asked for, world position, camera distance and per-light visibility.
#pragma once

#include "gl/objects.h"

#include <cstdint>
#include <string>
#include <vector>

namespace shadow::render {

/// What keeps targets of `width` x `height` (with `aovs`, for `passes` passes) from being made:
/// a size beyond the context's texture, renderbuffer or framebuffer limits, or targets over
/// `kMaxRenderTargetBytes` (with `screenStage`, the screen-space visibility stage's targets
/// counted too, with its material targets when `materialTargets`), said without the size (the
/// caller names it); empty when they can be. Reads the limits from the current context.
[[nodiscard]] std::string renderSizeProblem(int width, int height, bool aovs, int passes, bool screenStage = false,
                                            bool materialTargets = false);

/// What a main pass writes (`RenderTargets::bindPass`, `setOutputs`).
enum class PassOutputs {
    Lit,         ///< colour, and with AOVs position and distance (first pass) and visibility
    LitMarks,    ///< those and the marks (`attachMarks`): a deferred lit pass that resolves the stage
    Correction,  ///< colour and, with AOVs, visibility alone: what a lit pass's correction adds
};

class RenderTargets {
public:
    /// GPU memory (bytes) of the targets for `width` x `height`: colour (RGBA32F) and depth
    /// (32F), and with `aovs` position (RGBA32F), distance (R32F) and two RGBA32F visibility
    /// textures per pass of `passes`.
    [[nodiscard]] static std::int64_t bytesFor(int width, int height, bool aovs, int passes);
    /// Makes the targets fit `width` x `height`, with AOV targets for `passes` main passes when
    /// `aovs`; keeps the current ones when they already fit. Throws `GlError` naming the size
    /// before allocating anything when it is beyond the context's limits or the memory cap
    /// (`checkRenderSize`), and when the framebuffer is incomplete.
    void ensure(int width, int height, bool aovs, int passes);
    /// Attaches what main pass `pass` writes, sets its draw buffers (`setOutputs`) and, with
    /// AOVs, sets its visibility to 1.
    void bindPass(int pass, PassOutputs outputs = PassOutputs::Lit);
    /// Sets the draw buffers of main pass `pass` (attached by `bindPass`) to `outputs`.
    void setOutputs(int pass, PassOutputs outputs);
    /// Attaches `texture` (R8UI, the targets' size; 0: none) as the marks a deferred lit pass
    /// writes (SG_OUT_MARKS).
    void attachMarks(GLuint texture);
    /// Clears the marks (within the scissor, when on) of a pass bound with PassOutputs::LitMarks.
    void clearMarks();
    /// Clears colour (0), depth (far), and the AOVs (position and depth 0, visibility 1).
    void clear();

    [[nodiscard]] GLuint framebuffer() const { return framebuffer_.get(); }
    [[nodiscard]] GLuint depthBuffer() const { return depthBuffer_.get(); }
    /// The linear colour (RGBA32F) the lit passes write.
    [[nodiscard]] GLuint color() const { return color_.get(); }
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
