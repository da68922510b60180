// The screen-space shadow mask (shadow_mask.h): a full-screen pass over a game's depth buffer
// that writes each light's visibility into one channel of the game's texture.
#include <shadow/shadow_mask.h>

#include "core/camera.h"
#include "core/light_records.h"
#include "core/screen_bounds.h"
#include "core/shader_resources.h"
#include "core/stage_resolution.h"
#include "gl/gl_state.h"
#include "gl/no_throw.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "gl/technique_glsl.h"
#include "shadow/shader_records.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadow {

namespace {

/// What a mask program is specialised for: the lights in use, the normal texture (for the
/// resolve: whether it writes the refine's prior, `refinesPerLight`), the resolve's
/// divisor (0x80 | divisor; 0 for the program of the lights' techniques, which serves every
/// resolution), and per slot the light's type, technique and kernel.
using MaskKey = std::array<std::uint8_t, 3 + 3 * SG_MAX_MASK_LIGHTS>;

/// Key bit of the resolve program.
constexpr std::uint8_t kResolveKey = 0x80;

/// One specialisation of the mask pass and its uniform locations.
struct MaskProgram {
    gpu::Program program;
    GLint csFromClip = -1;
    GLint cameraForward = -1;
    GLint zeroToOne = -1;
    GLint backgroundDepth = -1;
    GLint divisor = -1;  ///< the techniques' program: the blocks a sample stands for
    GLint refine = -1;   ///< the techniques' program: 1 in the refine after a resolve
};

MaskKey maskKey(const ShadowShaderInputs& in, bool normals) {
    MaskKey key{};
    key[0] = static_cast<std::uint8_t>(in.lights);
    key[1] = normals ? 1 : 0;
    for (std::size_t i = 0; i < SG_MAX_MASK_LIGHTS; ++i) {
        key[3 + 3 * i] = static_cast<std::uint8_t>(in.type[i]);
        key[4 + 3 * i] = static_cast<std::uint8_t>(in.technique[i]);
        key[5 + 3 * i] = static_cast<std::uint8_t>(in.kernel[i]);
    }
    return key;
}

/// The uniform locations every mask program has.
void findMaskUniforms(MaskProgram& p) {
    const GLuint id = p.program.get();
    p.csFromClip = gl.GetUniformLocation(id, "uCsFromClip");
    p.cameraForward = gl.GetUniformLocation(id, "uCameraForward");
    p.zeroToOne = gl.GetUniformLocation(id, "uZeroToOne");
    p.backgroundDepth = gl.GetUniformLocation(id, "uBackgroundDepth");
    p.divisor = gl.GetUniformLocation(id, "uDivisor");
    p.refine = gl.GetUniformLocation(id, "uRefine");
}

/// `refinesPerLight` of the mask's lights.
bool refinesPerLight(const ShadowShaderInputs& in) {
    return shadow::refinesPerLight(std::span(in.technique).first(static_cast<std::size_t>(in.lights)));
}

/// The resolve of a mask of `lights` lights computed at 1 / `divisor` resolution: no technique;
/// with `perLight` it writes the refine's prior.
MaskProgram buildResolve(int lights, int divisor, bool perLight) {
    std::vector<std::string> defines{"SG_MASK_LIGHTS " + std::to_string(lights), "SG_MASK_RESOLVE",
                                     "SG_MASK_DIVISOR " + std::to_string(divisor)};
    if (perLight) defines.emplace_back("SG_MASK_REFINE_PER_LIGHT");
    MaskProgram p;
    p.program = gpu::buildProgram(
        {"Shadow/Mask/resolve" + std::to_string(divisor), "fullscreen.vert.glsl", "shadow_mask.frag.glsl", defines, 0});
    findMaskUniforms(p);
    return p;
}

/// The mask's program of `in`'s lights: at full resolution, the samples and the refine.
MaskProgram buildMask(const ShadowShaderInputs& in, bool normals) {
    // The samples' program serves every resolution: it reports each sample's narrowest feature.
    std::vector<std::string> defines{"SG_MASK_LIGHTS " + std::to_string(in.lights), "SG_STAGE_FEATURES"};
    std::string label;
    std::array<gpu::SlotConfig, SG_MAX_MASK_LIGHTS> slots{};
    for (int i = 0; i < in.lights; ++i) {
        const auto s = static_cast<std::size_t>(i);
        slots[s] = {in.type[s], in.technique[s], in.kernel[s]};
        if (!label.empty()) label += ',';
        label += techniqueName(static_cast<ShadowTechnique>(in.technique[s]));
    }
    gpu::appendSlotGroupDefines(std::span(slots).first(static_cast<std::size_t>(in.lights)), SG_MAX_MASK_LIGHTS,
                                defines);
    gpu::appendTechniqueDefines(in.techniques, defines);
    if (normals) defines.emplace_back("SG_MASK_NORMALS");
    if (refinesPerLight(in)) defines.emplace_back("SG_MASK_REFINE_PER_LIGHT");
    MaskProgram p;
    p.program = gpu::buildProgram({"Shadow/Mask[" + label + (normals ? ",normals]" : "]"), "fullscreen.vert.glsl",
                                   "shadow_mask.frag.glsl", defines, in.techniques});
    findMaskUniforms(p);
    return p;
}

/// Texture units the mask pass binds (the three shadow arrays, depth, normals) and the uniform
/// binding points: what its guard puts back.
/// Units 0 to SG_UNIT_MASK_NORMAL, the distance-field technique's two and the reduced
/// resolution's two.
constexpr std::array<GLint, SG_UNIT_MASK_NORMAL + 5> maskUnits() {
    std::array<GLint, SG_UNIT_MASK_NORMAL + 5> units{};
    std::iota(units.begin(), units.end() - 4, 0);
    units[units.size() - 4] = SG_UNIT_SDF_ATLAS;
    units[units.size() - 3] = SG_UNIT_SDF_INSTANCES;
    units[units.size() - 2] = SG_UNIT_MASK_STAGE;
    units[units.size() - 1] = SG_UNIT_MASK_STAGE_POSITION;
    return units;
}
constexpr std::array<GLint, SG_UNIT_MASK_NORMAL + 5> kMaskUnits = maskUnits();
constexpr std::array<GLint, 3> kMaskBindings{SG_BINDING_LIGHTS, SG_BINDING_LAYERS, SG_BINDING_KERNELS};
static_assert(SG_UNIT_MASK_DEPTH >= SG_UNIT_SHADOW_MINMAX + SG_MAX_LIGHTS_PER_PASS);

void validateMask(std::span<const int> sceneLights, const ShadowMaskRequest& r) {
    if (sceneLights.size() > SG_MAX_MASK_LIGHTS) {
        throw std::invalid_argument("renderMask: " + std::to_string(sceneLights.size()) + " lights, a mask holds " +
                                    std::to_string(SG_MAX_MASK_LIGHTS));
    }
    if (!r.depthTexture) throw std::invalid_argument("renderMask: no depth texture");
    if (!r.target) throw std::invalid_argument("renderMask: no target texture");
    if (r.width < 1 || r.height < 1) {
        throw std::invalid_argument("renderMask: size " + std::to_string(r.width) + " x " + std::to_string(r.height));
    }
    const auto resolution = static_cast<int>(r.resolution);
    if (resolution < static_cast<int>(MaskResolution::Full) || resolution > static_cast<int>(MaskResolution::Auto)) {
        throw std::invalid_argument("renderMask: resolution " + std::to_string(resolution) +
                                    " is not a MaskResolution (Full, Half, Quarter, Auto)");
    }
}

/// The divisor of the request's resolution for lights `in`.
int maskDivisor(const ShadowMaskRequest& r, const ShadowShaderInputs& in) {
    switch (r.resolution) {
        case MaskResolution::Full: return 1;
        case MaskResolution::Half: return 2;
        case MaskResolution::Quarter: return 4;
        case MaskResolution::Auto: break;
    }
    return stageDivisor(std::span(in.technique).first(static_cast<std::size_t>(in.lights)), r.height);
}

/// The projection the request's depth was drawn with.
glm::dmat4 clipFromView(const ShadowMaskRequest& r) {
    return r.clipFromView != glm::dmat4(0.0) ? r.clipFromView : cameraClipFromView(r.camera);
}

/// The pixels the mask's lights can reach (the union of their screen bounds), or the whole
/// target when the request does not scissor.
PixelRect maskBounds(const ShadowFrame& frame, std::span<const int> sceneLights, const ShadowMaskRequest& r,
                     const glm::dmat4& projection) {
    if (!r.scissorToLights) return PixelRect{0, 0, r.width, r.height};
    const ScreenView view{projection * r.camera.viewFromWorld, r.width, r.height, frame.wsGeometry};
    PixelRect bounds;
    for (const int light : sceneLights) {
        bounds = unite(bounds, screenBounds(frame.lights[static_cast<std::size_t>(light)], view));
    }
    return bounds;
}

/// `refine`: the techniques' program runs as the refine after a resolve (at `divisor` 1).
void setMaskUniforms(const MaskProgram& p, const ShadowMaskRequest& r, const glm::dmat4& projection, int divisor = 1,
                     bool refine = false) {
    const GLuint id = p.program.get();
    gl.ProgramUniform1i(id, p.divisor, divisor);
    gl.ProgramUniform1i(id, p.refine, refine ? 1 : 0);
    const glm::dmat4 clipFromCs = cameraClipFromCs(r.camera, projection);
    const glm::vec3 forward = cameraForward(r.camera);
    gl.ProgramUniformMatrix4fv(id, p.csFromClip, 1, GL_FALSE, glm::value_ptr(glm::mat4(glm::inverse(clipFromCs))));
    gl.ProgramUniform3fv(id, p.cameraForward, 1, glm::value_ptr(forward));
    gl.ProgramUniform1i(id, p.zeroToOne, r.zeroToOneDepth ? 1 : 0);
    gl.ProgramUniform1f(id, p.backgroundDepth, r.backgroundDepth);
}

}  // namespace

