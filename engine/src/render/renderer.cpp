// The forward renderer (see renderer.h): light and layer buffers, shader variants per set of
// techniques, the lit passes, and readback of colour and AOVs.
#include <shadow/context.h>
#include <shadow/renderer.h>

#include "gl/objects.h"
#include "gl/program.h"
#include "render/gpu_types.h"
#include "render/pass_timer.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <string_view>

namespace shadow {
namespace {

/// Best-candidate (Mitchell) Poisson disk in the unit disk: each point is the candidate farthest
/// from those before it, so every prefix of the sequence is well spread. Deterministic.
std::vector<glm::vec2> poissonDisk(int count) {
    std::vector<glm::vec2> points;
    std::uint32_t state = 0x9e3779b9u;
    auto next = [&state] {  // xorshift32
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        return static_cast<float>(state) * (1.0f / 4294967296.0f);
    };
    while (static_cast<int>(points.size()) < count) {
        glm::vec2 best(0.0f);
        float bestDistance = -1.0f;
        for (int c = 0; c < 32 * static_cast<int>(points.size() + 1); ++c) {
            const float r = std::sqrt(next());
            const float a = 6.28318531f * next();
            const glm::vec2 candidate(r * std::cos(a), r * std::sin(a));
            float nearest = 4.0f;
            for (const glm::vec2& p : points) nearest = std::min(nearest, glm::distance(p, candidate));
            if (nearest > bestDistance) {
                bestDistance = nearest;
                best = candidate;
            }
        }
        points.push_back(best);
    }
    return points;
}

/// A compiled variant of the lit program and its uniform locations.
struct LitProgram {
    gpu::Program program;
    GLint csFromLocal = -1, normalFromLocal = -1, clipFromCs = -1;
    GLint firstLight = -1, lightCount = -1, receiveShadows = -1;
    GLint albedo = -1, specular = -1, shininess = -1, ambient = -1, cameraForward = -1;
    GLint debugView = -1, debugLight = -1;
};

/// Bit per technique (1 << SG_TECH_*) plus the AOV flag: the key of a program variant.
using VariantKey = unsigned;
constexpr unsigned kAovBit = 1u << 16;

LitProgram buildLit(VariantKey key) {
    gpu::ProgramDesc desc;
    desc.vertexFile = "lit.vert.glsl";
    desc.fragmentFile = "lit.frag.glsl";
    std::string name;
    const std::array<std::pair<int, const char*>, 4> techniques = {{{SG_TECH_HARD, "HARD"},
                                                                    {SG_TECH_PCF, "PCF"},
                                                                    {SG_TECH_PCSS, "PCSS"},
                                                                    {SG_TECH_PCSS_TEXTBOOK, "PCSS_TEXTBOOK"}}};
    for (const auto& [id, label] : techniques) {
        if (key & (1u << id)) {
            desc.defines.push_back(std::string("SG_TECH_") + label + "_ENABLED");
            if (!name.empty()) name += ',';
            name += label;
        }
    }
    if (key & kAovBit) desc.defines.emplace_back("SG_WRITE_AOVS");
    if (key & kAovBit) name += name.empty() ? "AOV" : ",AOV";
    desc.label = "Main/Lit[" + name + "]";
    LitProgram p;
    p.program = gpu::buildProgram(desc);
    const GLuint id = p.program.get();
    auto loc = [id](const char* n) { return gl.GetUniformLocation(id, n); };
    p.csFromLocal = loc("uCsFromLocal");
    p.normalFromLocal = loc("uNormalFromLocal");
    p.clipFromCs = loc("uClipFromCs");
    p.firstLight = loc("uFirstLight");
    p.lightCount = loc("uLightCount");
    p.receiveShadows = loc("uReceiveShadows");
    p.albedo = loc("uAlbedo");
    p.specular = loc("uSpecular");
    p.shininess = loc("uShininess");
    p.ambient = loc("uAmbient");
    p.cameraForward = loc("uCameraForward");
    p.debugView = loc("uDebugView");
    p.debugLight = loc("uDebugLight");
    static const std::vector<glm::vec2> disk = poissonDisk(SG_MAX_SAMPLES);
    gl.ProgramUniform2fv(id, loc("uPoissonDisk"), SG_MAX_SAMPLES, glm::value_ptr(disk[0]));
    return p;
}

/// A storage buffer that grows to the largest size asked of it and is otherwise reused.
struct GrowingBuffer {
    gpu::Buffer buffer;
    std::size_t capacity = 0;

