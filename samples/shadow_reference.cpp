// shadow_reference: the ray-traced truth of every light's visibility, for the pixels
// shadow_render draws.
//
//   shadow_reference SCENE [--out DIR] [--size WxH] [--camera N] [--time T] [--samples N]
//                    [--positions FILE] [--threads K] [--seed S] [--animation NAME|INDEX|all]
//                    [--no-default-lights] [--no-ground]
//
// SCENE, --size, --camera, --time, --animation, --no-default-lights and --no-ground mean what
// they mean to shadow_render (a file without lights gets the same default rig), so both programs
// shade the same pixels; the scene's load warnings go to stderr and reference.json. Each pixel's
// point is the first surface on its camera ray or, with
// --positions, the world position in an engine position.exr (its size is then the image size;
// a covered pixel that is not finite is bad input, one beyond 1e9 m in some coordinate is
// background, counted in reference.json's pixels.positionsBeyondReach).
// For every light, --samples stratified shadow rays go to its emitter (engine/src/reference/
// shadow/reference.h states the choices). Writes into DIR: visibility_<i>.exr (and a grey
// visibility_<i>.png to look at), stderr_<i>.exr
// (binomial standard error per pixel), lit_<i>.exr (1 where the light shades the surface), position.exr and reference.json. Progress goes to stderr
// when it is a terminal. Bad input: one message, exit code 2.
#include <shadow/scene.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>

#include <shadow/reference.h>
#include "cli_common.h"
#include "command_line.h"
#include "render_output.h"

namespace {

using namespace shadow;

using samples::kExitBadInput;
using samples::kExitFailure;
constexpr const char* kDefaultSize = "640x360";

struct Options {
    std::string scene;
    std::string out = "out";
    std::string size = kDefaultSize;
    bool sizeGiven = false;
    std::optional<int> camera;
    double time = 0.0;
    int samples = 256;
    std::string positions;
    int threads = 0;
    std::uint32_t seed = 1;
    std::string animation;          ///< which clip plays: empty (the first), all, an index or a name
    samples::DefaultRigChoice rig;  ///< for a file without lights, as shadow_render's
};

int fail(int code, const std::string& message) { return samples::failAs("shadow_reference", code, message); }

/// Prints "tracing NN%" over itself, only when stderr is a terminal.
std::function<void(int, int)> progressPrinter() {
    if (::isatty(STDERR_FILENO) == 0) return {};
    return [last = -1](int done, int total) mutable {
        const int percent = 100 * done / std::max(total, 1);
        if (percent == last) return;
        last = percent;
        std::fprintf(stderr, "\rshadow_reference: tracing %3d%%%s", percent, done == total ? "\n" : "");
        std::fflush(stderr);
    };
}

nlohmann::json lightsJson(const Scene& scene, const reference::ReferenceResult& r) {
    nlohmann::json lights = nlohmann::json::array();
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const World& w = scene.world;
        const Name* name = w.tryGet<Name>(scene.lights[i]);
        const Light* light = w.tryGet<Light>(scene.lights[i]);
        const reference::LightReference& l = r.lights[i];
        nlohmann::json j;
        j["index"] = i;
        j["node"] = name != nullptr ? name->value : "";
        j["type"] = light != nullptr ? lightTypeName(light->type) : "";
        if (light != nullptr) {
            if (light->type == LightType::Directional)
                j["angularRadius"] = light->angularRadius;
            else
                j["radius"] = light->radius;
        }
        j["raysPerPixel"] = l.raysPerPixel;
        j["meanStandardError"] = l.meanStandardError;
        j["maxStandardError"] = l.maxStandardError;
        j["meanVisibility"] = l.meanVisibility;
        j["sizeClamped"] = l.sizeClamped;
        j["missing"] = l.missing;
        j["visibility"] = "visibility_" + std::to_string(i) + ".exr";
        j["standardError"] = "stderr_" + std::to_string(i) + ".exr";
        j["litMask"] = "lit_" + std::to_string(i) + ".exr";
        lights.push_back(j);
    }
    return lights;
}

