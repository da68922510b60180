// The forward renderer: Blinn-Phong per light times that light's visibility, summed over the
// lights (the split of the seeds' approximated rendering equation), into linear HDR colour;
// optional AOVs (world position, camera distance, per-light visibility).
//
// Lights are shaded SG_MAX_LIGHTS_PER_PASS (8) at a time; more lights add further passes on the
// first pass's surfaces (depth test EQUAL) with additive blending. Each pass's program is specialised for its
// lights' types and techniques (compiled on first use and cached): a frame whose lights use only
// PCF compiles no PCSS code, and no pixel runs code for a light type it does not have.
#pragma once

#include <shadow/image_io.h>
#include <shadow/mesh_cache.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>
#include <shadow/stats.h>

#include <memory>
#include <string>
#include <vector>

namespace shadow {

/// Debug views of the main pass (`--debug NAME`).
enum class DebugView {
    None,
    Cascade,       ///< cascade index of the debug light, tinted
    BlockerDepth,  ///< PCSS average blocker depth (m) of the debug light
    Penumbra,      ///< PCSS penumbra half-width (m) of the debug light
    Visibility,    ///< visibility of the debug light
};

/// What to render.
struct RenderOptions {
    int width = 640;
    int height = 360;
    /// Write position, depth and per-light visibility outputs as well as colour.
    bool aovs = false;
    DebugView debugView = DebugView::None;
    int debugLight = 0;        ///< scene light index the debug view shows
    glm::vec3 ambient{0.03f};  ///< constant ambient radiance times albedo (unshadowed)
    /// Fill the depth buffer first, so that the lit passes shade each visible pixel once. Off by
    /// default: on a CPU rasteriser the second pass over the triangles costs more than the
    /// overdraw it saves (BENCHMARKS.md, fragment costs: overdraw 1.01 on the bunny scene, the
    /// pre-pass +44 ms at 1280x720); on a GPU with deep overdraw it pays.
    bool depthPrepass = false;
};

/// Images read back after a frame. Rows top first. Empty when not requested.
struct FrameImages {
    ImageF color;     ///< linear RGB
    ImageF position;  ///< world xyz + coverage (1 on geometry, 0 on background)
    ImageF depth;     ///< distance from the camera (m); 0 on background
    /// Per scene light (index = `Scene::lights` position): visibility, 1 on background.
    std::vector<ImageF> visibility;
};

/// The forward renderer. Requires a current OpenGL 4.5 context with `loadGl` done.
/// `render` and `readback` put back the GL state they change (as `ShadowSystem::render` does;
/// here also texture units 0-23 with their samplers and uniform-buffer bindings 0-2) and report
/// an error the host left pending as a `HostGlError` warning instead of throwing it.
class Renderer {
public:
    /// Throws `GlError` when `loadGl` has not run.
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Renders one frame seen by `camera` (optionally after a depth pre-pass), lighting every
    /// light of `shadows.frame()` (prepared and rendered this frame; its lights are the scene's,
    /// in scene order) with its own technique. Adds timings and counters. Throws `GlError` when
    /// a program or the framebuffer cannot be made.
    void render(World& world, const CameraView& camera, const ShadowSystem& shadows, const RenderOptions& options,
                FrameStats& stats);

    /// Reads back the last frame. `camera` turns camera-relative positions back into world ones.
    [[nodiscard]] FrameImages readback(const CameraView& camera, FrameStats& stats) const;

    /// Copies the last frame's linear colour to the default framebuffer of size `width` x
    /// `height` (windowed viewers), scaled to fit.
    void present(int width, int height) const;

    [[nodiscard]] MeshCache& meshes();
    /// Per-pass timing of `render` and `readback`, as `ShadowSystem::setTiming` (default off).
    void setTiming(bool enabled);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
