// The forward renderer (see renderer.h): one lit pass per group of up to SG_MAX_LIGHTS_PER_PASS
// lights, each with the program specialised for its lights, after an optional depth pre-pass.
#include <shadow/context.h>
#include <shadow/gpu_records.h>
#include <shadow/renderer.h>
#include <shadow/shadow_system.h>

#include "core/camera.h"
#include "core/shader_resources.h"
#include "gl/gl_state.h"
#include "gl/mesh_cache_access.h"
#include "gl/objects.h"
#include "gl/pass_timer.h"
#include "render/edge_counts.h"
#include "render/light_packing.h"
#include "render/lit_programs.h"
#include "render/present.h"
#include "render/render_targets.h"
#include "render/screen_visibility.h"

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>

namespace shadow {
namespace {

using render::PassLights;

int debugViewId(DebugView v) {
    switch (v) {
        case DebugView::None: return SG_DEBUG_NONE;
        case DebugView::Cascade: return SG_DEBUG_CASCADE;
        case DebugView::BlockerDepth: return SG_DEBUG_BLOCKER_DEPTH;
        case DebugView::Penumbra: return SG_DEBUG_PENUMBRA;
        case DebugView::Visibility: return SG_DEBUG_VISIBILITY;
        case DebugView::MarchSteps: return SG_DEBUG_MARCH_STEPS;
        case DebugView::Closest: return SG_DEBUG_CLOSEST;
    }
    return SG_DEBUG_NONE;
}

/// A uniform buffer holding one block per pass at a stride the GL accepts for bind ranges.
struct PassBlocks {
    gpu::Buffer buffer;
    std::size_t blockBytes = 0, stride = 0, capacity = 0;