std::string referenceJson(const Scene& scene, const Options& o, int cameraIndex, int width, int height,
                          const reference::ReferenceResult& r, double startTime, double totalSeconds) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["startTime"] = startTime;  // shadow_compare: files older than this are an earlier run's
    j["sceneSpec"] = o.scene;
    j["size"] = {width, height};
    j["camera"] = cameraIndex;
    j["time"] = o.time;
    j["mode"] = o.positions.empty() ? "camera" : "positions";
    j["positions"] = o.positions;
    j["samplesPerPixel"] = o.samples;
    j["seed"] = o.seed;
    j["threads"] = r.threads;
    j["epsilon"] = {{"min", r.epsilonMin}, {"max", r.epsilonMax}};  // shadow-ray offsets (m), per point
    j["standardErrorModel"] = "binomial sqrt(v(1-v)/N); an upper bound for stratified samples";
    j["timeSeconds"] = {{"build", r.buildSeconds}, {"trace", r.traceSeconds}, {"total", totalSeconds}};
    j["pixels"] = {{"covered", r.coveredPixels},
                   {"nonReceiver", r.nonReceiverPixels},
                   {"positionsWithoutSurface", r.positionsWithoutSurface},
                   {"positionsBeyondReach", r.positionsBeyondReach}};
    j["lights"] = lightsJson(scene, r);
    j["animation"] = samples::animationJson(scene);
    // The scene's own (the default rig's notice among them), printed on stderr too.
    j["warnings"] = samples::warningsJson({&scene.warnings});
    return j.dump(2) + "\n";
}

Status writeOutputs(const std::string& dir, reference::ReferenceResult& r) {
    FrameImages images;
    images.position = std::move(r.wsPosition);
    images.visibility = std::move(r.visibility);
    const samples::OutputSelection selection{false, true, true, false};
    if (Status s = samples::writeFrameImages(dir, images, selection, 1.0f); !s) return s;
    for (std::size_t i = 0; i < images.visibility.size(); ++i) {
        // A picture of the truth to look at: visibility as grey, 0 black and 1 white, linear.
        const ImageF& v = images.visibility[i];
        std::vector<std::uint8_t> grey(static_cast<std::size_t>(v.width) * static_cast<std::size_t>(v.height) * 3U);
        for (std::size_t p = 0; p * 3U < grey.size(); ++p) {
            const float value = v.pixels[p * static_cast<std::size_t>(v.channels)];
            const auto byte = static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(value, 0.0f, 1.0f)));
            grey[3U * p] = grey[3U * p + 1] = grey[3U * p + 2] = byte;
        }
        const std::string path = dir + "/visibility_" + std::to_string(i) + ".png";
        if (Status s = writePng(path, v.width, v.height, 3, grey); !s) return s;
    }
    for (std::size_t i = 0; i < r.standardError.size(); ++i) {
        const std::string path = dir + "/stderr_" + std::to_string(i) + ".exr";
        if (Status s = writeExr(path, r.standardError[i], {"Y"}); !s) return s;
        if (Status s = writeExr(dir + "/lit_" + std::to_string(i) + ".exr", r.lit[i], {"Y"}); !s) return s;
    }
    return Ok{};
}

