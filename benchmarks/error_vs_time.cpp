// error_vs_time: every shadow technique and setting on an error-against-time chart.
//
// For each scene, every configuration of the sweep (technique x map size x tap counts x
// kernel) is rendered with the engine: frames are timed without AOVs (median of the timed
// frames after a warm-up frame, shadow layers redrawn every frame so the figure is the full
// cost of a frame), then one frame with AOVs gives the visibility that is compared with the
// ray-traced reference (`shadow_reference`, read from REFERENCES/<scene>/). Writes:
//   OUT/error_vs_time.csv, OUT/error_vs_time.json   one row per (scene, configuration)
//   OUT/error_vs_time.md                            the tables BENCHMARKS.md shows
//   OUT/plot/*.dat, OUT/error_vs_time.gp            data and script for gnuplot
// Run through benchmarks/run_error_vs_time.sh, which makes the references and the plot.
#include <shadow/context_osmesa.h>
#include <shadow/metrics.h>
#include <shadow/frame_runner.h>
#include <shadow/scene.h>

#include "render_output.h"
#include "cli_common.h"
#include "command_line.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace {

using namespace shadow;
namespace fs = std::filesystem;

/// One point of the sweep: what every shadowed light of the scene is set to.
struct Config {
    ShadowTechnique technique = ShadowTechnique::Hard;
    int mapSize = 1024;
    int pcfSamples = 16;
    int blockerSamples = 16;
    FilterKernel kernel = FilterKernel::Vogel;
    float lightBleedReduction = 0.0f;
    DepthMode depthMode = DepthMode::Nearest;  ///< midpoint and second with zero constant and slope bias
    int sdfSteps = 48;
    int fieldVoxels = 64;  ///< sdf: voxels along each field's edge (ShadowLimits::distanceFieldVoxels, cubed)
    /// PCF and VSM: the filter radius (m) set on every light, or kAutomatic to leave each light's
    /// own (the default: 1.5 texels).
    float pcfRadius = kAutomatic;
    /// Where the renderer computes visibility: forward (Off) or the screen-space stage at a
    /// forced resolution (Full, Half, Quarter).
    ScreenVisibility screen = ScreenVisibility::Off;

    /// The series of the chart it belongs to: its technique, the depth mode when not nearest (the
    /// field's resolution for sdf), and the screen-space stage's resolution when it runs.
    [[nodiscard]] std::string series() const {
        const std::string stage = screen == ScreenVisibility::Off ? "" : std::string("-screen");
        if (technique == ShadowTechnique::Sdf) return "sdf-field" + std::to_string(fieldVoxels) + stage;
        return std::string(techniqueName(technique)) +
               (depthMode == DepthMode::Nearest ? "" : std::string("-") + depthModeName(depthMode)) + stage;
    }

    [[nodiscard]] std::string label() const {
        std::ostringstream s;
        const std::string stage =
            screen == ScreenVisibility::Off ? "" : std::string(" screen-") + screenVisibilityName(screen);
        if (technique == ShadowTechnique::Sdf) {
            s << "sdf field" << fieldVoxels << " steps" << sdfSteps << stage;
            return s.str();
        }
        s << techniqueName(technique) << " map" << mapSize;
        if (depthMode != DepthMode::Nearest) s << " " << depthModeName(depthMode);
        if (technique == ShadowTechnique::Pcf) s << " taps" << pcfSamples;
        if (!isAutomatic(pcfRadius)) s << " r" << pcfRadius << "m";
        if (technique == ShadowTechnique::Pcss || technique == ShadowTechnique::PcssTextbook) {
            s << " taps" << blockerSamples << "+" << pcfSamples;
        }
        if (technique == ShadowTechnique::Vsm || technique == ShadowTechnique::Vssm) {
            s << " bleed" << lightBleedReduction;
        } else if (technique == ShadowTechnique::Msm || technique == ShadowTechnique::MsmSoft) {
            // no knob of their own
        } else if (technique != ShadowTechnique::Hard) {
            s << " " << filterKernelName(kernel);
        }
        s << stage;
        return s.str();
    }
};

