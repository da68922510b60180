// The engine as a guest in a host's GL context (engine/src/gl/gl_state.h): every public call
// that talks to GL leaves the state it changes as it found it, draws the same pixels whatever
// state the host left, never binds back an object it deleted meanwhile, and reports an error the
// host left pending as the host's (a HostGlError warning), never throws it as the engine's.
#include "gl/gl_state.h"

#include <shadow/mesh_cache.h>
#include <shadow/shared_constants.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

/// Texture units checked: the first 32 (every one the engine binds, up to the screen-space
/// visibility stage's SG_UNIT_SCREEN_VISIBILITY; as many as GlState holds). Uniform-buffer
/// binding points: every one the engine binds, and one beyond.
std::vector<GLint> unitsChecked() {
    static_assert(SG_UNIT_SCREEN_VISIBILITY < 32);
    std::vector<GLint> units;
    for (GLint i = 0; i < 32; ++i) units.push_back(i);
    return units;
}
const std::vector<GLint> kBindingsChecked{0, 1, 2, 3};
const std::vector<GLint> kImagesChecked{SG_IMAGE_MINMAX, SG_IMAGE_MINMAX + 1};

gpu::GlState captureChecked() { return gpu::captureGlState(unitsChecked(), kBindingsChecked, kImagesChecked); }

/// A GL entry point the engine's table does not hold (the host's own calls), from the context.
template <typename Proc>
Proc hostProc(const char* name) {
    auto* p = reinterpret_cast<Proc>(test::glContext().loader()(name));
    if (p == nullptr) throw std::runtime_error(std::string("the context lacks ") + name);
    return p;
}

/// Leaves GL_INVALID_ENUM pending, as a host's faulty call would.
void leaveHostError() { gl.Enable(0x7fff); }

/// A host whose GL state is unlike anything the engine sets: its own framebuffer, vertex array
/// and linked program; a texture on every target of unit 0 (a cube map and a 2D array among
/// them), a 3D texture on the first raw-depth unit, a 2D multisample texture on the first
/// filter-chain unit, textures on the mask's units, samplers; polygon mode GL_LINE, clip control
/// GL_UPPER_LEFT / GL_ZERO_TO_ONE, depth range [0.25, 0.75], an odd viewport and scissor, depth
/// test off with GREATER and no writes, front-face culling, clockwise front faces, blending with
/// its own function and a MIN equation, a partial colour mask, every capability of
/// `gpu::kPassOffCapabilities` on (rasterizer discard, depth clamp, logic op INVERT, sRGB, ...),
/// every pack parameter off its default with read clamping on, unpack parameters off theirs with
/// an unpack buffer bound, the first vertex provoking, texture unit 5 active, uniform
/// buffers on bindings 0-3 and an image on the pyramid builder's image unit.
struct HostObjects {
    GLuint framebuffer = 0, colour = 0, vertexArray = 0, program = 0, buffer = 0;
    std::vector<GLuint> textures;  ///< one per target of `gpu::kTextureTargets`
    GLuint cube = 0, volume = 0, multisample = 0, array = 0, flat = 0;
    GLuint samplers[3] = {0, 0, 0};

