// The engine as a guest in a host's GL context (engine/src/gl/gl_state.h): every public call
// that draws leaves the state it changes as it found it, and an error the host left pending is
// reported as the host's (a HostGlError warning), not thrown as the engine's.
#include "gl/gl_state.h"

#include <shadow/shared_constants.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "render/render_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

/// Texture units and uniform-buffer binding points checked: every one the engine binds, and one
/// beyond.
std::vector<GLint> unitsChecked() {
    std::vector<GLint> units;
    for (GLint i = 0; i <= SG_UNIT_MASK_NORMAL + 1; ++i) units.push_back(i);
    return units;
}
const std::vector<GLint> kBindingsChecked{0, 1, 2, 3};
const std::vector<GLint> kImagesChecked{SG_IMAGE_MINMAX, SG_IMAGE_MINMAX + 1};

/// Host state unlike anything the engine sets: its own framebuffer, VAO, program 0, an odd
/// viewport and scissor, depth test off with GREATER and no writes, front-face culling, blending
/// with its own function, a partial colour mask, pack alignment 1, texture unit 5 active, a
/// texture and a sampler on unit 0 and a uniform buffer on binding 1.
struct HostObjects {
    GLuint framebuffer = 0, colour = 0, vertexArray = 0, texture = 0, sampler = 0, buffer = 0;

    HostObjects() {
        gl.CreateTextures(GL_TEXTURE_2D, 1, &colour);
        gl.TextureStorage2D(colour, 1, GL_RGBA8, 32, 32);
        gl.CreateFramebuffers(1, &framebuffer);
        gl.NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);
        gl.CreateVertexArrays(1, &vertexArray);
        gl.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
        gl.TextureStorage3D(texture, 1, GL_R8, 4, 4, 2);
        gl.CreateSamplers(1, &sampler);
        gl.CreateBuffers(1, &buffer);
        gl.NamedBufferStorage(buffer, 1024, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    ~HostObjects() {
        gl.DeleteFramebuffers(1, &framebuffer);
        gl.DeleteTextures(1, &colour);
        gl.DeleteTextures(1, &texture);
        gl.DeleteVertexArrays(1, &vertexArray);
        gl.DeleteSamplers(1, &sampler);
        gl.DeleteBuffers(1, &buffer);
    }
    HostObjects(const HostObjects&) = delete;
    HostObjects& operator=(const HostObjects&) = delete;

    void bindHostState() const {
        gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        gl.BindVertexArray(vertexArray);
        gl.UseProgram(0);
        gl.Viewport(3, 5, 17, 19);
        gl.Scissor(1, 2, 7, 9);
        gl.Enable(GL_SCISSOR_TEST);
        gl.Disable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_GREATER);
        gl.DepthMask(GL_FALSE);
        gl.Enable(GL_CULL_FACE);
        gl.CullFace(GL_FRONT);
        gl.Enablei(GL_BLEND, 0);
        gl.BlendFuncSeparate(GL_ONE, GL_ZERO, GL_SRC_ALPHA, GL_ONE);
        gl.ColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.BindTextureUnit(0, texture);
        gl.BindSampler(0, sampler);
        gl.BindBufferRange(GL_UNIFORM_BUFFER, 1, buffer, 256, 512);
        gl.ActiveTexture(GL_TEXTURE5);
        gl.FrontFace(GL_CW);
        gl.BindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
        gl.PixelStorei(GL_PACK_ROW_LENGTH, 7);
        // The pyramid builder writes through an image unit: the host's image there comes back.
        gl.BindImageTexture(SG_IMAGE_MINMAX, texture, 0, GL_FALSE, 1, GL_READ_ONLY, GL_R8);
    }
    /// GL's defaults for what `bindHostState` sets (other tests share the context).
    static void bindDefaultState() {
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl.BindVertexArray(0);
        gl.Disable(GL_SCISSOR_TEST);
        gl.DepthFunc(GL_LESS);
        gl.DepthMask(GL_TRUE);
        gl.Disable(GL_CULL_FACE);
        gl.CullFace(GL_BACK);
        gl.Disablei(GL_BLEND, 0);
        gl.BlendFuncSeparate(GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
        gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl.BindTextureUnit(0, 0);
        gl.BindSampler(0, 0);
        gl.BindImageTexture(SG_IMAGE_MINMAX, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
        gl.BindBufferBase(GL_UNIFORM_BUFFER, 1, 0);
        gl.ActiveTexture(GL_TEXTURE0);
        gl.FrontFace(GL_CCW);
        gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    }
};

long hostErrors(const FrameStats& stats) {
    return std::count_if(stats.warnings.begin(), stats.warnings.end(),
                         [](const Warning& w) { return w.code == WarningCode::HostGlError; });
}

void expectSameState(const gpu::GlState& before, const gpu::GlState& after, const char* call) {
    EXPECT_EQ(after.drawFramebuffer, before.drawFramebuffer) << call;
    EXPECT_EQ(after.readFramebuffer, before.readFramebuffer) << call;
    EXPECT_EQ(after.program, before.program) << call;
    EXPECT_EQ(after.vertexArray, before.vertexArray) << call;
    EXPECT_EQ(after.viewport, before.viewport) << call;
    EXPECT_EQ(after.scissorBox, before.scissorBox) << call;
    EXPECT_EQ(after.depthFunc, before.depthFunc) << call;
    EXPECT_EQ(after.blendFunc, before.blendFunc) << call;
    EXPECT_EQ(after.units, before.units) << call;
    EXPECT_EQ(after.uniformBindings, before.uniformBindings) << call;
    EXPECT_EQ(after.images, before.images) << call;
    EXPECT_TRUE(after == before) << call << ": some other piece of state changed";
}

TEST(GlManners, EveryPublicCallLeavesTheHostStateAsItFoundIt) {
    test::glContext();
    Scene scene = test::threeLightScene();
    FrameRunner runner;
    test::renderFrame(runner, scene, 64, 48);  // first frame: programs built, maps allocated
    HostObjects host;
    host.bindHostState();
    const gpu::GlState before = gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked);
    ASSERT_EQ(before.drawFramebuffer, static_cast<GLint>(host.framebuffer));  // the set-up took

    RenderOptions options;
    options.width = 64;
    options.height = 48;
    options.aovs = true;
    FrameStats stats = runner.runFrame(scene, 0.5, scene.cameras.at(0), options);
    expectSameState(before, gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked),
                    "FrameRunner::runFrame");

