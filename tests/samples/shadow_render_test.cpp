// The shadow_render CLI contract (docs/output_contract.md): the files it writes, what is in them, stats.json,
// and bad input answered by one message and exit code 2 with nothing written.
#include <gtest/gtest.h>

#include "scene/gltf_test_support.h"
#include "test_support.h"
#include <shadow/image_io.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace shadow::shadow_render_test {
namespace {

namespace fs = std::filesystem;

using test::kExitBadInput;
constexpr int kWidth = 96;
constexpr int kHeight = 54;

using test::TempDir;
using CliRun = test::ProcessRun;

std::string quoted(const std::string& s) { return test::shellQuoted(s); }

/// Runs shadow_render with `args` (already quoted where needed), capturing its output.
CliRun runCli(const TempDir& tmp, const std::string& args) {
    return test::runProgram(SHADOW_BIN_DIR "/shadow_render", args, tmp / "cli.log");
}

bool emptyOrAbsent(const fs::path& dir) {
    std::error_code ec;
    return !fs::exists(dir, ec) || (fs::is_directory(dir, ec) && fs::is_empty(dir, ec));
}

ImageF readOrFail(const std::string& path, const std::vector<std::string>& channels) {
    Result<ImageF> image = readExr(path, channels);
    if (!image) {
        ADD_FAILURE() << path << ": " << image.error().message;
        return {};
    }
    return std::move(image.value());
}

nlohmann::json readJson(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
}

TEST(ShadowRenderCli, DefaultSceneWritesEveryOutputOfTheContract) {
    TempDir tmp;
    const std::string out = tmp / "out";
    const CliRun run = runCli(tmp, "builtin:default --out " + quoted(out) + " --size 96x54");
    ASSERT_EQ(run.exitCode, 0) << run.output;

    for (const char* name : {"color.png", "color.exr", "visibility_0.exr", "visibility_1.exr", "visibility_2.exr",
                             "position.exr", "depth.exr", "stats.json"}) {
        EXPECT_TRUE(fs::is_regular_file(fs::path(out) / name)) << name;
    }
    EXPECT_FALSE(fs::exists(fs::path(out) / "visibility_3.exr")) << "the default scene has three lights";
    {
        std::ifstream png(out + "/color.png", std::ios::binary);
        char signature[8] = {};
        png.read(signature, 8);
        EXPECT_EQ(std::string(signature + 1, 3), "PNG");
    }

    const ImageF color = readOrFail(out + "/color.exr", {"R", "G", "B"});
    const ImageF position = readOrFail(out + "/position.exr", {"R", "G", "B", "A"});
    const ImageF depth = readOrFail(out + "/depth.exr", {"Y"});
    for (const ImageF* image : {&color, &position, &depth}) {
        ASSERT_EQ(image->width, kWidth);
        ASSERT_EQ(image->height, kHeight);
    }
    int covered = 0;
    int badCoverage = 0;
    int badDepth = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const float a = position.at(x, y, 3);
            const float d = depth.at(x, y, 0);
            if (a != 0.0f && a != 1.0f) ++badCoverage;
            covered += a == 1.0f ? 1 : 0;
            // Geometry lies in front of the camera; the background has depth 0.
            if (!std::isfinite(d) || (a == 1.0f ? !(d > 0.0f) : d != 0.0f)) ++badDepth;
        }
    }
    EXPECT_EQ(badCoverage, 0) << "position A must be 1 on geometry and 0 elsewhere";
    EXPECT_EQ(badDepth, 0);
    EXPECT_GT(covered, kWidth * kHeight / 4);
    EXPECT_LT(covered, kWidth * kHeight) << "the default view shows some background";

    for (int i = 0; i < 3; ++i) {
        const ImageF v = readOrFail(out + "/visibility_" + std::to_string(i) + ".exr", {"Y"});
        ASSERT_EQ(v.width, kWidth);
        ASSERT_EQ(v.height, kHeight);
        int invalid = 0;
        int darkBackground = 0;
        int shadowed = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const float value = v.at(x, y, 0);
                if (!(value >= 0.0f && value <= 1.0f)) ++invalid;  // also catches NaN
                if (position.at(x, y, 3) == 0.0f && value != 1.0f) ++darkBackground;
                if (value < 0.5f) ++shadowed;
            }
        }
        EXPECT_EQ(invalid, 0) << "visibility_" << i;
        EXPECT_EQ(darkBackground, 0) << "visibility_" << i << " on the background";
        EXPECT_GT(shadowed, 0) << "visibility_" << i << ": every light of the default scene casts a shadow in view";
    }

    const nlohmann::json stats = readJson(out + "/stats.json");
    ASSERT_FALSE(stats.is_discarded()) << "stats.json is not JSON";
    EXPECT_EQ(stats.value("frames", 0), 1);
    EXPECT_EQ(stats["size"], nlohmann::json::array({kWidth, kHeight}));
    ASSERT_TRUE(stats["lights"].is_array());
    ASSERT_EQ(stats["lights"].size(), 3u);
    EXPECT_EQ(stats["warnings"], nlohmann::json::array()) << "the default scene is in range";
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(stats["lights"][i]["visibility"], "visibility_" + std::to_string(i) + ".exr");
    }
}

