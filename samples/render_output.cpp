#include "render_output.h"

#include <chrono>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <shadow/default_rig.h>
#include <shadow/distance_field.h>
#include <shadow/program_cache.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <unistd.h>

namespace shadow::samples {

Result<std::pair<int, int>> parseSize(const std::string& text) {
    static const std::regex kSize(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(text, m, kSize))
        return Error{ErrorCode::InvalidArgument, "--size '" + text + "': expected WxH, e.g. 640x360"};
    const int w = std::stoi(m[1].str());
    const int h = std::stoi(m[2].str());
    if (w < 1 || h < 1 || w > 16384 || h > 16384) {
        return Error{ErrorCode::InvalidArgument, "--size '" + text + "': width and height must be in [1, 16384]"};
    }
    return std::make_pair(w, h);
}

Result<Entity> chooseCamera(Scene& scene, std::optional<int> index, double time) {
    if (index) {
        if (*index < 0 || *index >= static_cast<int>(scene.cameras.size())) {
            return Error{ErrorCode::InvalidArgument, "--camera " + std::to_string(*index) + ": the scene has " +
                                                         std::to_string(scene.cameras.size()) + " cameras"};
        }
        return scene.cameras[static_cast<std::size_t>(*index)];
    }
    if (!scene.cameras.empty()) return scene.cameras.front();
    animate(scene.world, time);
    (void)updateTransforms(scene.world);
    return addDefaultCamera(scene);
}

void addRigFlags(CommandLine& app, DefaultRigChoice& rig) {
    app.flag(
        "--no-default-lights", [&rig] { rig.lights = false; },
        "show a file without lights as it is (ambient light only) instead of under the default rig (a shadowed sun "
        "placed from the model's bounds, a ground under the model, a camera framing both when the file has none)");
    app.flag(
        "--no-ground", [&rig] { rig.ground = false; }, "the default rig without its shadow-catcher ground");
}

Result<Entity> chooseCameraAndRig(Scene& scene, std::optional<int> index, double time, const DefaultRigChoice& rig,
                                  double imageAspect) {
    if (!rig.lights || !scene.lights.empty()) return chooseCamera(scene, index, time);
    std::optional<Entity> camera;
    if (index || !scene.cameras.empty()) {
        Result<Entity> chosen = chooseCamera(scene, index, time);
        if (!chosen) return chosen;
        camera = *chosen;
    }
    DefaultRigOptions options;
    options.ground = rig.ground;
    options.imageAspect = imageAspect;
    return addDefaultRig(scene, camera, options).camera;
}

Result<OutputSelection> parseAovList(const std::string& list) {
    OutputSelection s{false, false, false, false};
    std::stringstream in(list);
    std::string item;
    bool any = false;
    while (std::getline(in, item, ',')) {
        if (item == "color")
            s.color = true;
        else if (item == "visibility")
            s.visibility = true;
        else if (item == "position")
            s.position = true;
        else if (item == "depth")
            s.depth = true;
        else
            return Error{ErrorCode::InvalidArgument,
                         "--aov: unknown output '" + item + "' (known: color, visibility, position, depth)"};
        any = true;
    }
    if (!any) return Error{ErrorCode::InvalidArgument, "--aov: empty list (known: color, visibility, position, depth)"};
    return s;
}

Status prepareOutputDir(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return Error{ErrorCode::FileUnwritable, "--out " + dir + ": cannot create folder: " + ec.message()};
    if (!fs::is_directory(dir, ec)) return Error{ErrorCode::FileUnwritable, "--out " + dir + ": not a folder"};
    const fs::path probe = fs::path(dir) / (".write-probe-" + std::to_string(::getpid()));
    {
        std::ofstream out(probe);
        if (!out || !(out << "probe") || !(out.flush())) {
            return Error{ErrorCode::FileUnwritable, "--out " + dir + ": folder is not writable"};
        }
    }
    fs::remove(probe, ec);
    return Ok{};
}

Status writeFrameImages(const std::string& dir, const FrameImages& images, const OutputSelection& selection,
                        float exposure) {
    const std::string base = dir + "/";
    if (selection.color) {
        const std::vector<std::uint8_t> srgb = toneMapToSrgb8(images.color, exposure);
        if (Status s = writePng(base + "color.png", images.color.width, images.color.height, 3, srgb); !s) return s;
        if (Status s = writeExr(base + "color.exr", images.color, {"R", "G", "B"}, ExrPixelType::Half); !s) return s;
    }
    if (selection.position && images.position.width > 0) {
        if (Status s = writeExr(base + "position.exr", images.position, {"R", "G", "B", "A"}); !s) return s;
    }
    if (selection.depth && images.depth.width > 0) {
        if (Status s = writeExr(base + "depth.exr", images.depth, {"Y"}); !s) return s;
    }
    if (selection.visibility) {
        for (std::size_t i = 0; i < images.visibility.size(); ++i) {
            const std::string path = base + "visibility_" + std::to_string(i) + ".exr";
            if (Status s = writeExr(path, images.visibility[i], {"Y"}); !s) return s;
        }
    }
    return Ok{};
}

Spread spreadOf(std::vector<double> values) {
    Spread s;
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    s.min = values.front();
    s.max = values.back();
    return s;
}

static_assert(kMinFieldEdge * kMinFieldEdge * kMinFieldEdge == kMinDistanceFieldVoxels);
static_assert(kMaxFieldEdge * kMaxFieldEdge * kMaxFieldEdge == kMaxDistanceFieldVoxels);

void setFieldEdge(ShadowPlanner& planner, int edge) {
    ShadowLimits limits = planner.limits();
    limits.distanceFieldVoxels = edge * edge * edge;
    planner.setLimits(limits);
}

void applyDepthMode(Shadow& s, DepthMode mode) {
    s.depthMode = mode;
    if (mode != DepthMode::Nearest) s.constantBias = s.slopeBias = 0.0f;
}

Result<ScreenVisibility> parseScreenVisibilitySetting(const std::string& name) {
    if (const auto v = parseScreenVisibility(name)) return *v;
    return Error{ErrorCode::InvalidArgument, "unknown setting '" + name + "' (known: off, auto, full, half, quarter)"};
}

Result<ShadowTechnique> parseTechnique(const std::string& name) {
    if (name == kAutoTechniqueName) return ShadowTechnique::Pcss;  // the planner chooses (Shadow::autoTechnique)
    if (const auto t = techniqueFromName(name)) return *t;
    return Error{ErrorCode::InvalidArgument,
                 "unknown technique '" + name + "' (known: " + techniqueNameList() + ", " + kAutoTechniqueName + ")"};
}

namespace {

nlohmann::json spreadJson(const std::vector<double>& values) {
    const Spread s = spreadOf(values);
    return {{"median", s.median}, {"min", s.min}, {"max", s.max}, {"samples", values.size()}};
}

/// Technique auto's choice for light `ls` and what the planner predicted of it, beside what its
/// shadow passes measured in frame `last`.
nlohmann::json autoJson(const LightShadowStats& ls, const FrameStats& last) {
    const AutoLightChoice& a = ls.autoChoice;
    const double predicted = a.predictedShadowPassMs + a.predictedLookupMs;
    return {{"technique", ls.technique},
            {"mapSize", ls.mapSize},
            {"pcfSamples", ls.pcfSamples},
            {"blockerSamples", ls.blockerSamples},
            {"predictedMs", predicted},
            {"predictedShadowPassMs", a.predictedShadowPassMs},
            {"predictedLookupMs", a.predictedLookupMs},
            {"predictedRmse", a.predictedRmse},
            {"penumbraTexels1024", a.input.penumbraTexels1024},
            {"edgeShare1024", a.input.edgeShare1024},
            {"penumbraShare", a.input.penumbraShare},
            {"pixels", a.input.pixels},
            {"measuredShadowPassMs", last.passMs("Shadow/" + ls.name + "/")}};
}

nlohmann::json lightsJson(const Scene& scene, const FrameStats& last) {
    nlohmann::json lights = nlohmann::json::array();
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Entity e = scene.lights[i];
        const World& w = scene.world;
        const Name* name = w.tryGet<Name>(e);
        const Light* light = w.tryGet<Light>(e);
        const Shadow* shadow = w.tryGet<Shadow>(e);
        nlohmann::json j;
        j["index"] = i;
        j["node"] = name != nullptr ? name->value : "";
        j["type"] = light != nullptr ? shadow::lightTypeName(light->type) : "";
        j["technique"] = shadow == nullptr       ? "none"
                         : shadow->autoTechnique ? kAutoTechniqueName
                                                 : techniqueName(shadow->technique);
        j["visibility"] = "visibility_" + std::to_string(i) + ".exr";
        // FrameStats::lights is indexed like Scene::lights; lights that asked for no map have none.
        if (i < last.lights.size() && last.lights[i].requestedMapSize > 0) {
            const LightShadowStats& ls = last.lights[i];
            j["shadow"] = {{"mapSize", ls.mapSize},
                           {"requestedMapSize", ls.requestedMapSize},
                           {"pcfRadiusMetres", ls.pcfRadiusMetres},
                           {"maxFilterTexels", ls.maxFilterTexels},
                           {"pcfSamples", ls.pcfSamples},
                           {"blockerSamples", ls.blockerSamples},
                           {"layers", ls.layers},
                           {"layersDrawn", ls.layersDrawn},
                           {"layersReused", ls.layersReused},
                           {"layersCleared", ls.layersCleared},
                           {"mapAllocated", ls.mapAllocated},
                           {"mapBytes", ls.mapBytes},
                           {"filterChainBytes", ls.filterChainBytes},
                           {"castersDrawn", ls.castersDrawn},
                           {"backgroundsDrawn", ls.backgroundsDrawn},
                           {"castersCulled", ls.castersCulled},
                           {"pyramidTexelsRead", ls.pyramidTexelsRead},
                           {"affectsView", ls.affectsView},
                           {"regionTest", ls.regionTest},
                           {"depthMode", shadow != nullptr ? depthModeName(shadow->depthMode) : "nearest"}};
            if (ls.automatic) j["auto"] = autoJson(ls, last);
        }
        lights.push_back(j);
    }
    return lights;
}

}  // namespace