struct ShadowMask::Impl {
    gpu::ShaderResources resources;
    /// The mask's own records and buffers: the game's shader inputs (`ShadowShaderContract`),
    /// bound for its own passes, stay as they were.
    gpu::ShaderRecords records{resources, "Shadow/Mask"};
    std::map<MaskKey, MaskProgram> programs;
    gpu::VertexArray empty;
    gpu::Framebuffer framebuffer;
    gpu::Sampler point;            ///< nearest, no comparison: the game's textures read as values
    std::vector<Warning> pending;  ///< host errors the constructor found, for the next render
    /// Reduced resolution: the samples' visibility and positions and their framebuffer, and the
    /// refine's marks and prior (sg_refinePrior) at full resolution; made on first use, again
    /// when the sizes change.
    gpu::Texture stageMask, stagePosition, marks, prior;
    gpu::Framebuffer stageFramebuffer;
    int stageWidth = 0, stageHeight = 0, marksWidth = 0, marksHeight = 0;

    Impl();
    /// The program of `key`, built by `build` on first use.
    template <class Build>
    const MaskProgram& program(const MaskKey& key, Build&& build);
    /// Makes the reduced resolution's targets fit a `width` x `height` mask at 1 / `divisor`.
    void ensureStage(int width, int height, int divisor);
    /// The samples of `in`'s lights at 1 / `divisor` resolution over `bounds`, then their resolve
    /// into the target, which leaves the framebuffer's depth test passing only the pixels the
    /// refine (the full-resolution program, drawn next) must recompute.
    void drawReduced(const ShadowShaderInputs& in, bool normals, int divisor, const ShadowMaskRequest& r,
                     const glm::dmat4& projection, const PixelRect& bounds);
};