// A setting out of range is clamped and reported: one line on stderr, and in stats.json an
// object with the warning's code, the light it concerns and the same line.
TEST(ShadowRenderCli, ClampedSettingIsReportedInStatsJsonAndOnStderr) {
    TempDir tmp;
    const std::string scene = tmp / "lamp.gltf";
    {
        std::ofstream f(scene);
        f << R"({
  "asset": {"version": "2.0"},
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "intensity": 20, "spot": {"outerConeAngle": 0.7},
     "extras": {"shadow": {"technique": "pcf", "mapSize": 256, "pcfSamples": 100}}}]}},
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100}}],
  "nodes": [
    {"name": "lamp", "translation": [0, 4, 0], "rotation": [-0.7071068, 0, 0, 0.7071068],
     "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "camera", "translation": [0, 2, 6], "camera": 0}
  ]
})";
    }
    const std::string out = tmp / "out";
    const CliRun run = runCli(tmp, quoted(scene) + " --size 32x18 --out " + quoted(out));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string line = "lamp: pcfSamples 100 clamped to 64";
    EXPECT_NE(run.output.find("shadow_render: warning: " + line + "\n"), std::string::npos) << run.output;
    const nlohmann::json stats = readJson(out + "/stats.json");
    ASSERT_FALSE(stats.is_discarded()) << "stats.json is not JSON";
    const nlohmann::json expected = {{{"code", "SettingClamped"}, {"element", "lamp"}, {"message", line}}};
    EXPECT_EQ(stats["warnings"], expected) << stats["warnings"].dump(2);
}