std::vector<Config> sweep() {
    std::vector<Config> out;
    for (int size : {512, 1024, 2048}) out.push_back({ShadowTechnique::Hard, size, 1, 1, FilterKernel::Vogel});
    for (FilterKernel k : {FilterKernel::Vogel, FilterKernel::Poisson}) {
        for (int taps : {4, 8, 16, 32}) out.push_back({ShadowTechnique::Pcf, 1024, taps, 1, k});
    }
    for (FilterKernel k : {FilterKernel::Vogel, FilterKernel::Poisson}) {
        for (int taps : {4, 8, 16, 32}) out.push_back({ShadowTechnique::Pcss, 1024, taps, taps, k});
    }
    out.push_back({ShadowTechnique::Pcss, 2048, 32, 32, FilterKernel::Vogel});
    for (int taps : {4, 8, 16, 32})
        out.push_back({ShadowTechnique::PcssTextbook, 1024, taps, taps, FilterKernel::Poisson});
    for (ShadowTechnique t : {ShadowTechnique::Vsm, ShadowTechnique::Vssm}) {
        for (int size : {512, 1024, 2048}) out.push_back({t, size, 1, 1, FilterKernel::Vogel, 0.0f});
        for (float bleed : {0.2f, 0.4f}) out.push_back({t, 1024, 1, 1, FilterKernel::Vogel, bleed});
    }
    // The fixed radius in metres the defaults had before they followed the texel (5 cm), for PCF
    // and VSM: a wide filter suits these metre-scale scenes' wide emitters, not any scale.
    for (ShadowTechnique t : {ShadowTechnique::Pcf, ShadowTechnique::Vsm}) {
        Config c{t, 1024, 16, 1, FilterKernel::Vogel};
        c.pcfRadius = 0.05f;
        out.push_back(c);
    }
    for (ShadowTechnique t : {ShadowTechnique::Msm, ShadowTechnique::MsmSoft}) {
        for (int size : {512, 1024, 2048}) out.push_back({t, size, 1, 1, FilterKernel::Vogel, 0.0f});
    }
    // Second-depth maps without bias, and the distance-field march at three step counts.
    out.push_back({ShadowTechnique::Hard, 1024, 1, 1, FilterKernel::Vogel, 0.0f, DepthMode::Midpoint});
    out.push_back({ShadowTechnique::Pcf, 1024, 16, 1, FilterKernel::Vogel, 0.0f, DepthMode::Midpoint});
    out.push_back({ShadowTechnique::Pcss, 1024, 16, 16, FilterKernel::Vogel, 0.0f, DepthMode::Midpoint});
    for (int voxels : {64, 128}) {
        for (int steps : {24, 48, 96}) {
            out.push_back(
                {ShadowTechnique::Sdf, 1024, 1, 1, FilterKernel::Vogel, 0.0f, DepthMode::Nearest, steps, voxels});
        }
    }
    // The screen-space visibility stage (RenderOptions::screenVisibility) at the resolutions it
    // offers, for the default setting of each filtered technique: what its upsample costs in
    // error, next to the same setting forward above.
    for (const ScreenVisibility screen : {ScreenVisibility::Full, ScreenVisibility::Half, ScreenVisibility::Quarter}) {
        for (const Config base :
             {Config{ShadowTechnique::Pcf, 1024, 16, 1, FilterKernel::Vogel},
              Config{ShadowTechnique::Pcss, 1024, 16, 16, FilterKernel::Vogel},
              Config{ShadowTechnique::Vssm, 1024, 1, 1, FilterKernel::Vogel},
              Config{ShadowTechnique::MsmSoft, 1024, 1, 1, FilterKernel::Vogel},
              Config{ShadowTechnique::Sdf, 1024, 1, 1, FilterKernel::Vogel, 0.0f, DepthMode::Nearest, 48, 64}}) {
            Config c = base;
            c.screen = screen;
            out.push_back(c);
        }
    }
    return out;
}

/// What one configuration measured on one scene.
struct Row {
    std::string scene;
    Config config;
    samples::Spread frameMs, shadowMs, mainMs;
    VisibilityErrors errors;  // all lights' receiver pixels as one population
    bool pareto = false;
};