    void upload(const std::string& label, const void* data, std::size_t bytes) {
        if (bytes > capacity || !buffer) {
            capacity = std::max<std::size_t>(bytes, 256);
            buffer = gpu::makeBuffer(label, static_cast<GLsizeiptr>(capacity), nullptr, GL_DYNAMIC_STORAGE_BIT);
        }
        if (bytes > 0) gl.NamedBufferSubData(buffer.get(), 0, static_cast<GLsizeiptr>(bytes), data);
    }
};

/// The offscreen targets of the main pass.
struct Targets {
    int width = 0, height = 0, visibilityTextures = 0;
    gpu::Framebuffer framebuffer;
    gpu::Texture color, position, depthAov, depthBuffer;
    std::vector<gpu::Texture> visibility;  // two RGBA per pass: lights 0-3 and 4-7 of the pass
};

gpu::Texture makeTarget(const std::string& label, GLenum format, int w, int h) {
    gpu::Texture t = gpu::makeTexture(label, GL_TEXTURE_2D);
    gl.TextureStorage2D(t.get(), 1, format, w, h);
    return t;
}

int lightTypeId(LightType t) {
    switch (t) {
        case LightType::Directional: return SG_LIGHT_DIRECTIONAL;
        case LightType::Spot: return SG_LIGHT_SPOT;
        case LightType::Point: return SG_LIGHT_POINT;
    }
    return SG_LIGHT_POINT;
}

int techniqueId(ShadowTechnique t) {
    switch (t) {
        case ShadowTechnique::None: return SG_TECH_NONE;
        case ShadowTechnique::Hard: return SG_TECH_HARD;
        case ShadowTechnique::Pcf: return SG_TECH_PCF;
        case ShadowTechnique::Pcss: return SG_TECH_PCSS;
        case ShadowTechnique::PcssTextbook: return SG_TECH_PCSS_TEXTBOOK;
    }
    return SG_TECH_NONE;
}

int debugViewId(DebugView v) {
    switch (v) {
        case DebugView::None: return SG_DEBUG_NONE;
        case DebugView::Cascade: return SG_DEBUG_CASCADE;
        case DebugView::BlockerDepth: return SG_DEBUG_BLOCKER_DEPTH;
        case DebugView::Penumbra: return SG_DEBUG_PENUMBRA;
        case DebugView::Visibility: return SG_DEBUG_VISIBILITY;
    }
    return SG_DEBUG_NONE;
}

/// The light's name for messages.
std::string_view nameOf(const World& world, Entity e) {
    const Name* n = world.tryGet<Name>(e);
    return n != nullptr ? std::string_view(n->value) : std::string_view("light");
}

/// The light as the shader sees it, without shadow data.
gpu::GpuLight packLight(const Light& light, const WorldTransform& wt, const glm::dvec3& camera) {
    gpu::GpuLight g{};
    g.csPosition = glm::vec3(glm::dvec3(wt.worldFromLocal[3]) - camera);
    glm::dvec3 dir = -glm::dvec3(wt.worldFromLocal[2]);
    const double len = glm::length(dir);
    g.wsDirection = glm::vec3(len > 1e-12 && std::isfinite(len) ? dir / len : glm::dvec3(0, 0, -1));
    g.type = lightTypeId(light.type);
    g.range = light.range;
    g.radiance = light.color * light.intensity;
    g.emitterSize = light.type == LightType::Directional ? light.angularRadius : light.radius;
    g.cosOuter = std::cos(light.outerConeAngle);
    g.cosInner = std::cos(light.innerConeAngle);
    g.technique = SG_TECH_NONE;
    return g;
}

/// Adds the shadow data of `plan` to `g` and its layers to `layers`.
void packShadow(const ShadowLightPlan& plan, const glm::dvec3& camera, gpu::GpuLight& g,
                std::vector<gpu::GpuShadowLayer>& layers) {
    const Shadow& s = plan.settings;
    g.technique = techniqueId(s.technique);
    g.emitterSize = plan.light.type == LightType::Directional ? plan.light.angularRadius : plan.light.radius;
    g.layerCount = static_cast<int>(plan.layers.size());
    g.constantBias = s.constantBias;
    g.slopeBias = s.slopeBias;
    g.normalOffset = s.normalOffset;
    g.pcfRadius = s.pcfRadius;
    g.pcfSamples = s.pcfSamples;
    g.blockerSamples = s.blockerSamples;
    g.maxFilterTexels = s.maxFilterTexels;
    g.mapSize = static_cast<float>(plan.mapSize);
    g.firstLayer = static_cast<int>(layers.size());
    g.cascadeBlend = s.cascadeBlend;
    g.kernel = static_cast<int>(s.kernel);
    const glm::dmat4 worldFromCs = glm::translate(glm::dmat4(1.0), camera);
    for (const ShadowLayerPlan& layer : plan.layers) {
        gpu::GpuShadowLayer l{};
        l.lightFromWorld = glm::mat4(layer.lightFromWorld * worldFromCs);
        l.clipFromLight = glm::mat4(layer.clipFromLight);
        l.depthScale = layer.depthScale;
        l.depthNear = layer.depthNear;
        l.splitFar = layer.splitFar;
        l.orthographic = layer.orthographic ? 1 : 0;
        layers.push_back(l);
    }
}

}  // namespace

struct Renderer::Impl {
    MeshCache meshes;
    std::map<VariantKey, LitProgram> programs;
    GrowingBuffer lightBuffer, layerBuffer;
    std::vector<gpu::GpuLight> lights;
    std::vector<gpu::GpuShadowLayer> layers;
    std::vector<std::string> scratchWarnings;
    gpu::Sampler compareSampler, depthSampler;
    Targets targets;
    bool aovs = false;
    int lightCount = 0;
    bool softwareRenderer = false;