ShadowMask::Impl::Impl() {
    empty = gpu::makeVertexArray("Shadow/Mask/empty vertex array");
    framebuffer = gpu::makeFramebuffer("Shadow/Mask/framebuffer");
    GLuint s = 0;
    gl.CreateSamplers(1, &s);
    point = gpu::Sampler(s);
    gl.SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.SamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    point.label("Shadow/Mask/pointSampler");
    gpu::checkGlError("creating the shadow mask");
}

template <class Build>
const MaskProgram& ShadowMask::Impl::program(const MaskKey& key, Build&& build) {
    auto it = programs.find(key);
    if (it == programs.end()) it = programs.emplace(key, build()).first;
    return it->second;
}

void ShadowMask::Impl::ensureStage(int width, int height, int divisor) {
    const int w = (width + divisor - 1) / divisor, h = (height + divisor - 1) / divisor;
    if (!stageFramebuffer) {
        stageFramebuffer = gpu::makeFramebuffer("Shadow/Mask/stage framebuffer");
        const std::array<GLenum, 2> buffers{GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        gl.NamedFramebufferDrawBuffers(stageFramebuffer.get(), 2, buffers.data());
    }
    if (w != stageWidth || h != stageHeight) {
        // Float visibility: a game's float target gets what full resolution would write.
        stageMask = gpu::makeScreenTarget("Shadow/Mask/stage", GL_RGBA16F, w, h);
        stagePosition = gpu::makeScreenTarget("Shadow/Mask/stage positions", GL_RGBA32F, w, h);
        gl.NamedFramebufferTexture(stageFramebuffer.get(), GL_COLOR_ATTACHMENT0, stageMask.get(), 0);
        gl.NamedFramebufferTexture(stageFramebuffer.get(), GL_COLOR_ATTACHMENT1, stagePosition.get(), 0);
        stageWidth = w;
        stageHeight = h;
    }
    if (width != marksWidth || height != marksHeight) {
        marks = gpu::makeScreenTarget("Shadow/Mask/refine marks", GL_DEPTH_COMPONENT32F, width, height);
        prior = gpu::makeScreenTarget("Shadow/Mask/refine prior", GL_RGBA16F, width, height);
        marksWidth = width;
        marksHeight = height;
    }
}

void ShadowMask::Impl::drawReduced(const ShadowShaderInputs& in, bool normals, int divisor, const ShadowMaskRequest& r,
                                   const glm::dmat4& projection, const PixelRect& bounds) {
    ensureStage(r.width, r.height, divisor);
    // The samples: the blocks of the lights' bounds and one ring more, the resolve's neighbours.
    const MaskProgram& samples = program(maskKey(in, normals), [&] { return buildMask(in, normals); });
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, stageFramebuffer.get());
    gl.Viewport(0, 0, stageWidth, stageHeight);
    gl.Disable(GL_SCISSOR_TEST);
    const std::array<float, 4> lit{1.0f, 1.0f, 1.0f, 1.0f}, nothing{0.0f, 0.0f, 0.0f, 0.0f};
    gl.ClearNamedFramebufferfv(stageFramebuffer.get(), GL_COLOR, 0, lit.data());
    gl.ClearNamedFramebufferfv(stageFramebuffer.get(), GL_COLOR, 1, nothing.data());
    const PixelRect blocks =
        grownWithin(PixelRect{bounds.x0 / divisor, bounds.y0 / divisor, (bounds.x1 + divisor - 1) / divisor,
                              (bounds.y1 + divisor - 1) / divisor},
                    1, stageWidth, stageHeight);
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(blocks.x0, blocks.y0, blocks.x1 - blocks.x0, blocks.y1 - blocks.y0);
    setMaskUniforms(samples, r, projection, divisor);
    gl.UseProgram(samples.program.get());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);

    // The resolve into the target; depth 0 marks a pixel for the refine.
    MaskKey resolveKey{};
    resolveKey[0] = static_cast<std::uint8_t>(in.lights);
    const bool perLight = refinesPerLight(in);
    resolveKey[1] = perLight ? 1 : 0;
    resolveKey[2] = static_cast<std::uint8_t>(kResolveKey | divisor);
    const MaskProgram& resolve = program(resolveKey, [&] { return buildResolve(in.lights, divisor, perLight); });
    gl.NamedFramebufferTexture(framebuffer.get(), GL_DEPTH_ATTACHMENT, marks.get(), 0);
    if (perLight) {
        gl.NamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT1, prior.get(), 0);
        const std::array<GLenum, 2> both{GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        gl.NamedFramebufferDrawBuffers(framebuffer.get(), 2, both.data());
    }
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer.get());
    gl.Viewport(0, 0, r.width, r.height);
    gl.Scissor(bounds.x0, bounds.y0, bounds.x1 - bounds.x0, bounds.y1 - bounds.y0);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_ALWAYS);
    gl.DepthMask(GL_TRUE);
    const float unmarked = 1.0f;
    gl.ClearNamedFramebufferfv(framebuffer.get(), GL_DEPTH, 0, &unmarked);
    gl.BindTextureUnit(SG_UNIT_MASK_STAGE, stageMask.get());
    gl.BindSampler(SG_UNIT_MASK_STAGE, point.get());
    gl.BindTextureUnit(SG_UNIT_MASK_STAGE_POSITION, stagePosition.get());
    gl.BindSampler(SG_UNIT_MASK_STAGE_POSITION, point.get());
    setMaskUniforms(resolve, r, projection);
    gl.UseProgram(resolve.program.get());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    if (perLight) {
        // The refine reads the prior and writes the target alone.
        const GLenum one = GL_COLOR_ATTACHMENT0;
        gl.NamedFramebufferDrawBuffers(framebuffer.get(), 1, &one);
        gl.NamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT1, 0, 0);
        gl.BindTextureUnit(SG_UNIT_MASK_STAGE, prior.get());
    }
    // The refine's triangle lies at window depth 0.5: over the marks (0) only.
    gl.DepthFunc(GL_GREATER);
    gl.DepthMask(GL_FALSE);
}

