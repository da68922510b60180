// The forward renderer: Lambert + GGX shading per light times that light's visibility, summed over the
// lights (the split of the seeds' approximated rendering equation), into linear HDR colour;
// optional AOVs (world position, camera distance, per-light visibility).
//
// Lights are shaded SG_MAX_LIGHTS_PER_PASS (8) at a time; more lights add further passes on the
// first pass's surfaces (depth test EQUAL) with additive blending. Each pass's program is specialised for its
// lights' types and techniques (compiled on first use and cached): a frame whose lights use only
// PCF compiles no PCSS code, and no pixel runs code for a light type it does not have.
#pragma once

#include <shadow/gl_handles.h>
#include <shadow/image_io.h>
#include <shadow/mesh_cache.h>
#include <shadow/scene.h>
#include <shadow/shadow_maps.h>
#include <shadow/shadow_planner.h>
#include <shadow/stats.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadow {

class ShadowSystem;

/// Debug views of the main pass (`--debug NAME`).
enum class DebugView {
    None,
    Cascade,       ///< cascade of the debug light: 0 red, 1 green, 2 blue, 3 yellow (+ 0.2 x visibility)
    BlockerDepth,  ///< PCSS average blocker depth (m) of the debug light
    Penumbra,      ///< PCSS penumbra half-width (m) of the debug light
    Visibility,    ///< visibility of the debug light
    MarchSteps,    ///< sdf: steps the debug light's march took, over its `sdfSteps` (grey, 1 = all)
    Closest,       ///< sdf: the march's smallest clearance over the cone, -1 (black) to 1 (white)
};

/// Where the lit passes get their lights' visibility (`RenderOptions::screenVisibility`).
enum class ScreenVisibility {
    /// Forward: each lit fragment runs its lights' techniques.
    Off,
    /// The screen-space visibility stage where it measured faster than forward (a light with
    /// technique pcss or sdf, two or more lights that filter their shadows, or in images of 720
    /// rows or more any light that filters them) and when a light
    /// asks for contact shadows; forward otherwise. The stage: the scene drawn once into
    /// surface targets; each group of four lights' visibility computed over the screen, at full
    /// resolution for hard-edged shadows and at half resolution for filtered ones, quarter in
    /// images of 720 rows or more (a penumbra is low-frequency, and as many samples wide as at
    /// half resolution in 360 rows); brought back to full resolution by an upsample that never blends a sample
    /// of another surface, and recomputed at full resolution where the samples kept disagree (an
    /// edge sharper than the samples); then the lights shaded by one full-screen pass per group
    /// of eight. Debug views render forward. Measured on llvmpipe (BENCHMARKS.md, screen-space
    /// visibility): at 1280x720 sdf's frame 3.6x faster than forward, the sample scenes' up to 2.2x; error
    /// against the truth as forward's or lower on the bunny spots.
    Auto,
    Full,     ///< the stage, every light at full resolution
    Half,     ///< the stage, every light at half resolution (upsampled)
    Quarter,  ///< the stage, every light at quarter resolution (upsampled)
};

/// "off", "auto", "full", "half", "quarter".
[[nodiscard]] const char* screenVisibilityName(ScreenVisibility v);
/// The setting named `name`, if one is.
[[nodiscard]] std::optional<ScreenVisibility> parseScreenVisibility(std::string_view name);

/// What to render.
struct RenderOptions {
    int width = 640;
    int height = 360;
    /// Write position, depth and per-light visibility outputs as well as colour.
    bool aovs = false;
    DebugView debugView = DebugView::None;
    int debugLight = 0;  ///< scene light index the debug view shows
    /// Hemisphere ambient light (unshadowed; W/(sr m^2) in the lights' units, each >= 0): radiance
    /// from every direction above the horizon (+y) and below it. It lights the diffuse and the
    /// specular term (a metal in shadow shows the sky in its colour), times the material's
    /// ambient occlusion; equal halves are a uniform ambient.
    glm::vec3 ambientSky{0.03f};
    glm::vec3 ambientGround{0.03f};
    /// Fill the depth buffer first, so that the lit passes shade each visible pixel once. Off by
    /// default: on a CPU rasteriser the second pass over the triangles costs more than the
    /// overdraw it saves (BENCHMARKS.md, fragment costs: overdraw 1.01 on the bunny scene, the
    /// pre-pass +44 ms at 1280x720); on a GPU with deep overdraw it pays.
    bool depthPrepass = false;
    /// Forward lit passes, or the screen-space visibility stage (`ScreenVisibility`).
    ScreenVisibility screenVisibility = ScreenVisibility::Off;
};

/// Most GPU memory the renderer's targets may take (bytes): colour and depth (20 bytes a pixel),
/// and with AOVs position, distance and per pass two visibility textures (52 more, + 32 a pass
/// beyond the first). 2 GiB: 8192x8192 without AOVs, 4096x4096 with them for up to 8 lights.
inline constexpr std::int64_t kMaxRenderTargetBytes = std::int64_t{2} << 30;