/// A lamp over a triangle that two clips move (0: "left", 1: "right"), with what a file may hold
/// that the loader lets pass: an unknown extras.shadow key, a light of an unknown type, a camera
/// on a matrix without rotation, a scene listing a child node, an unlit material.
fs::path warningScene(const fs::path& dir) {
    using gltf_test::json;
    gltf_test::Doc doc;
    doc.light({{"type", "spot"},
               {"intensity", 20},
               {"spot", {{"outerConeAngle", 0.7}}},
               {"extras", {{"shadow", {{"technique", "hard"}, {"mapSize", 128}, {"mapsize", 256}}}}}});
    doc.light({{"type", "area"}});
    doc.push("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.05}, {"zfar", 100}}}});
    doc.node({{"name", "lamp"},
              {"translation", {0, 4, 0}},
              {"rotation", {-0.7071068, 0, 0, 0.7071068}},
              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    doc.node({{"name", "panel"}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    doc.node({{"name", "camera"}, {"translation", {0, 2, 6}}, {"camera", 0}});
    doc.node({{"name", "eye2"}, {"camera", 0}, {"matrix", {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 3, 1}}});
    const int unlit = doc.push("materials", {{"extensions", {{"KHR_materials_unlit", json::object()}}}});
    doc.node({{"name", "plate"}, {"mesh", doc.triangleMesh(unlit)}, {"children", {5}}});
    doc.node({{"name", "tip"}, {"translation", {0, 1, 0}}});
    doc.j["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_unlit"};
    doc.scene({0, 1, 2, 3, 4, 5});
    const int times = doc.floats({0, 1}, "SCALAR");
    for (const char* name : {"left", "right"}) {
        const float x = std::string(name) == "left" ? -1.0f : 1.0f;
        const json sampler = {{"input", times}, {"output", doc.floats({0, 0, 0, x, 0, 0}, "VEC3")}};
        doc.push("animations",
                 {{"name", name},
                  {"samplers", json::array({sampler})},
                  {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 4}, {"path", "translation"}}}}})}});
    }
    return doc.write(dir / "warned.gltf");
}

TEST(ShadowRenderCli, SceneWarningsReachStderrOnceAndStatsJson) {
    TempDir tmp;
    const fs::path scene = warningScene(tmp.path());
    const std::string out = tmp / "out";
    const CliRun run = runCli(tmp, quoted(scene.string()) + " --size 32x18 --frames 2 --out " + quoted(out));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json stats = readJson(out + "/stats.json");
    ASSERT_FALSE(stats.is_discarded()) << "stats.json is not JSON";
    std::vector<std::string> codes;
    for (const nlohmann::json& w : stats["warnings"]) {
        codes.push_back(w["code"].get<std::string>());
        const std::string line = "shadow_render: warning: " + w["message"].get<std::string>() + "\n";
        std::size_t count = 0;
        for (std::size_t at = run.output.find(line); at != std::string::npos; at = run.output.find(line, at + 1))
            ++count;
        EXPECT_EQ(count, 1u) << line << run.output;
    }
    for (const char* code :
         {"UnknownSetting", "UnsupportedLight", "DegenerateTransform", "SceneNodeNotRoot", "UnsupportedFeature"}) {
        EXPECT_EQ(std::count(codes.begin(), codes.end(), code), 1) << code << " in " << stats["warnings"].dump(2);
    }
}

TEST(ShadowRenderCli, AnimationFlagPlaysTheChosenClipAndStatsJsonSaysWhich) {
    TempDir tmp;
    const fs::path scene = warningScene(tmp.path());
    const auto played = [&](const std::string& flag) {
        const std::string out = tmp / ("out" + std::to_string(flag.size()));
        const CliRun run =
            runCli(tmp, quoted(scene.string()) + " --size 32x18 --aov color " + flag + " --out " + quoted(out));
        EXPECT_EQ(run.exitCode, 0) << run.output;
        return readJson(out + "/stats.json")["animation"]["played"];
    };
    using Json = nlohmann::json;
    EXPECT_EQ(played(""), Json::parse(R"([{"index": 0, "name": "left"}])"));
    EXPECT_EQ(played("--animation right"), Json::parse(R"([{"index": 1, "name": "right"}])"));
    EXPECT_EQ(played("--animation 1"), Json::parse(R"([{"index": 1, "name": "right"}])"));
    EXPECT_EQ(played("--animation all"),
              Json::parse(R"([{"index": 0, "name": "left"}, {"index": 1, "name": "right"}])"));
    const CliRun bad = runCli(tmp, quoted(scene.string()) + " --animation up --out " + quoted(tmp / "bad"));
    EXPECT_EQ(bad.exitCode, kExitBadInput) << bad.output;
    EXPECT_NE(bad.output.find("animation \"up\": no clip of that name (the scene's: 0 \"left\", 1 \"right\", or all)"),
              std::string::npos)
        << bad.output;
}

