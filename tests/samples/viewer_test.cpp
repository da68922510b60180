// shadow_viewer's scripted mode (samples/viewer_script.h, docs/viewer.md), run under Xvfb: its
// screenshot of a scene is shadow_render's color.png of the same scene, camera, time and size,
// and a bad script line is one message naming the line, exit code 2 and nothing written.
#include <gtest/gtest.h>

#include "scene/cube_scene.h"
#include "test_support.h"
#include <stb/stb_image.h>  // decoder only; its implementation comes from libstb

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace shadow::viewer_test {
namespace {

namespace fs = std::filesystem;

using test::kExitBadInput;
constexpr int kWidth = 320;
constexpr int kHeight = 180;

/// Both programs render through Mesa's llvmpipe (shadow_render in an OSMesa context, the viewer
/// in a GLX one on Xvfb) with the same code, shaders, camera, time and tone map (shadow/tone_map.h:
/// run on the CPU by shadow_render, on the GPU by the viewer), into framebuffers of the engine's
/// own formats; so the images should agree to the byte. Measured on builtin:default at 320x180:
/// 0 of 57 600 pixels differ. The tolerance leaves room for one
/// 8-bit step of rounding in a few pixels (a driver build that orders a sum differently between
/// the two context types), and no more: a camera, time or exposure off by a little moves whole
/// edges and fails it.
constexpr int kMaxChannelStep = 1;            // 8-bit sRGB steps
constexpr double kMaxDifferingPixels = 1e-3;  // fraction of the pixels that may differ by that step

bool installed(const std::string& program) {
    return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0;
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
}

struct Rgb {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;
};

Rgb readPng(const std::string& path) {
    Rgb image;
    int channels = 0;
    stbi_uc* decoded = stbi_load(path.c_str(), &image.width, &image.height, &channels, 3);
    if (decoded == nullptr) {
        ADD_FAILURE() << path << ": not a PNG stb can read";
        return {};
    }
    image.pixels.assign(decoded, decoded + static_cast<std::size_t>(image.width) * image.height * 3);
    stbi_image_free(decoded);
    return image;
}

/// `actual` (the viewer's) is `expected` (shadow_render's) within the tolerance above.
void expectSameFrame(const Rgb& expected, const Rgb& actual) {
    ASSERT_EQ(actual.width, kWidth);
    ASSERT_EQ(actual.height, kHeight);
    ASSERT_EQ(expected.width, kWidth);
    ASSERT_EQ(expected.height, kHeight);
    int largest = 0;
    std::size_t differing = 0;
    for (std::size_t p = 0; p < actual.pixels.size(); p += 3) {
        int step = 0;
        for (std::size_t c = 0; c < 3; ++c)
            step = std::max(step, std::abs(actual.pixels[p + c] - expected.pixels[p + c]));
        largest = std::max(largest, step);
        differing += step > 0 ? 1 : 0;
    }
    const double fraction = static_cast<double>(differing) / (kWidth * kHeight);
    std::cout << "viewer vs shadow_render: " << differing << " pixels differ (" << fraction * 100.0
              << " %), by at most " << largest << " steps\n";
    EXPECT_LE(largest, kMaxChannelStep);
    EXPECT_LE(fraction, kMaxDifferingPixels);
}

/// Runs the viewer under a virtual X server of its own.
test::ProcessRun runViewerUnderXvfb(const test::TempDir& tmp, const std::string& args) {
    return test::runProgram(
        "xvfb-run", "-a -s '-screen 0 640x480x24' " + test::shellQuoted(SHADOW_BIN_DIR "/shadow_viewer") + " " + args,
        tmp / "viewer.log");
}

TEST(ShadowViewerScript, ScreenshotMatchesShadowRenderOfTheSameFrame) {
#ifndef SHADOW_VIEWER_BUILT
    GTEST_SKIP() << "the viewer is not built (SHADOW_BUILD_VIEWER=OFF)";
#endif
    if (!installed("xvfb-run") || !installed("Xvfb") || !installed("xauth")) {
        GTEST_SKIP() << "Xvfb is not installed (Debian packages xvfb and xauth)";
    }
    test::TempDir tmp("viewer_test");
    const std::string rendered = tmp / "render";
    const std::string viewed = tmp / "viewer";
    // Three frames from t = 1.4 s in steps of 0.05 s: the shadow layers of the moving casters are
    // redrawn and the static ones reused, in both programs alike.
    const test::ProcessRun render =
        test::runProgram(SHADOW_BIN_DIR "/shadow_render",
                         "builtin:default --size 320x180 --time 1.4 --frames 3 --dt 0.05 --aov color --out " +
                             test::shellQuoted(rendered),
                         tmp / "render.log");
    ASSERT_EQ(render.exitCode, 0) << render.output;

    const std::string script = tmp / "frame.txt";
    writeText(script, "# the frame shadow_render drew\ntime 1.4\ndt 0.05\nframes 3\nscreenshot " + viewed +
                          "/color.png\nscreenshot-ui " + viewed + "/color_ui.png\nquit\n");
    const auto start = std::chrono::steady_clock::now();
    const test::ProcessRun view =
        runViewerUnderXvfb(tmp, "builtin:default --size 320x180 --script " + test::shellQuoted(script));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(view.exitCode, 0) << view.output;
    std::cout << "viewer run under Xvfb: " << seconds << " s\n";

    const Rgb actual = readPng(viewed + "/color.png");
    expectSameFrame(readPng(rendered + "/color.png"), actual);

    // The window with the UI over the frame: the window's size, and not the bare frame.
    const Rgb withUi = readPng(viewed + "/color_ui.png");
    EXPECT_EQ(withUi.width, kWidth);
    EXPECT_EQ(withUi.height, kHeight);
    EXPECT_NE(withUi.pixels, actual.pixels) << "the UI screenshot shows no UI";
}

// A file without lights: the viewer lights it with the default rig as shadow_render does (the
// same sun, ground and framing camera), so its frame is shadow_render's color.png. Fails when the
// viewer leaves the rig out or places it otherwise (another sun, or a camera framed for another
// image shape).
TEST(ShadowViewerScript, FileWithoutLightsShowsTheDefaultRigAsShadowRenderDoes) {
#ifndef SHADOW_VIEWER_BUILT
    GTEST_SKIP() << "the viewer is not built (SHADOW_BUILD_VIEWER=OFF)";
#endif
    if (!installed("xvfb-run") || !installed("Xvfb") || !installed("xauth")) {
        GTEST_SKIP() << "Xvfb is not installed (Debian packages xvfb and xauth)";
    }
    test::TempDir tmp("viewer_test");
    const std::string cube = test::shellQuoted(test::writeCube(tmp.path() / "cube.gltf", false).string());
    const std::string rendered = tmp / "render", viewed = tmp / "viewer";
    const test::ProcessRun render =
        test::runProgram(SHADOW_BIN_DIR "/shadow_render",
                         cube + " --size 320x180 --aov color --out " + test::shellQuoted(rendered), tmp / "render.log");
    ASSERT_EQ(render.exitCode, 0) << render.output;
    const test::ProcessRun view =
        runViewerUnderXvfb(tmp, cube + " --size 320x180 --frames 1 --screenshot " + test::shellQuoted(viewed));
    ASSERT_EQ(view.exitCode, 0) << view.output;
    expectSameFrame(readPng(rendered + "/color.png"), readPng(viewed + "/color.png"));
}

TEST(ShadowViewerScript, BadLineIsOneMessageNamingItExitTwoNothingWritten) {
#ifndef SHADOW_VIEWER_BUILT
    GTEST_SKIP() << "the viewer is not built (SHADOW_BUILD_VIEWER=OFF)";
#endif
    test::TempDir tmp("viewer_test");
    const std::string out = tmp / "shots";
    const std::string script = tmp / "bad.txt";
    // Line 4 is the bad one; the screenshot before it must not be written. Checked before any
    // window opens, so no display is needed.
    writeText(script, "time 0.5\nscreenshot " + out + "/a.png\n# a comment\nset 0 mapsize 512\nquit\n");
    const test::ProcessRun run =
        test::runProgram(SHADOW_BIN_DIR "/shadow_viewer",
                         "builtin:default --size 64x36 --script " + test::shellQuoted(script), tmp / "viewer.log");
    EXPECT_EQ(run.exitCode, kExitBadInput) << run.output;
    EXPECT_NE(run.output.find("bad.txt:4: unknown setting 'mapsize'"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("mapSize"), std::string::npos) << "the message lists the known keys: " << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << "one message: " << run.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing written for a script that does not parse";

    // A bad argument is the same: one message naming it, exit 2.
    const test::ProcessRun badSize =
        test::runProgram(SHADOW_BIN_DIR "/shadow_viewer", "builtin:default --size 64by36 --frames 1", tmp / "size.log");
    EXPECT_EQ(badSize.exitCode, kExitBadInput) << badSize.output;
    EXPECT_NE(badSize.output.find("--size '64by36'"), std::string::npos) << badSize.output;
    const test::ProcessRun badStage = test::runProgram(
        SHADOW_BIN_DIR "/shadow_viewer", "builtin:default --screen-visibility sometimes --frames 1", tmp / "stage.log");
    EXPECT_EQ(badStage.exitCode, kExitBadInput) << badStage.output;
    EXPECT_NE(badStage.output.find("--screen-visibility: unknown setting 'sometimes'"), std::string::npos)
        << badStage.output;
}

TEST(ShadowViewerScript, ScriptThatIsNoRegularFileOrTooLargeIsOneMessage) {
#ifndef SHADOW_VIEWER_BUILT
    GTEST_SKIP() << "the viewer is not built (SHADOW_BUILD_VIEWER=OFF)";
#endif
    // Checked before any window opens (no display needed) and before anything is read: a FIFO
    // would block, /dev/zero would grow without end.
    test::TempDir tmp("viewer_test");
    const std::string fifo = tmp / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string big = tmp / "big.txt";
    writeText(big, std::string(1U << 20U, '#') + "\nquit\n");  // a comment line of 1 MiB, over the cap
    const std::string longLine = tmp / "long.txt";
    writeText(longLine, "time 1\n" + std::string(100000, 'x') + "\n");  // within the size cap
    const std::string wordy = tmp / "wordy.txt";
    writeText(wordy, "frames " + std::string(3000, '7') + "\n");  // a line within the cap, a long word
    struct Case {
        std::string script, mention;
    };
    const std::vector<Case> cases = {
        {tmp.path().string(), "not a regular file (a directory)"},
        {fifo, "not a regular file (a FIFO)"},
        {"/dev/zero", "not a regular file (a device)"},
        {big, "bytes; a script holds at most 1048576 (1 MiB)"},
        {longLine, "long.txt:2: a line of 100000 bytes; a line holds at most 4096"},
        {wordy, "wordy.txt:1: frames '777"},
    };
    for (const Case& c : cases) {
        const auto start = std::chrono::steady_clock::now();
        const test::ProcessRun run = test::runProgram(
            SHADOW_BIN_DIR "/shadow_viewer", "builtin:default --size 64x36 --script " + test::shellQuoted(c.script),
            tmp / "viewer.log");
        EXPECT_EQ(run.exitCode, kExitBadInput) << c.script << ": " << run.output;
        EXPECT_NE(run.output.find(c.mention), std::string::npos) << c.script << ": " << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << "one message: " << run.output;
        EXPECT_LE(run.output.size(), 1100U) << c.script << ": the message is capped";
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30)) << c.script;
    }
}

}  // namespace
}  // namespace shadow::viewer_test
