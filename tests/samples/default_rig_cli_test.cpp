// The default rig in the programs (samples/render_output.cpp, chooseCameraAndRig): a glTF file
// without lights renders under a shadowed sun whose shadow on the rig's ground is where the
// geometry puts it; --no-default-lights and --no-ground take it away; a file with lights gets
// none; stats.json, reference.json and stderr say it was added; shadow_reference traces the same
// rig, so shadow_compare compares like with like.
#include <gtest/gtest.h>
#include <shadow/default_rig.h>
#include <shadow/image_io.h>

#include "scene/cube_scene.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace shadow::default_rig_cli_test {
namespace {

namespace fs = std::filesystem;
using test::writeCube;

test::ProcessRun run(const test::TempDir& tmp, const std::string& program, const std::string& args) {
    return test::runProgram(std::string(SHADOW_BIN_DIR "/") + program, args, tmp / (program + ".log"));
}

nlohmann::json readJson(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
}

/// A run of shadow_render on a cube: the process, its output folder and its stats.json (a
/// discarded value when it wrote none).
struct CubeRender {
    test::ProcessRun process;
    std::string out;
    nlohmann::json stats;
};

/// shadow_render on a cube written to `name` in `tmp` (with a lamp of its own when `withLight`),
/// with `args`, into `tmp`/out.
CubeRender renderCube(const test::TempDir& tmp, const std::string& args, const char* name = "cube.gltf",
                      bool withLight = false) {
    const fs::path file = writeCube(tmp.path() / name, withLight);
    CubeRender r;
    r.out = tmp / "out";
    r.process =
        run(tmp, "shadow_render", test::shellQuoted(file.string()) + " " + args + " --out " + test::shellQuoted(r.out));
    r.stats = readJson(r.out + "/stats.json");
    return r;
}

int countCode(const nlohmann::json& warnings, const std::string& code) {
    int n = 0;
    for (const nlohmann::json& w : warnings) n += w.value("code", "") == code ? 1 : 0;
    return n;
}

std::size_t countOf(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

/// Whether the ray from `p` along `towardsLight` meets the box [lo, hi] (slabs).
bool rayMeetsBox(const glm::dvec3& p, const glm::dvec3& towardsLight, const glm::dvec3& lo, const glm::dvec3& hi) {
    double enter = 0.0, leave = 1e30;
    for (int k = 0; k < 3; ++k) {
        if (std::abs(towardsLight[k]) < 1e-12) {
            if (p[k] < lo[k] || p[k] > hi[k]) return false;
            continue;
        }
        double a = (lo[k] - p[k]) / towardsLight[k], b = (hi[k] - p[k]) / towardsLight[k];
        if (a > b) std::swap(a, b);
        enter = std::max(enter, a);
        leave = std::min(leave, b);
    }
    return enter <= leave;
}

// The command line's overrides reach the rig's sun as they reach a file's own lights: before,
// they were applied before the rig was added, and its sun kept PCSS at its defaults whatever
// --technique said.
TEST(DefaultRigCli, TheCommandLinesShadowOverridesReachTheRigsSun) {
    test::TempDir tmp("default_rig_cli");
    const CubeRender render = renderCube(tmp, "--size 64x48 --aov color --technique hard --map-size 256");
    ASSERT_EQ(render.process.exitCode, 0) << render.process.output;
    const nlohmann::json& stats = render.stats;
    ASSERT_FALSE(stats.is_discarded());
    ASSERT_EQ(stats["lights"].size(), 1u);
    EXPECT_EQ(stats["lights"][0]["node"], "default sun");
    EXPECT_EQ(stats["lights"][0]["technique"], "hard");
    EXPECT_EQ(stats["lights"][0]["shadow"]["mapSize"], 256);
}

// The ground's shadow against the cube's projection along the sun: a ground pixel whose ray
// towards the sun meets the cube shrunk by kEdge is in the umbra, one whose ray misses the cube
// grown by kEdge is lit; the band between (the penumbra of the 0.02 rad sun, at most 2.6 cm wide
// 1.3 m from the cube's top edge, plus a shadow texel) is left out. Tolerance: 1 % of each side
// may disagree. Fails without the rig (no light, no visibility_0.exr), with the sun placed other
// than the rig says (its shadow would not be where the rig's direction projects the cube), or
// with the ground above or below the cube's base (no ground pixels at the rig's height).
TEST(DefaultRigCli, FileWithoutLightsCastsTheCubesShadowWhereGeometrySays) {
    test::TempDir tmp("default_rig_cli");
    const CubeRender render = renderCube(tmp, "--size 160x120 --aov color,visibility,position");
    ASSERT_EQ(render.process.exitCode, 0) << render.process.output;

    // Said once on stderr and in stats.json; the rig's sun is light 0.
    EXPECT_EQ(countOf(render.process.output, "no lights; added the default rig"), 1u) << render.process.output;
    const nlohmann::json& stats = render.stats;
    ASSERT_FALSE(stats.is_discarded());
    EXPECT_EQ(countCode(stats["warnings"], "DefaultRigAdded"), 1) << stats["warnings"].dump(2);
    ASSERT_EQ(stats["lights"].size(), 1u);
    EXPECT_EQ(stats["lights"][0]["node"], "default sun");
    EXPECT_EQ(stats["lights"][0]["type"], "directional");
    EXPECT_EQ(stats["lights"][0]["technique"], "pcss");

    // The rig the program added, rebuilt here by the same library call.
    Result<Scene> scene = loadScene(tmp / "cube.gltf");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const DefaultRig rig = addDefaultRig(*scene, std::nullopt);
    const ImageF position = readExr(render.out + "/position.exr", {"R", "G", "B", "A"}).value();
    const ImageF visibility = readExr(render.out + "/visibility_0.exr", {"Y"}).value();
    constexpr double kEdge = 0.05;  // m: the excluded band on each side of the projected edge
    const glm::dvec3 towardsSun = -rig.sunDirection;
    int ground = 0, umbra = 0, lit = 0, umbraWrong = 0, litWrong = 0;
    for (int y = 0; y < position.height; ++y) {
        for (int x = 0; x < position.width; ++x) {
            if (position.at(x, y, 3) < 0.5f) continue;
            const glm::dvec3 p(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
            if (std::abs(p.y - rig.groundHeight) > 1e-3) continue;  // the cube's own faces
            ++ground;
            const float v = visibility.at(x, y, 0);
            if (rayMeetsBox(p, towardsSun, glm::dvec3(-0.5 + kEdge, kEdge, -0.5 + kEdge),
                            glm::dvec3(0.5 - kEdge, 1.0 - kEdge, 0.5 - kEdge))) {
                ++umbra;
                umbraWrong += v >= 0.5f ? 1 : 0;
            } else if (!rayMeetsBox(p, towardsSun, glm::dvec3(-0.5 - kEdge, -kEdge, -0.5 - kEdge),
                                    glm::dvec3(0.5 + kEdge, 1.0 + kEdge, 0.5 + kEdge))) {
                ++lit;
                litWrong += v < 0.5f ? 1 : 0;
            }
        }
    }
    std::cout << "ground pixels " << ground << ": umbra " << umbra << " (" << umbraWrong << " lit), lit " << lit << " ("
              << litWrong << " shadowed)\n";
    EXPECT_GT(ground, position.width * position.height / 4) << "the ground fills much of the frame";
    EXPECT_GT(umbra, ground / 50) << "the shadow is in view";
    EXPECT_LE(umbraWrong, umbra / 100);
    EXPECT_LE(litWrong, lit / 100);
}

// Fails when --no-default-lights is ignored (a light and a visibility file appear), or when the
// ambient term alone is not what lights the cube.
TEST(DefaultRigCli, NoDefaultLightsKeepsTheFileUnlit) {
    test::TempDir tmp("default_rig_cli");
    const CubeRender render = renderCube(tmp, "--no-default-lights --size 64x48");
    ASSERT_EQ(render.process.exitCode, 0) << render.process.output;
    EXPECT_EQ(render.process.output.find("default rig"), std::string::npos) << render.process.output;
    const nlohmann::json& stats = render.stats;
    EXPECT_EQ(stats["lights"].size(), 0u);
    EXPECT_EQ(countCode(stats["warnings"], "DefaultRigAdded"), 0);
    EXPECT_FALSE(fs::exists(fs::path(render.out) / "visibility_0.exr"));
    // Ambient only: the hemispheres' radiance (0.03 each) times the diffuse and the specular
    // directional albedo together, which stay under 1 (0.8 diffuse for the default material).
    const ImageF color = readExr(render.out + "/color.exr", {"R", "G", "B"}).value();
    float brightest = 0.0f;
    for (const float c : color.pixels) brightest = std::max(brightest, c);
    EXPECT_GT(brightest, 0.0f) << "the cube is in view";
    EXPECT_LE(brightest, 0.03f + 1e-4f);
}

// Fails when a file's own light is joined by the rig's (two lights, a DefaultRigAdded warning).
TEST(DefaultRigCli, FileWithLightsGetsNoRig) {
    test::TempDir tmp("default_rig_cli");
    const CubeRender render = renderCube(tmp, "--size 64x48 --aov color,position", "lamp.gltf", true);
    ASSERT_EQ(render.process.exitCode, 0) << render.process.output;
    const nlohmann::json& stats = render.stats;
    ASSERT_EQ(stats["lights"].size(), 1u);
    EXPECT_EQ(stats["lights"][0]["node"], "lamp");
    EXPECT_EQ(countCode(stats["warnings"], "DefaultRigAdded"), 0);
    // No ground: every covered pixel is on the cube.
    const ImageF position = readExr(render.out + "/position.exr", {"R", "G", "B", "A"}).value();
    for (std::size_t i = 0; i < position.pixels.size(); i += 4) {
        if (position.pixels[i + 3] > 0.5f) {
            ASSERT_GE(position.pixels[i + 1], -1e-4f) << "a pixel below the cube";
        }
    }
}

// Fails when --no-ground leaves the ground in (pixels below the cube's base).
TEST(DefaultRigCli, NoGroundLeavesTheSunAlone) {
    test::TempDir tmp("default_rig_cli");
    const CubeRender render = renderCube(tmp, "--no-ground --size 64x48 --aov color,position");
    ASSERT_EQ(render.process.exitCode, 0) << render.process.output;
    const nlohmann::json& stats = render.stats;
    EXPECT_EQ(stats["lights"].size(), 1u);
    const ImageF position = readExr(render.out + "/position.exr", {"R", "G", "B", "A"}).value();
    int covered = 0;
    for (std::size_t i = 0; i < position.pixels.size(); i += 4) {
        if (position.pixels[i + 3] < 0.5f) continue;
        ++covered;
        ASSERT_GE(position.pixels[i + 1], -1e-4f) << "a ground pixel";
    }
    EXPECT_GT(covered, 0);
}

// shadow_reference traces the rig shadow_render drew (the same light, named alike), so
// shadow_compare accepts the pair and finds them close. Fails when the reference sees no rig
// (no light 0: shadow_compare exits 2) or another one (a large error).
TEST(DefaultRigCli, ReferenceTracesTheSameRig) {
    if (!fs::exists(SHADOW_BIN_DIR "/shadow_reference")) GTEST_SKIP() << "shadow_reference is not built";
    test::TempDir tmp("default_rig_cli");
    const fs::path file = writeCube(tmp.path() / "cube.gltf", false);
    const std::string scene = test::shellQuoted(file.string());
    const std::string est = tmp / "est", ref = tmp / "ref";
    ASSERT_EQ(
        run(tmp, "shadow_render", scene + " --size 80x60 --aov visibility,position --out " + test::shellQuoted(est))
            .exitCode,
        0);
    const test::ProcessRun traced =
        run(tmp, "shadow_reference", scene + " --size 80x60 --samples 64 --out " + test::shellQuoted(ref));
    ASSERT_EQ(traced.exitCode, 0) << traced.output;
    EXPECT_EQ(countOf(traced.output, "no lights; added the default rig"), 1u) << traced.output;
    const nlohmann::json record = readJson(ref + "/reference.json");
    ASSERT_EQ(record["lights"].size(), 1u);
    EXPECT_EQ(record["lights"][0]["node"], "default sun");
    EXPECT_EQ(countCode(record["warnings"], "DefaultRigAdded"), 1);
    const test::ProcessRun compared = run(tmp, "shadow_compare", test::shellQuoted(est) + " " + test::shellQuoted(ref));
    ASSERT_EQ(compared.exitCode, 0) << compared.output;
    const nlohmann::json metrics =
        nlohmann::json::parse(compared.output.substr(compared.output.find('{')), nullptr, false);
    ASSERT_FALSE(metrics.is_discarded()) << compared.output;
    const double rmse = metrics["lights"][0]["rmse"];
    std::cout << "default rig, PCSS against the traced truth at 80x60: RMSE " << rmse << "\n";
    // 0.040 measured (the penumbrae at 80x60); a sun 30 degrees off puts a tenth of the ground on
    // the wrong side of the shadow edge, an RMSE near 0.3.
    EXPECT_LT(rmse, 0.08) << "the reference traced another light";
}

}  // namespace
}  // namespace shadow::default_rig_cli_test