TEST(ShadowRenderCli, DepthModeFlagSetsEveryShadowedLightAndReportsTheScratch) {
    TempDir tmp;
    const std::string out = tmp / "out";
    const CliRun run =
        runCli(tmp, "builtin:default --size 32x18 --aov color --depth-mode midpoint --out " + quoted(out));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json stats = readJson(out + "/stats.json");
    ASSERT_FALSE(stats.is_discarded()) << "stats.json is not JSON";
    int shadowed = 0;
    for (const nlohmann::json& light : stats["lights"]) {
        if (!light.contains("shadow")) continue;
        ++shadowed;
        EXPECT_EQ(light["shadow"]["depthMode"], "midpoint") << light.dump();
    }
    EXPECT_GT(shadowed, 0);
    EXPECT_GT(stats["counters"]["shadowScratchBytes"].get<long long>(), 0);
    // The default scene's ground is an open plane: each light says so once.
    int open = 0;
    for (const nlohmann::json& w : stats["warnings"]) open += w["code"] == "OpenCaster" ? 1 : 0;
    EXPECT_EQ(open, shadowed) << stats["warnings"].dump(2);
}

/// stats.json's lights with a shadow map after `shadow_render builtin:default --size 32x18 --aov
/// color ARGS`; empty (with a failure) when the run or its stats.json went wrong.
std::vector<nlohmann::json> shadowedLightsOf(const std::string& args) {
    TempDir tmp;
    const std::string out = tmp / "out";
    const CliRun run = runCli(tmp, "builtin:default --size 32x18 --aov color " + args + " --out " + quoted(out));
    EXPECT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json stats = readJson(out + "/stats.json");
    EXPECT_FALSE(stats.is_discarded()) << "stats.json is not JSON";
    std::vector<nlohmann::json> lights;
    if (stats.is_discarded()) return lights;
    for (const nlohmann::json& light : stats["lights"]) {
        if (light.contains("shadow")) lights.push_back(light);
    }
    return lights;
}

TEST(ShadowRenderCli, TechniqueAutoReportsEachLightsChoiceWithinTheBudget) {
    // A budget below any candidate's predicted time: every light takes its cheapest, hard at 512.
    const std::vector<nlohmann::json> lights =
        shadowedLightsOf("--frames 8 --technique auto --shadow-budget-ms 0.0001");
    for (const nlohmann::json& light : lights) {
        EXPECT_EQ(light["technique"], "auto") << light.dump();
        ASSERT_TRUE(light.contains("auto")) << light.dump();
        const nlohmann::json& a = light["auto"];
        EXPECT_EQ(a["technique"], "hard") << a.dump();
        EXPECT_EQ(a["mapSize"], 512) << a.dump();
        EXPECT_EQ(light["shadow"]["mapSize"], 512) << light.dump();
        EXPECT_GT(a["predictedMs"].get<double>(), 0.0) << a.dump();
        EXPECT_GT(a["predictedRmse"].get<double>(), 0.0) << a.dump();
        EXPECT_GE(a["measuredShadowPassMs"].get<double>(), 0.0) << a.dump();
    }
    EXPECT_EQ(lights.size(), 3u);
}

TEST(ShadowRenderCli, MapSizeAndTapOverridesReachEveryShadowedLight) {
    const std::vector<nlohmann::json> lights =
        shadowedLightsOf("--technique pcss --map-size 256 --pcf-samples 8 --blocker-samples 4");
    for (const nlohmann::json& light : lights) {
        EXPECT_EQ(light["shadow"]["mapSize"], 256) << light.dump();
        EXPECT_EQ(light["shadow"]["pcfSamples"], 8) << light.dump();
        EXPECT_EQ(light["shadow"]["blockerSamples"], 4) << light.dump();
    }
    EXPECT_EQ(lights.size(), 3u);
}

struct BadInput {
    const char* what;
    std::string args;  // everything after the scene and --out
    std::string scene;
    std::string mention;  // the message must name this
};