    void upload(const char* label, std::size_t bytes, GLint alignment, const std::vector<PassLights>& passes,
                const void* (*blockOf)(const PassLights&)) {
        blockBytes = bytes;
        const std::size_t align = static_cast<std::size_t>(std::max(alignment, 16));
        stride = (bytes + align - 1) / align * align;
        const std::size_t total = stride * passes.size();
        if (total > capacity || !buffer) {
            capacity = std::max(total, capacity * 2);
            buffer = gpu::makeBuffer(label, static_cast<GLsizeiptr>(capacity), nullptr, GL_DYNAMIC_STORAGE_BIT);
        }
        for (std::size_t p = 0; p < passes.size(); ++p) {
            gl.NamedBufferSubData(buffer.get(), static_cast<GLintptr>(p * stride), static_cast<GLsizeiptr>(bytes),
                                  blockOf(passes[p]));
        }
    }
    void bind(GLuint binding, std::size_t pass) const {
        gl.BindBufferRange(GL_UNIFORM_BUFFER, binding, buffer.get(), static_cast<GLintptr>(pass * stride),
                           static_cast<GLsizeiptr>(blockBytes));
    }
};

/// Camera matrices of the main pass, camera-relative (cs = world - camera).
struct MainCamera {
    glm::mat4 clipFromCs{1.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
    render::ScreenRays rays;  ///< the screen-space visibility stage's view of it
};

/// The depth pre-pass's programs the frame draws with (by alpha test, then deformation:
/// `[alpha * gpu::kMeshDeforms + deform]`), built on first use (counted in `stats`), each given
/// the camera: the alpha-tested ones when the scene has cut-outs, those of each deformation
/// `deforms` (bit 1 << deform) holds.
template <typename Programs>
void preparePrepasses(Programs& programs, bool cutouts, unsigned deforms, const MainCamera& mc, FrameStats& stats) {
    for (std::size_t i = 0; i < programs.size(); ++i) {
        const bool alpha = i >= gpu::kMeshDeforms;
        const auto deform = static_cast<unsigned>(i % gpu::kMeshDeforms);
        if ((alpha && !cutouts) || (deforms & (1u << deform)) == 0) continue;
        if (!programs[i]) {
            programs[i] = render::buildDepthPrepass(alpha, deform);
            ++stats.programsCompiled;
        }
        gl.ProgramUniformMatrix4fv(programs[i]->program.get(), programs[i]->mesh.clipFromCs, 1, GL_FALSE,
                                   glm::value_ptr(mc.clipFromCs));
    }
}

/// What the frame's materials need of the programs and targets.
struct FrameMaterials {
    bool cutouts = false;   ///< a cut-out material (its holes need an alpha test)
    bool maps = false;      ///< a material with maps (the maps variant)
    bool textured = false;  ///< a material with a base-colour texture (SG_BASE_COLOR_TEXTURE)
    /// A normal map or emission: the stage's surfaces store the lighting normal and emission.
    bool materialTargets = false;
    /// The meshes' deformations (gpu::meshDeform), bit 1 << deform each: the programs' variants.
    unsigned deforms = 0;
};

FrameMaterials frameMaterials(const World& world) {
    FrameMaterials f;
    world.view<Mesh, Material>().each([&](Entity e, const Mesh&, const Material& m) {
        f.deforms |= 1u << gpu::meshDeform(world.tryGet<Skin>(e), world.tryGet<Morph>(e));
        f.cutouts = f.cutouts || m.cutout();
        f.maps = f.maps || m.usesMaps();
        f.textured = f.textured || m.baseColorTexture != nullptr;
        f.materialTargets =
            f.materialTargets || m.normalMap.texture != nullptr || m.emits() || m.emissiveMap.texture != nullptr;
    });
    return f;
}

MainCamera mainCamera(const CameraView& cam, int width, int height) {
    MainCamera m;
    const glm::dmat4 clipFromView = cameraClipFromView(cam);
    m.clipFromCs = glm::mat4(cameraClipFromCs(cam, clipFromView));
    m.forward = cameraForward(cam);
    // View axes in world space (rows of the view's rotation) scaled to a pixel at unit depth.
    const glm::dmat3 viewRotation(cam.viewFromWorld);
    const glm::dvec3 right = glm::row(viewRotation, 0), up = glm::row(viewRotation, 1);
    const double tanX = 1.0 / std::abs(clipFromView[0][0]), tanY = 1.0 / std::abs(clipFromView[1][1]);
    const double w = std::max(width, 1), h = std::max(height, 1);
    m.rays.forward = m.forward;
    m.rays.pixelAngle = static_cast<float>(2.0 * tanY / h);
    m.rays.ray00 = glm::vec3(glm::dvec3(m.forward) - right * tanX - up * tanY);
    m.rays.dx = glm::vec3(right * (2.0 * tanX / w));
    m.rays.dy = glm::vec3(up * (2.0 * tanY / h));
    m.rays.clipFromCs = m.clipFromCs;
    return m;
}

/// The pixels a deferred lit pass of `pass` shades: its lights' bounds, or with AOVs the screen
/// (each light's visibility is written wherever there is geometry).
PixelRect litBounds(const PassLights& pass, const RenderOptions& options) {
    return options.aovs ? PixelRect{0, 0, options.width, options.height} : pass.bounds;
}

/// Turns the scissor test on, to `b`.
void scissorTo(const PixelRect& b) {
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0);
}

/// Whether a deferred lit pass resolves (part of) the stage itself, and has a correction.
bool resolvesStage(const render::LitVariant& v) { return v.resolve[0] > 1 || v.resolve[1] > 1; }

/// The uniforms a lit program takes per pass: the camera's direction, and for the first pass
/// (which adds them, LitVariant::ambient) the ambient's radiances.
void setPassUniforms(const render::LitProgram& p, const MainCamera& mc, const RenderOptions& options) {
    const GLuint id = p.program.get();
    gl.ProgramUniform3fv(id, p.cameraForward, 1, glm::value_ptr(mc.forward));
    gl.ProgramUniform3fv(id, p.ray00, 1, glm::value_ptr(mc.rays.ray00));
    gl.ProgramUniform3fv(id, p.rayDx, 1, glm::value_ptr(mc.rays.dx));
    gl.ProgramUniform3fv(id, p.rayDy, 1, glm::value_ptr(mc.rays.dy));
    gl.ProgramUniform1f(id, p.pixelAngle, mc.rays.pixelAngle);
    gl.ProgramUniform3fv(id, p.ambientSky, 1, glm::value_ptr(glm::max(options.ambientSky, glm::vec3(0.0f))));
    gl.ProgramUniform3fv(id, p.ambientGround, 1, glm::value_ptr(glm::max(options.ambientGround, glm::vec3(0.0f))));
}

}  // namespace

struct Renderer::Impl {
    MeshCache meshes;                ///< owned and collected here (Renderer::meshes)
    gpu::ShaderResources resources;  ///< the samplers and kernel the lit passes bind
    render::LitProgramCache programs;
    /// By alpha test and deformation (`preparePrepasses`), each built on first use.
    std::array<std::optional<render::DepthPrepassProgram>, 2 * gpu::kMeshDeforms> prepasses;
    std::optional<render::ScreenStage> screen;   ///< made on first use
    std::optional<render::Presenter> presenter;  ///< made on first use
    /// By `render::SurfaceProgramBits`, each built on first use.
    std::array<std::optional<render::SurfaceProgram>, render::kSurfacePrograms> surfaces;
    render::RenderTargets targets;
    std::vector<PassLights> passes;
    /// Per pass, into `programs` (stable), by material maps and deformation: `[maps *
    /// gpu::kMeshDeforms + deform]`, null for a kind the frame does not draw (forward: the maps
    /// variant for materials with maps, a variant for each deformation; deferred: [0] only).
    std::vector<std::array<const render::LitProgram*, 2 * gpu::kMeshDeforms>> passPrograms;
    FrameMaterials materials;                        ///< this frame's
    std::vector<render::PackingEntry> packingOrder;  ///< scratch of packLights
    PassBlocks lightBlocks, layerBlocks;
    GLint uniformAlignment = 256;
    std::size_t lightCount = 0;  ///< scene lights of the last frame
    bool prepassRan = false;     ///< this frame: asked for, or needed by a cut-out material
    bool deferred = false;       ///< this frame runs the screen-space visibility stage
    bool softwareRenderer = false;
    render::EdgeCounts edgeCounts;  ///< technique auto's (SG_COUNT_EDGES)
    gpu::PassTimer timer;           ///< the main passes'
    std::vector<Warning> pending;   ///< host errors found by calls without a FrameStats

