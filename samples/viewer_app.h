// The viewer's state and what it does to it, apart from drawing the UI (viewer_ui.h) and reading
// input (shadow_viewer.cpp): loading a scene, rendering a frame, taking screenshots.
#pragma once

#include "render_output.h"
#include "viewer_camera.h"
#include "viewer_gl.h"

#include <shadow/frame_runner.h>
#include <shadow/scene.h>
#include <shadow/window.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace shadow::viewer {

/// The last frames' timings (ms), for the UI's graphs: a ring of `kFrames`.
struct TimingHistory {
    static constexpr int kFrames = 240;
    enum Series { Shadow, Main, Present, Cpu, Frame, kSeries };
    static constexpr std::array<const char*, kSeries> kNames = {"shadow passes", "main passes", "present",
                                                                "CPU (animate..submit)", "whole frame"};
    std::array<std::array<float, kFrames>, kSeries> ms{};
    int next = 0;    ///< where the next frame goes (the oldest entry)
    int filled = 0;  ///< frames recorded, up to kFrames

    void push(const FrameStats& stats, double frameMs);
};

/// Which shadow-map layer the UI shows.
struct ShadowMapView {
    bool shown = false;
    int light = 0;
    int layer = 0;
    bool stale = true;  ///< the selection changed: read the layer again
};

/// Everything the viewer keeps between frames.
struct ViewerState {
    Window* window = nullptr;
    std::string sceneSpec;
    /// Which clip plays (`--animation`, the clip picker): empty for the first, `all`, an index or
    /// a name; a dropped file plays its first.
    std::string animation;
    Scene scene;
    /// Whether a scene without lights gets the default rig (--no-default-lights, --no-ground,
    /// the Scene panel's checkboxes), and whether the one shown got it.
    samples::DefaultRigChoice rigChoice;
    bool defaultRigShown = false;
    CameraRig rig;
    std::unique_ptr<FrameRunner> runner;  ///< made anew per scene (its caches are per scene)
    FrameStats stats;                     ///< reused every frame
    RenderOptions options;                ///< the debug view and the render size
    /// Render at this size; absent: the window's framebuffer size.
    std::optional<std::pair<int, int>> fixedSize;
    double time = 0.0;  ///< animation time (s)
    bool paused = false;
    float speed = 1.0f;
    bool autoExposure = true;  ///< each frame's exposure from its own image, as shadow_render's
    float exposure = 1.0f;     ///< the last frame's, or the fixed one
    bool showUi = true;
    ShadowMapView mapView;
    /// The last frame, tone-mapped on the GPU (the renderer's display texture, which it owns).
    GlTexture frameTexture;
    UiTexture mapTexture;
    int frameWidth = 0, frameHeight = 0;
    TimingHistory history;
    std::string status;     ///< the last message for the user (a screenshot written, ...)
    std::string loadError;  ///< why the last dropped scene did not load (the old one is kept)
    /// A setting, the time or the view changed since the last frame (a script's screenshot
    /// renders a frame first).
    bool dirty = true;
    int screenshots = 0;
};

/// Loads `spec` into `state` (a new frame runner, the clip of `state.animation`, the camera of
/// `--camera`/the scene's first/the default one, posed at `state.time`) and prints its load
/// warnings on stderr (the Frame panel lists them). On an error `state` is untouched and the
/// error returned.
[[nodiscard]] Status loadInto(ViewerState& state, const std::string& spec, std::optional<int> camera);
/// Renders one frame of the scene at `state.time`, meters its exposure (when automatic) and
/// tone-maps it into `frameTexture`, both on the GPU (Renderer::meterExposure,
/// presentToTexture); records timings. `frameMs` is the whole last frame's wall time.
void renderFrame(ViewerState& state, double frameMs);
/// Refreshes `mapTexture` from the shown shadow-map layer when it changed.
void updateShadowMapTexture(ViewerState& state);
/// Writes the last rendered frame (no UI) to `path` as PNG.
[[nodiscard]] Status writeFrameScreenshot(const ViewerState& state, const std::string& path);
/// Writes the window's back buffer (the scene with the UI) to `path` as PNG.
[[nodiscard]] Status writeWindowScreenshot(const ViewerState& state, const std::string& path);

}  // namespace shadow::viewer