    HostObjects() {
        gl.CreateTextures(GL_TEXTURE_2D, 1, &colour);
        gl.TextureStorage2D(colour, 1, GL_RGBA8, 32, 32);
        gl.CreateFramebuffers(1, &framebuffer);
        gl.NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);
        gl.CreateVertexArrays(1, &vertexArray);
        gl.CreateBuffers(1, &buffer);
        gl.NamedBufferStorage(buffer, 4096, nullptr, GL_DYNAMIC_STORAGE_BIT);
        program = linkProgram();
        const auto storage1D = hostProc<PFNGLTEXTURESTORAGE1DPROC>("glTextureStorage1D");
        const auto storage2DMs = hostProc<PFNGLTEXTURESTORAGE2DMULTISAMPLEPROC>("glTextureStorage2DMultisample");
        const auto storage3DMs = hostProc<PFNGLTEXTURESTORAGE3DMULTISAMPLEPROC>("glTextureStorage3DMultisample");
        const auto textureBuffer = hostProc<PFNGLTEXTUREBUFFERPROC>("glTextureBuffer");
        for (const GLenum target : gpu::kTextureTargets) {
            GLuint t = 0;
            gl.CreateTextures(target, 1, &t);
            switch (target) {
                case GL_TEXTURE_1D: storage1D(t, 1, GL_R8, 4); break;
                case GL_TEXTURE_1D_ARRAY:
                case GL_TEXTURE_2D:
                case GL_TEXTURE_CUBE_MAP:
                case GL_TEXTURE_RECTANGLE: gl.TextureStorage2D(t, 1, GL_R8, 4, 4); break;
                case GL_TEXTURE_2D_ARRAY:
                case GL_TEXTURE_3D: gl.TextureStorage3D(t, 1, GL_R8, 4, 4, 2); break;
                case GL_TEXTURE_CUBE_MAP_ARRAY: gl.TextureStorage3D(t, 1, GL_R8, 4, 4, 6); break;
                case GL_TEXTURE_BUFFER: textureBuffer(t, GL_R8, buffer); break;
                case GL_TEXTURE_2D_MULTISAMPLE: storage2DMs(t, 4, GL_RGBA8, 4, 4, GL_TRUE); break;
                case GL_TEXTURE_2D_MULTISAMPLE_ARRAY: storage3DMs(t, 4, GL_RGBA8, 4, 4, 2, GL_TRUE); break;
                default: break;
            }
            textures.push_back(t);
        }
        // Textures of their own for the units the shadow lookups and the mask read.
        gl.CreateTextures(GL_TEXTURE_CUBE_MAP, 1, &cube);
        gl.TextureStorage2D(cube, 1, GL_RGBA8, 8, 8);
        gl.CreateTextures(GL_TEXTURE_3D, 1, &volume);
        gl.TextureStorage3D(volume, 1, GL_RGBA8, 4, 4, 4);
        gl.CreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &multisample);
        storage2DMs(multisample, 4, GL_RGBA8, 8, 8, GL_TRUE);
        gl.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &array);
        gl.TextureStorage3D(array, 1, GL_R8, 4, 4, 2);
        gl.CreateTextures(GL_TEXTURE_2D, 1, &flat);
        gl.TextureStorage2D(flat, 1, GL_R8, 4, 4);
        gl.CreateSamplers(3, samplers);
        EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR)) << "making the host's objects";
    }
    ~HostObjects() {
        gl.DeleteFramebuffers(1, &framebuffer);
        gl.DeleteTextures(1, &colour);
        gl.DeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
        for (GLuint* t : {&cube, &volume, &multisample, &array, &flat}) gl.DeleteTextures(1, t);
        gl.DeleteVertexArrays(1, &vertexArray);
        gl.DeleteProgram(program);
        gl.DeleteSamplers(3, samplers);
        gl.DeleteBuffers(1, &buffer);
    }
    HostObjects(const HostObjects&) = delete;
    HostObjects& operator=(const HostObjects&) = delete;

    static GLuint linkProgram() {
        const char* vs = "#version 450 core\nvoid main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n";
        const char* fs = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
        const GLuint program = gl.CreateProgram();
        for (const auto& [stage, text] : {std::pair{GL_VERTEX_SHADER, vs}, std::pair{GL_FRAGMENT_SHADER, fs}}) {
            const GLuint s = gl.CreateShader(stage);
            gl.ShaderSource(s, 1, &text, nullptr);
            gl.CompileShader(s);
            gl.AttachShader(program, s);
            gl.DeleteShader(s);
        }
        gl.LinkProgram(program);
        GLint linked = GL_FALSE;
        gl.GetProgramiv(program, GL_LINK_STATUS, &linked);
        EXPECT_EQ(linked, GL_TRUE);
        return program;
    }

    void bindHostState() const {
        gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        gl.BindVertexArray(vertexArray);
        gl.UseProgram(program);
        gl.Viewport(3, 5, 17, 19);
        gl.Scissor(1, 2, 7, 9);
        gl.Enable(GL_SCISSOR_TEST);
        gl.Disable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_GREATER);
        gl.DepthMask(GL_FALSE);
        gl.DepthRange(0.25, 0.75);
        gl.ClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
        gl.PolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        gl.Enable(GL_CULL_FACE);
        gl.CullFace(GL_FRONT);
        gl.FrontFace(GL_CW);
        gl.Enable(GL_POLYGON_OFFSET_FILL);
        gl.PolygonOffset(4.0f, 64.0f);
        gl.Enablei(GL_BLEND, 0);
        gl.BlendFuncSeparate(GL_ONE, GL_ZERO, GL_SRC_ALPHA, GL_ONE);
        gl.BlendEquationSeparate(GL_MIN, GL_FUNC_REVERSE_SUBTRACT);
        gl.ColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
        for (const GLenum cap : gpu::kPassOffCapabilities) gl.Enable(cap);
        hostProc<PFNGLLOGICOPPROC>("glLogicOp")(GL_INVERT);
        hostProc<PFNGLSAMPLEMASKIPROC>("glSampleMaski")(0, 0u);
        hostProc<PFNGLSTENCILFUNCPROC>("glStencilFunc")(GL_NEVER, 0, 0xff);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 8);
        gl.PixelStorei(GL_PACK_ROW_LENGTH, 7);
        gl.PixelStorei(GL_PACK_IMAGE_HEIGHT, 3);
        gl.PixelStorei(GL_PACK_SKIP_PIXELS, 1);
        gl.PixelStorei(GL_PACK_SKIP_ROWS, 2);
        gl.PixelStorei(GL_PACK_SKIP_IMAGES, 1);
        gl.PixelStorei(GL_PACK_SWAP_BYTES, GL_TRUE);
        gl.PixelStorei(GL_PACK_LSB_FIRST, GL_TRUE);
        gl.ClampColor(GL_CLAMP_READ_COLOR, GL_TRUE);
        gl.BindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
        // Unpack off its defaults with an unpack buffer bound (the engine's texture uploads read
        // client memory), and the first vertex provoking (the moment passes' flat outputs).
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 8);
        gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 7);
        gl.PixelStorei(GL_UNPACK_SKIP_PIXELS, 1);
        gl.PixelStorei(GL_UNPACK_SKIP_ROWS, 2);
        gl.PixelStorei(GL_UNPACK_SWAP_BYTES, GL_TRUE);
        gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer);
        gl.ProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
        // Every target of unit 0, then textures of other targets on the units the lookups use.
        gl.ActiveTexture(GL_TEXTURE0);
        for (std::size_t t = 0; t < textures.size(); ++t) gl.BindTexture(gpu::kTextureTargets[t], textures[t]);
        bindOn(SG_UNIT_SHADOW_COMPARE + 1, GL_TEXTURE_CUBE_MAP, cube);
        bindOn(SG_UNIT_SHADOW_DEPTH, GL_TEXTURE_3D, volume);
        bindOn(SG_UNIT_SHADOW_MINMAX, GL_TEXTURE_2D_MULTISAMPLE, multisample);
        bindOn(SG_UNIT_SHADOW_MINMAX + 1, GL_TEXTURE_2D_ARRAY, array);
        bindOn(SG_UNIT_MASK_DEPTH, GL_TEXTURE_CUBE_MAP, cube);
        bindOn(SG_UNIT_MASK_NORMAL, GL_TEXTURE_2D, flat);
        bindOn(SG_UNIT_SCREEN_DEPTH, GL_TEXTURE_CUBE_MAP, cube);
        bindOn(SG_UNIT_SCREEN_VISIBILITY, GL_TEXTURE_2D_ARRAY, array);
        gl.BindSampler(SG_UNIT_SCREEN_VISIBILITY, samplers[1]);
        gl.BindSampler(0, samplers[0]);
        gl.BindSampler(SG_UNIT_SHADOW_DEPTH, samplers[1]);
        gl.BindSampler(SG_UNIT_MASK_DEPTH, samplers[2]);
        for (GLuint b = 0; b < 4; ++b) gl.BindBufferRange(GL_UNIFORM_BUFFER, b, buffer, 256 * (b + 1), 256);
        gl.BindBuffer(GL_UNIFORM_BUFFER, buffer);
        gl.ActiveTexture(GL_TEXTURE5);
        // The pyramid builder writes through an image unit: the host's image there comes back.
        gl.BindImageTexture(SG_IMAGE_MINMAX, array, 0, GL_FALSE, 1, GL_READ_ONLY, GL_R8);
    }
    static void bindOn(GLint unit, GLenum target, GLuint texture) {
        gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        gl.BindTexture(target, texture);
    }
};