    Impl();
    /// Adds what the options and the frame ask of every pass's program (AOVs, debug view, an auto
    /// light's edge counts) to its variant and
    /// builds the programs before any pass draws. Measured on llvmpipe (bunny-spot, hard, 1280x720):
    /// building the program between the passes of the first frame instead left the shadow pass of
    /// every later frame at 29-39 ms instead of 24-26.
    void preparePrograms(const ShadowFrame& frame, const RenderOptions& options, FrameStats& stats);
    void uploadPasses();
    /// Draws every visible mesh (those whose bounds meet `reach`, unless it is null), a skinned
    /// one in its pose; `perMesh(mesh, material, deform)` sets the material's uniforms and
    /// texture and returns the program to draw it with (made current here when it changes), one
    /// built for `deform` (gpu::meshDeform).
    template <typename PerMesh>
    void drawMeshes(const World& world, const CameraView& cam, const DAabb* reach, PerMesh&& perMesh,
                    FrameStats& stats);
    /// The depth pre-pass; `cutouts`: the scene has cut-out materials, whose holes it leaves out.
    void depthPrepass(const World& world, const CameraView& cam, const MainCamera& mc, bool cutouts, FrameStats& stats);
    void litPass(const World& world, const CameraView& cam, const MainCamera& mc, std::size_t index,
                 const ShadowMaps& maps, const RenderOptions& options, FrameStats& stats);
    /// Makes the screen-space stage's targets fit `options` (refused, naming the size, beyond the
    /// memory cap with the stage's targets counted).
    void prepareScreenStage(const RenderOptions& options);
    /// The present passes, made on first use.
    render::Presenter& presenterOf();
    /// The frame's main passes through the screen-space visibility stage, or forward.
    void renderScreenSpace(const World& world, const CameraView& camera, const ShadowFrame& frame, const MainCamera& mc,
                           const ShadowMaps& maps, const RenderOptions& options, FrameStats& stats);
    void renderForward(const World& world, const CameraView& camera, const MainCamera& mc, const ShadowMaps& maps,
                       const RenderOptions& options, FrameStats& stats);
    /// The screen-space visibility stage's surface pass.
    void surfacePass(const World& world, const CameraView& cam, const MainCamera& mc, FrameStats& stats);
    /// Lit pass `index` of the stage: its lights' visibility over the screen, then their shading.
    void screenLitPass(const MainCamera& mc, std::size_t index, const RenderOptions& options);
    /// The corrections of deferred lit pass `index` that resolved the stage itself, one per group
    /// of four it resolved: the lights it marked added at the marked pixels (lit.frag.glsl,
    /// SG_LIT_CORRECTION).
    void screenCorrection(const MainCamera& mc, std::size_t index, const RenderOptions& options, FrameStats& stats);
    /// The stage's visibility of pass `index`'s lights.
    void screenVisibilityPass(const ShadowFrame& frame, const MainCamera& mc, std::size_t index, const ShadowMaps& maps,
                              const RenderOptions& options, FrameStats& stats, gpu::PassTimer* timer);
};

Renderer::Impl::Impl() : softwareRenderer(queryGlInfo().softwareRenderer), timer(softwareRenderer) {
    timer.setEnabled(false);
    gl.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &uniformAlignment);
}

void Renderer::Impl::preparePrograms(const ShadowFrame& frame, const RenderOptions& options, FrameStats& stats) {
    passPrograms.clear();
    for (PassLights& pass : passes) {
        render::LitVariant& v = pass.variant;
        v.aovs = options.aovs;
        v.deferred = deferred;
        // The counting program on the frames that count only: its counting costs each lookup
        // even when no slot counts (the PCSS lit pass of builtin:plates 7.13 -> 8.00 ms, always
        // on, measured by bash benchmarks/run_auto_budget.sh).
        v.countEdges = false;
        v.ambient = &pass == &passes.front();
        v.textured = !deferred && materials.textured;
        for (std::size_t slot = 0; slot < pass.sceneLight.size() && !deferred; ++slot) {
            const ShadowLightPlan* plan = render::slotPlan(frame, pass, slot);
            v.countEdges = v.countEdges || (plan != nullptr && plan->countEdges);
        }
        // Deferred: one program reads the surfaces whatever their materials; forward: a second
        // program for the materials with maps.
        v.materialMaps = deferred && materials.materialTargets;
        v.resolve = deferred ? render::litResolveDivisors(options.screenVisibility, frame, pass, options.height)
                             : std::array<std::uint8_t, 2>{};
        v.debugView = debugViewId(options.debugView);
        const auto* const slot = std::find(pass.sceneLight.begin(), pass.sceneLight.end(), options.debugLight);
        v.debugSlot = slot != pass.sceneLight.end() && v.debugView != SG_DEBUG_NONE
                          ? static_cast<int>(slot - pass.sceneLight.begin())
                          : -1;
        auto& chosen = passPrograms.emplace_back();
        chosen.fill(nullptr);
        chosen[0] = &programs.get(v, stats.programsCompiled);
        if (deferred) {
            // One full-screen program reads whatever surfaces were drawn; one per group of four it
            // resolved itself corrects it where it marked lights ([1 + group]).
            for (std::size_t group = 0; group < v.resolve.size(); ++group) {
                if (v.resolve[group] <= 1) continue;
                chosen[1 + group] =
                    &programs.get(render::correctionVariant(v, static_cast<int>(group)), stats.programsCompiled);
            }
            continue;
        }
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            render::LitVariant kind = v;
            kind.materialMaps = k >= gpu::kMeshDeforms;
            kind.deform = static_cast<unsigned>(k % gpu::kMeshDeforms);
            if ((kind.materialMaps && !materials.maps) || (materials.deforms & (1u << kind.deform)) == 0) continue;
            chosen[k] = &programs.get(kind, stats.programsCompiled);
        }
    }
}

void Renderer::Impl::uploadPasses() {
    lightBlocks.upload("Main/lights", sizeof(PassLights::lights), uniformAlignment, passes,
                       [](const PassLights& p) -> const void* { return p.lights.data(); });
    layerBlocks.upload("Main/shadowLayers", sizeof(PassLights::layers), uniformAlignment, passes,
                       [](const PassLights& p) -> const void* { return p.layers.data(); });
}

