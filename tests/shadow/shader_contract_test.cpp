// The public shader contract (shadow/shadow_shaders.h): a host's own program, built from
// `shadowShaderSource` with binding points of its own choosing and fed by
// `ShadowSystem::shaderInputs`, computes the visibility the renderer's AOVs hold, within 1/255 on
// every covered pixel, for a PCSS spot, a PCF point light and a hard cascaded sun together.
// tests/embed does the same from an installed package.
#include "gl/gl_api.h"

#include <gtest/gtest.h>
#include <shadow/shadow_shaders.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/gl_test_support.h"
#include "render/render_test_support.h"

namespace shadow::shader_contract_test {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kLights = 3;

/// Binding points unlike the engine's defaults, as a host with its own bindings would choose.
ShadowBindingPoints hostPoints() {
    ShadowBindingPoints p;
    p.lightBlock = 5;
    p.layerBlock = 6;
    p.kernelBlock = 7;
    p.compareUnit = 3;
    p.depthUnit = 11;
    p.minMaxUnit = 19;
    p.sdfAtlasUnit = 28;
    p.sdfInstanceUnit = 2;
    return p;
}

const char* kHostVertex = R"(#version 450 core
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
uniform mat4 uCsFromLocal;
uniform mat3 uNormalFromLocal;
uniform mat4 uClipFromCs;
out vec3 vCsPosition;
out vec3 vNormal;
void main() {
    vec4 cs = uCsFromLocal * vec4(inPosition, 1.0);
    vCsPosition = cs.xyz;
    vNormal = uNormalFromLocal * inNormal;
    gl_Position = uClipFromCs * cs;
}
)";

const char* kHostFragmentMain = R"(
in vec3 vCsPosition;
in vec3 vNormal;
uniform vec3 uCameraForward;
layout(location = 0) out vec4 outVisibility;
void main() {
    sg_Surface s = sg_surface(vCsPosition, vNormal);
    float viewDistance = dot(vCsPosition, uCameraForward);
    vec3 v;
    for (int slot = 0; slot < 3; ++slot) v[slot] = sg_lightVisibility(slot, vCsPosition, s, viewDistance);
    outVisibility = vec4(v, 1.0);
}
)";

GLuint compile(GLenum stage, const std::string& text) {
    const test::CompiledShader compiled = test::compileShader(stage, text);
    if (!compiled.ok()) ADD_FAILURE() << "host shader: " << compiled.log;
    return compiled.shader;
}

/// The host's program: its own vertex shader, its fragment shader around the public text.
GLuint hostProgram(const ShadowBindingPoints& points, unsigned techniques) {
    const GLuint v = compile(GL_VERTEX_SHADER, kHostVertex);
    const GLuint f = compile(GL_FRAGMENT_SHADER, std::string("#version 450 core\n") +
                                                     shadowShaderSource(points, techniques) + kHostFragmentMain);
    const GLuint program = gl.CreateProgram();
    gl.AttachShader(program, v);
    gl.AttachShader(program, f);
    gl.LinkProgram(program);
    gl.DeleteShader(v);
    gl.DeleteShader(f);
    GLint ok = GL_FALSE;
    gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
    EXPECT_EQ(ok, GL_TRUE);
    return program;
}