void applyConfig(Scene& scene, const Config& c) {
    scene.world.view<Shadow>().each([&](Entity, Shadow& s) {
        if (s.technique == ShadowTechnique::None) return;
        s.technique = c.technique;
        s.mapSize = c.mapSize;
        s.pcfSamples = c.pcfSamples;
        s.blockerSamples = c.blockerSamples;
        s.kernel = c.kernel;
        s.lightBleedReduction = c.lightBleedReduction;
        samples::applyDepthMode(s, c.depthMode);
        s.sdfSteps = c.sdfSteps;
        if (!isAutomatic(c.pcfRadius)) s.pcfRadius = c.pcfRadius;
    });
}

struct Options {
    std::vector<std::string> scenes{"builtin:plates", "builtin:bunny", "builtin:default"};
    std::string references = "benchmarks/results/tmp/references";
    std::string out = "benchmarks/results";
    std::string size = "320x240";
    int frames = 5;
    std::string only;  ///< when set, only the configurations whose label contains it
};

Result<Row> measure(const std::string& spec, const Config& config, const Options& o, int width, int height) {
    Result<Scene> loaded = samples::loadSampleScene(spec);
    if (!loaded) return loaded.error();
    Scene& scene = *loaded;
    applyConfig(scene, config);
    const Entity camera = scene.cameras.front();
    FrameRunner runner;
    runner.shadows().planner().setCaching(false);  // every frame pays for its shadow maps
    samples::setFieldEdge(runner.shadows().planner(), config.fieldVoxels);
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.screenVisibility = config.screen;
    std::vector<double> frame, shadow, main;
    for (int f = 0; f <= o.frames; ++f) {
        const FrameStats s = runner.runFrame(scene, 0.0, camera, options);
        if (f == 0) continue;  // warm-up: programs compiled, meshes uploaded
        shadow.push_back(s.passMs("Shadow/"));
        main.push_back(s.passMs("Main/"));
        frame.push_back(shadow.back() + main.back());
    }
    options.aovs = true;
    FrameStats aovStats;
    (void)runner.runFrame(scene, 0.0, camera, options);
    const FrameImages images = runner.renderer().readback(runner.lastCamera(), aovStats);

    // Each light is judged where it shades the surface (the reference's lit_<i>.exr): elsewhere
    // V x shading = 0 and its visibility never reaches the image.
    const std::string refDir = o.references + "/" + scene.name;
    std::vector<ImageF> truths, masks;
    for (std::size_t i = 0; i < images.visibility.size(); ++i) {
        const std::string n = std::to_string(i);
        Result<ImageF> truth = readExr(refDir + "/visibility_" + n + ".exr", {"Y"});
        if (!truth) return truth.error();
        Result<ImageF> mask = readExr(refDir + "/lit_" + n + ".exr", {"Y"});
        if (!mask) return mask.error();
        truths.push_back(std::move(truth).value());
        masks.push_back(std::move(mask).value());
    }
    Result<VisibilityErrors> pooled = compareVisibilityPooled(images.visibility, truths, masks);
    if (!pooled) return pooled.error();
    Row row;
    row.scene = scene.name;
    row.config = config;
    row.frameMs = samples::spreadOf(frame);
    row.shadowMs = samples::spreadOf(shadow);
    row.mainMs = samples::spreadOf(main);
    row.errors = *pooled;
    return row;
}

/// Marks each scene's rows that no other row beats in both time and RMSE.
void markPareto(std::vector<Row>& rows) {
    for (Row& r : rows) {
        r.pareto = std::none_of(rows.begin(), rows.end(), [&](const Row& o) {
            return o.scene == r.scene && o.frameMs.median <= r.frameMs.median && o.errors.rmse <= r.errors.rmse &&
                   (o.frameMs.median < r.frameMs.median || o.errors.rmse < r.errors.rmse);
        });
    }
}

