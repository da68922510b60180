// penumbra_sweep: frame time against penumbra width. builtin:plates with its disk light's radius
// set so that the high plate's penumbra on the ground spans 2, 4, ... 64 texels of the light's
// map, rendered with each soft technique; prints a Markdown table of main-pass and frame medians
// and, per technique, the widest over the narrowest. PCSS takes more taps as the penumbra widens
// (up to its pcfSamples); the moment techniques read one mip level whatever the width; sdf
// marches the same steps whatever the emitter's size (its map holds no caster).
//
//   penumbra_sweep [--size WxH] [--frames N] [--rounds R]
//
// Shadow maps are redrawn every frame (caching off), so the frame holds the chain builds too.
// The rounds interleave the techniques and widths; each figure is the median over the rounds of
// the per-round medians.
#include <shadow/context_osmesa.h>
#include <shadow/frame_runner.h>
#include <shadow/scene.h>

#include "render_output.h"
#include "cli_common.h"
#include "command_line.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace shadow;

constexpr std::array kWidthsTexels{2, 4, 8, 16, 32, 64};
constexpr std::array kTechniques{ShadowTechnique::Pcss,    ShadowTechnique::PcssTextbook, ShadowTechnique::Vssm,
                                 ShadowTechnique::MsmSoft, ShadowTechnique::Vsm,          ShadowTechnique::Sdf};

struct Options {
    std::string size = "320x240";
    int frames = 5;
    int rounds = 3;
};

/// The high plate's full penumbra on the ground per metre of emitter radius, by similar
/// triangles: 2 (dReceiver - dBlocker) / dBlocker, the light straight above both.
double penumbraPerRadius(const PlatesGeometry& g) {
    const double highest = std::max_element(g.plates.begin(), g.plates.end(), [](const auto& a, const auto& b) {
                               return a.center.y < b.center.y;
                           })->center.y;
    const double dBlocker = g.lightHeight - highest;
    return 2.0 * (g.lightHeight - dBlocker) / dBlocker;
}

/// Ground texel (m) of the plates light's map straight below it, from the frame's plan.
double groundTexelMetres(FrameRunner& runner, const PlatesGeometry& g) {
    const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
    const ShadowLayerPlan& layer = plan.layers.at(0);
    return 2.0 * g.lightHeight / (layer.clipFromLight[0][0] * plan.mapSize);
}

/// Per-round medians of one technique at one width (ms).
struct Timing {
    std::vector<double> main, frame;
};

/// One configuration's medians (ms) over `frames` frames after one warm-up frame, and the
/// ground texel of its map (m).
struct Measured {
    double mainMs = 0.0, frameMs = 0.0, texelMetres = 0.0;
};

Measured measure(ShadowTechnique t, double radius, int frames, int width, int height) {
    Scene scene = makePlatesScene();
    const Entity light = scene.lights.front();
    scene.world.get<Light>(light).radius = static_cast<float>(radius);
    scene.world.get<Shadow>(light).technique = t;
    FrameRunner runner;
    runner.shadows().planner().setCaching(false);
    RenderOptions options;
    options.width = width;
    options.height = height;
    std::vector<double> main, frame;
    for (int f = 0; f <= frames; ++f) {
        const FrameStats s = runner.runFrame(scene, 0.0, scene.cameras.front(), options);
        if (f == 0) continue;
        main.push_back(s.passMs("Main/"));
        frame.push_back(s.passMs("Shadow/") + main.back());
    }
    return {samples::spreadOf(main).median, samples::spreadOf(frame).median,
            groundTexelMetres(runner, PlatesGeometry{})};
}

int run(const Options& o) {
    const Result<std::pair<int, int>> size = samples::parseSize(o.size);
    if (!size) {
        std::cerr << "penumbra_sweep: " << size.error().message << "\n";
        return 2;
    }
    const auto [width, height] = *size;
    auto context = createOsMesaContext();
    if (!context) {
        std::cerr << "penumbra_sweep: " << context.error().message << "\n";
        return 1;
    }
    const PlatesGeometry g;
    // The ground texel does not depend on the radius (the map is fitted to the cone and the
    // casters): one frame finds it.
    const double texel = measure(ShadowTechnique::Hard, g.lightRadius, 1, width, height).texelMetres;
    std::map<std::pair<ShadowTechnique, int>, Timing> timings;
    for (int round = 0; round < o.rounds; ++round) {
        for (int w : kWidthsTexels) {
            for (ShadowTechnique t : kTechniques) {
                const Measured m = measure(t, w * texel / penumbraPerRadius(g), o.frames, width, height);
                Timing& tm = timings[{t, w}];
                tm.main.push_back(m.mainMs);
                tm.frame.push_back(m.frameMs);
            }
        }
    }
    std::printf(
        "Renderer `%s`, %dx%d, `builtin:plates` with the disk light's radius set so that the high "
        "plate's penumbra spans the given texels of its 2048^2 map on the ground (ground texel %.2f mm); "
        "%d interleaved rounds of %d frames after one warm-up frame, shadow maps redrawn every frame. "
        "Main pass / whole frame, ms (median of the rounds' medians).\n\n",
        queryGlInfo().renderer.c_str(), width, height, 1000.0 * texel, o.rounds, o.frames);
    std::printf("| technique |");
    for (int w : kWidthsTexels) std::printf(" %d texels (R %.1f mm) |", w, 1000.0 * w * texel / penumbraPerRadius(g));
    std::printf(" widest / narrowest (main, frame) |\n|---|");
    for (std::size_t k = 0; k <= kWidthsTexels.size(); ++k) std::printf("---|");
    std::printf("\n");
    for (ShadowTechnique t : kTechniques) {
        std::printf("| `%s` |", techniqueName(t));
        std::vector<double> mains, frames;
        for (int w : kWidthsTexels) {
            const Timing& tm = timings[{t, w}];
            mains.push_back(samples::spreadOf(tm.main).median);
            frames.push_back(samples::spreadOf(tm.frame).median);
            std::printf(" %.1f / %.1f |", mains.back(), frames.back());
        }
        const auto ratio = [](const std::vector<double>& v) {
            return *std::max_element(v.begin(), v.end()) / *std::min_element(v.begin(), v.end());
        };
        std::printf(" %.2fx, %.2fx |\n", ratio(mains), ratio(frames));
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    shadow::samples::keepFreedHeap();
    Options o;
    samples::CommandLine app{"Frame time against penumbra width (see the file header)."};
    app.add("--size", o.size, "image size WxH");
    app.add("--frames", o.frames, "timed frames per configuration").range(1, 1000);
    app.add("--rounds", o.rounds, "interleaved rounds").range(1, 100);
    if (const std::optional<int> exit = app.parse(argc, argv, "penumbra_sweep")) return *exit;
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::cerr << "penumbra_sweep: " << e.what() << "\n";
        return 1;
    }
}