/// Draws every mesh of `scene` with the host's program into an RGBA32F target and reads the
/// visibility of the three lights back, rows top first (as the renderer's images).
/// With `keepDepth`, the host's depth texture is left to the caller there.
/// `beforeDraw`, when given, runs between binding the inputs and drawing.
std::vector<glm::vec4> hostVisibility(Scene& scene, FrameRunner& runner, const ShadowBindingPoints& points,
                                      unsigned techniques = kAllShadowTechniques, GLuint* keepDepth = nullptr,
                                      const std::function<void()>& beforeDraw = {}) {
    const CameraView& cam = runner.lastCamera();
    GLuint colour = 0, depth = 0, framebuffer = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &colour);
    gl.TextureStorage2D(colour, 1, GL_RGBA32F, kWidth, kHeight);
    gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
    gl.TextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
    gl.CreateFramebuffers(1, &framebuffer);
    gl.NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);
    gl.NamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.Viewport(0, 0, kWidth, kHeight);
    // Every state the host's draw relies on (a test before may have left its own).
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_SCISSOR_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disablei(GL_BLEND, 0);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // Clears follow the depth and colour masks: after them.
    const std::array<float, 4> clear{0.0f, 0.0f, 0.0f, 0.0f};
    gl.ClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, clear.data());
    const float far = 1.0f;
    gl.ClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &far);

    const GLuint program = hostProgram(points, techniques);
    gl.UseProgram(program);
    const glm::dmat4 viewFromCs = cam.viewFromWorld * glm::translate(glm::dmat4(1.0), cam.wsPosition);
    const glm::dmat4 clipFromView = glm::perspective(static_cast<double>(cam.yfov), static_cast<double>(cam.aspect),
                                                     static_cast<double>(cam.znear), static_cast<double>(cam.zfar));
    const glm::mat4 clipFromCs(clipFromView * viewFromCs);
    const glm::vec3 forward = glm::normalize(glm::vec3(-glm::dvec3(glm::transpose(cam.viewFromWorld)[2])));
    gl.ProgramUniformMatrix4fv(program, gl.GetUniformLocation(program, "uClipFromCs"), 1, GL_FALSE,
                               glm::value_ptr(clipFromCs));
    gl.ProgramUniform3fv(program, gl.GetUniformLocation(program, "uCameraForward"), 1, glm::value_ptr(forward));

    const std::array<int, kLights> lights{0, 1, 2};
    ShadowSystem& shadows = runner.shadows();
    const ShadowShaderInputs& inputs = shadows.shaderInputs(lights, cam.wsPosition);
    EXPECT_EQ(inputs.lights, kLights);
    unsigned used = 0;  // the techniques of the scene's lights
    for (int light : lights)
        used |= techniqueBit(runner.shadows().frame().lights.at(static_cast<std::size_t>(light)).technique());
    EXPECT_EQ(inputs.techniques, used);
    shadows.bindShaderInputs(inputs, points);
    if (beforeDraw) {
        beforeDraw();
        gl.UseProgram(program);
        gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        gl.Viewport(0, 0, kWidth, kHeight);
    }

    scene.world.view<Mesh, WorldTransform>().each([&](Entity, Mesh& mesh, WorldTransform& wt) {
        glm::dmat4 csFromLocal = wt.worldFromLocal;
        csFromLocal[3] -= glm::dvec4(cam.wsPosition, 0.0);
        const glm::mat3 normalFromLocal(glm::transpose(glm::inverse(glm::dmat3(wt.worldFromLocal))));
        gl.ProgramUniformMatrix4fv(program, gl.GetUniformLocation(program, "uCsFromLocal"), 1, GL_FALSE,
                                   glm::value_ptr(glm::mat4(csFromLocal)));
        gl.ProgramUniformMatrix3fv(program, gl.GetUniformLocation(program, "uNormalFromLocal"), 1, GL_FALSE,
                                   glm::value_ptr(normalFromLocal));
        const int indices = runner.renderer().meshes().bind(mesh.data);
        gl.DrawElements(GL_TRIANGLES, indices, GL_UNSIGNED_INT, nullptr);
    });
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));

    std::vector<glm::vec4> pixels(static_cast<std::size_t>(kWidth) * kHeight);
    gl.ReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, pixels.data());
    std::vector<glm::vec4> topFirst(pixels.size());
    for (int y = 0; y < kHeight; ++y) {
        std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(y) * kWidth, kWidth,
                    topFirst.begin() + static_cast<std::ptrdiff_t>(kHeight - 1 - y) * kWidth);
    }
    gl.BindVertexArray(0);
    gl.UseProgram(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.DeleteProgram(program);
    gl.DeleteFramebuffers(1, &framebuffer);
    gl.DeleteTextures(1, &colour);
    if (keepDepth != nullptr) {
        *keepDepth = depth;
    } else {
        gl.DeleteTextures(1, &depth);
    }
    return topFirst;
}

/// Renders `scene` with the engine and with a host's own shader (its own binding points) and
/// checks that every light's visibility agrees on every covered pixel, to 1/255.
void expectHostMatchesRenderer(Scene& scene, const std::string& what) {
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    ASSERT_EQ(frame.images.visibility.size(), static_cast<std::size_t>(kLights));
    const std::vector<glm::vec4> host = hostVisibility(scene, runner, hostPoints());

    for (int light = 0; light < kLights; ++light) {
        const ImageF& engine = frame.images.visibility[static_cast<std::size_t>(light)];
        double worst = 0.0;
        int covered = 0, shadowed = 0, lit = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x);
                if (frame.images.position.at(x, y, 3) < 0.5f || host[i].a < 0.5f) continue;
                ++covered;
                const float e = engine.at(x, y, 0);
                worst = std::max(worst, static_cast<double>(std::abs(e - host[i][light])));
                shadowed += e < 0.1f ? 1 : 0;
                lit += e > 0.9f ? 1 : 0;
            }
        }
        SCOPED_TRACE(what + ", light " + std::to_string(light));
        EXPECT_GT(covered, kWidth * kHeight / 2);
        // Both shadow and light on screen: a host that read nothing (all lit) could not pass.
        EXPECT_GT(shadowed, 100);
        EXPECT_GT(lit, 100);
        EXPECT_LE(worst, 1.0 / 255.0);
        std::printf("%s, light %d: %d pixels covered, largest difference %.3g\n", what.c_str(), light, covered, worst);
    }
}