TEST(ShadowRenderCli, BadInputExitsWithCode2AndWritesNothing) {
    TempDir tmp;
    const std::string missing = tmp / "no_such_scene.gltf";
    const std::string required = tmp / "required.gltf";
    std::ofstream(required) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["EXT_made_up"],
                                   "extensionsRequired": ["EXT_made_up"]})";
    const std::string halfCutoff = tmp / "half.gltf";
    std::ofstream(halfCutoff) << R"({"asset": {"version": "2.0"}, "materials": [{"alphaCutoff": "half"}]})";
    const std::vector<BadInput> cases = {
        {"unknown builtin", "", "builtin:nope", "nope"},
        {"missing file", "", missing, "no_such_scene.gltf"},
        {"zero width", "--size 0x5", "builtin:default", "--size"},
        {"size not a size", "--size abc", "builtin:default", "--size"},
        {"unknown technique", "--technique foo", "builtin:default", "foo"},
        {"unknown depth mode", "--depth-mode mid", "builtin:default", "--depth-mode: unknown depth mode 'mid'"},
        {"negative shadow budget", "--shadow-budget-ms -1", "builtin:default", "--shadow-budget-ms: must be"},
        {"NaN shadow budget", "--shadow-budget-ms nan", "builtin:default", "--shadow-budget-ms"},
        {"shadow budget not a number", "--shadow-budget-ms fast", "builtin:default", "--shadow-budget-ms"},
        {"depth mode without a value", "--depth-mode", "builtin:default", "--depth-mode"},
        {"unknown screen visibility", "--screen-visibility halfway", "builtin:default",
         "--screen-visibility: unknown setting 'halfway'"},
        {"screen visibility without a value", "--screen-visibility", "builtin:default", "--screen-visibility"},
        {"camera out of range", "--camera 99", "builtin:default", "--camera"},
        {"unknown AOV", "--aov bogus", "builtin:default", "bogus"},
        {"no frames", "--frames 0", "builtin:default", "--frames"},
        // Every flag with its value missing, malformed or out of range (tests/stability/README.md).
        {"--out without a value", "--out", "builtin:default", "--out"},
        {"--size without a value", "--size", "builtin:default", "--size"},
        {"size without a height", "--size 100x", "builtin:default", "--size"},
        {"negative size", "--size -5x5", "builtin:default", "--size"},
        {"size beyond 16384", "--size 20000x10", "builtin:default", "--size"},
        // Within the GL limit, beyond the renderer's memory cap (kMaxRenderTargetBytes): refused
        // before anything is allocated, not an incomplete framebuffer (exit 1).
        {"size over the targets' memory cap", "--size 16384x16384", "builtin:default", "--size"},
        {"AOVs over the targets' memory cap", "--size 8192x8192 --aov color,visibility", "builtin:default", "--size"},
        {"--camera without a value", "--camera", "builtin:default", "--camera"},
        {"camera not a number", "--camera abc", "builtin:default", "--camera"},
        {"camera not an integer", "--camera 1.5", "builtin:default", "--camera"},
        {"--time without a value", "--time", "builtin:default", "--time"},
        {"time not a number", "--time abc", "builtin:default", "--time"},
        {"time NaN", "--time nan", "builtin:default", "--time"},
        {"time infinite", "--time inf", "builtin:default", "--time"},
        {"time overflowing a double", "--time 1e400", "builtin:default", "--time"},
        {"--frames without a value", "--frames", "builtin:default", "--frames"},
        {"frames not an integer", "--frames 1e9", "builtin:default", "--frames"},
        {"negative frames", "--frames -1", "builtin:default", "--frames"},
        {"too many frames", "--frames 100001", "builtin:default", "--frames"},
        {"--dt without a value", "--frames 2 --dt", "builtin:default", "--dt"},
        {"dt not a number", "--dt abc", "builtin:default", "--dt"},
        {"dt NaN", "--dt nan", "builtin:default", "--dt"},
        {"--technique without a value", "--technique", "builtin:default", "--technique"},
        {"empty technique", "--technique ''", "builtin:default", "--technique"},
        {"--aov without a value", "--aov", "builtin:default", "--aov"},
        {"empty AOV list", "--aov ''", "builtin:default", "--aov"},
        {"empty AOV in the list", "--aov color,,depth", "builtin:default", "--aov"},
        {"--debug without a value", "--debug", "builtin:default", "--debug"},
        {"unknown debug view", "--debug foo", "builtin:default", "foo"},
        {"--debug-light without a value", "--debug-light", "builtin:default", "--debug-light"},
        {"debug light not a number", "--debug-light x", "builtin:default", "--debug-light"},
        {"negative debug light", "--debug-light -1", "builtin:default", "--debug-light"},
        {"debug light out of range", "--debug-light 3", "builtin:default", "--debug-light"},
        {"--exposure without a value", "--exposure", "builtin:default", "--exposure"},
        {"exposure not a number", "--exposure abc", "builtin:default", "--exposure"},
        {"exposure NaN", "--exposure nan", "builtin:default", "--exposure"},
        {"exposure zero", "--exposure 0", "builtin:default", "--exposure"},
        {"exposure negative", "--exposure -1", "builtin:default", "--exposure"},
        {"exposure infinite", "--exposure inf", "builtin:default", "--exposure"},
        {"flag with a malformed value", "--no-cache=maybe", "builtin:default", "--no-cache"},
        {"field voxels too few", "--field-voxels 8", "builtin:default", "--field-voxels"},
        {"field voxels too many", "--field-voxels 512", "builtin:default", "--field-voxels"},
        {"field voxels not an integer", "--field-voxels x", "builtin:default", "--field-voxels"},
        {"start offset negative", "--sdf-start-offset -1", "builtin:default", "--sdf-start-offset"},
        {"start offset NaN", "--sdf-start-offset nan", "builtin:default", "--sdf-start-offset"},
        {"start offset over 1 m", "--sdf-start-offset 2", "builtin:default", "--sdf-start-offset"},
        {"march steps under 4", "--sdf-steps 3", "builtin:default", "--sdf-steps"},
        {"march steps over 256", "--sdf-steps 257", "builtin:default", "--sdf-steps"},
        {"march steps not an integer", "--sdf-steps 2.5", "builtin:default", "--sdf-steps"},
        {"filter under a texel", "--max-filter-texels 0.5", "builtin:default", "--max-filter-texels"},
        {"filter over 256 texels", "--max-filter-texels 300", "builtin:default", "--max-filter-texels"},
        {"filter NaN", "--max-filter-texels nan", "builtin:default", "--max-filter-texels"},
        {"map size 0", "--map-size 0", "builtin:default", "--map-size"},
        {"map size over 16384", "--map-size 20000", "builtin:default", "--map-size"},
        {"map size not an integer", "--map-size 1.5", "builtin:default", "--map-size"},
        {"no PCF taps", "--pcf-samples 0", "builtin:default", "--pcf-samples"},
        {"blocker points over 64", "--blocker-samples 65", "builtin:default", "--blocker-samples"},
        {"unknown flag", "--bogus", "builtin:default", "--bogus"},
        {"a clip the scene lacks", "--animation walk", "builtin:default", "animation \"walk\""},
        {"--animation without a value", "--animation", "builtin:default", "--animation"},
        {"required extension unknown", "", required, "extensionsRequired[0]: the file requires EXT_made_up"},
        {"alphaCutoff of the wrong type", "", halfCutoff, "materials[0].alphaCutoff: must be a number"},
        {"extra argument", "extra", "builtin:default", "extra"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const BadInput& c = cases[i];
        const std::string out = tmp / ("out" + std::to_string(i));
        const CliRun run = runCli(tmp, quoted(c.scene) + " --out " + quoted(out) + " " + c.args);
        EXPECT_EQ(run.exitCode, kExitBadInput) << c.what << ": " << run.output;
        EXPECT_NE(run.output.find(c.mention), std::string::npos)
            << c.what << ": message does not name '" << c.mention << "': " << run.output;
        EXPECT_TRUE(emptyOrAbsent(out)) << c.what << ": wrote into " << out;
    }
}

