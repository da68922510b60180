// The main pass's targets (engine/src/render/render_targets.cpp): sizes, formats and the AOVs
// asked for, kept while they fit and made anew when not, what a clear writes, and what each pass
// writes to.
#include <gtest/gtest.h>
#include <shadow/shared_constants.h>

#include <shadow/context.h>
#include <shadow/renderer.h>

#include "gl/gl_state.h"
#include "render/render_targets.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "render/render_test_support.h"

namespace shadow::render {
namespace {

/// The texture attached at `attachment` of `framebuffer` (0: none).
GLuint attached(GLuint framebuffer, GLenum attachment) {
    GLint name = 0;
    auto get = reinterpret_cast<PFNGLGETNAMEDFRAMEBUFFERATTACHMENTPARAMETERIVPROC>(
        test::glContext().loader()("glGetNamedFramebufferAttachmentParameteriv"));
    get(framebuffer, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    return static_cast<GLuint>(name);
}

/// Level 0 of `texture` (`channels` floats a texel, `width` x `height`).
std::vector<float> read(GLuint texture, GLenum format, int channels, int width, int height) {
    std::vector<float> out(static_cast<std::size_t>(width) * height * channels);
    const gpu::GlState saved = gpu::captureGlState({}, {});
    gpu::setReadbackDefaults();
    gl.GetTextureSubImage(texture, 0, 0, 0, 0, width, height, 1, format, GL_FLOAT,
                          static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
    gpu::restoreGlState(saved);
    return out;
}

/// The internal format and size of `texture`.
std::array<GLint, 3> formatAndSize(GLuint texture) {
    auto get = reinterpret_cast<PFNGLGETTEXTURELEVELPARAMETERIVPROC>(
        test::glContext().loader()("glGetTextureLevelParameteriv"));
    std::array<GLint, 3> out{};
    get(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &out[0]);
    get(texture, 0, GL_TEXTURE_WIDTH, &out[1]);
    get(texture, 0, GL_TEXTURE_HEIGHT, &out[2]);
    return out;
}

TEST(RenderTargets, MakesColourAndDepthOfTheSizeAskedAndKeepsThemWhileTheyFit) {
    test::glContext();
    RenderTargets t;
    t.ensure(40, 30, false, 1);
    EXPECT_EQ(t.width(), 40);
    EXPECT_EQ(t.height(), 30);
    EXPECT_FALSE(t.aovs());
    const GLuint fb = t.framebuffer();
    ASSERT_NE(fb, 0u);
    const GLuint colour = attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR);
    EXPECT_EQ(formatAndSize(colour), (std::array<GLint, 3>{GL_RGBA32F, 40, 30}));
    EXPECT_EQ(formatAndSize(attached(fb, GL_DEPTH_ATTACHMENT)), (std::array<GLint, 3>{GL_DEPTH_COMPONENT32F, 40, 30}));
    EXPECT_EQ(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION), 0u) << "no AOV asked for";

    t.ensure(40, 30, false, 3);  // more passes without AOVs need nothing more
    EXPECT_EQ(t.framebuffer(), fb);
    EXPECT_EQ(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR), colour) << "kept while it fits";
    t.ensure(41, 30, false, 1);
    EXPECT_EQ(t.width(), 41);
    EXPECT_EQ(formatAndSize(attached(t.framebuffer(), GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR))[1], 41);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(RenderTargets, AovsHaveTwoVisibilityTexturesPerPassAndTheClearsTheShadersExpect) {
    test::glContext();
    RenderTargets t;
    t.ensure(16, 8, true, 2);
    EXPECT_TRUE(t.aovs());
    const GLuint fb = t.framebuffer();
    EXPECT_EQ(formatAndSize(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION))[0], GL_RGBA32F);
    EXPECT_EQ(formatAndSize(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH))[0], GL_R32F);
    // Slots 0-3 and 4-7 of each pass: four distinct textures for two passes.
    const std::array<GLuint, 4> visibility{t.visibility(0, 0), t.visibility(0, 4), t.visibility(1, 0),
                                           t.visibility(1, 7)};
    for (std::size_t a = 0; a < visibility.size(); ++a) {
        EXPECT_EQ(formatAndSize(visibility[a]), (std::array<GLint, 3>{GL_RGBA32F, 16, 8}));
        for (std::size_t b = a + 1; b < visibility.size(); ++b) EXPECT_NE(visibility[a], visibility[b]);
    }
    EXPECT_EQ(t.visibility(1, 3), t.visibility(1, 0)) << "slots 0-3 share a texture";
    t.ensure(16, 8, true, 1);  // fewer passes: the targets of two still fit
    EXPECT_EQ(t.visibility(1, 0), visibility[2]);