/// GL's state as the test found it, put back at the end (other tests share the context).
class HostStateTest : public ::testing::Test {
protected:
    void SetUp() override {
        test::glContext();
        initial_ = captureChecked();
        stencilFunc_ = hostProc<PFNGLSTENCILFUNCPROC>("glStencilFunc");
    }
    void TearDown() override {
        gpu::restoreGlState(initial_);
        hostProc<PFNGLLOGICOPPROC>("glLogicOp")(GL_COPY);
        hostProc<PFNGLSAMPLEMASKIPROC>("glSampleMaski")(0, ~0u);
        stencilFunc_(GL_ALWAYS, 0, 0xff);
        gl.PolygonOffset(0.0f, 0.0f);
        while (gl.GetError() != GL_NO_ERROR) {}
    }

private:
    gpu::GlState initial_;
    PFNGLSTENCILFUNCPROC stencilFunc_ = nullptr;
};

long hostErrors(const std::vector<Warning>& warnings, const std::string& call = {}) {
    return std::count_if(warnings.begin(), warnings.end(), [&](const Warning& w) {
        return w.code == WarningCode::HostGlError && (call.empty() || w.element == call);
    });
}

void expectSameState(const gpu::GlState& before, const gpu::GlState& after, const std::string& call) {
    EXPECT_EQ(after.drawFramebuffer, before.drawFramebuffer) << call;
    EXPECT_EQ(after.readFramebuffer, before.readFramebuffer) << call;
    EXPECT_EQ(after.program, before.program) << call;
    EXPECT_EQ(after.vertexArray, before.vertexArray) << call;
    EXPECT_EQ(after.viewport, before.viewport) << call;
    EXPECT_EQ(after.scissorBox, before.scissorBox) << call;
    EXPECT_EQ(after.depthFunc, before.depthFunc) << call;
    EXPECT_EQ(after.depthRange, before.depthRange) << call;
    EXPECT_EQ(after.clipOrigin, before.clipOrigin) << call;
    EXPECT_EQ(after.clipDepthMode, before.clipDepthMode) << call;
    EXPECT_EQ(after.polygonMode, before.polygonMode) << call;
    EXPECT_EQ(after.blendFunc, before.blendFunc) << call;
    EXPECT_EQ(after.blendEquation, before.blendEquation) << call;
    EXPECT_EQ(after.offCapabilities, before.offCapabilities) << call;
    for (std::size_t i = 0; i < before.unitCount; ++i) {
        EXPECT_EQ(after.units[i].textures, before.units[i].textures) << call << ": unit " << before.units[i].unit;
        EXPECT_EQ(after.units[i].sampler, before.units[i].sampler) << call << ": unit " << before.units[i].unit;
    }
    EXPECT_EQ(after.uniformBindings, before.uniformBindings) << call;
    EXPECT_EQ(after.images, before.images) << call;
    EXPECT_TRUE(after == before) << call << ": some other piece of state changed";
}