TEST(ShaderContract, HostShaderGetsTheRenderersVisibility) {
    Scene scene = test::threeLightScene();
    expectHostMatchesRenderer(scene, "PCSS spot, PCF point, cascaded sun");
}

TEST(ShaderContract, HostShaderGetsTheRenderersDistanceFieldVisibility) {
    Scene scene = test::threeLightScene();
    scene.world.view<Shadow>().each([](Entity, Shadow& s) { s.technique = ShadowTechnique::Sdf; });
    expectHostMatchesRenderer(scene, "sdf");
}

/// Reads an RGBA32F texture, rows top first.
std::vector<glm::vec4> readTopFirst(GLuint texture) {
    std::vector<glm::vec4> pixels(static_cast<std::size_t>(kWidth) * kHeight);
    gl.GetTextureSubImage(texture, 0, 0, 0, 0, kWidth, kHeight, 1, GL_RGBA, GL_FLOAT,
                          static_cast<GLsizei>(pixels.size() * sizeof(glm::vec4)), pixels.data());
    std::vector<glm::vec4> topFirst(pixels.size());
    for (int y = 0; y < kHeight; ++y) {
        std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(y) * kWidth, kWidth,
                    topFirst.begin() + static_cast<std::ptrdiff_t>(kHeight - 1 - y) * kWidth);
    }
    return topFirst;
}

/// How close a mask must come to the renderer's visibility: the share of covered pixels within
/// `within` of it, and the most the mean difference may be.
struct MaskTolerance {
    double within = 1.0 / 255.0;
    double share = 0.99;
    double meanDifference = 0.002;
};

/// The screen-space mask of `scene`'s three lights over the host's depth, at `resolution`,
/// against the renderer's forward visibility; returns the mask (rows top first).
std::vector<glm::vec4> expectMaskMatchesRenderer(Scene& scene, const std::string& what,
                                                 MaskResolution resolution = MaskResolution::Full,
                                                 MaskTolerance tolerance = {}) {
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    GLuint depth = 0;
    (void)hostVisibility(scene, runner, ShadowBindingPoints{}, kAllShadowTechniques, &depth);
    GLuint target = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &target);
    gl.TextureStorage2D(target, 1, GL_RGBA32F, kWidth, kHeight);
    ShadowMaskRequest request;
    request.depthTexture = GlTexture{depth};
    request.target = GlTexture{target};
    request.width = kWidth;
    request.height = kHeight;
    request.camera = runner.lastCamera();
    request.resolution = resolution;
    FrameStats stats;
    const std::array<int, kLights> lights{0, 1, 2};
    runner.shadows().renderMask(lights, request, stats);
    std::vector<glm::vec4> mask = readTopFirst(target);
    gl.DeleteTextures(1, &target);
    gl.DeleteTextures(1, &depth);

    for (int light = 0; light < kLights; ++light) {
        const ImageF& engine = frame.images.visibility[static_cast<std::size_t>(light)];
        int covered = 0, close = 0, background = 0;
        double sum = 0.0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const float m = mask[static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x)][light];
                if (frame.images.position.at(x, y, 3) < 0.5f) {
                    background += m == 1.0f ? 1 : 0;
                    continue;
                }
                ++covered;
                const double d = std::abs(static_cast<double>(m) - engine.at(x, y, 0));
                sum += d;
                close += d <= tolerance.within ? 1 : 0;
            }
        }
        SCOPED_TRACE(what + ", light " + std::to_string(light));
        std::printf("%s, mask light %d: %d pixels, %.2f %% within %.4f, mean difference %.4f\n", what.c_str(), light,
                    covered, 100.0 * close / std::max(covered, 1), tolerance.within, sum / std::max(covered, 1));
        EXPECT_EQ(background, kWidth * kHeight - covered);  // no geometry: lit
        EXPECT_GE(close, static_cast<int>(covered * tolerance.share));
        EXPECT_LE(sum / std::max(covered, 1), tolerance.meanDifference);
    }
    return mask;
}