template <typename PerMesh>
void Renderer::Impl::drawMeshes(const World& world, const CameraView& cam, const DAabb* reach, PerMesh&& perMesh,
                                FrameStats& stats) {
    bool culling = false;
    gl.Disable(GL_CULL_FACE);
    GLuint current = 0;
    world.view<Mesh, WorldTransform, Material>().each([&](Entity e, const Mesh& mesh, const WorldTransform& wt,
                                                          const Material& m) {
        if (!wt.finite || mesh.data == nullptr || mesh.data->indices.empty()) return;
        if (reach != nullptr) {
            const WorldBounds* b = world.tryGet<WorldBounds>(e);
            if (b != nullptr && !b->box.empty() &&
                glm::any(glm::lessThan(b->box.max, reach->min) || glm::greaterThan(b->box.min, reach->max))) {
                return;  // beyond the pass's lights
            }
        }
        if (culling == m.doubleSided) {
            culling = !m.doubleSided;
            if (culling) {
                gl.Enable(GL_CULL_FACE);
            } else {
                gl.Disable(GL_CULL_FACE);
            }
        }
        const Skin* skin = world.tryGet<Skin>(e);
        if (skin != nullptr && !skin->posed) return;
        // A skinned mesh is drawn in its skin's frame, its own transform not applied (glTF).
        const glm::dmat4& worldFromLocal = skin != nullptr ? skin->worldFromFrame : wt.worldFromLocal;
        const glm::dmat3 linear(worldFromLocal);
        if (!(std::abs(glm::determinant(linear)) > 1e-30)) return;  // collapsed to zero area: nothing to see
        const Morph* morph = world.tryGet<Morph>(e);
        const auto [program, uniforms] = perMesh(mesh, m, gpu::meshDeform(skin, morph));
        if (program != current) {
            gl.UseProgram(program);
            current = program;
        }
        glm::dmat4 csFromLocal = worldFromLocal;
        csFromLocal[3] -= glm::dvec4(cam.wsPosition, 0.0);
        gl.ProgramUniformMatrix4fv(program, uniforms->csFromLocal, 1, GL_FALSE, glm::value_ptr(glm::mat4(csFromLocal)));
        const glm::mat3 normalFromLocal(glm::transpose(glm::inverse(linear)));
        gl.ProgramUniformMatrix3fv(program, uniforms->normalFromLocal, 1, GL_FALSE, glm::value_ptr(normalFromLocal));
        const int indices =
            gpu::MeshCacheAccess::bindDeformed(meshes, mesh.data, program, uniforms->deform, skin, morph);
        gl.DrawElements(GL_TRIANGLES, indices, GL_UNSIGNED_INT, nullptr);
        ++stats.mainDrawCalls;
        stats.mainTriangles += indices / 3;
    });
    gl.Disable(GL_CULL_FACE);
}