/// Runs `call` under the host's state with an error left pending, and checks that it put every
/// piece of state back, left no error of its own, and reported the host's in `warnings` (the
/// list the call reports into) under its own name `name`.
void checkCall(const HostObjects& host, const std::string& name, const std::function<void()>& call,
               const std::function<const std::vector<Warning>&()>& warnings) {
    host.bindHostState();
    const gpu::GlState before = captureChecked();
    ASSERT_EQ(before.drawFramebuffer, static_cast<GLint>(host.framebuffer));  // the set-up took
    ASSERT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR)) << "the set-up left an error";
    leaveHostError();
    ASSERT_NO_THROW(call()) << name;
    const GLenum left = gl.GetError();
    EXPECT_EQ(left, static_cast<GLenum>(GL_NO_ERROR)) << name << " left " << gpu::glErrorName(left);
    expectSameState(before, captureChecked(), name);
    EXPECT_EQ(hostErrors(warnings(), name), 1) << name << ":\n" << test::describe(warnings());
}

/// A scene with more lights than one pass takes (blending adds the later passes) and a light of
/// every technique: the three of `threeLightScene` and seven local spots; and a textured box, so
/// that the first frame uploads a texture from client memory (a 3x2 image: rows of 12 bytes,
/// which an unpack alignment of 8 or a row length would misread); and a mat that receives but
/// does not cast, which the moment lights draw behind their casters (their backgrounds: a
/// scissored pass and a copy).
Scene hostileScene() {
    Scene scene = test::threeLightScene();
    auto image = std::make_shared<Texture>();
    image->name = "host test 3x2";
    image->width = 3;
    image->height = 2;
    image->rgba = {255, 0,   0, 255, 0, 255, 0,   255, 0,   0, 255, 255,
                   255, 255, 0, 255, 0, 255, 255, 255, 255, 0, 255, 255};
    Material textured;
    textured.baseColorTexture = image;
    addMeshInstance(scene.world, "textured box", makeBoxMesh(glm::vec3(0.2f)), test::placed({1.2, 0.2, 1.0}), textured);
    const Entity mat = addMeshInstance(scene.world, "mat", makePlaneMesh(1.5f, 2), test::placed({0.0, 0.01, 0.5}));
    scene.world.get<Mesh>(mat).castShadows = false;
    const ShadowTechnique techniques[] = {ShadowTechnique::Vsm,     ShadowTechnique::Vssm,         ShadowTechnique::Msm,
                                          ShadowTechnique::MsmSoft, ShadowTechnique::PcssTextbook, ShadowTechnique::Pcf,
                                          ShadowTechnique::Hard};
    for (int i = 0; i < 7; ++i) {
        Light spot = test::pointSizedLight(LightType::Spot, 0.6f);
        spot.radius = 0.05f;
        spot.range = 4.0f;
        Shadow s = test::hardShadow(64);
        s.technique = techniques[i];
        const double x = -1.5 + 0.5 * i;
        addLight(scene, "local" + std::to_string(i), spot, s, {x, 2.5, 0.5}, {0.0, -1.0, 0.0});
    }
    return scene;
}

RenderOptions options64x48() {
    RenderOptions options;
    options.width = 64;
    options.height = 48;
    options.aovs = true;
    return options;
}