TEST(ShaderContract, ScreenSpaceMaskFromTheHostsDepthMatchesTheRenderer) {
    Scene scene = test::threeLightScene();
    expectMaskMatchesRenderer(scene, "PCSS spot, PCF point, cascaded sun");
}

TEST(ShaderContract, ScreenSpaceMaskOfDistanceFieldLightsMatchesTheRenderer) {
    Scene scene = test::threeLightScene();
    scene.world.view<Shadow>().each([](Entity, Shadow& s) { s.technique = ShadowTechnique::Sdf; });
    expectMaskMatchesRenderer(scene, "sdf");
}

// At half and quarter resolution the mask is an upsample with refined edges: close to the
// renderer's forward visibility, not equal to it. Measured (160x120, the three-light scene, each
// light refined where its own samples call for it): at half 99.66-99.77 % of pixels within
// 0.05, mean difference 0.0007-0.0009; at quarter 99.59-99.80 %, 0.0007-0.0014.
TEST(ShaderContract, ScreenSpaceMaskAtReducedResolutionStaysCloseToTheRenderer) {
    Scene scene = test::threeLightScene();
    const std::vector<glm::vec4> full = expectMaskMatchesRenderer(scene, "full");
    for (const MaskResolution resolution : {MaskResolution::Half, MaskResolution::Quarter}) {
        const std::string what = resolution == MaskResolution::Half ? "half" : "quarter";
        const std::vector<glm::vec4> reduced =
            expectMaskMatchesRenderer(scene, what, resolution, MaskTolerance{0.05, 0.99, 0.003});
        // The reduced path ran: the upsample is not the full-resolution mask pixel for pixel.
        int differing = 0;
        for (std::size_t i = 0; i < full.size(); ++i) differing += full[i] != reduced[i] ? 1 : 0;
        std::printf("%s: %d pixels differ from the full-resolution mask\n", what.c_str(), differing);
        EXPECT_GT(differing, 0) << what;
    }
}

TEST(ShaderContract, TheMaskLeavesTheHostsForwardPassAlone) {
    // A game binds the inputs of its forward pass, asks for a mask of other lights (another
    // order, another camera position), and draws: its pixels are those it draws without the mask.
    test::glContext();
    Scene scene = test::threeLightScene();
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, kWidth, kHeight);
    const std::vector<glm::vec4> alone = hostVisibility(scene, runner, hostPoints());
    GLuint depth = 0;
    (void)hostVisibility(scene, runner, ShadowBindingPoints{}, kAllShadowTechniques, &depth);
    GLuint target = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &target);
    gl.TextureStorage2D(target, 1, GL_RGBA8, kWidth, kHeight);
    auto mask = [&] {
        ShadowMaskRequest request;
        request.depthTexture = GlTexture{depth};
        request.target = GlTexture{target};
        request.width = kWidth;
        request.height = kHeight;
        request.camera = runner.lastCamera();
        request.camera.wsPosition += glm::dvec3(0.5, 0.0, 0.0);
        FrameStats stats;
        const std::array<int, 2> lights{2, 0};
        runner.shadows().renderMask(lights, request, stats);
    };
    const std::vector<glm::vec4> withMask =
        hostVisibility(scene, runner, hostPoints(), kAllShadowTechniques, nullptr, mask);
    gl.DeleteTextures(1, &target);
    gl.DeleteTextures(1, &depth);
    int covered = 0, wrong = 0;
    for (std::size_t i = 0; i < alone.size(); ++i) {
        if (alone[i].a < 0.5f) continue;
        ++covered;
        const glm::vec4 d = glm::abs(alone[i] - withMask[i]);
        wrong += std::max({d.r, d.g, d.b}) > 1.0f / 255.0f ? 1 : 0;
    }
    std::printf("host's forward pass after a mask: %d of %d covered pixels differ by more than 1/255\n", wrong,
                covered);
    EXPECT_GT(covered, kWidth * kHeight / 2);
    EXPECT_EQ(wrong, 0);
}