void Renderer::Impl::depthPrepass(const World& world, const CameraView& cam, const MainCamera& mc, bool cutouts,
                                  FrameStats& stats) {
    preparePrepasses(prepasses, cutouts, materials.deforms, mc, stats);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.DepthMask(GL_TRUE);
    gl.DepthFunc(GL_LESS);
    drawMeshes(
        world, cam, nullptr,
        [this](const Mesh&, const Material& m, unsigned deform) {
            using Choice = std::pair<GLuint, const render::MeshUniforms*>;
            const render::DepthPrepassProgram& p = *prepasses[(m.cutout() ? gpu::kMeshDeforms : 0) + deform];
            if (!m.cutout()) return Choice{p.program.get(), &p.mesh};
            gl.ProgramUniform1f(p.program.get(), p.alpha, m.alpha);
            gl.ProgramUniform1f(p.program.get(), p.alphaCutoff, m.alphaCutoff);
            gpu::MeshCacheAccess::bindTexture(meshes, m.baseColorTexture, SG_UNIT_BASE_COLOR);
            return Choice{p.program.get(), &p.mesh};
        },
        stats);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void Renderer::Impl::prepareScreenStage(const RenderOptions& options) {
    const std::string why = render::renderSizeProblem(options.width, options.height, options.aovs,
                                                      static_cast<int>(passes.size()), true, materials.materialTargets);
    if (!why.empty()) {
        throw GlError("main pass targets of " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                      ": " + why);
    }
    if (!screen) screen.emplace();
    screen->ensure(options.width, options.height, targets.depthBuffer(), materials.materialTargets);
}

void Renderer::Impl::renderScreenSpace(const World& world, const CameraView& camera, const ShadowFrame& frame,
                                       const MainCamera& mc, const ShadowMaps& maps, const RenderOptions& options,
                                       FrameStats& stats) {
    {
        gpu::ScopedPass timed(timer, "Main/Surfaces");
        surfacePass(world, camera, mc, stats);
    }
    screenVisibilityPass(frame, mc, 0, maps, options, stats, &timer);  // times its passes itself
    {
        gpu::ScopedPass timed(timer, "Main/Lit");
        screenLitPass(mc, 0, options);
    }
    if (resolvesStage(passes[0].variant)) {
        gpu::ScopedPass timed(timer, "Main/ScreenVisibility/refine");
        screenCorrection(mc, 0, options, stats);
    }
    if (passes.size() > 1) {
        gpu::ScopedPass timed(timer, "Main/LitMore");
        for (std::size_t pass = 1; pass < passes.size(); ++pass) {
            screenVisibilityPass(frame, mc, pass, maps, options, stats, nullptr);
            screenLitPass(mc, pass, options);
            if (resolvesStage(passes[pass].variant)) screenCorrection(mc, pass, options, stats);
        }
    }
    prepassRan = false;
}

void Renderer::Impl::renderForward(const World& world, const CameraView& camera, const MainCamera& mc,
                                   const ShadowMaps& maps, const RenderOptions& options, FrameStats& stats) {
    // A cut-out material needs the pre-pass: it leaves the holes out, so that the lit passes,
    // whose cost a discard would raise for every pixel on a CPU rasteriser, need no alpha test.
    const bool cutouts = materials.cutouts;
    prepassRan = options.depthPrepass || cutouts;
    if (prepassRan) {
        gpu::ScopedPass timed(timer, "Main/DepthPrepass");
        depthPrepass(world, camera, mc, cutouts, stats);
    }
    {
        gpu::ScopedPass timed(timer, "Main/Lit");
        litPass(world, camera, mc, 0, maps, options, stats);
    }
    if (passes.size() > 1) {
        // Timed as one: a fence per small pass would cost more than many of them.
        gpu::ScopedPass timed(timer, "Main/LitMore");
        for (std::size_t pass = 1; pass < passes.size(); ++pass) litPass(world, camera, mc, pass, maps, options, stats);
    }
}

void Renderer::Impl::surfacePass(const World& world, const CameraView& cam, const MainCamera& mc, FrameStats& stats) {
    screen->beginSurfaces(materials.materialTargets);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    const unsigned frameBits = (materials.materialTargets ? render::kSurfaceMaterialTargets : 0u) |
                               (materials.textured ? render::kSurfaceTextured : 0u);
    drawMeshes(
        world, cam, nullptr,
        [this, &mc, &stats, frameBits](const Mesh& mesh, const Material& m, unsigned deform) {
            const unsigned bits = frameBits | (m.cutout() ? render::kSurfaceAlphaTested : 0u) |
                                  (m.usesMaps() ? render::kSurfaceMaps : 0u) | deform * render::kSurfaceDeformUnit;
            std::optional<render::SurfaceProgram>& slot = surfaces[bits];
            if (!slot) {
                slot = render::buildSurfaceProgram(bits);
                ++stats.programsCompiled;
            }
            const render::SurfaceProgram& p = *slot;
            const GLuint id = p.program.get();
            gl.ProgramUniformMatrix4fv(id, p.mesh.clipFromCs, 1, GL_FALSE, glm::value_ptr(mc.clipFromCs));
            gl.ProgramUniform3fv(id, p.cameraForward, 1, glm::value_ptr(mc.forward));
            render::setMaterial(id, p.material, mesh, m);
            if (m.cutout()) {
                gl.ProgramUniform1f(id, p.alpha, m.alpha);
                gl.ProgramUniform1f(id, p.alphaCutoff, m.alphaCutoff);
            }
            render::bindMaterialTextures(meshes, m, m.usesMaps());
            return std::pair<GLuint, const render::MeshUniforms*>{id, &p.mesh};
        },
        stats);
}

void Renderer::Impl::screenVisibilityPass(const ShadowFrame& frame, const MainCamera& mc, std::size_t index,
                                          const ShadowMaps& maps, const RenderOptions& options, FrameStats& stats,
                                          gpu::PassTimer* timer) {
    const PassLights& pass = passes[index];
    lightBlocks.bind(SG_BINDING_LIGHTS, index);
    layerBlocks.bind(SG_BINDING_LAYERS, index);
    gpu::bindShadowResources(resources, maps, pass.sceneLight, ShadowBindingPoints{});
    screen->computeVisibility(frame, pass, litBounds(pass, options), options.screenVisibility, mc.rays, stats, timer);
}

void Renderer::Impl::screenLitPass(const MainCamera& mc, std::size_t index, const RenderOptions& options) {
    const PassLights& pass = passes[index];
    const render::LitProgram& p = *passPrograms[index][0];
    lightBlocks.bind(SG_BINDING_LIGHTS, index);
    gl.BindFramebuffer(GL_FRAMEBUFFER, targets.framebuffer());
    gl.Viewport(0, 0, options.width, options.height);
    const bool resolves = resolvesStage(pass.variant);
    if (resolves) targets.attachMarks(screen->marks());
    if (index == 0 || options.aovs || resolves) {
        targets.bindPass(static_cast<int>(index), resolves ? render::PassOutputs::LitMarks : render::PassOutputs::Lit);
    }
    screen->bindForLighting(materials.materialTargets, pass.variant);
    // Only the pixels the surface pass drew (GREATER than its depth, at the far plane): the
    // background keeps the targets' clear values, as forward leaves it.
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_GREATER);
    gl.DepthMask(GL_FALSE);
    if (index > 0) {
        gl.Enablei(GL_BLEND, 0);
        gl.BlendFunc(GL_ONE, GL_ONE);
    }
    scissorTo(litBounds(pass, options));
    if (resolves) targets.clearMarks();
    const GLuint id = p.program.get();
    gl.UseProgram(id);
    setPassUniforms(p, mc, options);
    gl.BindVertexArray(screen->emptyVertexArray());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_SCISSOR_TEST);
    if (resolves) {
        // Draws no more into the marks: the correction reads them.
        targets.setOutputs(static_cast<int>(index), render::PassOutputs::Lit);
        targets.attachMarks(0);
    }
}

