// The default rig on real assets: renders each glTF file as shadow_render does (a file without
// lights gets the default rig, a camera framing the model when it has none) and prints a
// Markdown table: the model's bounds, the share of the frame the model covers and whether it
// stays inside the frame, the share of the ground's pixels in the sun's shadow (below 0.5
// visibility), and the mean sRGB colour of the picture.
//
//   build/bin/default_rig_table [--size WxH] [--time T] [--out DIR] FILE...
//
// With --out, each file's color.png goes to DIR/<stem>.png. A file that does not load is a row
// saying why. Headless (OSMesa).
#include <shadow/context_osmesa.h>
#include <shadow/default_rig.h>
#include <shadow/frame_runner.h>
#include <shadow/image_io.h>

#include "cli_common.h"
#include "command_line.h"
#include "render_output.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace shadow;

/// What one picture shows of the rig.
struct Row {
    std::string bounds;
    double modelShare = 0.0;   ///< of the frame's pixels
    bool inside = true;        ///< no model pixel on the frame's border
    double shadowShare = 0.0;  ///< of the ground's pixels, visibility < 0.5
    double mean[3] = {0.0, 0.0, 0.0};
};

Row measure(const FrameImages& images, const std::vector<std::uint8_t>& srgb, const DefaultRig& rig) {
    Row row;
    const DAabb& b = rig.modelBounds;
    char text[160];
    std::snprintf(text, sizeof(text), "(%.3g, %.3g, %.3g) - (%.3g, %.3g, %.3g)", b.min.x, b.min.y, b.min.z, b.max.x,
                  b.max.y, b.max.z);
    row.bounds = text;
    const ImageF& p = images.position;
    const double tolerance = 1e-4 * glm::length(b.extent());
    long model = 0, ground = 0, shadowed = 0;
    for (int y = 0; y < p.height; ++y) {
        for (int x = 0; x < p.width; ++x) {
            if (p.at(x, y, 3) < 0.5f) continue;
            if (std::abs(p.at(x, y, 1) - rig.groundHeight) <= tolerance && !rig.ground.isNull()) {
                ++ground;
                shadowed += images.visibility.at(0).at(x, y, 0) < 0.5f ? 1 : 0;
                continue;
            }
            ++model;
            if (x == 0 || y == 0 || x == p.width - 1 || y == p.height - 1) row.inside = false;
        }
    }
    row.modelShare = static_cast<double>(model) / (static_cast<double>(p.width) * p.height);
    row.shadowShare = ground > 0 ? static_cast<double>(shadowed) / static_cast<double>(ground) : 0.0;
    for (std::size_t i = 0; i < srgb.size(); ++i) row.mean[i % 3] += srgb[i];
    for (double& m : row.mean) m /= static_cast<double>(srgb.size() / 3);
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    shadow::samples::keepFreedHeap();
    std::vector<std::string> files;
    std::string size = "640x360", out;
    double time = 0.0;
    samples::CommandLine app{
        "The default rig on glTF files: the model's framing and the sun's shadow, as a Markdown table."};
    app.add("files", files, ".gltf/.glb files").required();
    app.add("--size", size, "image size WxH");
    app.add("--time", time, "animation time (s)");
    app.add("--out", out, "write each picture to this folder as <stem>.png");
    if (const auto exit = app.parse(argc, argv, "default_rig_table")) return *exit;
    const auto parsed = samples::parseSize(size);
    if (!parsed) return samples::failAs("default_rig_table", samples::kExitBadInput, parsed.error().message);
    auto context = createOsMesaContext();
    if (!context) return samples::failAs("default_rig_table", samples::kExitFailure, context.error().message);
    if (!out.empty()) std::filesystem::create_directories(out);
    std::printf("| asset | model bounds (m, with margin) | model in frame | inside | ground in shadow | mean sRGB |\n");
    std::printf("|---|---|---:|---|---:|---|\n");
    for (const std::string& file : files) {
        const std::string stem = std::filesystem::path(file).stem().string();
        Result<Scene> scene = loadScene(file);
        if (!scene) {
            std::printf("| %s | %s | | | | |\n", stem.c_str(), scene.error().message.c_str());
            continue;
        }
        if (!scene->lights.empty()) {
            std::printf("| %s | the file has lights: no rig | | | | |\n", stem.c_str());
            continue;
        }
        DefaultRigOptions options;
        options.imageAspect = static_cast<double>(parsed->first) / parsed->second;
        const DefaultRig rig = addDefaultRig(*scene, std::nullopt, options);
        RenderOptions render;
        render.width = parsed->first;
        render.height = parsed->second;
        render.aovs = true;
        render.screenVisibility = ScreenVisibility::Auto;
        FrameRunner runner;
        FrameStats stats = runner.runFrame(*scene, time, rig.camera, render);
        const FrameImages images = runner.renderer().readback(runner.lastCamera(), stats);
        const std::vector<std::uint8_t> srgb = toneMapToSrgb8(images.color, autoExposure(images.color));
        if (!out.empty()) (void)writePng(out + "/" + stem + ".png", render.width, render.height, 3, srgb);
        const Row row = measure(images, srgb, rig);
        std::printf("| %s | %s | %.1f %% | %s | %.1f %% | (%.0f, %.0f, %.0f) |\n", stem.c_str(), row.bounds.c_str(),
                    100.0 * row.modelShare, row.inside ? "yes" : "no", 100.0 * row.shadowShare, row.mean[0],
                    row.mean[1], row.mean[2]);
    }
    return 0;
}