/// Whether frames of `options`' size can be rendered for a scene of `lights` lights: within the
/// current context's GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE and GL_MAX_FRAMEBUFFER_WIDTH
/// and _HEIGHT, and inside `kMaxRenderTargetBytes` (with AOVs for the passes of `lights` lights,
/// eight a pass). An `Error` naming the limit otherwise (the caller names the size): what
/// `Renderer::render` would throw as a `GlError` before allocating, for a program to refuse the
/// size up front.
/// Requires a current context with `loadGl` done.
[[nodiscard]] Status checkRenderSize(const RenderOptions& options, int lights = 0);

/// Images read back after a frame. Rows top first. Empty when not requested.
struct FrameImages {
    ImageF color;     ///< linear RGB
    ImageF position;  ///< world xyz + coverage (1 on geometry, 0 on background)
    ImageF depth;     ///< distance from the camera (m); 0 on background
    /// Per scene light (index = `Scene::lights` position): visibility, 1 on background.
    std::vector<ImageF> visibility;
};

/// The forward renderer. Requires a current OpenGL 4.5 context with `loadGl` done.
/// `render`, `readback` and the present calls put back the GL state they change (as `ShadowSystem::render` does;
/// here also every texture target of units 0-31 it binds (0-28, and the screen-space stage's 29-31) with their samplers, uniform-buffer
/// bindings 0-2, and the storage bindings 3-5: joint matrices, morph displacements, technique auto's edge counts) and report an error the host left pending as a `HostGlError` warning instead of throwing
/// it; the constructor, `present` and `readPresented`, which have no `FrameStats`, keep theirs in `warnings()`.
class Renderer {
public:
    /// Throws `GlError` when `loadGl` has not run.
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Renders one frame seen by `camera` (optionally after a depth pre-pass), lighting every
    /// light of `frame` (prepared this frame; its lights are the scene's, in scene order) with
    /// its own technique and its maps in `maps` (rendered from `frame`). Draws its meshes from
    /// `meshes()`, which it owns and collects here, once a frame. Adds timings and counters.
    /// Throws `GlError` when a program or the framebuffer cannot be made.
    void render(const World& world, const CameraView& camera, const ShadowFrame& frame, const ShadowMaps& maps,
                const RenderOptions& options, FrameStats& stats);
    /// `render` with the last frame and the maps of `shadows`.
    void render(const World& world, const CameraView& camera, const ShadowSystem& shadows, const RenderOptions& options,
                FrameStats& stats);

    /// Reads back the last frame. `camera` turns camera-relative positions back into world ones.
    [[nodiscard]] FrameImages readback(const CameraView& camera, FrameStats& stats) const;

    /// The exposure meter's histogram of the last frame's linear colour, counted on the GPU (a
    /// compute pass over the colour target): what `luminanceHistogram(readback(...).color)`
    /// counts on the CPU, without reading the frame back (1.5 KB of counters). Give it to
    /// `exposureFromHistogram`. Times the pass as `Present/Meter` in `stats` when timing is on.
    [[nodiscard]] LuminanceHistogram meterExposure(FrameStats& stats);
    /// Tone-maps the last frame's linear colour with `exposure` on the GPU, by the functions of
    /// shadow/tone_map.h that `toneMapToSrgb8` runs on the CPU (they agree within 1/255), into
    /// the renderer's display texture: RGBA8 holding sRGB-encoded values, the frame's size, row 0
    /// the image's top row (a UI draws it with texture coordinate (0, 0) at its top-left). The
    /// texture stays the renderer's and is rewritten by the next call. Times the pass as
    /// `Present/ToneMap` in `stats` when timing is on.
    GlTexture presentToTexture(float exposure, FrameStats& stats);
    /// The display texture of the last `presentToTexture` as 8-bit RGB, rows top first (a
    /// screenshot); empty before the first.
    [[nodiscard]] std::vector<std::uint8_t> readPresented() const;
    /// `presentToTexture`, then the display texture copied to the default framebuffer of size
    /// `width` x `height` (a window without a UI), stretched to it.
    void present(int width, int height, float exposure);

    /// The GPU copies of the scene's meshes: owned by the renderer, which collects them in
    /// `render`; the shadow maps draw from the same cache (`ShadowSystem::render(world, meshes,
    /// stats)`) without collecting it.
    [[nodiscard]] MeshCache& meshes();
    /// `HostGlError` warnings of the calls without a `FrameStats` (the constructor, `present`, `readPresented`),
    /// at most 16 until cleared; the next `render` or `readback` moves them into its stats.
    [[nodiscard]] const std::vector<Warning>& warnings() const;
    /// Forgets the warnings read.
    void clearWarnings();
    /// Per-pass timing of `render` and `readback`, as `ShadowSystem::setTiming` (default off).
    void setTiming(bool enabled);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