// `--camera N` indexes the scene's cameras; a negative N names none of them and is bad input,
// not a silent fall-back to the first camera.
TEST(ShadowRenderCli, NegativeCameraIndexIsBadInput) {
    TempDir tmp;
    const std::string out = tmp / "out";
    const CliRun run = runCli(tmp, "builtin:default --size 32x18 --camera -5 --out " + quoted(out));
    EXPECT_EQ(run.exitCode, kExitBadInput) << run.output;
    EXPECT_NE(run.output.find("--camera"), std::string::npos) << run.output;
    EXPECT_TRUE(emptyOrAbsent(out)) << "wrote into " << out;
}

TEST(ShadowRenderCli, UnwritableOutputFolderExitsWithCode2) {
    TempDir tmp;
    const std::string file = tmp / "a_regular_file";
    {
        std::ofstream f(file);
        f << "keep me";
    }
    const std::string out = file + "/images";
    const CliRun run = runCli(tmp, "builtin:default --size 32x18 --out " + quoted(out));
    EXPECT_EQ(run.exitCode, kExitBadInput) << run.output;
    EXPECT_NE(run.output.find("--out"), std::string::npos) << run.output;
    EXPECT_TRUE(fs::is_regular_file(file));
    std::ifstream in(file);
    std::string text;
    std::getline(in, text);
    EXPECT_EQ(text, "keep me");
}