    Impl() {
        softwareRenderer = queryGlInfo().softwareRenderer;
        GLuint s[2] = {0, 0};
        gl.CreateSamplers(2, s);
        compareSampler = gpu::Sampler(s[0]);
        depthSampler = gpu::Sampler(s[1]);
        const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // outside the map: nothing blocks
        for (const gpu::Sampler* smp : {&compareSampler, &depthSampler}) {
            gl.SamplerParameteri(smp->get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
            gl.SamplerParameteri(smp->get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
            gl.SamplerParameterfv(smp->get(), GL_TEXTURE_BORDER_COLOR, border);
        }
        // Hardware comparison with linear filtering: every tap is a 2x2 bilinear PCF.
        gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.SamplerParameteri(depthSampler.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.SamplerParameteri(depthSampler.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        compareSampler.label("Shadow/compareSampler");
        depthSampler.label("Shadow/depthSampler");
    }

    LitProgram& program(VariantKey key, FrameStats& stats) {
        auto it = programs.find(key);
        if (it == programs.end()) {
            it = programs.emplace(key, buildLit(key)).first;
            ++stats.programsCompiled;
        }
        return it->second;
    }

    void ensureTargets(int w, int h, int visibilityTextures);
    void drawPass(World& world, const CameraView& cam, const LitProgram& p, int firstLight, int count,
                  const ShadowSystem& shadows, const RenderOptions& options, FrameStats& stats);
};

void Renderer::Impl::ensureTargets(int w, int h, int visibilityTextures) {
    Targets& t = targets;
    if (t.width == w && t.height == h && t.visibilityTextures >= visibilityTextures && t.framebuffer) return;
    t = Targets{};
    t.width = w;
    t.height = h;
    t.visibilityTextures = visibilityTextures;
    t.framebuffer = gpu::makeFramebuffer("Main/framebuffer");
    t.color = makeTarget("Main/color", GL_RGBA32F, w, h);
    t.position = makeTarget("Main/position", GL_RGBA32F, w, h);
    t.depthAov = makeTarget("Main/depth", GL_R32F, w, h);
    t.depthBuffer = makeTarget("Main/depthBuffer", GL_DEPTH_COMPONENT32F, w, h);
    for (int i = 0; i < visibilityTextures; ++i) {
        t.visibility.push_back(makeTarget("Main/visibility" + std::to_string(i), GL_RGBA32F, w, h));
    }
    const GLuint fb = t.framebuffer.get();
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, t.color.get(), 0);
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION, t.position.get(), 0);
    gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH, t.depthAov.get(), 0);
    gl.NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, t.depthBuffer.get(), 0);
}

void Renderer::Impl::drawPass(World& world, const CameraView& cam, const LitProgram& p, int firstLight,
                              int count, const ShadowSystem& shadows, const RenderOptions& options,
                              FrameStats& stats) {
    const GLuint id = p.program.get();
    gl.UseProgram(id);
    gl.ProgramUniform1i(id, p.firstLight, firstLight);
    gl.ProgramUniform1i(id, p.lightCount, count);
    const glm::vec3 ambient = firstLight == 0 ? options.ambient : glm::vec3(0.0f);
    gl.ProgramUniform3fv(id, p.ambient, 1, glm::value_ptr(ambient));
    const glm::dmat4 viewFromCs = cam.viewFromWorld * glm::translate(glm::dmat4(1.0), cam.wsPosition);
    const glm::dmat4 clipFromView = glm::perspective(static_cast<double>(cam.yfov), static_cast<double>(cam.aspect),
                                                     static_cast<double>(cam.znear), static_cast<double>(cam.zfar));
    gl.ProgramUniformMatrix4fv(id, p.clipFromCs, 1, GL_FALSE, glm::value_ptr(glm::mat4(clipFromView * viewFromCs)));
    const glm::vec3 forward(-glm::dvec3(glm::transpose(cam.viewFromWorld)[2]));
    gl.ProgramUniform3fv(id, p.cameraForward, 1, glm::value_ptr(glm::normalize(forward)));
    const int debugSlot = options.debugLight - firstLight;
    gl.ProgramUniform1i(id, p.debugView, debugViewId(options.debugView));
    gl.ProgramUniform1i(id, p.debugLight, debugSlot >= 0 && debugSlot < count ? debugSlot : -1);

    // Bind each slot's shadow array to its comparison unit and its raw-depth unit.
    const ShadowFrame& frame = shadows.frame();
    for (int slot = 0; slot < SG_MAX_LIGHTS_PER_PASS; ++slot) {
        GLuint texture = 0;
        if (slot < count) {
            for (std::size_t i = 0; i < frame.lights.size(); ++i) {
                if (frame.lights[i].sceneIndex == firstLight + slot) texture = shadows.textureOf(i);
            }
        }
        gl.BindTextureUnit(SG_UNIT_SHADOW_COMPARE + slot, texture);
        gl.BindSampler(SG_UNIT_SHADOW_COMPARE + slot, compareSampler.get());
        gl.BindTextureUnit(SG_UNIT_SHADOW_DEPTH + slot, texture);
        gl.BindSampler(SG_UNIT_SHADOW_DEPTH + slot, depthSampler.get());
    }

    world.view<Mesh, WorldTransform, Material>().each([&](Entity, Mesh& mesh, WorldTransform& wt, Material& m) {
        if (!wt.finite || mesh.data == nullptr || mesh.data->indices.empty()) return;
        const glm::dmat3 linear(wt.worldFromLocal);
        const double det = glm::determinant(linear);
        if (!(std::abs(det) > 1e-30)) return;  // collapsed to zero area: nothing to see
        glm::dmat4 csFromLocal = wt.worldFromLocal;
        csFromLocal[3] -= glm::dvec4(cam.wsPosition, 0.0);
        gl.ProgramUniformMatrix4fv(id, p.csFromLocal, 1, GL_FALSE, glm::value_ptr(glm::mat4(csFromLocal)));
        const glm::mat3 normalFromLocal(glm::transpose(glm::inverse(linear)));
        gl.ProgramUniformMatrix3fv(id, p.normalFromLocal, 1, GL_FALSE, glm::value_ptr(normalFromLocal));
        gl.ProgramUniform1i(id, p.receiveShadows, mesh.receiveShadows ? 1 : 0);
        gl.ProgramUniform3fv(id, p.albedo, 1, glm::value_ptr(m.albedo));
        gl.ProgramUniform3fv(id, p.specular, 1, glm::value_ptr(m.specular));
        gl.ProgramUniform1f(id, p.shininess, std::clamp(m.shininess, 1.0f, 4096.0f));
        const int indices = meshes.bind(mesh.data);
        gl.DrawElements(GL_TRIANGLES, indices, GL_UNSIGNED_INT, nullptr);
        ++stats.mainDrawCalls;
    });
}

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

MeshCache& Renderer::meshes() { return impl_->meshes; }

void Renderer::render(World& world, const CameraView& camera, const std::vector<Entity>& lights,
                      const ShadowSystem& shadows, const RenderOptions& options, FrameStats& stats) {
    Impl& r = *impl_;
    // Light and layer buffers: every scene light, in scene order, camera-relative.
    r.lights.clear();
    r.layers.clear();
    const ShadowFrame& frame = shadows.frame();
    VariantKey key = options.aovs ? kAovBit : 0u;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light* light = world.tryGet<Light>(lights[i]);
        const WorldTransform* wt = world.tryGet<WorldTransform>(lights[i]);
        const auto plan = std::find_if(
            frame.lights.begin(), frame.lights.end(),
            [&](const ShadowLightPlan& p) { return p.sceneIndex == static_cast<int>(i); });
        // A light without a Light or with a non-finite transform (reported by the transform
        // system) contributes nothing; its visibility stays 1.
        gpu::GpuLight g{};
        if (light != nullptr && wt != nullptr && wt->finite) {
            // Out-of-range fields are drawn clamped. The planner reported those of every light it
            // planned (all with a Shadow of a technique other than None); report the others here.
            Light shaded = *light;
            r.scratchWarnings.clear();
            clampLight(shaded, nameOf(world, lights[i]), r.scratchWarnings);
            const Shadow* shadow = world.tryGet<Shadow>(lights[i]);
            if (shadow == nullptr || shadow->technique == ShadowTechnique::None) {
                stats.warnings.insert(stats.warnings.end(), r.scratchWarnings.begin(),
                                      r.scratchWarnings.end());
            }
            g = packLight(shaded, *wt, camera.wsPosition);
        }
        if (plan != frame.lights.end()) {
            packShadow(*plan, camera.wsPosition, g, r.layers);
            key |= 1u << g.technique;
        }
        r.lights.push_back(g);
    }
    r.lightCount = static_cast<int>(r.lights.size());
    r.lightBuffer.upload("Main/lights", r.lights.data(), r.lights.size() * sizeof(gpu::GpuLight));
    r.layerBuffer.upload("Main/shadowLayers", r.layers.data(), r.layers.size() * sizeof(gpu::GpuShadowLayer));
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SG_BINDING_LIGHTS, r.lightBuffer.buffer.get());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SG_BINDING_LAYERS, r.layerBuffer.buffer.get());

    const int passes = std::max(1, (r.lightCount + SG_MAX_LIGHTS_PER_PASS - 1) / SG_MAX_LIGHTS_PER_PASS);
    r.aovs = options.aovs;
    r.ensureTargets(options.width, options.height, options.aovs ? 2 * passes : 0);
    LitProgram& program = r.program(key, stats);

    gpu::PassTimer timer(r.softwareRenderer);
    const GLuint fb = r.targets.framebuffer.get();
    gl.BindFramebuffer(GL_FRAMEBUFFER, fb);
    gl.Viewport(0, 0, options.width, options.height);
    gl.Disable(GL_CULL_FACE);  // two-sided: open meshes are seen from both sides
    gl.Enable(GL_DEPTH_TEST);
    for (int pass = 0; pass < passes; ++pass) {
        const int first = pass * SG_MAX_LIGHTS_PER_PASS;
        const int count = std::clamp(r.lightCount - first, 0, SG_MAX_LIGHTS_PER_PASS);
        std::array<GLenum, 5> buffers = {GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, GL_NONE, GL_NONE, GL_NONE, GL_NONE};
        GLsizei bufferCount = 1;
        if (options.aovs) {
            gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0, r.targets.visibility[2 * pass].get(), 0);
            gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY1,
                                       r.targets.visibility[2 * pass + 1].get(), 0);
            // Position and depth are written once, by the first pass.
            const GLenum position = pass == 0 ? GLenum{GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION} : GLenum{GL_NONE};
            const GLenum depth = pass == 0 ? GLenum{GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH} : GLenum{GL_NONE};
            buffers = {GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, position, depth, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0,
                       GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY1};
            bufferCount = 5;
        }
        gl.NamedFramebufferDrawBuffers(fb, bufferCount, buffers.data());
        gpu::checkGlError("main pass framebuffer");
        if (gl.CheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw GlError("main pass framebuffer is incomplete");
        }
        gpu::ScopedPass timed(timer, pass == 0 ? "Main/Lit" : "Main/Lit" + std::to_string(pass));
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        if (pass == 0) {
            const float farDepth = 1.0f;
            gl.DepthMask(GL_TRUE);
            gl.ClearNamedFramebufferfv(fb, GL_DEPTH, 0, &farDepth);
            gl.ClearNamedFramebufferfv(fb, GL_COLOR, 0, zero);
            gl.DepthFunc(GL_LESS);
            gl.Disable(GL_BLEND);
        } else {
            // Later passes add light onto the same surfaces: equal depth, additive colour only.
            gl.DepthMask(GL_FALSE);
            gl.DepthFunc(GL_EQUAL);
            gl.Enablei(GL_BLEND, 0);
            gl.BlendFunc(GL_ONE, GL_ONE);
        }
        if (options.aovs) {
            if (pass == 0) {
                gl.ClearNamedFramebufferfv(fb, GL_COLOR, 1, zero);
                gl.ClearNamedFramebufferfv(fb, GL_COLOR, 2, zero);
            }
            gl.ClearNamedFramebufferfv(fb, GL_COLOR, 3, one);
            gl.ClearNamedFramebufferfv(fb, GL_COLOR, 4, one);
        }
        r.drawPass(world, camera, program, first, count, shadows, options, stats);
        ++stats.mainPasses;
    }
    gl.Disable(GL_BLEND);
    gl.DepthMask(GL_TRUE);
    gl.DepthFunc(GL_LESS);
    gl.BindVertexArray(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gpu::checkGlError("main pass");
    timer.collect(stats);
}

