// shadow_render: renders a scene headless (OSMesa) and writes images, AOVs and stats.json.
//
//   shadow_render SCENE [--out DIR] [--size WxH] [--camera N] [--time T] [--frames N --dt S]
//                 [--technique NAME|auto] [--shadow-budget-ms MS] [--depth-mode MODE] [--aov color,visibility,position,depth]
//                 [--debug NAME] [--debug-light I] [--frame-images] [--no-cache] [--exposure E]
//                 [--shader-cache DIR] [--field-voxels N] [--sdf-steps N] [--sdf-start-offset M] [--max-filter-texels N]
//                 [--map-size N] [--pcf-samples N] [--blocker-samples N]
//                 [--animation NAME|INDEX|all] [--no-default-lights] [--no-ground]
//
// SCENE is a sample scene's name (samples/scenes, e.g. courtyard), a .gltf/.glb path or
// builtin:NAME. With --frames N the scene is animated from
// --time T in steps of --dt S; the images are those of the last frame and the timings in
// stats.json are medians over the frames after the first. --frame-images also writes every
// frame's colour as frames/color_<k>.png. A file without lights is lit by the default rig (a
// shadowed sun and a ground placed from the model's bounds) unless --no-default-lights. Bad
// input: one message, exit code 2.
#include <shadow/context_osmesa.h>
#include <shadow/frame_runner.h>
#include <shadow/program_cache.h>
#include <shadow/scene.h>

#include "cli_common.h"
#include "command_line.h"
#include "render_output.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>

namespace {

using namespace shadow;

using samples::kExitBadInput;
using samples::kExitFailure;

struct Options {
    std::string scene;
    std::string out = "out";
    std::string size = "640x360";
    std::optional<int> camera;
    double time = 0.0;
    int frames = 1;
    double dt = 1.0 / 30.0;
    std::optional<std::string> technique;  ///< absent: each light keeps its own
    std::optional<double> shadowBudgetMs;  ///< technique auto's budget; absent: none
    std::optional<std::string> depthMode;  ///< absent: each light keeps its own
    std::string aov = "color,visibility,position,depth";
    std::string debug;
    int debugLight = 0;
    bool frameImages = false;
    bool noCache = false;
    int fieldVoxels = 64;                  ///< technique sdf: voxels along each mesh field's edge (cubed: the budget)
    std::optional<float> sdfStartOffset;   ///< absent: each light keeps its own
    std::optional<float> maxFilterTexels;  ///< absent: each light keeps its own
    std::optional<int> mapSize;            ///< absent: each light keeps its own
    std::optional<int> pcfSamples;         ///< absent: each light keeps its own
    std::optional<int> blockerSamples;     ///< absent: each light keeps its own
    std::optional<int> sdfSteps;           ///< absent: each light keeps its own
    std::string shaderCache;
    std::string screenVisibility = "auto";
    bool contactShadows = false;    ///< turn every shadowed light's contact shadows on
    std::optional<float> exposure;  ///< absent: from the first frame read back (autoExposure)
    std::string animation;          ///< which clip plays: empty (the first), all, an index or a name
    samples::DefaultRigChoice rig;  ///< for a file without lights
};

int fail(int code, const std::string& message) { return samples::failAs("shadow_render", code, message); }

/// A shadowed light's settings with the command line's overrides (checked before) applied.
void overrideShadow(Shadow& s, const Options& o, std::optional<ShadowTechnique> technique,
                    std::optional<DepthMode> depthMode) {
    if (technique) {
        s.technique = *technique;
        s.autoTechnique = o.technique == kAutoTechniqueName;
    }
    if (depthMode) samples::applyDepthMode(s, *depthMode);
    if (o.contactShadows) s.contactShadows = true;
    if (o.sdfStartOffset) s.sdfStartOffset = *o.sdfStartOffset;
    if (o.maxFilterTexels) s.maxFilterTexels = *o.maxFilterTexels;
    if (o.mapSize) s.mapSize = *o.mapSize;
    if (o.pcfSamples) s.pcfSamples = *o.pcfSamples;
    if (o.blockerSamples) s.blockerSamples = *o.blockerSamples;
    if (o.sdfSteps) s.sdfSteps = *o.sdfSteps;
}

/// The first of the integer overrides outside its range, as the message to fail with; empty
/// when all are in range.
std::string checkCountOverrides(const Options& o) {
    struct Count {
        const char* option;
        const std::optional<int>& value;
        int lo, hi;
    };
    const Count counts[] = {{"--map-size", o.mapSize, 1, 16384},
                            {"--pcf-samples", o.pcfSamples, 1, 64},
                            {"--blocker-samples", o.blockerSamples, 1, 64},
                            {"--sdf-steps", o.sdfSteps, 4, 256}};
    for (const Count& c : counts) {
        if (c.value && (*c.value < c.lo || *c.value > c.hi)) {
            return std::string(c.option) + ": must be in [" + std::to_string(c.lo) + ", " + std::to_string(c.hi) + "]";
        }
    }
    return {};
}

Result<DebugView> parseDebug(const std::string& name) {
    if (name.empty()) return DebugView::None;
    if (name == "cascade") return DebugView::Cascade;
    if (name == "blocker") return DebugView::BlockerDepth;
    if (name == "penumbra") return DebugView::Penumbra;
    if (name == "visibility") return DebugView::Visibility;
    if (name == "steps") return DebugView::MarchSteps;
    if (name == "closest") return DebugView::Closest;
    if (name == "shadowmap") return DebugView::None;  // written from the maps themselves
    return Error{ErrorCode::InvalidArgument,
                 "--debug '" + name +
                     "': unknown view (known: shadowmap, cascade, blocker, penumbra, visibility, steps, closest)"};
}

/// Writes every layer of every shadow map as linear depth (EXR, metres) and a grey PNG.
Status writeShadowMaps(const std::string& dir, const ShadowSystem& shadows) {
    const ShadowFrame& frame = shadows.frame();
    for (std::size_t i = 0; i < frame.lights.size(); ++i) {
        const ShadowLightPlan& plan = frame.lights[i];
        for (std::size_t k = 0; k < plan.layers.size(); ++k) {
            const std::vector<float> depth = shadows.maps().readLayerDepth(i, static_cast<int>(k));
            ImageF img = makeImage(plan.mapSize, plan.mapSize, 1);
            const float scale = plan.layers[k].depthScale;
            std::vector<std::uint8_t> grey(depth.size());
            for (int y = 0; y < plan.mapSize; ++y) {
                for (int x = 0; x < plan.mapSize; ++x) {
                    // Texture rows start at the bottom; images at the top.
                    const float d = depth[static_cast<std::size_t>(plan.mapSize - 1 - y) * plan.mapSize + x];
                    img.at(x, y, 0) = d;
                    grey[static_cast<std::size_t>(y) * plan.mapSize + x] =
                        static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(d / scale, 0.0f, 1.0f)));
                }
            }
            const std::string stem =
                dir + "/shadowmap_" + std::to_string(plan.sceneIndex) + "_layer" + std::to_string(k);
            if (Status s = writeExr(stem + ".exr", img, {"Y"}); !s) return s;
            std::vector<std::uint8_t> rgb(grey.size() * 3);
            for (std::size_t p = 0; p < grey.size(); ++p) rgb[3 * p] = rgb[3 * p + 1] = rgb[3 * p + 2] = grey[p];
            if (Status s = writePng(stem + ".png", plan.mapSize, plan.mapSize, 3, rgb); !s) return s;
        }
    }
    return Ok{};
}