void Renderer::Impl::screenCorrection(const MainCamera& mc, std::size_t index, const RenderOptions& options,
                                      FrameStats& stats) {
    const PassLights& pass = passes[index];
    const PixelRect bounds = litBounds(pass, options);
    const GLuint fb = targets.framebuffer();
    targets.setOutputs(static_cast<int>(index), render::PassOutputs::Correction);
    lightBlocks.bind(SG_BINDING_LIGHTS, index);
    layerBlocks.bind(SG_BINDING_LAYERS, index);
    // It adds the marked lights' shading (and their visibility to the visibility AOVs); the mark
    // passes between its draws write depth alone.
    gl.BlendFunc(GL_ONE, GL_ONE);
    for (const int buffer : {SG_OUT_COLOR, SG_OUT_VISIBILITY0, SG_OUT_VISIBILITY1}) {
        if (buffer == SG_OUT_COLOR || options.aovs) gl.Enablei(GL_BLEND, static_cast<GLuint>(buffer));
    }
    for (std::size_t group = 0; group < pass.variant.resolve.size(); ++group) {
        if (pass.variant.resolve[group] <= 1) continue;
        screen->markCorrection(bounds, 15u << (4u * group), stats);
        gl.BindFramebuffer(GL_FRAMEBUFFER, fb);
        gl.Viewport(0, 0, options.width, options.height);
        // Tested against the marks (GREATER than 0, at depth 0.5): only the marked pixels run.
        gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, screen->correctionDepth(), 0);
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_GREATER);
        gl.DepthMask(GL_FALSE);
        scissorTo(bounds);
        const render::LitProgram& p = *passPrograms[index][1 + group];
        const GLuint id = p.program.get();
        gl.UseProgram(id);
        setPassUniforms(p, mc, options);
        gl.BindVertexArray(screen->emptyVertexArray());
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        gl.Disable(GL_SCISSOR_TEST);
        gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, targets.depthBuffer(), 0);
    }
    gl.Disable(GL_BLEND);
    targets.setOutputs(static_cast<int>(index), render::PassOutputs::Lit);
}

void Renderer::Impl::litPass(const World& world, const CameraView& cam, const MainCamera& mc, std::size_t index,
                             const ShadowMaps& maps, const RenderOptions& options, FrameStats& stats) {
    const PassLights& pass = passes[index];
    const auto& chosen = passPrograms[index];
    // Without AOVs every pass writes colour alone: the draw buffers set by the first stay (a
    // framebuffer change makes a CPU rasteriser flush its batch).
    if (index == 0 || options.aovs) targets.bindPass(static_cast<int>(index));
    lightBlocks.bind(SG_BINDING_LIGHTS, index);
    layerBlocks.bind(SG_BINDING_LAYERS, index);
    gpu::bindShadowResources(resources, maps, pass.sceneLight, ShadowBindingPoints{});
    // The first lit pass resolves visibility itself unless a pre-pass did; the passes after it
    // shade the same surfaces (equal depth, no depth writes) and add their light.
    const bool resolvesDepth = index == 0 && !prepassRan;
    gl.DepthMask(resolvesDepth ? GL_TRUE : GL_FALSE);
    gl.DepthFunc(resolvesDepth ? GL_LESS : GL_EQUAL);
    if (index > 0) {
        gl.Enablei(GL_BLEND, 0);
        gl.BlendFunc(GL_ONE, GL_ONE);
    }
    // A pass lights only its lights' screen bounds. With AOVs every pass covers the screen, so
    // that each light's visibility is written wherever there is geometry.
    const PixelRect bounds = litBounds(pass, options);
    const bool scissored = bounds != PixelRect{0, 0, options.width, options.height};
    if (scissored) scissorTo(bounds);
    const int counted = edgeCounts.slots(index);
    for (const render::LitProgram* program : chosen) {
        if (program == nullptr) continue;
        const GLuint id = program->program.get();
        gl.ProgramUniformMatrix4fv(id, program->mesh.clipFromCs, 1, GL_FALSE, glm::value_ptr(mc.clipFromCs));
        setPassUniforms(*program, mc, options);
        if (program->countSlots >= 0) {
            gl.ProgramUniform1i(id, program->countSlots, counted);
            gl.ProgramUniform1i(id, program->countBase, static_cast<GLint>(render::EdgeCounts::firstCounter(index)));
        }
    }
    drawMeshes(
        world, cam, scissored && !pass.unbounded ? &pass.wsReach : nullptr,
        [this, &chosen](const Mesh& mesh, const Material& m, unsigned deform) {
            const bool withMaps = m.usesMaps() && materials.maps;
            const render::LitProgram& p = *chosen[(withMaps ? gpu::kMeshDeforms : 0) + deform];
            const GLuint program = p.program.get();
            render::setMaterial(program, p.material, mesh, m);
            render::bindMaterialTextures(meshes, m, withMaps);
            return std::pair<GLuint, const render::MeshUniforms*>{program, &p.mesh};
        },
        stats);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_SCISSOR_TEST);
}

namespace {

/// The texture units and uniform-buffer binding points the lit passes bind.
/// The three sampler arrays' units, the distance-field technique's two, the base colour's (the
/// stage as the deferred lit pass resolves it shares it), the other material maps' (the stage's
/// surface targets, its extra target and its sample depths share them) and the stage's visibility.
constexpr std::size_t kLitUnitCount = SG_UNIT_SHADOW_MINMAX + SG_MAX_LIGHTS_PER_PASS + 8;
constexpr std::array<GLint, kLitUnitCount> litTextureUnits() {
    std::array<GLint, kLitUnitCount> units{};
    std::iota(units.begin(), units.end() - 8, 0);
    const std::array<GLint, 8> others{SG_UNIT_SDF_ATLAS,          SG_UNIT_SDF_INSTANCES,    SG_UNIT_BASE_COLOR,
                                      SG_UNIT_METALLIC_ROUGHNESS, SG_UNIT_NORMAL_MAP,       SG_UNIT_OCCLUSION,
                                      SG_UNIT_EMISSIVE,           SG_UNIT_SCREEN_VISIBILITY};
    static_assert(SG_UNIT_GBUFFER_SURFACE == SG_UNIT_METALLIC_ROUGHNESS &&
                  SG_UNIT_GBUFFER_MATERIAL == SG_UNIT_NORMAL_MAP && SG_UNIT_SCREEN_DEPTH == SG_UNIT_OCCLUSION &&
                  SG_UNIT_GBUFFER_EXTRA == SG_UNIT_EMISSIVE && SG_UNIT_LIT_STAGE == SG_UNIT_BASE_COLOR);
    std::copy(others.begin(), others.end(), units.end() - 8);
    return units;
}
constexpr std::array<GLint, kLitUnitCount> kLitTextureUnits = litTextureUnits();
constexpr std::array<GLint, 3> kLitUniformBindings{SG_BINDING_LIGHTS, SG_BINDING_LAYERS, SG_BINDING_KERNELS};

}  // namespace