// --frames 3 --dt 0.1 animates from t = 0 to t = 0.2 and writes the last frame: its geometry is
// the frame a single render at --time 0.2 gives.
TEST(ShadowRenderCli, FramesAndDtRenderTheLastFrameAndReportThem) {
    TempDir tmp;
    const std::string animated = tmp / "animated";
    const std::string still = tmp / "still";
    const std::string start = tmp / "start";
    const CliRun run = runCli(tmp, "builtin:default --size 96x54 --frames 3 --dt 0.1 --out " + quoted(animated));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    ASSERT_EQ(runCli(tmp, "builtin:default --size 96x54 --time 0.2 --out " + quoted(still)).exitCode, 0);
    ASSERT_EQ(runCli(tmp, "builtin:default --size 96x54 --out " + quoted(start)).exitCode, 0);

    const nlohmann::json stats = readJson(animated + "/stats.json");
    ASSERT_FALSE(stats.is_discarded()) << "stats.json is not JSON";
    EXPECT_EQ(stats.value("frames", 0), 3);
    ASSERT_TRUE(stats.contains("timingMethod"));
    EXPECT_TRUE(stats["timingMethod"].is_string());
    EXPECT_FALSE(stats["timingMethod"].get<std::string>().empty());
    ASSERT_TRUE(stats["perFrame"].is_array());
    EXPECT_EQ(stats["perFrame"].size(), 3u);

    const ImageF last = readOrFail(animated + "/position.exr", {"R", "G", "B", "A"});
    const ImageF at02 = readOrFail(still + "/position.exr", {"R", "G", "B", "A"});
    const ImageF at0 = readOrFail(start + "/position.exr", {"R", "G", "B", "A"});
    EXPECT_EQ(last.pixels, at02.pixels) << "the written frame is not the one at t = 0.2";
    EXPECT_NE(last.pixels, at0.pixels) << "nothing moved between t = 0 and t = 0.2";
    // Shadows of the last frame too (layers reused or redrawn, the result is the same).
    for (int i = 0; i < 3; ++i) {
        const std::string name = "/visibility_" + std::to_string(i) + ".exr";
        const ImageF a = readOrFail(animated + name, {"Y"});
        const ImageF b = readOrFail(still + name, {"Y"});
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        float worst = 0.0f;
        for (std::size_t p = 0; p < a.pixels.size(); ++p) worst = std::max(worst, std::abs(a.pixels[p] - b.pixels[p]));
        EXPECT_LT(worst, 1e-5f) << name;
    }
}