TEST(ShaderContract, TechniquesLeftOutReadAsLit) {
    test::glContext();
    Scene scene = test::threeLightScene();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    // Hard shadows only: the PCSS spot (slot 0) and the PCF bulb (slot 1) read as lit, the sun
    // (slot 2) as the renderer has it.
    const std::vector<glm::vec4> host =
        hostVisibility(scene, runner, ShadowBindingPoints{}, techniqueBit(ShadowTechnique::Hard));
    double worstSun = 0.0;
    float darkest = 1.0f;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::vec4& h = host[static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x)];
            if (h.a < 0.5f) continue;
            darkest = std::min({darkest, h.r, h.g});
            worstSun = std::max(worstSun, static_cast<double>(std::abs(h.b - frame.images.visibility[2].at(x, y, 0))));
        }
    }
    EXPECT_EQ(darkest, 1.0f);
    EXPECT_LE(worstSun, 1.0 / 255.0);
}

TEST(ShaderContract, BadBindingPointsAreRefusedByName) {
    ShadowBindingPoints shared;
    shared.layerBlock = shared.lightBlock;
    EXPECT_THROW((void)shadowShaderSource(shared), std::invalid_argument);
    ShadowBindingPoints overlapping;
    overlapping.depthUnit = overlapping.compareUnit + 4;
    try {
        (void)shadowShaderSource(overlapping);
        ADD_FAILURE() << "overlapping units accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("compareUnit"), std::string::npos) << e.what();
    }
    ShadowBindingPoints negative;
    negative.kernelBlock = -1;
    EXPECT_THROW((void)shadowShaderSource(negative), std::invalid_argument);
}

TEST(ShaderContract, ShaderInputsRefuseWhatIsNotASceneLight) {
    test::glContext();
    Scene scene = test::threeLightScene();
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, 32, 24);
    const std::array<int, 1> missing{7};
    EXPECT_THROW((void)runner.shadows().shaderInputs(missing, glm::dvec3(0.0)), std::invalid_argument);
    const std::array<int, SG_MAX_LIGHTS_PER_PASS + 1> tooMany{};
    EXPECT_THROW((void)runner.shadows().shaderInputs(tooMany, glm::dvec3(0.0)), std::invalid_argument);
    const std::array<int, 2> two{2, 0};
    const ShadowShaderInputs& inputs = runner.shadows().shaderInputs(two, glm::dvec3(0.0));
    EXPECT_EQ(inputs.sceneLight[0], 2);
    EXPECT_EQ(inputs.sceneLight[1], 0);
    EXPECT_EQ(inputs.sceneLight[2], -1);
    EXPECT_EQ(inputs.depthArray[0], runner.shadows().maps().textureOf(2));
    EXPECT_FALSE(inputs.minMax[0]);  // a hard light has no pyramid
    EXPECT_TRUE(inputs.minMax[1]);   // a PCSS light has one

    // A mask request that names no texture, or a target that cannot be drawn to: one clear error.
    ShadowMaskRequest request;
    request.width = 32;
    request.height = 24;
    request.camera = runner.lastCamera();
    FrameStats stats;
    EXPECT_THROW(runner.shadows().renderMask(two, request, stats), std::invalid_argument);
    GLuint depth = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
    gl.TextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 32, 24);
    request.depthTexture = GlTexture{depth};
    request.target = GlTexture{depth};  // a depth texture is no colour target
    EXPECT_THROW(runner.shadows().renderMask(two, request, stats), GlError);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    const std::array<int, SG_MAX_MASK_LIGHTS + 1> five{};
    request.target = GlTexture{depth};
    EXPECT_THROW(runner.shadows().renderMask(five, request, stats), std::invalid_argument);
    // The same as error values, for a game built without exceptions.
    const Status mask = runner.shadows().tryRenderMask(five, request, stats);
    ASSERT_FALSE(mask.ok());
    EXPECT_NE(mask.error().message.find("renderMask"), std::string::npos) << mask.error().message;
    const Result<const ShadowShaderInputs*> inputsOrError = runner.shadows().tryShaderInputs(missing, glm::dvec3(0.0));
    ASSERT_FALSE(inputsOrError.ok());
    EXPECT_NE(inputsOrError.error().message.find("not a scene light"), std::string::npos);
    EXPECT_TRUE(runner.shadows().tryShaderInputs(two, glm::dvec3(0.0)).ok());
    // A resolution that is no MaskResolution (a game's cast of a stray integer), named.
    const std::array<int, 1> one{0};
    request.resolution = static_cast<MaskResolution>(7);
    const Status badResolution = runner.shadows().tryRenderMask(one, request, stats);
    ASSERT_FALSE(badResolution.ok());
    EXPECT_NE(badResolution.error().message.find("resolution 7"), std::string::npos) << badResolution.error().message;
    gl.DeleteTextures(1, &depth);
}

}  // namespace
}  // namespace shadow::shader_contract_test