ShadowMask::ShadowMask() {
    gpu::requireLoaded("ShadowMask");
    std::vector<Warning> pending;
    gpu::reportHostGlErrors("ShadowMask", pending, gpu::kMaxPendingWarnings);
    impl_ = std::make_unique<Impl>();
    impl_->pending = std::move(pending);
}

ShadowMask::~ShadowMask() = default;

Result<std::unique_ptr<ShadowMask>> ShadowMask::create() noexcept {
    return gpu::noThrow<std::unique_ptr<ShadowMask>>("ShadowMask", [] { return std::make_unique<ShadowMask>(); });
}

void ShadowMask::render(const ShadowFrame& frame, const ShadowMaps& maps, std::span<const int> sceneLights,
                        const ShadowMaskRequest& r, FrameStats& stats) {
    validateMask(sceneLights, r);
    gpu::reportHostGlErrors("ShadowMask::render", stats);
    gpu::movePendingWarnings(impl_->pending, stats.warnings);
    const gpu::GlStateGuard hostState(kMaskUnits, kMaskBindings);
    Impl& m = *impl_;
    const ShadowShaderInputs& in =
        gpu::uploadShaderInputs(m.records, frame, maps, sceneLights, r.camera.wsPosition, "renderMask");
    gpu::bindShaderInputs(m.resources, maps, in, ShadowBindingPoints{});

    gl.NamedFramebufferTexture(m.framebuffer.get(), GL_COLOR_ATTACHMENT0, r.target.name, 0);
    if (gl.CheckNamedFramebufferStatus(m.framebuffer.get(), GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        const std::string pending = gpu::takePendingErrors();
        gl.NamedFramebufferTexture(m.framebuffer.get(), GL_COLOR_ATTACHMENT0, 0, 0);
        throw GlError("renderMask: the target texture cannot be drawn to (not a colour-renderable 2D texture?)" +
                      (pending.empty() ? std::string() : " (" + pending + ")"));
    }
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, m.framebuffer.get());
    gl.Viewport(0, 0, r.width, r.height);
    gpu::setPassDefaults();
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    const std::array<float, 4> lit{1.0f, 1.0f, 1.0f, 1.0f};
    gl.ClearNamedFramebufferfv(m.framebuffer.get(), GL_COLOR, 0, lit.data());

    // Only the lights' screen bounds run the lights; the clear wrote 1 everywhere else.
    const glm::dmat4 projection = clipFromView(r);
    const PixelRect bounds = maskBounds(frame, sceneLights, r, projection);
    if (!bounds.empty() && in.techniques != 0) {
        const bool normals = static_cast<bool>(r.normalTexture);
        gl.BindTextureUnit(SG_UNIT_MASK_DEPTH, r.depthTexture.name);
        gl.BindSampler(SG_UNIT_MASK_DEPTH, m.point.get());
        gl.BindTextureUnit(SG_UNIT_MASK_NORMAL, r.normalTexture.name);
        gl.BindSampler(SG_UNIT_MASK_NORMAL, m.point.get());
        gl.BindVertexArray(m.empty.get());
        // At reduced resolution the samples and the resolve come first; the full-resolution
        // program then runs only where the resolve marked a pixel (the refine).
        const int divisor = maskDivisor(r, in);
        if (divisor > 1) m.drawReduced(in, normals, divisor, r, projection, bounds);
        const MaskProgram& p = m.program(maskKey(in, normals), [&] { return buildMask(in, normals); });
        setMaskUniforms(p, r, projection, 1, divisor > 1);
        gl.Enable(GL_SCISSOR_TEST);
        gl.Scissor(bounds.x0, bounds.y0, bounds.x1 - bounds.x0, bounds.y1 - bounds.y0);
        gl.UseProgram(p.program.get());
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl.NamedFramebufferTexture(m.framebuffer.get(), GL_COLOR_ATTACHMENT0, 0, 0);
    gl.NamedFramebufferTexture(m.framebuffer.get(), GL_DEPTH_ATTACHMENT, 0, 0);
    gpu::checkGlError("renderMask");
}

Status ShadowMask::tryRender(const ShadowFrame& frame, const ShadowMaps& maps, std::span<const int> sceneLights,
                             const ShadowMaskRequest& request, FrameStats& stats) noexcept {
    return gpu::noThrowStatus("renderMask", [&] { render(frame, maps, sceneLights, request, stats); });
}

}  // namespace shadow
