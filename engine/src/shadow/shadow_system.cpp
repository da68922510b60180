// ShadowSystem: the facade over the planner, the maps, the shader contract and the mask
// (shadow_system.h). It owns them and passes each the planner's last frame; the work is theirs.
#include <shadow/context.h>
#include <shadow/shadow_system.h>

#include "gl/gl_state.h"
#include "gl/mesh_cache_access.h"
#include "gl/no_throw.h"
#include "gl/program.h"

#include <optional>

namespace shadow {

struct ShadowSystem::Impl {
    ShadowPlanner planner;
    ShadowMaps maps;
    ShadowShaderContract contract;
    MeshCache meshes;                ///< for `render` without a cache: the system owns and collects it
    std::optional<ShadowMask> mask;  ///< made on the first `renderMask`
    std::vector<Warning> pending;    ///< see `warnings`
};

namespace {

/// Copies `from` to the end of `to`: a part's pending warnings into a frame's (the caller clears them).
void drain(const std::vector<Warning>& from, std::vector<Warning>& to) {
    to.insert(to.end(), from.begin(), from.end());
}

}  // namespace

ShadowSystem::ShadowSystem() {
    gpu::requireLoaded("ShadowSystem");
    // Before the parts make their objects: the host's error is reported once, as the system's.
    std::vector<Warning> pending;
    gpu::reportHostGlErrors("ShadowSystem", pending, gpu::kMaxPendingWarnings);
    impl_ = std::make_unique<Impl>();
    impl_->pending = std::move(pending);
    const GlInfo info = queryGlInfo();
    ShadowLimits limits;
    limits.maxTextureSize = info.maxTextureSize;
    limits.maxArrayLayers = info.maxArrayLayers;
    impl_->planner.setLimits(limits);
}

ShadowSystem::~ShadowSystem() = default;

Result<std::unique_ptr<ShadowSystem>> ShadowSystem::create() noexcept {
    return gpu::noThrow<std::unique_ptr<ShadowSystem>>("ShadowSystem", [] { return std::make_unique<ShadowSystem>(); });
}

const ShadowFrame& ShadowSystem::prepare(const World& world, const CameraView& camera,
                                         const std::vector<Entity>& lights) {
    return impl_->planner.prepare(world, camera, lights);
}

void ShadowSystem::render(const World& world, FrameStats& stats) {
    render(world, impl_->meshes, stats);
    gpu::MeshCacheAccess::collect(impl_->meshes);  // its owner: the GPU copies of meshes gone
}

void ShadowSystem::render(const World& world, MeshCache& meshes, FrameStats& stats) {
    Impl& s = *impl_;
    gpu::reportHostGlErrors("ShadowSystem::render", stats);
    gpu::movePendingWarnings(s.pending, stats.warnings);
    drain(s.contract.warnings(), stats.warnings);
    s.contract.clearWarnings();
    const std::uint64_t built = gpu::programsBuilt();  // the passes build their programs on first use
    s.maps.render(s.planner.frame(), world, meshes, stats);
    stats.programsCompiled += static_cast<int>(gpu::programsBuilt() - built);
}

Status ShadowSystem::tryRender(const World& world, FrameStats& stats) noexcept {
    return gpu::noThrowStatus("ShadowSystem::render", [&] { render(world, stats); });
}

Status ShadowSystem::tryRender(const World& world, MeshCache& meshes, FrameStats& stats) noexcept {
    return gpu::noThrowStatus("ShadowSystem::render", [&] { render(world, meshes, stats); });
}

void ShadowSystem::setTiming(bool enabled) { impl_->maps.setTiming(enabled); }

const ShadowShaderInputs& ShadowSystem::shaderInputs(std::span<const int> sceneLights, const glm::dvec3& wsCamera) {
    gpu::reportHostGlErrors("ShadowSystem::shaderInputs", impl_->pending, gpu::kMaxPendingWarnings);
    return impl_->contract.inputs(impl_->planner.frame(), impl_->maps, sceneLights, wsCamera);
}

Result<const ShadowShaderInputs*> ShadowSystem::tryShaderInputs(std::span<const int> sceneLights,
                                                                const glm::dvec3& wsCamera) noexcept {
    return gpu::noThrow<const ShadowShaderInputs*>("shaderInputs",
                                                   [&] { return &shaderInputs(sceneLights, wsCamera); });
}

void ShadowSystem::bindShaderInputs(const ShadowShaderInputs& inputs, const ShadowBindingPoints& points) {
    gpu::reportHostGlErrors("ShadowSystem::bindShaderInputs", impl_->pending, gpu::kMaxPendingWarnings);
    impl_->contract.bind(inputs, points);
}

void ShadowSystem::renderMask(std::span<const int> sceneLights, const ShadowMaskRequest& request, FrameStats& stats) {
    Impl& s = *impl_;
    gpu::reportHostGlErrors("ShadowSystem::renderMask", stats);
    const std::uint64_t built = gpu::programsBuilt();
    if (!s.mask) s.mask.emplace();
    s.mask->render(s.planner.frame(), s.maps, sceneLights, request, stats);
    stats.programsCompiled += static_cast<int>(gpu::programsBuilt() - built);
}

Status ShadowSystem::tryRenderMask(std::span<const int> sceneLights, const ShadowMaskRequest& request,
                                   FrameStats& stats) noexcept {
    return gpu::noThrowStatus("renderMask", [&] { renderMask(sceneLights, request, stats); });
}

GlTexture ShadowSystem::textureOfLight(Entity light) const { return impl_->maps.textureOfLight(light); }

const ShadowFrame& ShadowSystem::frame() const { return impl_->planner.frame(); }
ShadowPlanner& ShadowSystem::planner() { return impl_->planner; }
ShadowMaps& ShadowSystem::maps() { return impl_->maps; }
const ShadowMaps& ShadowSystem::maps() const { return impl_->maps; }
ShadowShaderContract& ShadowSystem::contract() { return impl_->contract; }
MeshCache& ShadowSystem::meshes() { return impl_->meshes; }

const std::vector<Warning>& ShadowSystem::warnings() const { return impl_->pending; }

void ShadowSystem::clearWarnings() { impl_->pending.clear(); }

}  // namespace shadow