/// Our PCSS against the textbook PCSS of the same run: time at equal error and error at equal
/// time, for each textbook configuration; and the bound on any speed-up, the textbook's time over
/// the scene's fastest frame of all configurations (every one draws the same depth layers).
nlohmann::json versusTextbook(const std::vector<Row>& rows) {
    nlohmann::json out = nlohmann::json::array();
    for (const Row& t : rows) {
        if (t.config.technique != ShadowTechnique::PcssTextbook) continue;
        const Row* fastestAsGood = nullptr;
        const Row* bestAsFast = nullptr;
        const Row* fastest = nullptr;
        for (const Row& r : rows) {
            if (r.scene == t.scene && (!fastest || r.frameMs.median < fastest->frameMs.median)) fastest = &r;
        }
        for (const Row& r : rows) {
            if (r.scene != t.scene || r.config.technique != ShadowTechnique::Pcss) continue;
            if (r.errors.rmse <= t.errors.rmse &&
                (!fastestAsGood || r.frameMs.median < fastestAsGood->frameMs.median)) {
                fastestAsGood = &r;
            }
            if (r.frameMs.median <= t.frameMs.median && (!bestAsFast || r.errors.rmse < bestAsFast->errors.rmse)) {
                bestAsFast = &r;
            }
        }
        nlohmann::json j{{"scene", t.scene},
                         {"textbook", t.config.label()},
                         {"textbookMs", t.frameMs.median},
                         {"textbookRmse", t.errors.rmse},
                         {"fastest", fastest->config.label()},
                         {"fastestMs", fastest->frameMs.median},
                         {"speedupBound", t.frameMs.median / fastest->frameMs.median}};
        if (fastestAsGood) {
            j["equalError"] = {{"ours", fastestAsGood->config.label()},
                               {"oursMs", fastestAsGood->frameMs.median},
                               {"speedup", t.frameMs.median / fastestAsGood->frameMs.median}};
        }
        if (bestAsFast) {
            j["equalTime"] = {
                {"ours", bestAsFast->config.label()},
                {"oursRmse", bestAsFast->errors.rmse},
                {"errorRatio", bestAsFast->errors.rmse > 0 ? t.errors.rmse / bestAsFast->errors.rmse : 0.0}};
        }
        out.push_back(j);
    }
    return out;
}

std::string machineName() {
    std::ifstream cpu("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpu, line)) {
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    }
    return "unknown CPU";
}

void writeCsv(const std::string& path, const std::vector<Row>& rows) {
    std::ofstream f(path);
    f << "scene,technique,config,mapSize,pcfSamples,blockerSamples,kernel,frameMsMedian,frameMsMin,frameMsMax,"
         "shadowMsMedian,mainMsMedian,rmse,penumbraRmse,mae,p99,acneFraction,leakFraction,pareto\n";
    for (const Row& r : rows) {
        f << r.scene << ',' << techniqueName(r.config.technique) << ",\"" << r.config.label() << "\","
          << r.config.mapSize << ',' << r.config.pcfSamples << ',' << r.config.blockerSamples << ','
          << filterKernelName(r.config.kernel) << ',' << r.frameMs.median << ',' << r.frameMs.min << ','
          << r.frameMs.max << ',' << r.shadowMs.median << ',' << r.mainMs.median << ',' << r.errors.rmse << ','
          << r.errors.penumbraRmse << ',' << r.errors.mae << ',' << r.errors.p99 << ',' << r.errors.acneFraction << ','
          << r.errors.leakFraction << ',' << (r.pareto ? 1 : 0) << '\n';
    }
}

nlohmann::json rowsJson(const std::vector<Row>& rows) {
    nlohmann::json out = nlohmann::json::array();
    for (const Row& r : rows) {
        out.push_back({{"scene", r.scene},
                       {"technique", techniqueName(r.config.technique)},
                       {"config", r.config.label()},
                       {"frameMs", {{"median", r.frameMs.median}, {"min", r.frameMs.min}, {"max", r.frameMs.max}}},
                       {"shadowMsMedian", r.shadowMs.median},
                       {"mainMsMedian", r.mainMs.median},
                       {"rmse", r.errors.rmse},
                       {"penumbraRmse", r.errors.penumbraRmse},
                       {"mae", r.errors.mae},
                       {"p99", r.errors.p99},
                       {"acneFraction", r.errors.acneFraction},
                       {"leakFraction", r.errors.leakFraction},
                       {"pareto", r.pareto}});
    }
    return out;
}

