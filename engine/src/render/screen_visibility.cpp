#include "render/screen_visibility.h"

#include <shadow/context.h>
#include <shadow/shared_constants.h>

#include "gl/program.h"
#include "gl/technique_glsl.h"
#include "render/lit_programs.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <span>
#include <string>
#include <vector>

namespace shadow::render {
namespace {

/// Points the contact march projects onto the screen.
constexpr int kContactSteps = 12;

int divisorIndex(int divisor) { return divisor == 4 ? 2 : divisor == 2 ? 1 : 0; }

/// Pixels of a target of 1/`divisor` the screen's size.
int reduced(int size, int divisor) { return (size + divisor - 1) / divisor; }

/// Runs `body`, timed as Main/ScreenVisibility/`what` when `timer` is given (a fence around
/// each draw on a CPU rasteriser).
template <typename Body>
void timed(gpu::PassTimer* timer, const char* what, Body&& body) {
    if (timer == nullptr) return body();
    gpu::ScopedPass scope(*timer, std::string("Main/ScreenVisibility/") + what);
    body();
}

}  // namespace

int visibilityDivisor(ScreenVisibility setting, const LitVariant& variant, int firstSlot, int slots, int height) {
    switch (setting) {
        case ScreenVisibility::Full: return 1;
        case ScreenVisibility::Half: return 2;
        case ScreenVisibility::Quarter: return 4;
        case ScreenVisibility::Off:
        case ScreenVisibility::Auto: break;
    }
    return stageDivisor(
        std::span(variant.technique).subspan(static_cast<std::size_t>(firstSlot), static_cast<std::size_t>(slots)),
        height);
}

std::array<std::uint8_t, 2> litResolveDivisors(ScreenVisibility setting, const ShadowFrame& frame,
                                               const PassLights& pass, int height) {
    std::array<std::uint8_t, 2> divisors{};
    int shared = 0;
    for (int first = 0; first < pass.variant.lights; first += 4) {
        const int count = std::min(4, pass.variant.lights - first);
        bool shadowed = false, contact = false;
        for (int i = first; i < first + count; ++i) {
            const auto slot = static_cast<std::size_t>(i);
            shadowed = shadowed || pass.variant.technique[slot] != SG_TECH_NONE;
            const int light = pass.sceneLight[slot];
            contact =
                contact || (light >= 0 && contactLengthUniform(frame.lights[static_cast<std::size_t>(light)]) != 0.0f);
        }
        const int d = visibilityDivisor(setting, pass.variant, first, count, height);
        if (!shadowed || contact || d <= 1 || (shared != 0 && d != shared)) continue;
        shared = d;
        divisors[static_cast<std::size_t>(first / 4)] = static_cast<std::uint8_t>(d);
    }
    return divisors;
}

float contactLengthUniform(const ShadowLightPlan& light) {
    const Shadow& s = light.settings;
    if (!s.contactShadows || light.technique() == ShadowTechnique::None) return 0.0f;
    return isAutomatic(s.contactLength) ? -1.0f : s.contactLength;
}

bool screenStagePays(ScreenVisibility setting, const ShadowFrame& frame, const std::vector<PassLights>& passes,
                     int height) {
    if (setting == ScreenVisibility::Off) return false;
    if (setting != ScreenVisibility::Auto) return true;
    const bool wideEnough = height >= kMinStageHeight;
    int filtered = 0;
    for (const PassLights& pass : passes) {
        for (int i = 0; i < pass.variant.lights; ++i) {
            const int light = pass.sceneLight[static_cast<std::size_t>(i)];
            if (light >= 0 && contactLengthUniform(frame.lights[static_cast<std::size_t>(light)]) != 0.0f) return true;
            const int t = pass.variant.technique[static_cast<std::size_t>(i)];
            if (wideEnough && (t == SG_TECH_PCSS || t == SG_TECH_SDF)) return true;
            if (filtersShadows(t)) ++filtered;
            if (filtered > 0 && height >= kMinQuarterStageHeight) return true;
        }
    }
    return wideEnough && filtered >= 2;
}

ScreenStage::ScreenStage() { empty_ = gpu::makeVertexArray("Screen/empty vertex array"); }

std::int64_t ScreenStage::bytesFor(int width, int height, bool materialTargets) {
    const std::int64_t pixels = std::int64_t{width} * height;
    // Full size: the surface and material targets (RGBA32UI each), two RGBA8 visibility layers,
    // the refine marks (32F) and its prior (RGBA16F); the extra target RGBA32UI. Half and quarter
    // size (each made on first use): two RGBA8 layers, two of the samples' depths and codes
    // (R32UI) and the coverage (32F). The lit pass's marks (R8UI), full size.
    const std::int64_t full = 16 + 16 + 2 * 4 + 4 + 8 + 1 + (materialTargets ? 16 : 0);
    const std::int64_t reduced = 2 * 4 + 2 * 4 + 4;
    return pixels * full + (pixels / 4 + pixels / 16) * reduced;
}

void ScreenStage::ensure(int width, int height, GLuint depthBuffer, bool materialTargets) {
    if (!surfaces_ || width_ != width || height_ != height) makeTargets(width, height);
    depthBuffer_ = depthBuffer;
    gl.NamedFramebufferTexture(surfaces_.get(), GL_DEPTH_ATTACHMENT, depthBuffer, 0);
    if (materialTargets && !extra_) {
        extra_ = gpu::makeScreenTarget("Main/Surfaces/extra", GL_RGBA32UI, width, height);
        gl.NamedFramebufferTexture(surfaces_.get(), GL_COLOR_ATTACHMENT2, extra_.get(), 0);
    }
}

void ScreenStage::makeTargets(int width, int height) {
    width_ = width;
    height_ = height;
    stage_ = {};
    stageDepth_ = {};
    coverage_ = {};
    surfaces_ = gpu::makeFramebuffer("Main/Surfaces/framebuffer");
    visibility_ = gpu::makeFramebuffer("Main/ScreenVisibility/framebuffer");
    // Packed (shaders/screen_gbuffer.glsl): each pass reads what it needs in one or two fetches.
    // The depth and the triangle's normal keep full floats: the shadow lookups compare depths on
    // the receiver's plane, which half floats would move by more than the automatic bias.
    surface_ = gpu::makeScreenTarget("Main/Surfaces/surface", GL_RGBA32UI, width, height);
    material_ = gpu::makeScreenTarget("Main/Surfaces/material", GL_RGBA32UI, width, height);
    full_ = gpu::makeScreenTarget("Main/ScreenVisibility/full", GL_RGBA8, width, height, 2);
    refine_ = gpu::makeScreenTarget("Main/ScreenVisibility/refine", GL_DEPTH_COMPONENT32F, width, height);
    marks_ = gpu::makeScreenTarget("Main/ScreenVisibility/marks", GL_R8UI, width, height);
    prior_ = {};
    extra_ = {};
    const GLuint fb = surfaces_.get();
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, surface_.get(), 0);
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT1, material_.get(), 0);
}