TEST_F(HostStateTest, EveryPublicCallLeavesTheHostStateAsItFoundIt) {
    Scene scene = hostileScene();
    FrameRunner runner;
    const test::RenderedFrame first = test::renderFrame(runner, scene, 64, 48);  // programs built, maps allocated
    int backgrounds = 0;
    for (const LightShadowStats& l : first.stats.lights) backgrounds += l.backgroundsDrawn;
    ASSERT_GE(backgrounds, 3) << "the moment lights drew no backgrounds";
    HostObjects host;
    const RenderOptions options = options64x48();
    ShadowSystem& shadows = runner.shadows();
    Renderer& renderer = runner.renderer();
    FrameStats stats;
    auto frameWarnings = [&]() -> const std::vector<Warning>& { return stats.warnings; };
    auto systemWarnings = [&]() -> const std::vector<Warning>& { return shadows.warnings(); };

    checkCall(
        host, "ShadowSystem::render",
        [&] {
            stats = runner.runFrame(scene, 0.5, scene.cameras.at(0), options);  // through FrameRunner
        },
        frameWarnings);
    shadows.planner().setCaching(false);  // every layer and pyramid drawn again
    shadows.prepare(scene.world, runner.lastCamera(), scene.lights);
    checkCall(
        host, "ShadowSystem::render",
        [&] {
            stats.reset();
            shadows.render(scene.world, renderer.meshes(), stats);
        },
        frameWarnings);
    checkCall(
        host, "Renderer::render",
        [&] {
            stats.reset();
            renderer.render(scene.world, runner.lastCamera(), shadows, options, stats);
        },
        frameWarnings);
    // The screen-space visibility stage: its surface, visibility, resolve, refine and deferred
    // lit passes (two groups of lights, contact shadows) put the host's state back too.
    scene.world.view<Shadow>().each([](Entity, Shadow& s) { s.contactShadows = true; });
    shadows.prepare(scene.world, runner.lastCamera(), scene.lights);
    RenderOptions screen = options;
    screen.screenVisibility = ScreenVisibility::Half;
    stats.reset();
    renderer.render(scene.world, runner.lastCamera(), shadows, screen, stats);  // its programs built
    checkCall(
        host, "Renderer::render",
        [&] {
            stats.reset();
            renderer.render(scene.world, runner.lastCamera(), shadows, screen, stats);
        },
        frameWarnings);
    FrameImages images;
    checkCall(
        host, "Renderer::readback",
        [&] {
            stats.reset();
            images = renderer.readback(runner.lastCamera(), stats);
        },
        frameWarnings);
    EXPECT_EQ(images.visibility.size(), scene.lights.size());
    // The present passes (a viewer's): the exposure meter's compute pass and storage binding, the
    // tone map's full-screen pass, the display texture read back.
    checkCall(
        host, "Renderer::meterExposure",
        [&] {
            stats.reset();
            EXPECT_GT(exposureFromHistogram(renderer.meterExposure(stats)), 0.0f);
        },
        frameWarnings);
    checkCall(
        host, "Renderer::presentToTexture",
        [&] {
            stats.reset();
            EXPECT_TRUE(renderer.presentToTexture(1.0f, stats));
        },
        frameWarnings);
    checkCall(
        host, "Renderer::readPresented",
        [&] {
            renderer.clearWarnings();
            EXPECT_FALSE(renderer.readPresented().empty());
        },
        [&]() -> const std::vector<Warning>& { return renderer.warnings(); });

    const std::array<int, 3> lights{0, 1, 2};
    const ShadowShaderInputs* inputs = nullptr;
    checkCall(
        host, "ShadowSystem::shaderInputs",
        [&] {
            shadows.clearWarnings();
            inputs = &shadows.shaderInputs(lights, runner.lastCamera().wsPosition);
        },
        systemWarnings);
    checkCall(
        host, "ShadowMaps::readLayerDepth",
        [&] {
            shadows.maps().clearWarnings();
            EXPECT_FALSE(shadows.maps().readLayerDepth(0, 0).empty());
        },
        [&]() -> const std::vector<Warning>& { return shadows.maps().warnings(); });
    // The shadow map binds change the host's draw state by design; the rest stays.
    host.bindHostState();
    leaveHostError();
    shadows.clearWarnings();
    shadows.bindShaderInputs(*inputs);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    EXPECT_EQ(hostErrors(shadows.warnings(), "ShadowSystem::bindShaderInputs"), 1);
    shadows.clearWarnings();
    leaveHostError();
    shadows.contract().bindResources(shadows.maps(), lights);
    EXPECT_EQ(hostErrors(shadows.contract().warnings(), "ShadowShaderContract::bindResources"), 1);
    // A system's pending warnings go to the next frame's stats.
    leaveHostError();
    (void)shadows.shaderInputs(lights, runner.lastCamera().wsPosition);
    stats.reset();
    shadows.render(scene.world, renderer.meshes(), stats);
    EXPECT_EQ(hostErrors(stats.warnings, "ShadowSystem::shaderInputs"), 1) << test::describe(stats.warnings);
    EXPECT_TRUE(shadows.warnings().empty());

    MeshCache& meshes = renderer.meshes();
    auto meshWarnings = [&]() -> const std::vector<Warning>& { return meshes.warnings(); };
    checkCall(
        host, "MeshCache::collect",
        [&] {
            meshes.clearWarnings();
            meshes.collect();
        },
        meshWarnings);
    std::shared_ptr<const MeshData> box;
    scene.world.view<Mesh>().each([&](Entity, Mesh& m) { box = m.data; });
    ASSERT_NE(box, nullptr);
    host.bindHostState();
    leaveHostError();
    meshes.clearWarnings();
    EXPECT_GT(meshes.bind(box), 0);  // binds the mesh's vertex array by design
    EXPECT_EQ(hostErrors(meshes.warnings(), "MeshCache::bind"), 1);

    // The screen-space mask over a depth texture of the host's.
    GLuint depth = 0, mask = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
    gl.TextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 64, 48);
    gl.CreateTextures(GL_TEXTURE_2D, 1, &mask);
    gl.TextureStorage2D(mask, 1, GL_RGBA8, 64, 48);
    ShadowMaskRequest request;
    request.depthTexture = GlTexture{depth};
    request.target = GlTexture{mask};
    request.width = 64;
    request.height = 48;
    request.camera = runner.lastCamera();
    // At full resolution, then at half: two more passes, targets and units of the mask's own.
    for (const MaskResolution resolution : {MaskResolution::Full, MaskResolution::Half}) {
        request.resolution = resolution;
        checkCall(
            host, "ShadowSystem::renderMask",
            [&] {
                stats.reset();
                shadows.renderMask(lights, request, stats);
            },
            frameWarnings);
    }
    gl.DeleteTextures(1, &depth);
    gl.DeleteTextures(1, &mask);

    // Objects made while the host has an error pending.
    std::unique_ptr<ShadowSystem> made;
    checkCall(
        host, "ShadowSystem", [&] { made = std::make_unique<ShadowSystem>(); },
        [&]() -> const std::vector<Warning>& { return made->warnings(); });
    std::unique_ptr<Renderer> madeRenderer;
    checkCall(
        host, "Renderer", [&] { madeRenderer = std::make_unique<Renderer>(); },
        [&]() -> const std::vector<Warning>& { return madeRenderer->warnings(); });
    std::unique_ptr<MeshCache> madeCache;
    checkCall(
        host, "MeshCache", [&] { madeCache = std::make_unique<MeshCache>(); },
        [&]() -> const std::vector<Warning>& { return madeCache->warnings(); });
}