void writeMarkdown(const std::string& path, const std::vector<Row>& rows, const nlohmann::json& textbook,
                   const std::string& renderer, const Options& o) {
    std::ofstream f(path);
    f.setf(std::ios::fixed);
    f.precision(4);
    f << "Renderer: " << renderer << "; CPU: " << machineName() << "; " << o.size << " pixels; frame time = "
      << "median of " << o.frames << " frames after one warm-up frame, shadow maps redrawn every frame, timed by "
      << "wall clock between glFinish fences.\n\n";
    std::string scene;
    for (const Row& r : rows) {
        if (r.scene != scene) {
            scene = r.scene;
            f << "\n### " << scene
              << "\n\n| configuration | frame ms (median) | shadow ms | main ms | RMSE | penumbra RMSE "
                 "| p99 abs error | acne | leak | Pareto |\n|---|---|---|---|---|---|---|---|---|---|\n";
        }
        f.precision(1);
        f << "| " << r.config.label() << " | " << r.frameMs.median << " | " << r.shadowMs.median << " | "
          << r.mainMs.median;
        f.precision(4);
        f << " | " << r.errors.rmse << " | " << r.errors.penumbraRmse << " | " << r.errors.p99 << " | "
          << r.errors.acneFraction << " | " << r.errors.leakFraction << " | " << (r.pareto ? "yes" : "") << " |\n";
    }
    f << "\n### Our PCSS against the textbook PCSS (same run)\n\n| scene | textbook | textbook ms | textbook RMSE "
         "| ours at equal error | speed-up | ours at equal time | error ratio | fastest frame of all | speed-up bound "
         "|\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& j : textbook) {
        f.precision(1);
        f << "| " << j["scene"].get<std::string>() << " | " << j["textbook"].get<std::string>() << " | "
          << j["textbookMs"].get<double>();
        f.precision(4);
        f << " | " << j["textbookRmse"].get<double>() << " | ";
        if (j.contains("equalError")) {
            f.precision(2);
            f << j["equalError"]["ours"].get<std::string>() << " (" << j["equalError"]["oursMs"].get<double>()
              << " ms) | " << j["equalError"]["speedup"].get<double>() << "x | ";
        } else {
            f << "none as accurate | | ";
        }
        if (j.contains("equalTime")) {
            f.precision(4);
            f << j["equalTime"]["ours"].get<std::string>() << " (RMSE " << j["equalTime"]["oursRmse"].get<double>()
              << ") | ";
            f.precision(2);
            f << j["equalTime"]["errorRatio"].get<double>() << "x | ";
        } else {
            f << "none as fast | | ";
        }
        f.precision(2);
        f << j["fastest"].get<std::string>() << " (" << j["fastestMs"].get<double>() << " ms) | "
          << j["speedupBound"].get<double>() << "x |\n";
    }
}

/// gnuplot data (one file per scene and technique, plus each scene's Pareto front) and script.
void writePlot(const std::string& out, const std::vector<Row>& rows) {
    fs::create_directories(out + "/plot");
    std::vector<std::string> scenes;
    for (const Row& r : rows) {
        if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
    }
    std::vector<std::string> series;  // one line of the chart each, in the sweep's order
    for (const Row& r : rows) {
        if (std::find(series.begin(), series.end(), r.config.series()) == series.end())
            series.push_back(r.config.series());
    }
    for (const std::string& s : scenes) {
        for (const std::string& name : series) {
            std::vector<const Row*> sel;
            for (const Row& r : rows) {
                if (r.scene == s && r.config.series() == name) sel.push_back(&r);
            }
            std::sort(sel.begin(), sel.end(),
                      [](const Row* a, const Row* b) { return a->frameMs.median < b->frameMs.median; });
            std::ofstream f(out + "/plot/" + s + "_" + name + ".dat");
            for (const Row* r : sel)
                f << r->frameMs.median << ' ' << r->errors.rmse << ' ' << r->errors.penumbraRmse << '\n';
        }
        std::vector<const Row*> front;
        for (const Row& r : rows) {
            if (r.scene == s && r.pareto) front.push_back(&r);
        }
        std::sort(front.begin(), front.end(),
                  [](const Row* a, const Row* b) { return a->frameMs.median < b->frameMs.median; });
        std::ofstream f(out + "/plot/" + s + "_pareto.dat");
        for (const Row* r : front)
            f << r->frameMs.median << ' ' << r->errors.rmse << ' ' << r->errors.penumbraRmse << '\n';
    }
    std::ofstream gp(out + "/error_vs_time.gp");
    gp << "# Generated by error_vs_time. Run from " << out << ": gnuplot error_vs_time.gp\n"
       << "set terminal pngcairo size " << 520 * scenes.size() << ",900 font ',10'\n"
       << "set output 'error_vs_time.png'\nset multiplot layout 2," << scenes.size() << "\n"
       << "set logscale x\nset grid\nset key top right\nset xlabel 'frame time (ms, median, log)'\n";
    for (int metric = 0; metric < 2; ++metric) {
        for (const std::string& s : scenes) {
            gp << "set title '" << s << ": " << (metric == 0 ? "RMSE" : "penumbra RMSE") << "'\n";
            gp << "set ylabel '" << (metric == 0 ? "RMSE of visibility" : "RMSE in the true penumbra") << "'\n";
            gp << "plot ";
            const int col = metric == 0 ? 2 : 3;
            for (const std::string& name : series) {
                gp << "'plot/" << s << "_" << name << ".dat' using 1:" << col << " with linespoints title '" << name
                   << "', ";
            }
            gp << "'plot/" << s << "_pareto.dat' using 1:" << col
               << " with lines dashtype 2 linewidth 2 linecolor 'black' title 'Pareto front (RMSE)'\n";
        }
    }
    gp << "unset multiplot\n";
}