void ScreenStage::ensureStageTarget(int divisor) {
    const auto i = static_cast<std::size_t>(divisorIndex(divisor));
    if (stage_[i]) return;
    const int w = reduced(width_, divisor), h = reduced(height_, divisor);
    if (!prior_) prior_ = gpu::makeScreenTarget("Main/ScreenVisibility/prior", GL_RGBA16F, width_, height_);
    stage_[i] = gpu::makeScreenTarget("Main/ScreenVisibility/stage" + std::to_string(divisor), GL_RGBA8, w, h, 2);
    stageDepth_[i] =
        gpu::makeScreenTarget("Main/ScreenVisibility/stageDepth" + std::to_string(divisor), GL_R32UI, w, h, 2);
    coverage_[i] =
        gpu::makeScreenTarget("Main/ScreenVisibility/coverage" + std::to_string(divisor), GL_DEPTH_COMPONENT32F, w, h);
    // The resolve gathers 2x2 samples: clamped at the border, never filtered.
    for (const GLuint t : {stage_[i].get(), stageDepth_[i].get()}) {
        gl.TextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl.TextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
}

void ScreenStage::attachCoverage(int divisor, FrameStats& stats) {
    const auto i = static_cast<std::size_t>(divisorIndex(divisor));
    const GLuint fb = visibility_.get();
    gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, coverage_[i].get(), 0);
    if ((coverageDrawn_ & (1u << i)) != 0) return;
    coverageDrawn_ |= 1u << i;
    if (!coveragePrograms_[i]) {
        coveragePrograms_[i] = gpu::buildProgram({"Main/ScreenVisibility/coverage" + std::to_string(divisor),
                                                  "fullscreen.vert.glsl",
                                                  "screen_coverage.frag.glsl",
                                                  {"SG_VIS_DIVISOR " + std::to_string(divisor), "SG_READS_GBUFFER"}});
        ++stats.programsCompiled;
    }
    // Depth only, over the whole target (the scissor is the caller's to set after).
    const GLenum none = GL_NONE;
    gl.NamedFramebufferDrawBuffers(fb, 1, &none);
    gl.Disable(GL_SCISSOR_TEST);
    gl.Viewport(0, 0, reduced(width_, divisor), reduced(height_, divisor));
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_ALWAYS);
    gl.DepthMask(GL_TRUE);
    gl.UseProgram(coveragePrograms_[i].get());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_SCISSOR_TEST);
}