int run(Options& o) {
    const auto start = std::chrono::steady_clock::now();
    const double startTime = samples::unixSecondsNow();
    auto size = samples::parseSize(o.size);
    if (!size) return fail(kExitBadInput, size.error().message);
    if (o.samples < 1 || o.samples > (1 << 20)) return fail(kExitBadInput, "--samples: must be in [1, 1048576]");
    if (o.threads < 0 || o.threads > 1024)
        return fail(kExitBadInput, "--threads: must be in [0, 1024] (0 = all cores)");
    if (!std::isfinite(o.time)) return fail(kExitBadInput, "--time: must be a finite number of seconds");
    if (o.camera && *o.camera < 0)
        return fail(kExitBadInput, "--camera " + std::to_string(*o.camera) + ": must be >= 0");

    std::optional<ImageF> positions;
    if (!o.positions.empty()) {
        Result<ImageF> read = readExr(o.positions, {"R", "G", "B", "A"});
        if (!read) return fail(kExitBadInput, "--positions " + o.positions + ": " + read.error().message);
        if (o.sizeGiven && (read->width != size->first || read->height != size->second)) {
            return fail(kExitBadInput, "--positions " + o.positions + ": image is " + std::to_string(read->width) +
                                           "x" + std::to_string(read->height) + " but --size is " + o.size);
        }
        if (Status s = reference::checkPositions(*read); !s) {
            return fail(kExitBadInput, "--positions " + o.positions + ": " + s.error().message);
        }
        *size = {read->width, read->height};
        positions = std::move(*read);
    }

    Result<Scene> loaded = samples::loadSampleScene(o.scene, o.animation);
    if (!loaded) return fail(kExitBadInput, loaded.error().message);
    Scene& scene = *loaded;
    Result<Entity> camera =
        samples::chooseCameraAndRig(scene, o.camera, o.time, o.rig, static_cast<double>(size->first) / size->second);
    if (!camera) {
        samples::printSceneWarnings("shadow_reference", scene);
        return fail(kExitBadInput, camera.error().message);
    }
    animate(scene.world, o.time);
    (void)updateTransforms(scene.world);
    reportTruncatedMorphs(scene.world, scene.warnings);  // the tracer draws the same targets
    samples::printSceneWarnings("shadow_reference", scene);
    const float aspect = static_cast<float>(size->first) / static_cast<float>(size->second);
    const CameraView view = makeCameraView(scene.world, *camera, aspect);
    int cameraIndex = 0;
    for (std::size_t k = 0; k < scene.cameras.size(); ++k) {
        if (scene.cameras[k] == *camera) cameraIndex = static_cast<int>(k);
    }

    // Input is valid: now the output folder, checked before any tracing.
    if (Status s = samples::prepareOutputDir(o.out); !s) return fail(kExitBadInput, s.error().message);

    reference::ReferenceOptions options;
    options.width = size->first;
    options.height = size->second;
    options.samples = o.samples;
    options.threads = o.threads;
    options.seed = o.seed;
    options.wsPositions = positions ? &*positions : nullptr;
    options.progress = progressPrinter();
    // Every error here is about the input (mesh data, positions); Embree itself does not fail
    // on valid input short of running out of memory.
    Result<reference::ReferenceResult> traced = reference::traceVisibility(scene, view, options);
    if (!traced) return fail(kExitBadInput, traced.error().message);

    const std::string json =
        referenceJson(scene, o, cameraIndex, size->first, size->second, *traced, startTime,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (Status s = writeOutputs(o.out, *traced); !s) return fail(kExitFailure, s.error().message);
    if (Status s = writeTextFileAtomic(o.out + "/reference.json", json); !s)
        return fail(kExitFailure, s.error().message);
    if (traced->positionsBeyondReach > 0) {
        std::cerr << "shadow_reference: warning: " << traced->positionsBeyondReach
                  << " positions beyond 1e9 m (kMaxWorldCoordinate) treated as background\n";
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    samples::CommandLine app{"Ray-traces every light's visibility (the reference the shadow maps approximate)."};
    app.add("scene", o.scene, "a sample scene's name, a .gltf/.glb file or builtin:NAME").required();
    app.add("--out", o.out, "output folder (created if missing)");
    const samples::CommandLine::Option sizeOption =
        app.add("--size", o.size, "image size WxH (default 640x360, or that of --positions)");
    app.add("--camera", o.camera, "index of the scene camera to use (default: the first)");
    app.add("--time", o.time, "animation time (s)");
    app.add("--animation", o.animation, samples::kAnimationHelp);
    app.add("--samples", o.samples, "shadow rays per pixel and light, [1, 1048576]");
    app.add("--positions", o.positions, "shade the world positions of an engine position.exr");
    app.add("--threads", o.threads, "worker threads (0 = all cores)");
    app.add("--seed", o.seed, "seed of the sample patterns");
    samples::addRigFlags(app, o.rig);
    if (const std::optional<int> exit = app.parse(argc, argv, "shadow_reference")) return *exit;
    o.sizeGiven = sizeOption.given();
    try {
        return run(o);
    } catch (const std::exception& e) {
        return fail(kExitFailure, e.what());
    }
}