int run(const Options& o) {
    const double startTime = samples::unixSecondsNow();
    auto size = samples::parseSize(o.size);
    if (!size) return fail(kExitBadInput, size.error().message);
    auto selection = samples::parseAovList(o.aov);
    if (!selection) return fail(kExitBadInput, selection.error().message);
    auto debug = parseDebug(o.debug);
    if (!debug) return fail(kExitBadInput, debug.error().message);
    std::optional<ShadowTechnique> technique;
    if (o.technique) {
        auto t = samples::parseTechnique(*o.technique);
        if (!t) return fail(kExitBadInput, "--technique: " + t.error().message);
        technique = *t;
    }
    if (o.shadowBudgetMs && !(std::isfinite(*o.shadowBudgetMs) && *o.shadowBudgetMs >= 0.0)) {
        return fail(kExitBadInput, "--shadow-budget-ms: must be a finite number of milliseconds >= 0 (0: no budget)");
    }
    const Result<ScreenVisibility> screenVisibility = samples::parseScreenVisibilitySetting(o.screenVisibility);
    if (!screenVisibility) return fail(kExitBadInput, "--screen-visibility: " + screenVisibility.error().message);
    std::optional<DepthMode> depthMode;
    if (o.depthMode) {
        depthMode = depthModeFromName(*o.depthMode);
        if (!depthMode) {
            return fail(kExitBadInput,
                        "--depth-mode: unknown depth mode '" + *o.depthMode + "' (known: nearest, midpoint, second)");
        }
    }
    if (!std::isfinite(o.time)) return fail(kExitBadInput, "--time: must be a finite number of seconds");
    if (o.exposure && !(std::isfinite(*o.exposure) && *o.exposure > 0.0f)) {
        return fail(kExitBadInput, "--exposure: must be a finite number > 0");
    }
    if (!std::isfinite(o.dt)) return fail(kExitBadInput, "--dt: must be a finite number of seconds");
    if (o.frames < 1 || o.frames > 100000) return fail(kExitBadInput, "--frames: must be in [1, 100000]");
    if (o.fieldVoxels < samples::kMinFieldEdge || o.fieldVoxels > samples::kMaxFieldEdge) {
        return fail(kExitBadInput, "--field-voxels: must be in [" + std::to_string(samples::kMinFieldEdge) + ", " +
                                       std::to_string(samples::kMaxFieldEdge) + "]");
    }
    if (o.sdfStartOffset && !(*o.sdfStartOffset >= 0.0f && *o.sdfStartOffset <= 1.0f)) {
        return fail(kExitBadInput, "--sdf-start-offset: must be a number of metres in [0, 1]");
    }
    if (o.maxFilterTexels && !(*o.maxFilterTexels >= 1.0f && *o.maxFilterTexels <= 256.0f)) {
        return fail(kExitBadInput, "--max-filter-texels: must be a number of texels in [1, 256]");
    }
    if (const std::string bad = checkCountOverrides(o); !bad.empty()) return fail(kExitBadInput, bad);
    if (o.camera && *o.camera < 0)
        return fail(kExitBadInput, "--camera " + std::to_string(*o.camera) + ": must be >= 0");

    Result<Scene> loaded = samples::loadSampleScene(o.scene, o.animation);
    if (!loaded) return fail(kExitBadInput, loaded.error().message);
    Scene& scene = *loaded;
    if (o.debugLight < 0 || (!scene.lights.empty() && o.debugLight >= static_cast<int>(scene.lights.size()))) {
        return fail(kExitBadInput, "--debug-light " + std::to_string(o.debugLight) + ": the scene has " +
                                       std::to_string(scene.lights.size()) + " lights");
    }
    Result<Entity> chosen =
        samples::chooseCameraAndRig(scene, o.camera, o.time, o.rig, static_cast<double>(size->first) / size->second);
    if (!chosen) return fail(kExitBadInput, chosen.error().message);
    // After the rig: its sun is a shadowed light like the file's own.
    scene.world.view<Shadow>().each([&](Entity, Shadow& s) { overrideShadow(s, o, technique, depthMode); });
    const Entity camera = *chosen;
    samples::printSceneWarnings("shadow_render", scene);  // the default rig's notice among them
    const std::size_t loadWarnings = scene.warnings.size();

    auto context = createOsMesaContext();
    if (!context) return fail(kExitFailure, context.error().message);
    if (!o.shaderCache.empty()) {
        if (Status s = setProgramBinaryCache(o.shaderCache); !s)
            return fail(kExitBadInput, "--shader-cache: " + s.error().message);
    }

    RenderOptions options;
    options.width = size->first;
    options.height = size->second;
    options.aovs = selection->anyAov() || *debug == DebugView::Visibility;
    options.debugView = *debug;
    options.debugLight = o.debugLight;
    options.screenVisibility = *screenVisibility;
    // The size against the context's limits and the renderer's memory cap, before anything is
    // allocated (an over-large size would otherwise end in an incomplete framebuffer).
    if (Status s = checkRenderSize(options, static_cast<int>(scene.lights.size())); !s) {
        return fail(kExitBadInput, "--size " + o.size + ": " + s.error().message);
    }

    // Input is valid: now the output folder, checked before any rendering so a bad one costs
    // nothing, and created only for input that will be rendered.
    if (Status s = samples::prepareOutputDir(o.out); !s) return fail(kExitBadInput, s.error().message);

    FrameRunner runner;
    runner.shadows().planner().setCaching(!o.noCache);
    if (o.shadowBudgetMs) {
        ShadowLimits limits = runner.shadows().planner().limits();
        limits.shadowBudgetMs = *o.shadowBudgetMs;
        runner.shadows().planner().setLimits(limits);
    }
    samples::setFieldEdge(runner.shadows().planner(), o.fieldVoxels);
    std::vector<FrameStats> frames;
    std::optional<float> exposure = o.exposure;
    if (o.frameImages) std::filesystem::create_directories(o.out + "/frames");
    for (int f = 0; f < o.frames; ++f) {
        const double t = o.time + o.dt * f;
        frames.push_back(runner.runFrame(scene, t, camera, options));
        const bool last = f + 1 == o.frames;
        if (!last && !o.frameImages) continue;
        FrameImages images = runner.renderer().readback(runner.lastCamera(), frames.back());
        // One exposure for the whole animation, so its frames do not flicker.
        if (!exposure) exposure = autoExposure(images.color);
        if (o.frameImages) {
            char name[64];
            std::snprintf(name, sizeof(name), "/frames/color_%04d.png", f);
            const auto srgb = toneMapToSrgb8(images.color, *exposure);
            if (Status s = writePng(o.out + name, images.color.width, images.color.height, 3, srgb); !s) {
                return fail(kExitFailure, s.error().message);
            }
        }
        if (last) {
            if (Status s = samples::writeFrameImages(o.out, images, *selection, *exposure); !s) {
                return fail(kExitFailure, s.error().message);
            }
        }
    }
    if (o.debug == "shadowmap") {
        if (Status s = writeShadowMaps(o.out, runner.shadows()); !s) return fail(kExitFailure, s.error().message);
    }
    const std::string json =
        samples::statsJson(scene, frames, options.width, options.height, o.technique.value_or(""), startTime);
    if (Status s = writeTextFileAtomic(o.out + "/stats.json", json); !s) return fail(kExitFailure, s.error().message);
    // The scene's warnings the frames added (once per entity), then the last frame's.
    samples::printSceneWarnings("shadow_render", scene, loadWarnings);
    for (const Warning& w : frames.back().warnings) std::cerr << "shadow_render: warning: " << w.message << "\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    shadow::samples::keepFreedHeap();
    Options o;
    samples::CommandLine app{
        "Renders a scene with per-light shadows, headless, and writes images, AOVs and stats.json."};
    app.add("scene", o.scene, "a sample scene's name, a .gltf/.glb file or builtin:NAME").required();
    app.add("--out", o.out, "output folder (created if missing)");
    app.add("--size", o.size, "image size WxH");
    app.add("--camera", o.camera, "index of the scene camera to use (default: the first)");
    app.add("--time", o.time, "animation time of the first frame (s)");
    app.add("--animation", o.animation, samples::kAnimationHelp);
    app.add("--frames", o.frames, "frames to render");
    app.add("--dt", o.dt, "time step between frames (s)");
    app.add("--technique", o.technique,
            "override every shadowed light: " + techniqueNameList() + ", " + kAutoTechniqueName +
                " (chosen per light and frame within --shadow-budget-ms)");
    app.add("--shadow-budget-ms", o.shadowBudgetMs,
            "technique auto: ms per frame the auto lights' shadow passes and lookups may take, >= 0 "
            "(default 0: no budget, least predicted error)");
    app.add("--depth-mode", o.depthMode,
            "override every shadowed light's depth mode: nearest|midpoint|second (midpoint and second "
            "also set constant and slope bias to 0)");
    app.add("--aov", o.aov, "outputs: color,visibility,position,depth");
    app.add("--debug", o.debug, "debug view: shadowmap|cascade|blocker|penumbra|visibility|steps|closest");
    app.add("--debug-light", o.debugLight, "scene light index the debug view shows");
    app.add("--exposure", o.exposure, "exposure of color.png (default: log-average luminance to 0.18)");
    app.flag("--frame-images", o.frameImages, "write every frame as frames/color_<k>.png");
    app.flag("--no-cache", o.noCache, "redraw every shadow layer every frame");
    app.add("--field-voxels", o.fieldVoxels,
            "technique sdf: voxels along the edge of each mesh's distance field, [16, 256] (default 64: 64^3 voxels)");
    app.add("--sdf-steps", o.sdfSteps, "technique sdf: override every light's sdfSteps (most march steps), [4, 256]");
    app.add("--sdf-start-offset", o.sdfStartOffset, "technique sdf: override every light's sdfStartOffset (m), [0, 1]");
    app.add("--max-filter-texels", o.maxFilterTexels,
            "override every light's maxFilterTexels (the widest filter, texels), [1, 256]");
    app.add("--map-size", o.mapSize,
            "override every light's mapSize (texels per layer edge), [1, 16384]; an auto light's is chosen");
    app.add("--pcf-samples", o.pcfSamples,
            "override every light's pcfSamples (most PCF taps), [1, 64]; an auto light's are chosen");
    app.add("--blocker-samples", o.blockerSamples,
            "override every light's blockerSamples (PCSS search points), [1, 64]; an auto light's are chosen");
    app.add("--screen-visibility", o.screenVisibility, samples::kScreenVisibilityHelp);
    app.flag("--contact-shadows", o.contactShadows,
             "turn on every shadowed light's screen-space contact shadows (drawn by the screen-space "
             "visibility stage: with --screen-visibility off they are left out)");
    samples::addRigFlags(app, o.rig);
    app.add("--shader-cache", o.shaderCache,
            "folder of linked program binaries, read and written (the driver's own cache aside)");
    if (const std::optional<int> exit = app.parse(argc, argv, "shadow_render")) return *exit;
    try {
        return run(o);
    } catch (const GlError& e) {
        return fail(kExitFailure, std::string("OpenGL: ") + e.what());
    } catch (const std::exception& e) {
        return fail(kExitFailure, e.what());
    }
}