void ScreenStage::beginSurfaces(bool materialTargets) {
    coverageDrawn_ = 0;
    const GLuint fb = surfaces_.get();
    // A frame without the extra target writes two: their programs have two outputs.
    const std::array<GLenum, 3> buffers{GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    gl.NamedFramebufferDrawBuffers(fb, materialTargets ? 3 : 2, buffers.data());
    if (gl.CheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw GlError("screen-space visibility: the surface framebuffer is incomplete");
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, fb);
    gl.Viewport(0, 0, width_, height_);
    const GLuint zero[4] = {0, 0, 0, 0};
    const float farDepth = 1.0f;
    gl.DepthMask(GL_TRUE);
    gl.ClearNamedFramebufferfv(fb, GL_DEPTH, 0, &farDepth);
    // Only the surface target's depth (0: nothing drawn) is read where nothing was drawn.
    gl.ClearNamedFramebufferuiv(fb, GL_COLOR, 0, zero);
}

ScreenStage::Program& ScreenStage::program(const LitVariant& group, int firstSlot, int divisor, Pass pass, bool contact,
                                           FrameStats& stats) {
    const Key key{group, firstSlot, divisor, pass, contact};
    auto it = programs_.find(key);
    if (it != programs_.end()) return it->second;
    std::vector<std::string> defines{"SG_SLOT_BASE " + std::to_string(firstSlot),
                                     "SG_VIS_DIVISOR " + std::to_string(divisor), "SG_READS_GBUFFER"};
    const bool resolve = pass == Pass::Resolve;
    if (resolve) defines.emplace_back("SG_VIS_RESOLVE");
    if (pass == Pass::Refine) defines.emplace_back("SG_VIS_REFINE");
    if (pass == Pass::Resolve && refinesPerLight(group, 0, group.lights))
        defines.emplace_back("SG_VIS_REFINE_PER_LIGHT");
    if (pass == Pass::Stage && divisor > 1) defines.emplace_back("SG_STAGE_FEATURES");
    // The stage (at any resolution) and the refine run depth-tested.
    if (!resolve) defines.emplace_back("SG_FULLSCREEN_FAR");
    if (contact) {
        defines.emplace_back("SG_VIS_CONTACT");
        defines.push_back("SG_CONTACT_STEPS " + std::to_string(kContactSteps));
        defines.push_back("SG_CONTACT_AUTO_TEXELS " + std::to_string(kAutoContactLengthTexels));
        defines.push_back("SG_CONTACT_AUTO_PIXELS " + std::to_string(kAutoContactLengthPixels));
    }
    defines.push_back("SG_VIS_LIGHTS " + std::to_string(group.lights));
    std::array<gpu::SlotConfig, SG_MAX_MASK_LIGHTS> slots{};
    for (int i = 0; i < group.lights; ++i) {
        const auto s = static_cast<std::size_t>(i);
        slots[s] = {group.type[s], group.technique[s], group.kernel[s]};
    }
    gpu::appendSlotGroupDefines(std::span(slots).first(static_cast<std::size_t>(group.lights)), SG_MAX_MASK_LIGHTS,
                                defines);
    const unsigned techniques = variantTechniques(group);
    gpu::appendTechniqueDefines(techniques, defines);
    std::string label = variantLabel(group);  // "Main/Lit[...]"
    label = "Main/ScreenVisibility" + label.substr(label.find('[')) + (resolve ? "/resolve" : "") +
            (pass == Pass::Refine ? "/refine" : "") + (contact ? "/contact" : "") + "/" + std::to_string(divisor);
    Program p;
    p.program = gpu::buildProgram({label, "fullscreen.vert.glsl", "screen_visibility.frag.glsl", defines, techniques});
    ++stats.programsCompiled;
    const GLuint id = p.program.get();
    p.cameraForward = gl.GetUniformLocation(id, "uCameraForward");
    p.pixelAngle = gl.GetUniformLocation(id, "uPixelAngle");
    p.stageLayer = gl.GetUniformLocation(id, "uStageLayer");
    p.ray00 = gl.GetUniformLocation(id, "uRay00");
    p.rayDx = gl.GetUniformLocation(id, "uRayDx");
    p.rayDy = gl.GetUniformLocation(id, "uRayDy");
    p.contactLength = gl.GetUniformLocation(id, "uContactLength");
    p.clipFromCs = gl.GetUniformLocation(id, "uClipFromCs");
    return programs_.emplace(key, std::move(p)).first->second;
}

void ScreenStage::computeVisibility(const ShadowFrame& frame, const PassLights& pass, const PixelRect& bounds,
                                    ScreenVisibility setting, const ScreenRays& rays, FrameStats& stats,
                                    gpu::PassTimer* timer) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, visibility_.get());
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_BLEND);
    gl.DepthMask(GL_FALSE);
    gl.BindVertexArray(empty_.get());
    gl.BindTextureUnit(SG_UNIT_GBUFFER_SURFACE, surface_.get());
    for (const GLuint unit : {SG_UNIT_GBUFFER_SURFACE, SG_UNIT_SCREEN_DEPTH, SG_UNIT_SCREEN_VISIBILITY}) {
        gl.BindSampler(unit, 0);
    }
    gl.Enable(GL_SCISSOR_TEST);
    for (int first = 0; first < pass.variant.lights; first += 4) {
        Group g;
        const int count = std::min(4, pass.variant.lights - first);
        g.variant = slotsVariant(pass.variant, first, count);
        if (variantTechniques(g.variant) == (1u << SG_TECH_NONE)) continue;  // no shadowed light: read as lit
        g.first = first;
        g.layer = first / 4;
        g.divisor = visibilityDivisor(setting, pass.variant, first, count, height_);
        for (int i = 0; i < count; ++i) {
            const int light = pass.sceneLight[static_cast<std::size_t>(first) + static_cast<std::size_t>(i)];
            if (light >= 0) g.contactLength[i] = contactLengthUniform(frame.lights[static_cast<std::size_t>(light)]);
        }
        g.contact = g.contactLength != glm::vec4(0.0f);
        g.bounds = bounds;
        if (pass.variant.resolve[static_cast<std::size_t>(g.layer)] > 1) {
            // The lit pass resolves it (litResolveDivisors, at this divisor): the stage alone.
            timed(timer, "stage", [&] { reducedStage(g, rays, stats); });
            continue;
        }
        visibilityOfGroup(g, rays, stats, timer);
    }
    gl.Disable(GL_SCISSOR_TEST);
    gl.NamedFramebufferTextureLayer(visibility_.get(), GL_COLOR_ATTACHMENT0, 0, 0, 0);
}

