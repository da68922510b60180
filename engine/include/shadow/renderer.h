// The forward renderer: Blinn-Phong per light times that light's visibility, summed over the
// lights (the split of the seeds' approximated rendering equation), into linear HDR colour;
// optional AOVs (world position, camera distance, per-light visibility).
//
// Lights are shaded SG_MAX_LIGHTS_PER_PASS (8) at a time; more lights add further passes with
// additive blending. Shader variants are compiled on first use for the set of techniques the
// frame's lights use, and cached: a frame whose lights use only PCF compiles no PCSS code.
#pragma once

#include <shadow/image_io.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>
#include <shadow/stats.h>

#include <memory>
#include <string>
#include <vector>

namespace shadow {

/// GPU copies of the scene's meshes, shared by the shadow system and the renderer. Each
/// `MeshData` is uploaded once, on first use.
class MeshCache {
public:
    MeshCache();
    ~MeshCache();
    MeshCache(const MeshCache&) = delete;
    MeshCache& operator=(const MeshCache&) = delete;

    /// Binds the vertex array of `mesh` (uploading it on first use) and returns its index count.
    int bind(const std::shared_ptr<const MeshData>& mesh);
    /// Number of meshes uploaded so far.
    [[nodiscard]] std::size_t size() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

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
    int debugLight = 0;  ///< scene light index the debug view shows
    glm::vec3 ambient{0.03f};  ///< constant ambient radiance times albedo (unshadowed)
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
class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Renders one frame of `lights` (the scene's light order) seen by `camera`, sampling the
    /// maps of `shadows` (prepared and rendered this frame). Adds timings and counters.
    void render(World& world, const CameraView& camera, const std::vector<Entity>& lights,
                const ShadowSystem& shadows, const RenderOptions& options, FrameStats& stats);

    /// Reads back the last frame. `camera` turns camera-relative positions back into world ones.
    [[nodiscard]] FrameImages readback(const CameraView& camera, FrameStats& stats) const;

    /// Copies the last frame's linear colour to the default framebuffer of size `width` x
    /// `height` (windowed viewers), scaled to fit.
    void present(int width, int height) const;

    [[nodiscard]] MeshCache& meshes();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Everything a frame needs, in the documented order: animate, transforms, shadow prepare,
/// shadow render, main pass. A convenience for samples and games with no loop of their own.
class FrameRunner {
public:
    FrameRunner();
    ~FrameRunner();
    FrameRunner(const FrameRunner&) = delete;
    FrameRunner& operator=(const FrameRunner&) = delete;

    /// Runs one frame of `scene` at time `t` (s) through camera entity `camera`.
    FrameStats runFrame(Scene& scene, double t, Entity camera, const RenderOptions& options);

    [[nodiscard]] ShadowSystem& shadows();
    [[nodiscard]] Renderer& renderer();
    /// The camera view of the last frame.
    [[nodiscard]] const CameraView& lastCamera() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