    runner.shadows().planner().setCaching(false);  // every layer and pyramid drawn again
    runner.shadows().prepare(scene.world, runner.lastCamera(), scene.lights);
    runner.shadows().render(scene.world, runner.renderer().meshes(), stats);
    expectSameState(before, gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked),
                    "ShadowSystem::render");

    runner.renderer().render(scene.world, runner.lastCamera(), runner.shadows(), options, stats);
    expectSameState(before, gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked), "Renderer::render");

    const FrameImages images = runner.renderer().readback(runner.lastCamera(), stats);
    expectSameState(before, gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked),
                    "Renderer::readback");

    // The screen-space mask over a depth texture of the host's.
    GLuint depth = 0, mask = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
    gl.TextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 64, 48);
    gl.CreateTextures(GL_TEXTURE_2D, 1, &mask);
    gl.TextureStorage2D(mask, 1, GL_RGBA8, 64, 48);
    host.bindHostState();
    const gpu::GlState beforeMask = gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked);
    ShadowMaskRequest request;
    request.depthTexture = depth;
    request.target = mask;
    request.width = 64;
    request.height = 48;
    request.camera = runner.lastCamera();
    const std::array<int, 3> lights{0, 1, 2};
    runner.shadows().renderMask(lights, request, stats);
    expectSameState(beforeMask, gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked),
                    "ShadowSystem::renderMask");
    gl.DeleteTextures(1, &depth);
    gl.DeleteTextures(1, &mask);
    EXPECT_EQ(images.visibility.size(), 3u);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    EXPECT_EQ(hostErrors(stats), 0) << test::describe(stats.warnings);
    HostObjects::bindDefaultState();
}