void ScreenStage::draw(Program& p, const Group& g, int divisor, const ScreenRays& rays) const {
    const GLuint id = p.program.get();
    gl.ProgramUniform4fv(id, p.contactLength, 1, glm::value_ptr(g.contactLength));
    gl.ProgramUniformMatrix4fv(id, p.clipFromCs, 1, GL_FALSE, glm::value_ptr(rays.clipFromCs));
    gl.ProgramUniform3fv(id, p.cameraForward, 1, glm::value_ptr(rays.forward));
    gl.ProgramUniform1f(id, p.pixelAngle, rays.pixelAngle);
    gl.ProgramUniform3fv(id, p.ray00, 1, glm::value_ptr(rays.ray00));
    gl.ProgramUniform3fv(id, p.rayDx, 1, glm::value_ptr(rays.dx));
    gl.ProgramUniform3fv(id, p.rayDy, 1, glm::value_ptr(rays.dy));
    gl.ProgramUniform1i(id, p.stageLayer, g.layer);
    // The pass's bounds at this resolution, a sample wider so the resolve finds its four.
    const PixelRect& b = g.bounds;
    const int pad = divisor > 1 ? 1 : 0;
    const int x0 = std::max(b.x0 / divisor - pad, 0), y0 = std::max(b.y0 / divisor - pad, 0);
    const int x1 = std::min(reduced(b.x1, divisor) + pad, reduced(width_, divisor));
    const int y1 = std::min(reduced(b.y1, divisor) + pad, reduced(height_, divisor));
    gl.Viewport(0, 0, reduced(width_, divisor), reduced(height_, divisor));
    gl.Scissor(x0, y0, x1 - x0, y1 - y0);
    gl.UseProgram(id);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
}

