// The shadow maps and their passes: every shadowed light of a `ShadowFrame` owns one
// GL_TEXTURE_2D_ARRAY of 32-bit float depth layers (directional: cascades; spot: one layer;
// point: six cube faces) and, for the techniques that read one, a filter chain (min/max pyramid,
// moments, summed-area table). `render` draws only the layers the frame marks dirty, clears the
// layers with no caster, leaves every other layer as the last frame left it, and brings the
// filter chain of every redrawn layer up to date (a layer with no caster keeps no summed-area
// table: its moment scale 0 has the lookups read lit).
#pragma once

#include <shadow/gl_handles.h>
#include <shadow/result.h>
#include <shadow/scene.h>
#include <shadow/shadow_planner.h>
#include <shadow/stats.h>
#include <shadow/warnings.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace shadow {

class MeshCache;

/// The GPU half of the shadow system: each light's maps, drawn from a `ShadowFrame`.
/// Requires a current OpenGL 4.5 context with `loadGl` done.
class ShadowMaps {
public:
    /// Throws `GlError` when `loadGl` has not run.
    ShadowMaps();
    /// For a game built without exceptions: the maps, or the error the constructor would throw.
    [[nodiscard]] static Result<std::unique_ptr<ShadowMaps>> create() noexcept;
    ~ShadowMaps();
    ShadowMaps(const ShadowMaps&) = delete;
    ShadowMaps& operator=(const ShadowMaps&) = delete;

    /// Draws the dirty layers of `frame` (the planner's last), depth only, the casters' meshes
    /// from `meshes` (which it binds, never collects: the cache's owner does) and the
    /// `ShadowCasterDraw`s of `world`. Gives every light of `frame` with a map an array of its
    /// size, reusing last frame's (a light gone, or a new size, frees its old one). Adds timings
    /// and counters to `stats`. A guest in the host's context: the GL state it changes
    /// (engine/src/gl/gl_state.h) is put back before it returns, also when it throws; a map it
    /// frees is left unbound, never bound back. An error the host left pending is read, cleared
    /// and reported as a `HostGlError` warning in `stats`, never thrown; `GlError` is thrown only
    /// for the engine's own.
    void render(const ShadowFrame& frame, const World& world, MeshCache& meshes, FrameStats& stats);
    /// `render` for a game built without exceptions: what it would throw, as an error value.
    [[nodiscard]] Status tryRender(const ShadowFrame& frame, const World& world, MeshCache& meshes,
                                   FrameStats& stats) noexcept;
    /// Per-pass timing into `FrameStats::passes` (see `ShadowSystem::setTiming`). Default off.
    void setTiming(bool enabled);

    /// The depth array of light entity `light`, none when it has no map: the same from frame to
    /// frame whatever the lights' order, until the map is made anew (a new size or layer count,
    /// e.g. from the memory budget), which `LightShadowStats::mapAllocated` reports.
    [[nodiscard]] GlTexture textureOfLight(Entity light) const;
    /// The depth array of scene light `i` of the last rendered frame, none when it has no map.
    [[nodiscard]] GlTexture textureOf(std::size_t i) const;
    /// The filter chain of scene light `i` (an array, one mip chain per layer): the min/max depth
    /// pyramid of PCF and PCSS lights (RG32F), the depth moments of VSM lights (RG32F) and of
    /// MSM-soft lights (RGBA32F), the summed-area table of VSSM lights (RGBA32F, one level:
    /// shaders/shadow_summed_area_format.glsl); none when it has none. It is what unit
    /// SG_UNIT_SHADOW_MINMAX + slot reads.
    [[nodiscard]] GlTexture filterChainOf(std::size_t i) const;
    /// Technique sdf: the atlas of the field casters' signed distance fields (a 3D R32F texture,
    /// one brick per mesh, baked when a light first marches through it); what unit
    /// SG_UNIT_SDF_ATLAS reads. None before a light uses sdf.
    [[nodiscard]] GlTexture fieldAtlas() const;
    /// Technique sdf: the instance records of the last rendered frame's field casters
    /// (shaders/shadow_sdf.glsl has their layout), positions relative to `wsCamera`, as a buffer
    /// texture (RGBA32F) that unit SG_UNIT_SDF_INSTANCES reads; uploaded again when the camera
    /// differs from the last call's. None before a light uses sdf.
    [[nodiscard]] GlTexture fieldInstances(const glm::dvec3& wsCamera) const;
    /// The instance records as the last `fieldInstances(wsCamera)` uploaded them (what a pass
    /// binds after its inputs were made for its camera). None before.
    [[nodiscard]] GlTexture fieldInstances() const;
    /// Layers of the map of scene light `i` (0 without one).
    [[nodiscard]] int layersOf(std::size_t i) const;
    /// Reads layer `layer` of scene light `i` as linear depth in metres (debug views, tests);
    /// empty when it has no such layer. A guest like `render`; an error the host left pending
    /// goes to `warnings()`.
    [[nodiscard]] std::vector<float> readLayerDepth(std::size_t i, int layer) const;

    /// `HostGlError` warnings of the calls without a `FrameStats` (the constructor,
    /// `readLayerDepth`), at most 16 until cleared; the next `render` moves them into its stats.
    [[nodiscard]] const std::vector<Warning>& warnings() const;
    /// Forgets the warnings read.
    void clearWarnings();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