/// The images of one frame of `scene` from a fresh runner, every layer drawn, with `hostile`
/// bound before every call when given; also the depth of every shadow-map layer and a mask.
struct Pictures {
    FrameImages images;
    std::vector<std::vector<float>> layers;
    std::vector<std::uint8_t> mask;
};

Pictures drawEverything(Scene& scene, const HostObjects* hostile, const std::vector<float>* maskDepth) {
    auto hostState = [&] {
        if (hostile != nullptr) hostile->bindHostState();
    };
    FrameRunner runner;
    const RenderOptions options = options64x48();
    hostState();
    FrameStats stats = runner.runFrame(scene, 0.0, scene.cameras.at(0), options);
    Pictures p;
    hostState();
    p.images = runner.renderer().readback(runner.lastCamera(), stats);
    const ShadowFrame& frame = runner.shadows().frame();
    for (std::size_t i = 0; i < frame.lights.size(); ++i) {
        for (std::size_t k = 0; k < frame.lights[i].layers.size(); ++k) {
            hostState();
            p.layers.push_back(runner.shadows().maps().readLayerDepth(i, static_cast<int>(k)));
        }
    }
    if (maskDepth == nullptr) return p;
    const gpu::GlState saved = captureChecked();
    GLuint depth = 0, target = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
    gl.TextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 64, 48);
    {
        const gpu::UnpackDefaults unpack;  // the test's own upload, past the host's unpack state
        hostProc<PFNGLTEXTURESUBIMAGE2DPROC>("glTextureSubImage2D")(depth, 0, 0, 0, 64, 48, GL_DEPTH_COMPONENT,
                                                                    GL_FLOAT, maskDepth->data());
    }
    gl.CreateTextures(GL_TEXTURE_2D, 1, &target);
    gl.TextureStorage2D(target, 1, GL_RGBA8, 64, 48);
    ShadowMaskRequest request;
    request.depthTexture = GlTexture{depth};
    request.target = GlTexture{target};
    request.width = 64;
    request.height = 48;
    request.camera = runner.lastCamera();
    const std::array<int, 4> lights{0, 1, 2, 3};
    // At full resolution, then at half (its resolve and refine passes): both images kept.
    for (const MaskResolution resolution : {MaskResolution::Full, MaskResolution::Half}) {
        request.resolution = resolution;
        hostState();
        runner.shadows().renderMask(lights, request, stats);
        gpu::restoreGlState(saved);
        std::vector<std::uint8_t> pixels(std::size_t{64} * 48 * 4);
        gpu::setReadbackDefaults();
        gl.GetTextureSubImage(target, 0, 0, 0, 0, 64, 48, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                              static_cast<GLsizei>(pixels.size()), pixels.data());
        gpu::restoreGlState(saved);
        p.mask.insert(p.mask.end(), pixels.begin(), pixels.end());
    }
    gl.DeleteTextures(1, &depth);
    gl.DeleteTextures(1, &target);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    return p;
}

/// Entries of `a` and `b` that differ (all of the longer one's tail).
template <typename T>
long differing(const std::vector<T>& a, const std::vector<T>& b) {
    long n = static_cast<long>(std::max(a.size(), b.size()) - std::min(a.size(), b.size()));
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) n += a[i] != b[i] ? 1 : 0;
    return n;
}

TEST_F(HostStateTest, TheHostsStateDoesNotChangeWhatTheEngineDraws) {
    // Tolerance 0: the engine sets every piece of state its passes rely on, so the pictures,
    // readbacks, shadow maps and masks drawn under the host's state are those drawn under GL's
    // defaults, bit for bit.
    Scene scene = hostileScene();
    const Pictures first = drawEverything(scene, nullptr, nullptr);
    FrameRunner view;
    (void)test::renderFrame(view, scene, 64, 48);
    const std::vector<float> maskDepth = test::windowDepth(first.images.position, view.lastCamera());
    const Pictures clean = drawEverything(scene, nullptr, &maskDepth);
    HostObjects host;
    const Pictures hosted = drawEverything(scene, &host, &maskDepth);
    const long colour = differing(hosted.images.color.pixels, clean.images.color.pixels);
    const long position = differing(hosted.images.position.pixels, clean.images.position.pixels);
    const long depth = differing(hosted.images.depth.pixels, clean.images.depth.pixels);
    long visibility = 0;
    ASSERT_EQ(hosted.images.visibility.size(), clean.images.visibility.size());
    for (std::size_t i = 0; i < hosted.images.visibility.size(); ++i) {
        visibility += differing(hosted.images.visibility[i].pixels, clean.images.visibility[i].pixels);
    }
    long layers = 0;
    ASSERT_EQ(hosted.layers.size(), clean.layers.size());
    for (std::size_t k = 0; k < hosted.layers.size(); ++k) layers += differing(hosted.layers[k], clean.layers[k]);
    const long mask = differing(hosted.mask, clean.mask);
    std::printf(
        "under the host's state: %ld colour, %ld position, %ld depth, %ld visibility values, %ld shadow-map "
        "texels and %ld mask values differ (of %zu, %zu, %zu, %zu x %zu, %zu layers, %zu)\n",
        colour, position, depth, visibility, layers, mask, clean.images.color.pixels.size(),
        clean.images.position.pixels.size(), clean.images.depth.pixels.size(), clean.images.visibility.size(),
        clean.images.visibility.at(0).pixels.size(), clean.layers.size(), clean.mask.size());
    EXPECT_EQ(colour, 0);
    EXPECT_EQ(position, 0);
    EXPECT_EQ(depth, 0);
    EXPECT_EQ(visibility, 0);
    EXPECT_EQ(layers, 0);
    EXPECT_EQ(mask, 0);
    // The pictures are worth comparing: the scene has light and shadow.
    const auto [lo, hi] =
        std::minmax_element(clean.images.visibility[0].pixels.begin(), clean.images.visibility[0].pixels.end());
    EXPECT_LT(*lo, 0.1f);
    EXPECT_GT(*hi, 0.9f);
}

