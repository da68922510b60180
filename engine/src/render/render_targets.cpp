#include "render/render_targets.h"

#include "render/screen_visibility.h"

#include <shadow/context.h>
#include <shadow/renderer.h>
#include <shadow/shared_constants.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace shadow::render {
namespace {

gpu::Texture makeTarget(const std::string& label, GLenum format, int w, int h) {
    gpu::Texture t = gpu::makeTexture(label, GL_TEXTURE_2D);
    gl.TextureStorage2D(t.get(), 1, format, w, h);
    return t;
}

}  // namespace

std::string renderSizeProblem(int width, int height, bool aovs, int passes, bool screenStage, bool materialTargets) {
    GLint maxTexture = 0, maxWidth = 0, maxHeight = 0, maxRenderbuffer = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    gl.GetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxWidth);
    gl.GetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &maxHeight);
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    if (width < 1 || height < 1) return "width and height must be at least 1";
    const int maxEdge = std::min(maxTexture, maxRenderbuffer);
    const int maxW = std::min(maxEdge, maxWidth), maxH = std::min(maxEdge, maxHeight);
    if (width > maxW || height > maxH) {
        return "beyond this context's limits (" + std::to_string(maxW) + "x" + std::to_string(maxH) +
               ": GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT)";
    }
    const std::int64_t bytes = RenderTargets::bytesFor(width, height, aovs, passes) +
                               (screenStage ? ScreenStage::bytesFor(width, height, materialTargets) : 0);
    if (bytes > kMaxRenderTargetBytes) {
        const double mib = 1024.0 * 1024.0;
        return "the targets would take " + std::to_string(std::llround(static_cast<double>(bytes) / mib)) + " MiB" +
               (aovs ? " with the AOVs" : "") + (screenStage ? " and the screen-space visibility stage" : "") +
               ", over the renderer's cap of " +
               std::to_string(std::llround(static_cast<double>(kMaxRenderTargetBytes) / mib)) +
               " MiB (kMaxRenderTargetBytes)";
    }
    return {};
}

std::int64_t RenderTargets::bytesFor(int width, int height, bool aovs, int passes) {
    const std::int64_t pixels = std::int64_t{width} * height;
    // Colour RGBA32F and depth 32F; AOVs: position RGBA32F, distance R32F, two RGBA32F a pass.
    const std::int64_t visibility = std::int64_t{32} * std::max(passes, 1);
    const std::int64_t perPixel = std::int64_t{16 + 4} + (aovs ? std::int64_t{16 + 4} + visibility : 0);
    return pixels * perPixel;
}

void RenderTargets::ensure(int width, int height, bool aovs, int passes) {
    const int aovPasses = aovs ? passes : 0;
    if (framebuffer_ && width_ == width && height_ == height && aovs_ == aovs && passes_ >= aovPasses) return;
    // Refused before anything is allocated: an incomplete framebuffer or an out-of-memory error
    // would say less, after the fact.
    if (const std::string why = renderSizeProblem(width, height, aovs, passes); !why.empty()) {
        throw GlError("main pass targets of " + std::to_string(width) + "x" + std::to_string(height) + ": " + why);
    }
    *this = RenderTargets{};
    width_ = width;
    height_ = height;
    aovs_ = aovs;
    passes_ = aovPasses;
    framebuffer_ = gpu::makeFramebuffer("Main/framebuffer");
    color_ = makeTarget("Main/color", GL_RGBA32F, width, height);
    depthBuffer_ = makeTarget("Main/depthBuffer", GL_DEPTH_COMPONENT32F, width, height);
    const GLuint fb = framebuffer_.get();
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, color_.get(), 0);
    gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, depthBuffer_.get(), 0);
    if (!aovs) return;
    position_ = makeTarget("Main/position", GL_RGBA32F, width, height);
    depthAov_ = makeTarget("Main/depth", GL_R32F, width, height);
    for (int i = 0; i < 2 * aovPasses; ++i) {
        visibility_.push_back(makeTarget("Main/visibility" + std::to_string(i), GL_RGBA32F, width, height));
    }
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION, position_.get(), 0);
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH, depthAov_.get(), 0);
}

GLuint RenderTargets::visibility(int pass, int slot) const {
    return visibility_[2 * static_cast<std::size_t>(pass) + static_cast<std::size_t>(slot / 4)].get();
}

void RenderTargets::bindPass(int pass, PassOutputs outputs) {
    const GLuint fb = framebuffer_.get();
    if (aovs_) {
        gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0, visibility(pass, 0), 0);
        gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY1, visibility(pass, 4), 0);
    }
    setOutputs(pass, outputs);
    if (aovs_) {
        const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        gl.ClearNamedFramebufferfv(fb, GL_COLOR, SG_OUT_VISIBILITY0, one);
        gl.ClearNamedFramebufferfv(fb, GL_COLOR, SG_OUT_VISIBILITY1, one);
    }
}

void RenderTargets::setOutputs(int pass, PassOutputs outputs) {
    const auto at = [](int location) { return GLenum{GL_COLOR_ATTACHMENT0} + static_cast<GLenum>(location); };
    std::array<GLenum, SG_OUT_MARKS + 1> buffers{};
    buffers.fill(GL_NONE);
    buffers[SG_OUT_COLOR] = at(SG_OUT_COLOR);
    if (aovs_) {
        // Position and depth are written once, by the first pass (never by a correction).
        if (pass == 0 && outputs != PassOutputs::Correction) {
            buffers[SG_OUT_POSITION] = at(SG_OUT_POSITION);
            buffers[SG_OUT_DEPTH] = at(SG_OUT_DEPTH);
        }
        buffers[SG_OUT_VISIBILITY0] = at(SG_OUT_VISIBILITY0);
        buffers[SG_OUT_VISIBILITY1] = at(SG_OUT_VISIBILITY1);
    }
    if (outputs == PassOutputs::LitMarks) buffers[SG_OUT_MARKS] = at(SG_OUT_MARKS);
    // The count: up to the last buffer written.
    GLsizei count = 1;
    for (std::size_t i = 0; i < buffers.size(); ++i)
        count = buffers[i] != GL_NONE ? static_cast<GLsizei>(i + 1) : count;
    gl.NamedFramebufferDrawBuffers(framebuffer_.get(), count, buffers.data());
}

void RenderTargets::clearMarks() {
    const std::array<GLuint, 4> none{0, 0, 0, 0};
    gl.ClearNamedFramebufferuiv(framebuffer_.get(), GL_COLOR, SG_OUT_MARKS, none.data());
}

void RenderTargets::attachMarks(GLuint texture) {
    gl.NamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0 + SG_OUT_MARKS, texture, 0);
}

void RenderTargets::clear() {
    const GLuint fb = framebuffer_.get();
    std::array<GLenum, 3> buffers = {GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, GL_NONE, GL_NONE};
    if (aovs_) {
        buffers = {GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION,
                   GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH};
    }
    gl.NamedFramebufferDrawBuffers(fb, aovs_ ? 3 : 1, buffers.data());
    if (gl.CheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw GlError("main pass framebuffer is incomplete");
    }
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float farDepth = 1.0f;
    gl.DepthMask(GL_TRUE);
    gl.ClearNamedFramebufferfv(fb, GL_DEPTH, 0, &farDepth);
    gl.ClearNamedFramebufferfv(fb, GL_COLOR, 0, zero);
    if (aovs_) {
        gl.ClearNamedFramebufferfv(fb, GL_COLOR, 1, zero);
        gl.ClearNamedFramebufferfv(fb, GL_COLOR, 2, zero);
    }
}

}  // namespace shadow::render