Status checkRenderSize(const RenderOptions& options, int lights) {
    gpu::requireLoaded("checkRenderSize");
    const int passes = std::max(1, (lights + SG_MAX_LIGHTS_PER_PASS - 1) / SG_MAX_LIGHTS_PER_PASS);
    const std::string why = render::renderSizeProblem(options.width, options.height, options.aovs, passes,
                                                      options.screenVisibility != ScreenVisibility::Off);
    if (!why.empty()) return Error{ErrorCode::LimitExceeded, why};
    return Ok{};
}

Renderer::Renderer() {
    gpu::requireLoaded("Renderer");
    // Before any member makes a GL object: the host's error is reported once, as the renderer's.
    std::vector<Warning> pending;
    gpu::reportHostGlErrors("Renderer", pending, gpu::kMaxPendingWarnings);
    impl_ = std::make_unique<Impl>();
    impl_->pending = std::move(pending);
}
Renderer::~Renderer() = default;

MeshCache& Renderer::meshes() { return impl_->meshes; }

void Renderer::setTiming(bool enabled) { impl_->timer.setEnabled(enabled); }

void Renderer::render(const World& world, const CameraView& camera, const ShadowSystem& shadows,
                      const RenderOptions& options, FrameStats& stats) {
    render(world, camera, shadows.frame(), shadows.maps(), options, stats);
}

void Renderer::render(const World& world, const CameraView& camera, const ShadowFrame& frame, const ShadowMaps& maps,
                      const RenderOptions& options, FrameStats& stats) {
    gpu::reportHostGlErrors("Renderer::render", stats);
    gpu::movePendingWarnings(impl_->pending, stats.warnings);
    gpu::movePendingWarnings(gpu::MeshCacheAccess::pending(impl_->meshes), stats.warnings);
    const gpu::GlStateGuard hostState(kLitTextureUnits, kLitUniformBindings);
    Impl& r = *impl_;
    // The cache's owner collects it: the GPU copies of meshes gone since the last frame.
    gpu::MeshCacheAccess::collect(r.meshes);
    r.lightCount = frame.lights.size();
    const ScreenView view{cameraClipFromWorld(camera), options.width, options.height, frame.wsGeometry};
    render::packLights(frame, camera.wsPosition, view, r.passes, r.packingOrder);
    // Technique sdf: the field casters' records relative to this camera, which every pass binds.
    if ((frame.techniquesInUse & techniqueBit(ShadowTechnique::Sdf)) != 0) (void)maps.fieldInstances(camera.wsPosition);
    r.materials = frameMaterials(world);
    r.deferred = options.debugView == DebugView::None &&
                 render::screenStagePays(options.screenVisibility, frame, r.passes, options.height);
    r.edgeCounts.collect(stats.edgeCounts, false);  // an earlier frame's, if the GPU is done with them
    r.preparePrograms(frame, options, stats);
    const bool countsEdges = r.edgeCounts.prepare(frame, r.passes, stats.edgeCounts);
    r.uploadPasses();
    r.targets.ensure(options.width, options.height, options.aovs, static_cast<int>(r.passes.size()));
    if (r.deferred) r.prepareScreenStage(options);

    const MainCamera mc = mainCamera(camera, options.width, options.height);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r.targets.framebuffer());
    gl.Viewport(0, 0, options.width, options.height);
    gpu::setPassDefaults();  // counter-clockwise front faces, GL's default and glTF's
    gl.CullFace(GL_BACK);
    gl.Enable(GL_DEPTH_TEST);
    r.targets.clear();
    if (r.deferred) {
        r.renderScreenSpace(world, camera, frame, mc, maps, options, stats);
    } else {
        r.renderForward(world, camera, mc, maps, options, stats);
    }
    if (countsEdges) r.edgeCounts.submitted();
    stats.mainPasses += static_cast<int>(r.passes.size());
    gl.DepthMask(GL_TRUE);
    gl.DepthFunc(GL_LESS);
    gl.BindVertexArray(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gpu::checkGlError("main pass");
    r.timer.collect(stats);
}

const std::vector<Warning>& Renderer::warnings() const { return impl_->pending; }

void Renderer::clearWarnings() { impl_->pending.clear(); }

namespace {

/// The one texture unit the present passes bind (the frame's colour).
constexpr std::array<GLint, 1> kPresentUnits{0};

}  // namespace

render::Presenter& Renderer::Impl::presenterOf() {
    if (!presenter) presenter.emplace();
    return *presenter;
}

LuminanceHistogram Renderer::meterExposure(FrameStats& stats) {
    gpu::reportHostGlErrors("Renderer::meterExposure", stats);
    Impl& r = *impl_;
    if (r.targets.width() == 0) return {};
    const gpu::GlStateGuard hostState(kPresentUnits, {});
    gpu::PassTimer timer(true);  // wall clock: the counters are read back at once
    timer.setEnabled(r.timer.enabled());
    timer.begin("Present/Meter");
    const LuminanceHistogram counts = r.presenterOf().meter(r.targets.color(), r.targets.width(), r.targets.height());
    timer.end();
    timer.collect(stats);
    gpu::checkGlError("meterExposure");
    return counts;
}