TEST(GlManners, TheHostsStateDoesNotChangeWhatTheEngineDraws) {
    // The engine sets every piece of state its passes rely on: a host's scissor, colour mask,
    // clockwise front faces, blending or pack buffer leave its pictures and readbacks as they are.
    test::glContext();
    Scene scene = test::threeLightScene();
    FrameRunner cleanRunner;
    const test::RenderedFrame clean = test::renderFrame(cleanRunner, scene, 64, 48);
    FrameRunner runner;  // its own targets and maps, all drawn under the host's state
    HostObjects host;
    host.bindHostState();
    RenderOptions options;
    options.width = 64;
    options.height = 48;
    options.aovs = true;
    FrameStats stats = runner.runFrame(scene, 0.0, scene.cameras.at(0), options);
    const FrameImages hosted = runner.renderer().readback(runner.lastCamera(), stats);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    HostObjects::bindDefaultState();
    EXPECT_EQ(hosted.color.pixels, clean.images.color.pixels);
    ASSERT_EQ(hosted.visibility.size(), clean.images.visibility.size());
    for (std::size_t i = 0; i < hosted.visibility.size(); ++i) {
        EXPECT_EQ(hosted.visibility[i].pixels, clean.images.visibility[i].pixels) << "light " << i;
    }
}

TEST(GlManners, AnErrorTheHostLeftPendingIsReportedNotThrown) {
    test::glContext();
    Scene scene = test::threeLightScene();
    FrameRunner runner;
    test::renderFrame(runner, scene, 64, 48);
    gl.Enable(0x7fff);  // not a capability: GL_INVALID_ENUM, left pending by the "host"
    RenderOptions options;
    options.width = 64;
    options.height = 48;
    FrameStats stats;
    EXPECT_NO_THROW(stats = runner.runFrame(scene, 0.5, scene.cameras.at(0), options));
    ASSERT_TRUE(test::hasWarning(stats.warnings, WarningCode::HostGlError, "ShadowSystem::render"))
        << test::describe(stats.warnings);
    EXPECT_EQ(hostErrors(stats), 1) << "reported once, by the first call that found it";
    for (const Warning& w : stats.warnings) {
        if (w.code == WarningCode::HostGlError) {
            EXPECT_NE(w.message.find("GL_INVALID_ENUM"), std::string::npos) << w.message;
        }
    }
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(GlManners, TimingIsOffUnlessAskedFor) {
    test::glContext();
    Scene scene = test::threeLightScene();
    RenderOptions options;
    options.width = 64;
    options.height = 48;
    FrameRunner runner;  // turns timing on
    FrameStats timed = runner.runFrame(scene, 0.0, scene.cameras.at(0), options);
    EXPECT_GT(timed.passMs("Shadow/"), 0.0);
    EXPECT_GT(timed.passMs("Main/"), 0.0);
    EXPECT_NE(timed.timingMethod, "off");

    // A shadow system and a renderer as a game makes them: no timing, no pass listed.
    ShadowSystem shadows;
    Renderer renderer;
    updateTransforms(scene.world);
    FrameStats quiet;
    shadows.prepare(scene.world, runner.lastCamera(), scene.lights);
    shadows.render(scene.world, renderer.meshes(), quiet);
    renderer.render(scene.world, runner.lastCamera(), shadows, options, quiet);
    EXPECT_TRUE(quiet.passes.empty());
    EXPECT_EQ(quiet.timingMethod, "off");
    EXPECT_GT(quiet.shadowLayersDrawn, 0) << "the frame was drawn all the same";
    shadows.setTiming(true);
    shadows.planner().setCaching(false);
    FrameStats again;
    shadows.prepare(scene.world, runner.lastCamera(), scene.lights);
    shadows.render(scene.world, renderer.meshes(), again);
    EXPECT_GT(again.passMs("Shadow/"), 0.0);
}

}  // namespace
}  // namespace shadow