    // A clear: colour 0, position and depth 0 (no geometry), depth buffer far; bindPass attaches
    // the pass's visibility textures and clears them to 1 (lit where nothing is drawn).
    // Every target holds something else first, so that the clears have work to show.
    const std::array<float, 4> other{0.5f, 0.5f, 0.5f, 0.5f};
    for (const GLenum a : {GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION}) {
        gl.ClearTexSubImage(attached(fb, a), 0, 0, 0, 0, 16, 8, 1, GL_RGBA, GL_FLOAT, other.data());
    }
    gl.ClearTexSubImage(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH), 0, 0, 0, 0, 16, 8, 1, GL_RED, GL_FLOAT,
                        other.data());
    gl.ClearTexSubImage(attached(fb, GL_DEPTH_ATTACHMENT), 0, 0, 0, 0, 16, 8, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                        other.data());
    for (const GLuint v : visibility) gl.ClearTexSubImage(v, 0, 0, 0, 0, 16, 8, 1, GL_RGBA, GL_FLOAT, other.data());
    const gpu::GlState saved = gpu::captureGlState({}, {});
    gl.BindFramebuffer(GL_FRAMEBUFFER, fb);
    t.clear();
    t.bindPass(1);
    gpu::restoreGlState(saved);
    EXPECT_EQ(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0), t.visibility(1, 0));
    EXPECT_EQ(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY1), t.visibility(1, 4));
    const auto all = [](const std::vector<float>& v, float x) {
        return std::all_of(v.begin(), v.end(), [x](float f) { return f == x; });
    };
    EXPECT_TRUE(all(read(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR), GL_RGBA, 4, 16, 8), 0.0f));
    EXPECT_TRUE(all(read(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION), GL_RGBA, 4, 16, 8), 0.0f));
    EXPECT_TRUE(all(read(attached(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH), GL_RED, 1, 16, 8), 0.0f));
    EXPECT_TRUE(all(read(attached(fb, GL_DEPTH_ATTACHMENT), GL_DEPTH_COMPONENT, 1, 16, 8), 1.0f));
    EXPECT_TRUE(all(read(t.visibility(1, 0), GL_RGBA, 4, 16, 8), 1.0f));
    EXPECT_TRUE(all(read(t.visibility(1, 4), GL_RGBA, 4, 16, 8), 1.0f));
    EXPECT_TRUE(all(read(t.visibility(0, 0), GL_RGBA, 4, 16, 8), 0.5f)) << "another pass's are its own to clear";
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(RenderTargets, ASizeOverTheLimitsOrTheMemoryCapIsRefusedBeforeAllocating) {
    test::glContext();
    GLint maxTexture = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    // The cap: 20 bytes a pixel without AOVs, 72 with them for one pass.
    EXPECT_EQ(RenderTargets::bytesFor(100, 10, false, 1), 100 * 10 * 20);
    EXPECT_EQ(RenderTargets::bytesFor(100, 10, true, 1), 100 * 10 * 72);
    EXPECT_EQ(RenderTargets::bytesFor(100, 10, true, 3), 100 * 10 * 136);
    RenderOptions options;
    options.width = 8192;
    options.height = 8192;
    EXPECT_TRUE(checkRenderSize(options).ok()) << "1.25 GiB without AOVs";
    options.aovs = true;
    const Status withAovs = checkRenderSize(options);
    ASSERT_FALSE(withAovs.ok());
    EXPECT_NE(withAovs.error().message.find("kMaxRenderTargetBytes"), std::string::npos) << withAovs.error().message;
    // The screen-space visibility stage's targets count too (60 more bytes a pixel at full
    // resolution): 8192^2 fits without them, not with them.
    options.aovs = false;
    options.screenVisibility = ScreenVisibility::Auto;
    const Status withStage = checkRenderSize(options);
    ASSERT_FALSE(withStage.ok());
    EXPECT_NE(withStage.error().message.find("screen-space visibility"), std::string::npos)
        << withStage.error().message;
    options.screenVisibility = ScreenVisibility::Off;
    options.width = maxTexture + 1;
    options.height = 1;
    const Status beyond = checkRenderSize(options);
    ASSERT_FALSE(beyond.ok());
    EXPECT_NE(beyond.error().message.find("GL_MAX_TEXTURE_SIZE"), std::string::npos) << beyond.error().message;

    // The renderer refuses what checkRenderSize refuses, naming the size, with nothing made.
    RenderTargets t;
    try {
        t.ensure(16384, 16384, false, 1);
        ADD_FAILURE() << "16384^2 of float colour and depth (5 GiB) was accepted";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("16384x16384"), std::string::npos) << e.what();
    }
    EXPECT_EQ(t.framebuffer(), 0u);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace shadow::render