TEST_F(HostStateTest, MapsTheEngineFreesAreNeverBoundBack) {
    // The host samples the shadow maps (bound as bindShaderInputs binds them); then a light is
    // removed, a map resized, a map halved by the memory budget: each frees a texture the host
    // had bound. GL unbinds a deleted texture; binding its name back would leave
    // GL_INVALID_OPERATION pending and fail the host's next call (and the next shaderInputs).
    Scene scene = test::threeLightScene();
    FrameRunner runner;
    test::renderFrame(runner, scene, 64, 48);
    HostObjects host;
    ShadowSystem& shadows = runner.shadows();
    const std::array<int, 3> lights{0, 1, 2};

    auto frameUnder = [&](const std::string& what, const std::function<void()>& change) {
        SCOPED_TRACE(what);
        host.bindHostState();
        shadows.bindShaderInputs(shadows.shaderInputs(lights, runner.lastCamera().wsPosition));
        const gpu::GlState before = captureChecked();
        change();
        // As a game runs the shadow half of its frame.
        updateTransforms(scene.world);
        shadows.prepare(scene.world, runner.lastCamera(), scene.lights);
        FrameStats stats;
        ASSERT_NO_THROW(shadows.render(scene.world, runner.renderer().meshes(), stats));
        EXPECT_EQ(hostErrors(stats.warnings), 0) << test::describe(stats.warnings);
        const GLenum left = gl.GetError();
        EXPECT_EQ(left, static_cast<GLenum>(GL_NO_ERROR)) << gpu::glErrorName(left);
        // What the host holds now: its own state, with every map that was freed unbound.
        gpu::GlState expected = before;
        int freed = 0;
        for (std::size_t u = 0; u < expected.unitCount; ++u) {
            for (GLint& t : expected.units[u].textures) {
                if (t != 0 && !gl.IsTexture(static_cast<GLuint>(t))) {
                    t = 0;
                    ++freed;
                }
            }
        }
        EXPECT_GT(freed, 0) << "the change freed no map the host held";
        if (what == "a map halved by the budget") {
            EXPECT_EQ(shadows.frame().lights[0].mapSize, 256);
            EXPECT_TRUE(test::hasWarning(stats.warnings, WarningCode::MapSizeReduced, "spot"))
                << test::describe(stats.warnings);
        }
        expectSameState(expected, captureChecked(), what);
        ASSERT_NO_THROW((void)shadows.shaderInputs(std::span<const int>(lights).first(scene.lights.size()),
                                                   runner.lastCamera().wsPosition));
        EXPECT_TRUE(shadows.warnings().empty()) << test::describe(shadows.warnings());
    };
    frameUnder("a map resized", [&] { scene.world.get<Shadow>(scene.lights[0]).mapSize = 512; });
    frameUnder("a map halved by the budget", [&] {
        // Room for every map as it is, but the spot's at 256^2 (the budget's floor): it is halved.
        ShadowLimits limits = shadows.planner().limits();
        limits.maxShadowBytes = 0;
        for (const ShadowLightPlan& p : shadows.frame().lights) {
            limits.maxShadowBytes += shadowMapBytes(p.technique(), p.sceneIndex == 0 ? 256 : p.mapSize,
                                                    static_cast<int>(p.layers.size()), p.settings.maxFilterTexels);
        }
        shadows.planner().setLimits(limits);
    });
    frameUnder("a light removed", [&] {
        scene.world.destroy(scene.lights[2]);
        scene.lights.pop_back();
    });
}

