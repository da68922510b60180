#include "viewer_app.h"

#include "render_output.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace shadow::viewer {
namespace {

/// Largest edge of the shadow-map view's texture (texels): larger maps are shown subsampled.
constexpr int kMaxMapViewTexels = 1024;

/// Width / height of the frames the viewer renders: --size's, else the window's.
double imageAspect(const ViewerState& state) {
    int width = 16, height = 9;
    if (state.fixedSize) {
        std::tie(width, height) = *state.fixedSize;
    } else if (state.window != nullptr) {
        state.window->framebufferSize(width, height);
    }
    return width > 0 && height > 0 ? static_cast<double>(width) / height : 16.0 / 9.0;
}

}  // namespace

void TimingHistory::push(const FrameStats& stats, double frameMs) {
    const double cpu = stats.cpuAnimateMs + stats.cpuTransformsMs + stats.cpuShadowPrepareMs + stats.cpuRenderSubmitMs;
    const std::array<double, kSeries> values = {stats.passMs("Shadow/"), stats.passMs("Main/"),
                                                stats.passMs("Present/"), cpu, frameMs};
    for (int s = 0; s < kSeries; ++s) ms[s][next] = static_cast<float>(values[s]);
    next = (next + 1) % kFrames;
    filled = std::min(filled + 1, kFrames);
}

Status loadInto(ViewerState& state, const std::string& spec, std::optional<int> camera) {
    Result<Scene> loaded = samples::loadSampleScene(spec, state.animation);
    if (!loaded) return loaded.error();
    Scene& scene = *loaded;
    Result<Entity> chosen = samples::chooseCameraAndRig(scene, camera, state.time, state.rigChoice, imageAspect(state));
    if (chosen) samples::printSceneWarnings("shadow_viewer", scene);  // the default rig's notice among them
    if (!chosen) return chosen.error();
    // Posed at the current time, so that the rig sees the scene's bounds and camera pose.
    animate(scene.world, state.time);
    (void)updateTransforms(scene.world);
    // The old runner's GL objects belong to the old scene's meshes and lights: free them first.
    state.frameTexture = {};  // the old runner's renderer owns it
    state.runner.reset();
    state.runner = std::make_unique<FrameRunner>();
    state.defaultRigShown = std::any_of(scene.warnings.begin(), scene.warnings.end(),
                                        [](const Warning& w) { return w.code == WarningCode::DefaultRigAdded; });
    state.scene = std::move(scene);
    state.sceneSpec = spec;
    state.rig.reset(state.scene, *chosen);
    const int lights = static_cast<int>(state.scene.lights.size());
    state.options.debugLight = std::clamp(state.options.debugLight, 0, std::max(lights - 1, 0));
    state.mapView.light = std::clamp(state.mapView.light, 0, std::max(lights - 1, 0));
    state.mapView.stale = true;
    state.history = {};
    state.dirty = true;
    return Ok{};
}

void renderFrame(ViewerState& state, double frameMs) {
    RenderOptions& options = state.options;
    if (state.fixedSize) {
        options.width = state.fixedSize->first;
        options.height = state.fixedSize->second;
    } else {
        state.window->framebufferSize(options.width, options.height);
    }
    if (options.width < 1 || options.height < 1) return;  // minimised
    // The visibility view reads the per-light visibility outputs (as shadow_render's does).
    options.aovs = options.debugView == DebugView::Visibility;
    state.runner->runFrame(state.scene, state.time, state.rig.camera(), options, state.stats);
    // Metered and tone-mapped where the frame is (shadow/tone_map.h, as shadow_render's
    // color.png on the CPU): reading the frame's floats back and mapping them here took 18-50 ms.
    Renderer& renderer = state.runner->renderer();
    if (state.autoExposure) state.exposure = exposureFromHistogram(renderer.meterExposure(state.stats));
    state.frameTexture = renderer.presentToTexture(state.exposure, state.stats);
    state.frameWidth = options.width;
    state.frameHeight = options.height;
    state.history.push(state.stats, frameMs);
    updateShadowMapTexture(state);
    state.dirty = false;
}

void updateShadowMapTexture(ViewerState& state) {
    ShadowMapView& view = state.mapView;
    if (!view.shown) return;
    const auto light = static_cast<std::size_t>(view.light);
    const ShadowFrame& frame = state.runner->shadows().frame();
    if (light >= frame.lights.size() || light >= state.stats.lights.size()) return;
    const LightShadowStats& ls = state.stats.lights[light];
    if (!view.stale && ls.layersDrawn == 0 && ls.layersCleared == 0 && !ls.mapAllocated) return;
    view.stale = false;
    const ShadowLightPlan& plan = frame.lights[light];
    if (view.layer >= static_cast<int>(plan.layers.size())) {
        state.mapTexture.upload(1, 1, {0, 0, 0});
        return;
    }
    const std::vector<float> depth = state.runner->shadows().maps().readLayerDepth(light, view.layer);
    const int size = ls.mapSize;  // as allocated (the memory budget may have halved the plan's)
    if (size < 1 || depth.size() != static_cast<std::size_t>(size) * size) return;
    // Linear depth over the layer's depth scale, near black, far white (as shadow_render's
    // shadowmap PNGs), every `step`-th texel so the texture stays within 1024^2; texture rows
    // start at the bottom, images at the top.
    const float scale = plan.layers[static_cast<std::size_t>(view.layer)].depthScale;
    const int step = (size + kMaxMapViewTexels - 1) / kMaxMapViewTexels;
    const int shown = size / step;
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(shown) * shown * 3);
    for (int y = 0; y < shown; ++y) {
        for (int x = 0; x < shown; ++x) {
            const float d = depth[static_cast<std::size_t>(size - 1 - y * step) * size + x * step];
            const auto grey = static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(d / scale, 0.0f, 1.0f)));
            const std::size_t p = (static_cast<std::size_t>(y) * shown + x) * 3;
            rgb[p] = rgb[p + 1] = rgb[p + 2] = grey;
        }
    }
    state.mapTexture.upload(shown, shown, rgb);
}

Status writeFrameScreenshot(const ViewerState& state, const std::string& path) {
    if (!state.runner) return Error{ErrorCode::Internal, "no frame rendered yet"};
    const std::vector<std::uint8_t> rgb = state.runner->renderer().readPresented();
    if (rgb.empty()) return Error{ErrorCode::Internal, "no frame rendered yet"};
    return writePng(path, state.frameWidth, state.frameHeight, 3, rgb);
}

Status writeWindowScreenshot(const ViewerState& state, const std::string& path) {
    int width = 0, height = 0;
    state.window->framebufferSize(width, height);
    if (width < 1 || height < 1) return Error{ErrorCode::Internal, "the window has no pixels (minimised)"};
    return writePng(path, width, height, 3, readWindowRgb(width, height));
}

}  // namespace shadow::viewer