int run(const Options& o) {
    auto size = std::string(o.size);
    const auto x = size.find('x');
    const int width = x == std::string::npos ? 0 : std::atoi(size.substr(0, x).c_str());
    const int height = x == std::string::npos ? 0 : std::atoi(size.substr(x + 1).c_str());
    if (width < 1 || height < 1) {
        std::cerr << "error_vs_time: --size '" << o.size << "': expected WxH\n";
        return 2;
    }
    auto context = createOsMesaContext();
    if (!context) {
        std::cerr << "error_vs_time: " << context.error().message << "\n";
        return 1;
    }
    const std::string renderer = queryGlInfo().renderer;
    std::vector<Row> rows;
    const std::vector<Config> configs = sweep();
    for (const std::string& spec : o.scenes) {
        for (const Config& c : configs) {
            if (!o.only.empty() && c.label().find(o.only) == std::string::npos) continue;
            Result<Row> row = measure(spec, c, o, width, height);
            if (!row) {
                std::cerr << "error_vs_time: " << spec << ", " << c.label() << ": " << row.error().message << "\n";
                return 2;
            }
            std::cerr << spec << "  " << c.label() << ": " << row->frameMs.median << " ms, RMSE " << row->errors.rmse
                      << "\n";
            rows.push_back(std::move(row).value());
        }
    }
    markPareto(rows);
    fs::create_directories(o.out);
    writeCsv(o.out + "/error_vs_time.csv", rows);
    const nlohmann::json textbook = versusTextbook(rows);
    nlohmann::json j{{"renderer", renderer},
                     {"cpu", machineName()},
                     {"size", o.size},
                     {"timedFrames", o.frames},
                     {"timingMethod", queryGlInfo().softwareRenderer ? "wall-clock-fence" : "timer-query"},
                     {"rows", rowsJson(rows)},
                     {"versusTextbook", textbook}};
    std::ofstream(o.out + "/error_vs_time.json") << j.dump(2) << "\n";
    writeMarkdown(o.out + "/error_vs_time.md", rows, textbook, renderer, o);
    writePlot(o.out, rows);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    shadow::samples::keepFreedHeap();
    Options o;
    samples::CommandLine app{"Error against time for every shadow technique and setting (see the file header)."};
    app.add("--scenes", o.scenes, "scenes to sweep").delimiter(',');
    app.add("--references", o.references, "folder with one shadow_reference output per scene name");
    app.add("--out", o.out, "results folder");
    app.add("--size", o.size, "image size WxH");
    app.add("--frames", o.frames, "timed frames per configuration").range(1, 1000);
    app.add("--only", o.only, "only the configurations whose label contains this text (e.g. 'sdf field128')");
    if (const std::optional<int> exit = app.parse(argc, argv, "error_vs_time")) return *exit;
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::cerr << "error_vs_time: " << e.what() << "\n";
        return 1;
    }
}