void ScreenStage::visibilityOfGroup(const Group& g, const ScreenRays& rays, FrameStats& stats, gpu::PassTimer* timer) {
    const GLuint fb = visibility_.get();
    const int d = g.divisor;
    if (d > 1) timed(timer, "stage", [&] { reducedStage(g, rays, stats); });
    const GLenum one = GL_COLOR_ATTACHMENT0;
    gl.NamedFramebufferDrawBuffers(fb, 1, &one);
    gl.NamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0, full_.get(), 0, g.layer);
    gl.Enable(GL_DEPTH_TEST);
    if (d == 1) {
        // Only where the surface pass drew (GREATER than its depth, at the far plane).
        gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, depthBuffer_, 0);
        gl.DepthFunc(GL_GREATER);
        timed(timer, "stage", [&] { draw(program(g.variant, g.first, 1, Pass::Stage, g.contact, stats), g, 1, rays); });
    } else {
        // The resolve marks in depth the pixels it cannot upsample for every light (0; 1
        // elsewhere) and writes the prior: its visibility, -1 for the lights to recompute. The
        // refine then runs where the depth test (GREATER than the mark, at the far plane) lets it,
        // and there computes only the lights the prior leaves.
        // With fewer than kMinPerLightRefineLights shadowed lights the refine is the stage at
        // full resolution (every light), without a prior.
        const bool perLight = refinesPerLight(g.variant, 0, g.variant.lights);
        gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, refine_.get(), 0);
        if (perLight) {
            gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT1, prior_.get(), 0);
            const std::array<GLenum, 2> both{GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
            gl.NamedFramebufferDrawBuffers(fb, 2, both.data());
        }
        gl.DepthMask(GL_TRUE);
        gl.DepthFunc(GL_ALWAYS);
        timed(timer, "resolve",
              [&] { draw(program(g.variant, g.first, d, Pass::Resolve, g.contact, stats), g, 1, rays); });
        if (perLight) {
            gl.NamedFramebufferDrawBuffers(fb, 1, &one);
            gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT1, 0, 0);
            gl.BindTextureUnit(SG_UNIT_SCREEN_VISIBILITY, prior_.get());
        }
        gl.DepthMask(GL_FALSE);
        gl.DepthFunc(GL_GREATER);
        const Pass refine = perLight ? Pass::Refine : Pass::Stage;
        timed(timer, "refine", [&] { draw(program(g.variant, g.first, 1, refine, g.contact, stats), g, 1, rays); });
    }
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_DEPTH_TEST);
    gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, 0, 0);
}

