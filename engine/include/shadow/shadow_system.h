// The shadow system as one object, for a game that wants one: it owns the four parts, each a
// class of its own with its own header, which a game may also use apart:
//   ShadowPlanner        (shadow_planner.h)  decides, on the CPU: a `ShadowFrame` per frame
//   ShadowMaps           (shadow_maps.h)     owns each light's depth array and filter chain and
//                                            draws the dirty layers of a frame
//   ShadowShaderContract (shader_contract.h) the records and bindings a game's shader reads
//   ShadowMask           (shadow_mask.h)     the screen-space mask over a game's depth
// Each part takes what it reads as `const` (the maps a `const ShadowFrame&`, the contract and the
// mask a `const ShadowFrame&` and `const ShadowMaps&`); this facade passes its planner's last
// frame and its maps. It also owns a `MeshCache` for games without the module's `Renderer`: the
// `render` that is not given a cache draws from it and collects it (its owner), once a frame.
//
// What this does not do (yet): no atlas packing across lights, no GPU-driven culling.
#pragma once

#include <shadow/mesh_cache.h>
#include <shadow/result.h>
#include <shadow/scene.h>
#include <shadow/shader_contract.h>
#include <shadow/shadow_maps.h>
#include <shadow/shadow_mask.h>
#include <shadow/shadow_planner.h>
#include <shadow/shadow_shaders.h>
#include <shadow/stats.h>
#include <shadow/warnings.h>

#include <memory>
#include <span>
#include <vector>

namespace shadow {

/// The planner, the maps, the shader contract and the mask in one object (see the header).
/// Requires a current OpenGL 4.5 context with `loadGl` done.
class ShadowSystem {
public:
    /// Throws `GlError` when `loadGl` has not run (there is no GL to talk to).
    ShadowSystem();
    /// For a game built without exceptions: the system, or the error the constructor would throw.
    [[nodiscard]] static Result<std::unique_ptr<ShadowSystem>> create() noexcept;
    ~ShadowSystem();
    ShadowSystem(const ShadowSystem&) = delete;
    ShadowSystem& operator=(const ShadowSystem&) = delete;

    /// `ShadowPlanner::prepare`: the CPU phase. The planner's limits are the context's, read at
    /// construction.
    const ShadowFrame& prepare(const World& world, const CameraView& camera, const std::vector<Entity>& lights);
    /// `ShadowMaps::render` of the last prepared frame, its meshes from the system's own
    /// `MeshCache`, which it then collects (the GPU copies of meshes gone). Moves the warnings
    /// the parts kept from calls without a `FrameStats` into `stats`.
    void render(const World& world, FrameStats& stats);
    /// `render` with a cache shared with the module's `Renderer` (`Renderer::meshes`), which
    /// owns and collects it.
    void render(const World& world, MeshCache& meshes, FrameStats& stats);
    /// `render` for a game built without exceptions: what it would throw, as an error value.
    [[nodiscard]] Status tryRender(const World& world, FrameStats& stats) noexcept;
    /// `render` with a shared cache, for a game built without exceptions.
    [[nodiscard]] Status tryRender(const World& world, MeshCache& meshes, FrameStats& stats) noexcept;
    /// Per-pass timing into `FrameStats::passes`. Default off: timing brackets every pass with
    /// glFinish on a CPU rasteriser, and on a GPU opens GL_TIME_ELAPSED queries (a host's own
    /// time-elapsed query cannot be open across the call) whose results are read a frame or
    /// more later, never stalling (`FrameStats::timingLagFrames`). FrameRunner turns it on.
    /// Off, `FrameStats::timingMethod` says "off" and no pass is listed.
    void setTiming(bool enabled);

    /// `ShadowShaderContract::inputs` of the last prepared and rendered frame.
    const ShadowShaderInputs& shaderInputs(std::span<const int> sceneLights, const glm::dvec3& wsCamera);
    /// `shaderInputs` for a game built without exceptions.
    [[nodiscard]] Result<const ShadowShaderInputs*> tryShaderInputs(std::span<const int> sceneLights,
                                                                    const glm::dvec3& wsCamera) noexcept;
    /// `ShadowShaderContract::bind`.
    void bindShaderInputs(const ShadowShaderInputs& inputs, const ShadowBindingPoints& points = {});
    /// `ShadowMask::render` of the last prepared and rendered frame.
    void renderMask(std::span<const int> sceneLights, const ShadowMaskRequest& request, FrameStats& stats);
    /// `renderMask` for a game built without exceptions.
    [[nodiscard]] Status tryRenderMask(std::span<const int> sceneLights, const ShadowMaskRequest& request,
                                       FrameStats& stats) noexcept;
    /// `ShadowMaps::textureOfLight`: the depth array of light entity `light`.
    [[nodiscard]] GlTexture textureOfLight(Entity light) const;

    /// The last prepared frame.
    [[nodiscard]] const ShadowFrame& frame() const;
    /// The parts, for what the facade does not forward.
    [[nodiscard]] ShadowPlanner& planner();
    [[nodiscard]] ShadowMaps& maps();
    [[nodiscard]] const ShadowMaps& maps() const;
    [[nodiscard]] ShadowShaderContract& contract();
    /// The system's own mesh cache (the one `render(world, stats)` draws from and collects).
    [[nodiscard]] MeshCache& meshes();

    /// `HostGlError` warnings of the calls without a `FrameStats` (the constructor,
    /// `shaderInputs`, `bindShaderInputs`): an error the host left pending before one of them is
    /// read, cleared and kept here (at most 16 until cleared), never thrown. The next `render`
    /// moves them into its `FrameStats`, with those the parts and the mesh cache kept.
    [[nodiscard]] const std::vector<Warning>& warnings() const;
    /// Forgets the warnings read.
    void clearWarnings();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