GlTexture Renderer::presentToTexture(float exposure, FrameStats& stats) {
    gpu::reportHostGlErrors("Renderer::presentToTexture", stats);
    Impl& r = *impl_;
    if (r.targets.width() == 0) return {};
    const gpu::GlStateGuard hostState(kPresentUnits, {});
    gpu::PassTimer timer(true);
    timer.setEnabled(r.timer.enabled());
    timer.begin("Present/ToneMap");
    const GLuint display = r.presenterOf().toneMap(r.targets.color(), r.targets.width(), r.targets.height(), exposure);
    timer.end();
    timer.collect(stats);
    gpu::checkGlError("presentToTexture");
    return GlTexture{display};
}

std::vector<std::uint8_t> Renderer::readPresented() const {
    gpu::reportHostGlErrors("Renderer::readPresented", impl_->pending, gpu::kMaxPendingWarnings);
    if (!impl_->presenter) return {};
    const gpu::GlStateGuard hostState({}, {});
    std::vector<std::uint8_t> rgb = impl_->presenter->readDisplay();
    gpu::checkGlError("readPresented");
    return rgb;
}

void Renderer::present(int width, int height, float exposure) {
    gpu::reportHostGlErrors("Renderer::present", impl_->pending, gpu::kMaxPendingWarnings);
    FrameStats untimed;  // the host's errors are taken above: none reaches it
    if (!presentToTexture(exposure, untimed)) return;
    const gpu::GlStateGuard hostState({}, {});
    const render::Presenter& p = *impl_->presenter;
    // The display texture's row 0 is the top; the window's is the bottom: flipped.
    gl.BlitNamedFramebuffer(p.displayFramebuffer(), 0, 0, 0, p.width(), p.height(), 0, height, width, 0,
                            GL_COLOR_BUFFER_BIT, GL_LINEAR);
    gpu::checkGlError("present");
}

FrameImages Renderer::readback(const CameraView& camera, FrameStats& stats) const {
    gpu::reportHostGlErrors("Renderer::readback", stats);
    gpu::movePendingWarnings(impl_->pending, stats.warnings);
    const gpu::GlStateGuard hostState({}, {});
    const Impl& r = *impl_;
    const render::RenderTargets& t = r.targets;
    FrameImages out;
    // Wall clock on every renderer: reading pixels back waits for the GPU anyway, and a query
    // read a frame later would outlive this call.
    gpu::PassTimer timer(true);
    timer.setEnabled(r.timer.enabled());
    timer.begin("Readback");
    const GLuint fb = t.framebuffer();
    auto read = [&](GLenum attachment, GLenum format, int channels) {
        ImageF img = makeImage(t.width(), t.height(), channels);
        gl.NamedFramebufferReadBuffer(fb, attachment);
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fb);
        gpu::setReadbackDefaults();
        std::vector<float> raw(img.pixels.size());
        gl.ReadPixels(0, 0, t.width(), t.height(), format, GL_FLOAT, raw.data());
        // GL rows start at the bottom; images here start at the top.
        const std::size_t row = static_cast<std::size_t>(t.width()) * channels;
        for (int y = 0; y < t.height(); ++y) {
            std::copy_n(raw.begin() + static_cast<std::ptrdiff_t>(row * (t.height() - 1 - y)), row,
                        img.pixels.begin() + static_cast<std::ptrdiff_t>(row * y));
        }
        return img;
    };
    out.color = read(GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, GL_RGB, 3);
    if (t.aovs()) {
        out.position = read(GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION, GL_RGBA, 4);
        for (std::size_t i = 0; i < out.position.pixels.size(); i += 4) {
            float* p = &out.position.pixels[i];
            if (p[3] > 0.5f) {
                for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(p[c] + camera.wsPosition[c]);
            }
        }
        out.depth = read(GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH, GL_RED, 1);
        // Every scene light has an image; a light no pass shaded keeps visibility 1.
        ImageF lit = makeImage(t.width(), t.height(), 1);
        std::fill(lit.pixels.begin(), lit.pixels.end(), 1.0f);
        out.visibility.assign(r.lightCount, lit);
        for (std::size_t pass = 0; pass < r.passes.size(); ++pass) {
            const PassLights& p = r.passes[pass];
            for (int first = 0; first < p.variant.lights; first += 4) {  // four slots per texture
                gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0,
                                           t.visibility(static_cast<int>(pass), first), 0);
                const ImageF rgba = read(GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0, GL_RGBA, 4);
                for (int slot = first; slot < std::min(first + 4, p.variant.lights); ++slot) {
                    ImageF& v = out.visibility[static_cast<std::size_t>(p.sceneLight[static_cast<std::size_t>(slot)])];
                    for (std::size_t i = 0; i < v.pixels.size(); ++i) v.pixels[i] = rgba.pixels[i * 4 + slot % 4];
                }
            }
        }
    }
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    timer.end();
    timer.collect(stats);
    gpu::checkGlError("readback");
    return out;
}

const char* screenVisibilityName(ScreenVisibility v) {
    switch (v) {
        case ScreenVisibility::Off: return "off";
        case ScreenVisibility::Auto: return "auto";
        case ScreenVisibility::Full: return "full";
        case ScreenVisibility::Half: return "half";
        case ScreenVisibility::Quarter: return "quarter";
    }
    return "off";
}

std::optional<ScreenVisibility> parseScreenVisibility(std::string_view name) {
    for (const ScreenVisibility v : {ScreenVisibility::Off, ScreenVisibility::Auto, ScreenVisibility::Full,
                                     ScreenVisibility::Half, ScreenVisibility::Quarter}) {
        if (name == screenVisibilityName(v)) return v;
    }
    return std::nullopt;
}

}  // namespace shadow
