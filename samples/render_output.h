// Writing a rendered frame to a folder as the CLI contract (docs/output_contract.md) names it, and
// stats.json. Shared by shadow_render and the benchmarks.
#pragma once

#include "command_line.h"

#include <shadow/renderer.h>
#include <shadow/result.h>
#include <shadow/scene.h>
#include <shadow/shadow_planner.h>
#include <shadow/stats.h>

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shadow::samples {

/// Which outputs to write.
struct OutputSelection {
    bool color = true;
    bool visibility = true;
    bool position = true;
    bool depth = true;
    [[nodiscard]] bool anyAov() const { return visibility || position || depth; }
};

/// Parses an image size "WxH" with 1 <= W, H <= 16384; the error names the flag's text.
[[nodiscard]] Result<std::pair<int, int>> parseSize(const std::string& text);

/// The camera of `--camera N` (an error when out of range), else the scene's first, else a
/// default one added after posing the scene at `time`. shadow_render and shadow_reference use
/// it, so both see the same pixels.
[[nodiscard]] Result<Entity> chooseCamera(Scene& scene, std::optional<int> index, double time);

/// What the CLIs and the viewer do with a scene that has no lights (`--no-default-lights`,
/// `--no-ground`): add the default rig (shadow/default_rig.h), with or without its ground.
struct DefaultRigChoice {
    bool lights = true;  ///< add the rig to a scene without lights
    bool ground = true;  ///< with its shadow-catcher ground
};
/// Declares `--no-default-lights` and `--no-ground` on `app`, each clearing its field of `rig`
/// (`rig` must outlive the parse).
void addRigFlags(CommandLine& app, DefaultRigChoice& rig);

/// `chooseCamera`, except for a scene without lights under `rig.lights`: the default rig
/// (`addDefaultRig`) is added, seen through the camera of `--camera N` (an error when out of
/// range) or the scene's first; with none, through the camera the rig adds, which frames the
/// model and its shadow in images of width / height `imageAspect`. shadow_render,
/// shadow_reference and the viewer all call it, so they light and see the same scene.
[[nodiscard]] Result<Entity> chooseCameraAndRig(Scene& scene, std::optional<int> index, double time,
                                                const DefaultRigChoice& rig, double imageAspect);

/// Parses "color,visibility,position,depth" (any subset, any order).
[[nodiscard]] Result<OutputSelection> parseAovList(const std::string& list);

/// Creates `dir` if needed and proves it writable (writes and removes a probe file).
[[nodiscard]] Status prepareOutputDir(const std::string& dir);

/// Writes color.png, color.exr, visibility_<i>.exr, position.exr, depth.exr as selected.
[[nodiscard]] Status writeFrameImages(const std::string& dir, const FrameImages& images,
                                      const OutputSelection& selection, float exposure);

/// Median, minimum and maximum of `values` (0 for none).
struct Spread {
    double median = 0.0, min = 0.0, max = 0.0;
};
[[nodiscard]] Spread spreadOf(std::vector<double> values);

/// Now, in seconds since the Unix epoch: a run's `startTime` in stats.json and reference.json,
/// by which shadow_compare tells a file of that run from one an earlier run left in the folder.
[[nodiscard]] double unixSecondsNow();

/// stats.json: the light mapping, the animation clips and which played, the last frame's
/// counters, the warnings of the scene's loading and of the last frame (each
/// `{"code", "element", "message"}`, codes as `warningCodeName` spells them), per-pass timing
/// spreads over `frames` (the first, warm-up frame left out when there are more), and the run's
/// `startTime` (unixSecondsNow when it began).
[[nodiscard]] std::string statsJson(const Scene& scene, const std::vector<FrameStats>& frames, int width, int height,
                                    const std::string& technique, double startTime);

/// Parses a technique name; error names the value.
[[nodiscard]] Result<ShadowTechnique> parseTechnique(const std::string& name);

/// `--screen-visibility`'s help text, and its value parsed (error names the value).
inline constexpr const char* kScreenVisibilityHelp =
    "where lights' visibility is computed: auto (the default: the screen-space stage for a pcss or sdf light, two "
    "or more filtered lights, any filtered light from 720 rows, or contact shadows; filtered shadows at half "
    "resolution, quarter from 720 rows, upsampled along surfaces), "
    "off (forward: every lit fragment runs its lights' filters), or the stage forced at full, half or quarter "
    "resolution";
[[nodiscard]] Result<ScreenVisibility> parseScreenVisibilitySetting(const std::string& name);

/// The range of `--field-voxels`, voxels along a distance field's edge: the cube roots of the
/// bake's limits (kMinDistanceFieldVoxels, kMaxDistanceFieldVoxels).
inline constexpr int kMinFieldEdge = 16;
inline constexpr int kMaxFieldEdge = 256;

/// Gives `planner` fields of `edge`^3 voxels (`ShadowLimits::distanceFieldVoxels`), its other
/// limits kept.
void setFieldEdge(ShadowPlanner& planner, int edge);

/// Sets `s` to depth mode `mode` as the modes are meant to be used: midpoint and second with
/// zero constant and slope bias (the surface behind the first is the margin), nearest as set.
void applyDepthMode(Shadow& s, DepthMode mode);

/// The folder of the sample scenes (samples/scenes/*.gltf): $SHADOW_SCENES_DIR when set, else the
/// source tree's.
[[nodiscard]] std::string sampleScenesDir();

/// The names of the sample scenes (their files' stems), sorted.
[[nodiscard]] std::vector<std::string> sampleSceneNames();

/// `loadScene` of SCENE as the CLIs name it: a sample scene's name (`courtyard`), a `.gltf`/`.glb`
/// path, or `builtin:NAME`, playing the clip `animation` names (`--animation`: empty for the
/// first, `all`, an index or a name; see `playAnimation`). A bare word that names neither a
/// sample scene nor a file is an error listing the sample scenes and the built-in ones.
[[nodiscard]] Result<Scene> loadSampleScene(const std::string& spec, const std::string& animation = "");

/// `--animation`'s help text.
inline constexpr const char* kAnimationHelp =
    "which of the file's animations plays: its index or name, or all (default: the first)";

/// One `{"code", "element", "message"}` object per warning of `lists`, in order (stats.json's
/// and reference.json's `warnings`).
[[nodiscard]] nlohmann::json warningsJson(std::initializer_list<const std::vector<Warning>*> lists);

/// The scene's animation clips (name, duration), the ones that play (index, name) and the
/// longest of those (s): stats.json's and reference.json's `animation`.
[[nodiscard]] nlohmann::json animationJson(const Scene& scene);

/// Prints the scene's warnings from index `from` on stderr, one line each (`program: warning:
/// ...`): those of loading once, when the scene is loaded, and those the frames added after
/// them; stats.json lists them too.
void printSceneWarnings(const char* program, const Scene& scene, std::size_t from = 0);

}  // namespace shadow::samples