// --shader-cache: the second run takes every program from the folder. Run with the driver's own
// cache on (Mesa makes program binaries only then) in a folder of the test's, so that neither
// run reads what another process left.
TEST(ShadowRenderCli, ShaderCacheFolderServesTheSecondRun) {
    const TempDir tmp("cli_shader_cache");
    const std::string env = "env -u MESA_SHADER_CACHE_DISABLE MESA_SHADER_CACHE_DIR=" + quoted(tmp / "mesa") + " ";
    const std::string cache = tmp / "programs";
    auto run = [&](const std::string& out) {
        const std::string command = env + test::shellQuoted(SHADOW_BIN_DIR "/shadow_render") +
                                    " builtin:default --size 32x18 --aov color --shader-cache " + quoted(cache) +
                                    " --out " + quoted(out) + " > " + quoted(tmp / "cli.log") + " 2>&1";
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        return readJson(out + "/stats.json");
    };
    const nlohmann::json first = run(tmp / "first");
    const nlohmann::json second = run(tmp / "second");
    const int compiled = first["counters"]["programsCompiled"].get<int>();
    EXPECT_GT(compiled, 0);
    EXPECT_GE(first["programCache"]["stored"].get<int>(), compiled);
    EXPECT_EQ(first["programCache"]["loaded"].get<int>(), 0);
    EXPECT_EQ(second["programCache"]["stored"].get<int>(), 0);
    EXPECT_EQ(second["programCache"]["loaded"].get<int>(), first["programCache"]["stored"].get<int>());
    EXPECT_EQ(second["programCache"]["rejected"].get<int>(), 0);
    // A file where the folder should be is bad input.
    std::ofstream(tmp / "file") << "x";
    const CliRun bad = runCli(
        tmp, "builtin:default --size 32x18 --shader-cache " + quoted(tmp / "file") + " --out " + quoted(tmp / "bad"));
    EXPECT_EQ(bad.exitCode, kExitBadInput) << bad.output;
    EXPECT_NE(bad.output.find("--shader-cache"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace shadow::shadow_render_test

namespace shadow::shadow_render_test {
namespace {

// Every sample scene (samples/scenes) renders headless by its name, animated, with every light
// of it visible in stats.json and no warning; a name that is no scene is bad input listing them.
TEST(ShadowRenderCli, SampleScenesRenderByName) {
    const std::vector<std::string> scenes{"character", "contact", "courtyard", "fence", "sunfield"};
    for (const std::string& name : scenes) {
        SCOPED_TRACE(name);
        TempDir tmp;
        const std::string out = tmp / "out";
        const CliRun run = runCli(
            tmp, name + " --out " + quoted(out) + " --size 96x54 --aov color,visibility " + "--frames 2 --dt 0.5");
        ASSERT_EQ(run.exitCode, 0) << run.output;
        EXPECT_TRUE(fs::exists(out + "/color.png"));
        const nlohmann::json stats = readJson(out + "/stats.json");
        ASSERT_TRUE(stats.is_object());
        EXPECT_TRUE(stats["warnings"].empty()) << stats["warnings"].dump();
        EXPECT_TRUE(fs::exists(out + "/visibility_0.exr"));
    }
    TempDir tmp;
    const CliRun bad = runCli(tmp, "no-such-scene --out " + quoted(tmp / "bad"));
    EXPECT_EQ(bad.exitCode, kExitBadInput);
    EXPECT_NE(bad.output.find("courtyard"), std::string::npos) << bad.output;
    EXPECT_TRUE(emptyOrAbsent(tmp / "bad"));
}

}  // namespace
}  // namespace shadow::shadow_render_test