nlohmann::json warningsJson(std::initializer_list<const std::vector<Warning>*> lists) {
    nlohmann::json warnings = nlohmann::json::array();
    for (const std::vector<Warning>* list : lists) {
        for (const Warning& w : *list) {
            warnings.push_back({{"code", warningCodeName(w.code)}, {"element", w.element}, {"message", w.message}});
        }
    }
    return warnings;
}

nlohmann::json animationJson(const Scene& scene) {
    nlohmann::json clips = nlohmann::json::array();
    for (const AnimationClip& clip : scene.clips) clips.push_back({{"name", clip.name}, {"duration", clip.duration}});
    nlohmann::json played = nlohmann::json::array();
    for (const std::size_t c : scene.playing) played.push_back({{"index", c}, {"name", scene.clips[c].name}});
    return {{"clips", clips}, {"played", played}, {"duration", scene.animationDuration}};
}

void printSceneWarnings(const char* program, const Scene& scene, std::size_t from) {
    for (std::size_t k = from; k < scene.warnings.size(); ++k) {
        std::cerr << program << ": warning: " << scene.warnings[k].message << "\n";
    }
}

double unixSecondsNow() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::string statsJson(const Scene& scene, const std::vector<FrameStats>& frames, int width, int height,
                      const std::string& technique, double startTime) {
    nlohmann::json j;
    const FrameStats& last = frames.back();
    j["scene"] = scene.name;
    j["startTime"] = startTime;
    j["renderer"] = last.renderer;
    j["timingMethod"] = last.timingMethod;
    j["timingLagFrames"] = last.timingLagFrames;
    j["size"] = {width, height};
    j["frames"] = frames.size();
    j["techniqueOverride"] = technique;
    j["lights"] = lightsJson(scene, last);
    j["animation"] = animationJson(scene);

    // Timings: every frame after the first (warm-up: shader compilation, first uploads).
    const std::size_t first = frames.size() > 1 ? 1 : 0;
    std::map<std::string, std::vector<double>> passes;
    std::vector<double> animate, transforms, prepare, submit, shadowTotal, mainTotal;
    for (std::size_t f = first; f < frames.size(); ++f) {
        std::map<std::string, double> perFrame;
        for (const PassTiming& p : frames[f].passes) perFrame[p.name] += p.ms;
        for (const auto& [name, ms] : perFrame) passes[name].push_back(ms);
        animate.push_back(frames[f].cpuAnimateMs);
        transforms.push_back(frames[f].cpuTransformsMs);
        prepare.push_back(frames[f].cpuShadowPrepareMs);
        submit.push_back(frames[f].cpuRenderSubmitMs);
        shadowTotal.push_back(frames[f].passMs("Shadow/"));
        mainTotal.push_back(frames[f].passMs("Main/"));
    }
    nlohmann::json timings;
    timings["warmupFramesExcluded"] = first;
    for (const auto& [name, values] : passes) timings["passes"][name] = spreadJson(values);
    timings["shadowPassesTotal"] = spreadJson(shadowTotal);
    timings["mainPassesTotal"] = spreadJson(mainTotal);
    timings["cpu"] = {{"animate", spreadJson(animate)},
                      {"transforms", spreadJson(transforms)},
                      {"shadowPrepare", spreadJson(prepare)},
                      {"renderSubmit", spreadJson(submit)}};
    j["timingsMs"] = timings;

    j["counters"] = {{"shadowLayersDrawn", last.shadowLayersDrawn},
                     {"shadowLayersReused", last.shadowLayersReused},
                     {"shadowLayersCleared", last.shadowLayersCleared},
                     {"shadowDrawCalls", last.shadowDrawCalls},
                     {"mainDrawCalls", last.mainDrawCalls},
                     {"mainTriangles", last.mainTriangles},
                     {"mainPasses", last.mainPasses},
                     {"programsCompiled", last.programsCompiled},
                     {"shadowScratchBytes", last.shadowScratchBytes},
                     {"distanceFieldBytes", last.distanceFieldBytes},
                     {"distanceFieldsBaked", last.distanceFieldsBaked},
                     {"distanceFieldBakeMs", last.distanceFieldBakeMs},
                     {"entitiesSkippedNonFinite", last.entitiesSkippedNonFinite}};
    nlohmann::json perFrame = nlohmann::json::array();
    for (const FrameStats& f : frames) {
        perFrame.push_back({{"shadowLayersDrawn", f.shadowLayersDrawn},
                            {"shadowLayersReused", f.shadowLayersReused},
                            {"shadowLayersCleared", f.shadowLayersCleared},
                            {"programsCompiled", f.programsCompiled},
                            {"shadowMs", f.passMs("Shadow/")},
                            {"mainMs", f.passMs("Main/")}});
    }
    j["perFrame"] = perFrame;
    // The program binary cache (--shader-cache): programs taken from it, written to it, refused.
    const ProgramCacheStats cache = programCacheStats();
    j["programCache"] = {{"loaded", cache.loaded}, {"stored", cache.stored}, {"rejected", cache.rejected}};
    // One object per warning, the scene's (loading) then the last frame's; "message" is the line
    // the CLI prints on stderr.
    j["warnings"] = warningsJson({&scene.warnings, &last.warnings});
    return j.dump(2) + "\n";
}