void Renderer::present(int width, int height) const {
    const Targets& t = impl_->targets;
    gl.NamedFramebufferReadBuffer(t.framebuffer.get(), GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR);
    gl.BlitNamedFramebuffer(t.framebuffer.get(), 0, 0, 0, t.width, t.height, 0, 0, width, height, GL_COLOR_BUFFER_BIT,
                            GL_LINEAR);
    gpu::checkGlError("present");
}

FrameImages Renderer::readback(const CameraView& camera, FrameStats& stats) const {
    const Impl& r = *impl_;
    const Targets& t = r.targets;
    FrameImages out;
    gpu::PassTimer timer(r.softwareRenderer);
    timer.begin("Readback");
    const GLuint fb = t.framebuffer.get();
    auto read = [&](GLenum attachment, GLenum format, int channels) {
        ImageF img = makeImage(t.width, t.height, channels);
        gl.NamedFramebufferReadBuffer(fb, attachment);
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fb);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        std::vector<float> raw(img.pixels.size());
        gl.ReadPixels(0, 0, t.width, t.height, format, GL_FLOAT, raw.data());
        // GL rows start at the bottom; images here start at the top.
        const std::size_t row = static_cast<std::size_t>(t.width) * channels;
        for (int y = 0; y < t.height; ++y) {
            std::copy_n(raw.begin() + static_cast<std::ptrdiff_t>(row * (t.height - 1 - y)), row,
                        img.pixels.begin() + static_cast<std::ptrdiff_t>(row * y));
        }
        return img;
    };
    out.color = read(GL_COLOR_ATTACHMENT0 + SG_OUT_COLOR, GL_RGB, 3);
    if (r.aovs) {
        out.position = read(GL_COLOR_ATTACHMENT0 + SG_OUT_POSITION, GL_RGBA, 4);
        for (std::size_t i = 0; i < out.position.pixels.size(); i += 4) {
            float* p = &out.position.pixels[i];
            if (p[3] > 0.5f) {
                for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(p[c] + camera.wsPosition[c]);
            }
        }
        out.depth = read(GL_COLOR_ATTACHMENT0 + SG_OUT_DEPTH, GL_RED, 1);
        // Each pass's two visibility targets hold its lights 0-3 and 4-7.
        for (int light = 0; light < r.lightCount; ++light) {
            const int pass = light / SG_MAX_LIGHTS_PER_PASS;
            const int slot = light % SG_MAX_LIGHTS_PER_PASS;
            const Targets& tt = t;
            const GLuint tex = tt.visibility[static_cast<std::size_t>(2 * pass + slot / 4)].get();
            gl.NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0, tex, 0);
            ImageF rgba = read(GL_COLOR_ATTACHMENT0 + SG_OUT_VISIBILITY0, GL_RGBA, 4);
            ImageF v = makeImage(t.width, t.height, 1);
            for (std::size_t p = 0; p < v.pixels.size(); ++p) v.pixels[p] = rgba.pixels[p * 4 + slot % 4];
            out.visibility.push_back(std::move(v));
        }
    }
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    timer.end();
    timer.collect(stats);
    gpu::checkGlError("readback");
    return out;
}

}  // namespace shadow