void ScreenStage::reducedStage(const Group& g, const ScreenRays& rays, FrameStats& stats) {
    const GLuint fb = visibility_.get();
    const int d = g.divisor;
    ensureStageTarget(d);
    const GLuint stage = stage_[static_cast<std::size_t>(divisorIndex(d))].get();
    const GLuint depth = stageDepth_[static_cast<std::size_t>(divisorIndex(d))].get();
    attachCoverage(d, stats);
    gl.NamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0, stage, 0, g.layer);
    gl.NamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT1, depth, 0, g.layer);
    const std::array<GLenum, 2> both{GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl.NamedFramebufferDrawBuffers(fb, 2, both.data());
    // Samples the depth test skips read as off every surface in the resolve (depth 0).
    const std::array<GLuint, 4> none{0, 0, 0, 0};
    gl.ClearNamedFramebufferuiv(fb, GL_COLOR, 1, none.data());
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_GREATER);
    draw(program(g.variant, g.first, d, Pass::Stage, g.contact, stats), g, d, rays);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_DEPTH_TEST);
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT1, 0, 0);
    gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, 0, 0);
    gl.BindTextureUnit(SG_UNIT_SCREEN_VISIBILITY, stage);
    gl.BindTextureUnit(SG_UNIT_SCREEN_DEPTH, depth);
}

void ScreenStage::bindForLighting(bool materialTargets, const LitVariant& pass) const {
    if (materialTargets) {
        gl.BindTextureUnit(SG_UNIT_GBUFFER_EXTRA, extra_.get());
        gl.BindSampler(SG_UNIT_GBUFFER_EXTRA, 0);
    }
    gl.BindTextureUnit(SG_UNIT_GBUFFER_SURFACE, surface_.get());
    gl.BindTextureUnit(SG_UNIT_GBUFFER_MATERIAL, material_.get());
    gl.BindTextureUnit(SG_UNIT_SCREEN_VISIBILITY, full_.get());
    for (const GLuint unit : {SG_UNIT_GBUFFER_SURFACE, SG_UNIT_GBUFFER_MATERIAL, SG_UNIT_SCREEN_VISIBILITY}) {
        gl.BindSampler(unit, 0);
    }
    // The groups the pass resolves itself share one divisor (litResolveDivisors).
    const int resolved = std::max(pass.resolve[0], pass.resolve[1]);
    if (resolved > 1) {
        const auto i = static_cast<std::size_t>(divisorIndex(resolved));
        gl.BindTextureUnit(SG_UNIT_LIT_STAGE, stage_[i].get());
        gl.BindTextureUnit(SG_UNIT_SCREEN_DEPTH, stageDepth_[i].get());
        gl.BindSampler(SG_UNIT_LIT_STAGE, 0);
        gl.BindSampler(SG_UNIT_SCREEN_DEPTH, 0);
    }
}

void ScreenStage::markCorrection(const PixelRect& bounds, unsigned slotBits, FrameStats& stats) {
    if (!marksProgram_) {
        marksProgram_ = gpu::buildProgram({"Main/ScreenVisibility/marks",
                                           "fullscreen.vert.glsl",
                                           "screen_coverage.frag.glsl",
                                           {"SG_COVERAGE_MARKS"}});
        marksBits_ = gl.GetUniformLocation(marksProgram_.get(), "uMarkBits");
        ++stats.programsCompiled;
    }
    const GLuint fb = visibility_.get();
    gl.BindFramebuffer(GL_FRAMEBUFFER, fb);
    gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, refine_.get(), 0);
    const GLenum none = GL_NONE;
    gl.NamedFramebufferDrawBuffers(fb, 1, &none);
    gl.Viewport(0, 0, width_, height_);
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(bounds.x0, bounds.y0, bounds.x1 - bounds.x0, bounds.y1 - bounds.y0);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_ALWAYS);
    gl.DepthMask(GL_TRUE);
    gl.BindTextureUnit(SG_UNIT_LIT_STAGE, marks_.get());
    gl.BindSampler(SG_UNIT_LIT_STAGE, 0);
    gl.ProgramUniform1i(marksProgram_.get(), marksBits_, static_cast<GLint>(slotBits));
    gl.UseProgram(marksProgram_.get());
    gl.BindVertexArray(empty_.get());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.DepthMask(GL_FALSE);
    gl.DepthFunc(GL_LESS);
    gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, 0, 0);
    gl.Disable(GL_SCISSOR_TEST);
}

}  // namespace shadow::render