// Binding the inputs binds their blocks, units and samplers and nothing else: the host's generic
// GL_UNIFORM_BUFFER binding stays, and without an sdf light so do the distance-field units.
TEST_F(HostStateTest, BindingTheInputsChangesOnlyWhatTheyBind) {
    Scene scene = test::threeLightScene();  // no sdf light
    FrameRunner runner;
    test::renderFrame(runner, scene, 64, 48);
    ShadowSystem& shadows = runner.shadows();
    const std::array<int, 3> lights{0, 1, 2};
    const ShadowShaderInputs& inputs = shadows.shaderInputs(lights, runner.lastCamera().wsPosition);
    ASSERT_EQ(inputs.techniques & techniqueBit(ShadowTechnique::Sdf), 0u);
    GLuint buffer = 0;
    GLuint textures[2] = {0, 0};
    gl.CreateBuffers(1, &buffer);
    gl.NamedBufferStorage(buffer, 256, nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl.CreateTextures(GL_TEXTURE_3D, 1, &textures[0]);
    gl.CreateTextures(GL_TEXTURE_BUFFER, 1, &textures[1]);
    gl.BindBuffer(GL_UNIFORM_BUFFER, buffer);
    const ShadowBindingPoints points;
    gl.BindTextureUnit(static_cast<GLuint>(points.sdfAtlasUnit), textures[0]);
    gl.BindTextureUnit(static_cast<GLuint>(points.sdfInstanceUnit), textures[1]);
    shadows.bindShaderInputs(inputs, points);
    GLint generic = 0;
    gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &generic);
    EXPECT_EQ(static_cast<GLuint>(generic), buffer) << "the host's generic uniform-buffer binding changed";
    GLint atlas = 0, instances = 0;
    gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(points.sdfAtlasUnit));
    gl.GetIntegerv(GL_TEXTURE_BINDING_3D, &atlas);
    gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(points.sdfInstanceUnit));
    gl.GetIntegerv(GL_TEXTURE_BINDING_BUFFER, &instances);
    gl.ActiveTexture(GL_TEXTURE0);
    EXPECT_EQ(static_cast<GLuint>(atlas), textures[0]) << "a distance-field unit bound without an sdf light";
    EXPECT_EQ(static_cast<GLuint>(instances), textures[1]) << "a distance-field unit bound without an sdf light";
    gl.BindBuffer(GL_UNIFORM_BUFFER, 0);
    gl.DeleteTextures(2, textures);
    gl.DeleteBuffers(1, &buffer);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// The distance-field instances, uploaded for a new camera, report an error the host left
// pending as the host's, as every other call does, instead of throwing it as their own.
TEST_F(HostStateTest, FieldInstancesReportTheHostsPendingError) {
    Scene scene = test::threeLightScene();
    scene.world.get<Shadow>(scene.lights.at(0)).technique = ShadowTechnique::Sdf;
    FrameRunner runner;
    test::renderFrame(runner, scene, 64, 48);
    ShadowMaps& maps = runner.shadows().maps();
    maps.clearWarnings();
    leaveHostError();
    GlTexture instances{};
    EXPECT_NO_THROW(instances = maps.fieldInstances(runner.lastCamera().wsPosition + glm::dvec3(0.5, 0.0, 0.0)));
    EXPECT_NE(instances.name, 0u);
    EXPECT_EQ(hostErrors(maps.warnings(), "ShadowMaps::fieldInstances"), 1);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(HostStateTest, TheMaskLeavesTheHostsShaderInputsAlone) {
    // The host binds the inputs of its forward pass (lights 0-2), then asks for a mask of other
    // lights in another order: its buffers, bindings, units and samplers hold what it bound.
    Scene scene = test::threeLightScene();
    FrameRunner runner;
    test::renderFrame(runner, scene, 64, 48);
    ShadowSystem& shadows = runner.shadows();
    const std::array<int, 3> forward{0, 1, 2};
    const ShadowShaderInputs& inputs = shadows.shaderInputs(forward, runner.lastCamera().wsPosition);
    const ShadowShaderInputs copy = inputs;
    shadows.bindShaderInputs(inputs);
    auto contents = [](GlBuffer buffer) {
        GLint64 size = 0;
        hostProc<PFNGLGETNAMEDBUFFERPARAMETERI64VPROC>("glGetNamedBufferParameteri64v")(buffer.name, GL_BUFFER_SIZE,
                                                                                        &size);
        std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
        hostProc<PFNGLGETNAMEDBUFFERSUBDATAPROC>("glGetNamedBufferSubData")(buffer.name, 0, size, bytes.data());
        return bytes;
    };
    const std::vector<std::uint8_t> lightBlock = contents(inputs.lightBuffer);
    const std::vector<std::uint8_t> layerBlock = contents(inputs.layerBuffer);
    const gpu::GlState before = captureChecked();

    GLuint depth = 0, target = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
    gl.TextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 64, 48);
    gl.CreateTextures(GL_TEXTURE_2D, 1, &target);
    gl.TextureStorage2D(target, 1, GL_RGBA8, 64, 48);
    ShadowMaskRequest request;
    request.depthTexture = GlTexture{depth};
    request.target = GlTexture{target};
    request.width = 64;
    request.height = 48;
    request.camera = runner.lastCamera();
    request.camera.wsPosition += glm::dvec3(1.0, 0.0, 0.0);  // records relative to another point
    const std::array<int, 2> maskLights{2, 1};
    FrameStats stats;
    shadows.renderMask(maskLights, request, stats);
    gl.DeleteTextures(1, &depth);
    gl.DeleteTextures(1, &target);

    const long lightBytes = differing(contents(inputs.lightBuffer), lightBlock);
    const long layerBytes = differing(contents(inputs.layerBuffer), layerBlock);
    std::printf("after renderMask: %ld of %zu light-block bytes and %ld of %zu layer-block bytes changed\n", lightBytes,
                lightBlock.size(), layerBytes, layerBlock.size());
    EXPECT_EQ(lightBytes, 0);
    EXPECT_EQ(layerBytes, 0);
    expectSameState(before, captureChecked(), "ShadowSystem::renderMask");
    EXPECT_EQ(inputs.sceneLight, copy.sceneLight) << "the inputs the host holds were rewritten";
    EXPECT_EQ(inputs.depthArray, copy.depthArray);
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