std::string sampleScenesDir() {
    const char* dir = std::getenv("SHADOW_SCENES_DIR");
    return dir != nullptr && *dir != '\0' ? std::string(dir) : std::string(SHADOW_SCENES_DIR);
}

std::vector<std::string> sampleSceneNames() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(sampleScenesDir(), ec)) {
        if (entry.path().extension() == ".gltf") names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

Result<Scene> loadSampleScene(const std::string& spec, const std::string& animation) {
    GltfLoadOptions options;
    options.animation = animation;
    const bool bareWord = !spec.empty() && spec.find_first_of("/.:") == std::string::npos;
    if (!bareWord) return loadScene(spec, options);
    const std::filesystem::path file = std::filesystem::path(sampleScenesDir()) / (spec + ".gltf");
    std::error_code ec;
    if (std::filesystem::is_regular_file(file, ec)) return loadScene(file.string(), options);
    if (std::filesystem::exists(spec, ec)) return loadScene(spec, options);
    std::string known;
    for (const std::string& name : sampleSceneNames()) known += (known.empty() ? "" : ", ") + name;
    for (const std::string& name : builtinSceneNames()) known += (known.empty() ? "builtin:" : ", builtin:") + name;
    return Error{ErrorCode::InvalidArgument, spec + ": no such scene (a .gltf/.glb path, or one of: " + known + ")"};
}

}  // namespace shadow::samples
