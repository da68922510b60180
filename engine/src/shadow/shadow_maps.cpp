// ShadowMaps: the GPU "do" phase. Each shadowed light owns one GL_TEXTURE_2D_ARRAY of
// GL_DEPTH_COMPONENT32F layers holding linear depth (see shaders/shadow_depth.frag.glsl).
#include <shadow/context.h>
#include <shadow/mesh_cache.h>
#include <shadow/shadow_maps.h>
#include <shadow/shared_constants.h>

#include "gl/gl_state.h"
#include "gl/mesh_cache_access.h"
#include "gl/no_throw.h"
#include "gl/objects.h"
#include "gl/pass_timer.h"
#include "gl/program.h"
#include "shadow/filter_chain.h"
#include "shadow/map_memory.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <optional>
#include <string_view>

namespace shadow {

namespace {

/// One shadowed light's depth texture array and the framebuffer its layers are drawn through.
struct ShadowMapGpu {
    gpu::Texture array;
    gpu::Framebuffer framebuffer;
    int mapSize = 0;
    int layers = 0;
    /// Per layer: stored depth -> metres, as last drawn (readLayerDepth).
    std::vector<float> depthScales;
    /// For the techniques that read one only (filterChainOf); `chainCurrent[k]` once layer k's
    /// chain matches its map.
    std::optional<FilterChain> chain;
    std::vector<bool> chainCurrent;
    /// Made this frame (a new light, or a new map size or layer count): its texture name changed.
    bool allocatedThisFrame = true;
};

/// The depth-only program shared by every light type.
struct DepthProgram {
    gpu::Program program;
    GLint lightFromLocal = -1;
    GLint clipFromLight = -1;
    GLint depthScale = -1;
    GLint orthographic = -1;

    DepthProgram() {
        program = gpu::buildProgram({"Shadow/Depth", "shadow_depth.vert.glsl", "shadow_depth.frag.glsl", {}});
        lightFromLocal = gl.GetUniformLocation(program.get(), "uLightFromLocal");
        clipFromLight = gl.GetUniformLocation(program.get(), "uClipFromLight");
        depthScale = gl.GetUniformLocation(program.get(), "uDepthScale");
        orthographic = gl.GetUniformLocation(program.get(), "uOrthographic");
    }
};

std::unique_ptr<ShadowMapGpu> allocate(const ShadowLightPlan& plan) {
    auto map = std::make_unique<ShadowMapGpu>();
    const std::string label = "Shadow/" + plan.name;
    map->mapSize = plan.mapSize;
    map->layers = static_cast<int>(plan.layers.size());
    map->depthScales.assign(plan.layers.size(), 1.0f);
    map->array = gpu::makeTexture(label + "/array", GL_TEXTURE_2D_ARRAY);
    gl.TextureStorage3D(map->array.get(), 1, GL_DEPTH_COMPONENT32F, map->mapSize, map->mapSize, map->layers);
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);  // the pyramid's gathers
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    map->framebuffer = gpu::makeFramebuffer(label + "/framebuffer");
    gl.NamedFramebufferDrawBuffer(map->framebuffer.get(), GL_NONE);
    gl.NamedFramebufferReadBuffer(map->framebuffer.get(), GL_NONE);
    gpu::checkGlError("allocating " + label);
    return map;
}

/// Sets `out` to the name of pass `what`<k> of `plan`'s map, e.g. "Shadow/sun/layer0". Into a
/// string kept from frame to frame: building names anew would allocate every frame.
void formatPassName(std::string& out, const ShadowLightPlan& plan, std::string_view what, std::size_t k) {
    char index[24];
    char* end = std::to_chars(index, index + sizeof(index), k).ptr;
    out.assign("Shadow/").append(plan.name).append("/").append(what).append(index, end);
}

/// Draws a caster of the game's own (`ShadowCasterDraw`) into the layer of `context`.
void drawOwnCaster(const ShadowCasterDraw& own, const WorldTransform& wt, const CasterDrawContext& context) {
    if (own.draw) {
        own.draw(context);
        gl.UseProgram(context.program.name);  // the callback may have used its own
        return;
    }
    context.setWorldFromLocal(wt.worldFromLocal);
    gl.BindVertexArray(own.vertexArray.name);
    gl.DrawElementsBaseVertex(
        GL_TRIANGLES, own.indexCount, static_cast<GLenum>(own.indexType),
        reinterpret_cast<const void*>(own.indexOffset),  // NOLINT(performance-no-int-to-ptr): GL's offset
        own.baseVertex);
}

/// Depth-only state of the shadow passes.
void beginDepthOnly() {
    gpu::setPassDefaults();
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_CULL_FACE);  // open meshes (planes) cast from both sides
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

void endDepthOnly() {
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.BindVertexArray(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

/// Fills what `ls` says of `plan` before any layer is drawn (its strings keep their storage).
void describe(const ShadowLightPlan& plan, LightShadowStats& ls) {
    ls.sceneIndex = plan.sceneIndex;
    ls.name.assign(plan.name);
    ls.type.assign(lightTypeName(plan.light.type));
    ls.technique.assign(techniqueName(plan.technique()));
    ls.mapSize = plan.mapSize;
    ls.requestedMapSize = plan.settings.technique != ShadowTechnique::None ? plan.settings.mapSize : 0;
    ls.layers = static_cast<int>(plan.layers.size());
    ls.affectsView = plan.affectsView;
}

}  // namespace

struct ShadowMaps::Impl {
    DepthProgram depth;
    FilterChainBuilder chains;
    gpu::PassTimer timer;
    std::string passName;  ///< the name of the pass being timed (see `formatPassName`)
    /// Per scene light (index = `ShadowFrame::lights`): its map, or null without one.
    std::vector<std::pair<Entity, std::unique_ptr<ShadowMapGpu>>> maps;
    /// Last frame's `maps` while `syncMaps` moves them to this frame's slots; empty otherwise.
    std::vector<std::pair<Entity, std::unique_ptr<ShadowMapGpu>>> lastMaps;

    std::vector<Warning> pending;  ///< host errors of the calls without a FrameStats

    explicit Impl(bool softwareRenderer) : timer(softwareRenderer) {}

    /// Gives every light of `frame` with a map an array of its size, reusing last frame's.
    void syncMaps(const ShadowFrame& frame);
    /// Draws layer `k` of `plan`'s map: its casters, depth only.
    void drawLayer(const World& world, MeshCache& meshes, const ShadowLightPlan& plan, std::size_t k,
                   LightShadowStats& ls);
    /// Brings the filter chain of every layer of `plan` whose map changed up to date.
    void updateChains(const ShadowLightPlan& plan);
};

void ShadowMaps::Impl::syncMaps(const ShadowFrame& frame) {
    // The two lists trade places every frame, so their storage is reused: only maps move.
    std::swap(maps, lastMaps);
    maps.clear();
    maps.resize(frame.lights.size());
    for (std::size_t i = 0; i < frame.lights.size(); ++i) {
        const ShadowLightPlan& plan = frame.lights[i];
        maps[i].first = plan.entity;
        if (!plan.hasMap()) continue;
        auto it = std::find_if(lastMaps.begin(), lastMaps.end(),
                               [&](const auto& m) { return m.second && m.first == plan.entity; });
        std::unique_ptr<ShadowMapGpu> map = it != lastMaps.end() ? std::move(it->second) : nullptr;
        if (!map || map->mapSize != plan.mapSize || map->layers != static_cast<int>(plan.layers.size())) {
            map = allocate(plan);
        } else {
            map->allocatedThisFrame = false;
        }
        const std::optional<FilterChainKind> kind = shadow::filterChainOf(plan.technique());
        if (!kind) {
            map->chain.reset();  // no technique of the light reads one: no memory for it
        } else if (const int levels =
                       FilterChain::levelsFor(plan.technique(), map->mapSize, plan.settings.maxFilterTexels);
                   !map->chain || map->chain->kind != *kind || map->chain->levels != levels) {
            map->chain = FilterChain::allocate("Shadow/" + plan.name, *kind, map->mapSize, map->layers, levels);
            map->chainCurrent.assign(static_cast<std::size_t>(map->layers), false);
        }
        maps[i].second = std::move(map);
    }
    lastMaps.clear();  // the maps of lights gone or without a map this frame
}

void ShadowMaps::Impl::updateChains(const ShadowLightPlan& plan) {
    ShadowMapGpu& map = *maps[static_cast<std::size_t>(plan.sceneIndex)].second;
    if (!map.chain) return;
    for (std::size_t k = 0; k < plan.layers.size(); ++k) {
        // A layer's moment scale follows its matrices and its casters' bounds, whose changes
        // mark it dirty: a clean layer's table holds the scale of this frame's plan.
        if (!plan.layers[k].dirty && map.chainCurrent[k]) continue;
        if (plan.layers[k].casters.empty() && map.chain->clearable()) {
            map.chain->clearLayer(map.mapSize, static_cast<int>(k));
        } else {
            formatPassName(passName, plan, map.chain->kind == FilterChainKind::MinMax ? "minmax" : "moments", k);
            const gpu::ScopedPass pass(timer, passName);
            chains.build(map.array.get(), *map.chain, map.mapSize, static_cast<int>(k), plan.layers[k].momentScale);
        }
        map.chainCurrent[k] = true;
    }
}

void ShadowMaps::Impl::drawLayer(const World& world, MeshCache& meshes, const ShadowLightPlan& plan, std::size_t k,
                                 LightShadowStats& ls) {
    const ShadowLayerPlan& layer = plan.layers[k];
    ShadowMapGpu& map = *maps[static_cast<std::size_t>(plan.sceneIndex)].second;
    map.depthScales[k] = layer.depthScale;
    const float far = 1.0f;
    if (layer.casters.empty()) {
        // Nothing casts into this layer: clear it to the far depth, draw nothing.
        gl.ClearTexSubImage(map.array.get(), 0, 0, 0, static_cast<GLint>(k), map.mapSize, map.mapSize, 1,
                            GL_DEPTH_COMPONENT, GL_FLOAT, &far);
        ++ls.layersCleared;
        return;
    }
    const GLuint program = depth.program.get();
    gl.NamedFramebufferTextureLayer(map.framebuffer.get(), GL_DEPTH_ATTACHMENT, map.array.get(), 0,
                                    static_cast<GLint>(k));
    gl.BindFramebuffer(GL_FRAMEBUFFER, map.framebuffer.get());
    gl.Viewport(0, 0, map.mapSize, map.mapSize);
    gl.ClearNamedFramebufferfv(map.framebuffer.get(), GL_DEPTH, 0, &far);
    gl.UseProgram(program);
    gl.ProgramUniformMatrix4fv(program, depth.clipFromLight, 1, GL_FALSE,
                               glm::value_ptr(glm::mat4(layer.clipFromLight)));
    gl.ProgramUniform1f(program, depth.depthScale, layer.depthScale);
    gl.ProgramUniform1i(program, depth.orthographic, layer.orthographic ? 1 : 0);
    const CasterDrawContext context{layer.lightFromWorld, layer.clipFromLight, layer.depthScale,
                                    layer.orthographic,   GlProgram{program},  depth.lightFromLocal};
    for (Entity caster : layer.casters) {
        const WorldTransform* wt = world.tryGet<WorldTransform>(caster);
        if (wt == nullptr || !wt->finite) continue;
        if (const Mesh* mesh = world.tryGet<Mesh>(caster); mesh != nullptr && mesh->data != nullptr) {
            context.setWorldFromLocal(wt->worldFromLocal);
            const int count = gpu::MeshCacheAccess::bind(meshes, mesh->data);
            gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
        } else if (const ShadowCasterDraw* own = world.tryGet<ShadowCasterDraw>(caster); own != nullptr) {
            drawOwnCaster(*own, *wt, context);
        } else {
            continue;
        }
        ++ls.castersDrawn;
    }
    ++ls.layersDrawn;
}

void CasterDrawContext::setWorldFromLocal(const glm::dmat4& worldFromLocal) const {
    // Composed in double: light-relative float values stay precise far from the origin.
    const glm::mat4 lightFromLocal(lightFromWorld * worldFromLocal);
    gl.ProgramUniformMatrix4fv(program.name, lightFromLocalLocation, 1, GL_FALSE, glm::value_ptr(lightFromLocal));
}

ShadowMaps::ShadowMaps() {
    gpu::requireLoaded("ShadowMaps");
    std::vector<Warning> pending;
    gpu::reportHostGlErrors("ShadowMaps", pending, gpu::kMaxPendingWarnings);
    impl_ = std::make_unique<Impl>(queryGlInfo().softwareRenderer);
    impl_->timer.setEnabled(false);
    impl_->pending = std::move(pending);
}

ShadowMaps::~ShadowMaps() = default;

Result<std::unique_ptr<ShadowMaps>> ShadowMaps::create() noexcept {
    return gpu::noThrow<std::unique_ptr<ShadowMaps>>("ShadowMaps", [] { return std::make_unique<ShadowMaps>(); });
}

Status ShadowMaps::tryRender(const ShadowFrame& frame, const World& world, MeshCache& meshes,
                             FrameStats& stats) noexcept {
    return gpu::noThrowStatus("ShadowMaps::render", [&] { render(frame, world, meshes, stats); });
}

void ShadowMaps::render(const ShadowFrame& frame, const World& world, MeshCache& meshes, FrameStats& stats) {
    gpu::reportHostGlErrors("ShadowMaps::render", stats);
    // What the calls without a FrameStats found since the last frame, in the order found.
    gpu::movePendingWarnings(impl_->pending, stats.warnings);
    gpu::movePendingWarnings(gpu::MeshCacheAccess::pending(meshes), stats.warnings);
    static constexpr std::array<GLint, 1> kUnits{SG_UNIT_MINMAX_SOURCE};
    static constexpr std::array<GLint, 1> kImageUnits{SG_IMAGE_MINMAX};
    const gpu::GlStateGuard hostState(kUnits, {}, kImageUnits);
    Impl& g = *impl_;
    g.syncMaps(frame);
    stats.warnings.insert(stats.warnings.end(), frame.warnings.begin(), frame.warnings.end());
    beginDepthOnly();
    for (const ShadowLightPlan& plan : frame.lights) {
        LightShadowStats& ls = stats.addLight();
        describe(plan, ls);
        const auto& map = g.maps[static_cast<std::size_t>(plan.sceneIndex)].second;
        ls.mapAllocated = map != nullptr && map->allocatedThisFrame;
        ls.mapBytes = map != nullptr ? depthArrayBytes(map->mapSize, map->layers) : 0;
        ls.filterChainBytes = map != nullptr && map->chain ? map->chain->bytes(map->mapSize, map->layers) : 0;
        for (std::size_t k = 0; k < plan.layers.size(); ++k) {
            if (!plan.layers[k].dirty) {
                ++ls.layersReused;
                continue;
            }
            const bool drawn = !plan.layers[k].casters.empty();
            std::optional<gpu::ScopedPass> pass;
            if (drawn) {
                formatPassName(g.passName, plan, "layer", k);
                pass.emplace(g.timer, g.passName);
            }
            g.drawLayer(world, meshes, plan, k, ls);
        }
        stats.shadowLayersDrawn += ls.layersDrawn;
        stats.shadowLayersReused += ls.layersReused;
        stats.shadowLayersCleared += ls.layersCleared;
        stats.shadowDrawCalls += ls.castersDrawn;
    }
    endDepthOnly();
    for (const ShadowLightPlan& plan : frame.lights) {
        if (plan.hasMap()) g.updateChains(plan);
    }
    gpu::checkGlError("shadow pass");
    g.timer.collect(stats);
}

void ShadowMaps::setTiming(bool enabled) { impl_->timer.setEnabled(enabled); }

GlTexture ShadowMaps::textureOf(std::size_t i) const {
    const auto& maps = impl_->maps;
    return GlTexture{i < maps.size() && maps[i].second ? maps[i].second->array.get() : 0u};
}

GlTexture ShadowMaps::textureOfLight(Entity light) const {
    for (const auto& [entity, map] : impl_->maps) {
        if (entity == light && map) return GlTexture{map->array.get()};
    }
    return {};
}

GlTexture ShadowMaps::filterChainOf(std::size_t i) const {
    const auto& maps = impl_->maps;
    return GlTexture{i < maps.size() && maps[i].second && maps[i].second->chain ? maps[i].second->chain->texture.get()
                                                                                : 0u};
}

int ShadowMaps::layersOf(std::size_t i) const {
    const auto& maps = impl_->maps;
    return i < maps.size() && maps[i].second ? maps[i].second->layers : 0;
}

std::vector<float> ShadowMaps::readLayerDepth(std::size_t i, int layer) const {
    const auto& maps = impl_->maps;
    if (i >= maps.size() || !maps[i].second) return {};
    const ShadowMapGpu& map = *maps[i].second;
    if (layer < 0 || layer >= map.layers) return {};
    gpu::reportHostGlErrors("ShadowMaps::readLayerDepth", impl_->pending, gpu::kMaxPendingWarnings);
    std::vector<float> depth(static_cast<std::size_t>(map.mapSize) * map.mapSize);
    const gpu::GlStateGuard hostState({}, {});
    gpu::setReadbackDefaults();
    gl.GetTextureSubImage(map.array.get(), 0, 0, 0, layer, map.mapSize, map.mapSize, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                          static_cast<GLsizei>(depth.size() * sizeof(float)), depth.data());
    const float scale = map.depthScales[static_cast<std::size_t>(layer)];
    for (float& d : depth) d *= scale;
    return depth;
}

const std::vector<Warning>& ShadowMaps::warnings() const { return impl_->pending; }

void ShadowMaps::clearWarnings() { impl_->pending.clear(); }

}  // namespace shadow
