// shadow_compare: error of one render folder's visibility against another's.
//
//   shadow_compare ESTIMATE_DIR TRUTH_DIR [--out DIR] [--mask FILE]
//
// ESTIMATE_DIR (A) holds the images under test, e.g. shadow_render --technique pcss output;
// TRUTH_DIR (B) the reference, e.g. the ray-traced visibility. Every visibility_<i>.exr of B
// must exist in A. Receiver pixels are those of B's position.exr (A = 1), else A's, else every
// pixel; --mask overrides. Prints one JSON document to stdout: per light and for all lights
// pooled, RMSE, MAE, p99 |error|, the fraction with |error| > 0.1, penumbra RMSE, false shadow
// in lit pixels, light leaking in the umbra and the pixel counts (definitions in
// shadow/metrics.h, echoed in the JSON's "definitions"). Writes a signed-error heat map
// error_<i>.png per light into --out (default: ESTIMATE_DIR): blue = estimate too dark, red =
// too light, white = exact, grey = not a receiver, black = NaN/Inf.
// Bad input (folders, files, sizes, unreadable EXR): one message, exit code 2.
#include <shadow/metrics.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>

namespace {

using namespace shadow;
/// Keys in the order written, so a report reads index, headline numbers, then counts.
using json = nlohmann::ordered_json;

constexpr int kExitBadInput = 2;
constexpr int kExitFailure = 1;

struct Options {
    std::string estimateDir;
    std::string truthDir;
    std::string out;  ///< empty: estimateDir
    std::string mask;
};

int fail(int code, const std::string& message) {
    std::cerr << "shadow_compare: " << message << "\n";
    return code;
}

json errorsJson(const VisibilityErrors& e) {
    return {{"rmse", e.rmse},
            {"mae", e.mae},
            {"meanError", e.meanError},
            {"maxAbsError", e.maxAbsError},
            {"p99", e.p99},
            {"fractionOver0_1", e.fractionOver0_1},
            {"penumbraRmse", e.penumbraRmse},
            {"acneFraction", e.acneFraction},
            {"acneMeanDarkening", e.acneMeanDarkening},
            {"leakFraction", e.leakFraction},
            {"faintLeakFraction", e.faintLeakFraction},
            {"interiorLeakFraction", e.interiorLeakFraction},
            {"leakMeanLightening", e.leakMeanLightening},
            {"counts",
             {{"receivers", e.receiverPixels},
              {"nonFinite", e.nonFinite},
              {"valid", e.validPixels},
              {"lit", e.litPixels},
              {"penumbra", e.penumbraPixels},
              {"umbra", e.umbraPixels},
              {"over0_1", e.over0_1Pixels},
              {"acne", e.acnePixels},
              {"leak", e.leakPixels},
              {"faintLeak", e.faintLeakPixels},
              {"interiorUmbra", e.interiorUmbraPixels},
              {"interiorLeak", e.interiorLeakPixels}}}};
}

/// The thresholds behind the numbers, so a JSON file read later explains itself.
json definitionsJson() {
    return {{"error", "estimate - truth (< 0: too dark, > 0: too light)"},
            {"receivers", "mask > 0.5; NaN/Inf pixels counted in nonFinite and excluded"},
            {"classEpsilon", kVisibilityClassEpsilon},
            {"lit", "truth >= 1 - classEpsilon"},
            {"umbra", "truth <= classEpsilon"},
            {"penumbra", "classEpsilon < truth < 1 - classEpsilon"},
            {"largeError", kLargeVisibilityError},
            {"wrongSide", kWrongSideVisibility},
            {"faintLeak", kFaintLeakVisibility},
            {"interiorUmbra", "umbra pixels whose every neighbour within interiorUmbraMargin pixels is umbra"},
            {"interiorUmbraMargin", kInteriorUmbraMargin},
            {"p99", "nearest rank: the ceil(0.99 N)-th smallest |error|"},
            {"acneMeanDarkening", "mean of max(0, truth - estimate) over all lit pixels"},
            {"leakMeanLightening", "mean of max(0, estimate - truth) over all umbra pixels"},
            {"allLights", "every light's pixels pooled (pixel-weighted)"}};
}

/// Creates `dir` if needed; the error names it.
Status prepareOutDir(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) return Error{"--out " + dir + ": cannot create folder: " + ec.message()};
    if (!std::filesystem::is_directory(dir, ec)) return Error{"--out " + dir + ": not a folder"};
    return Ok{};
}

int run(const Options& o) {
    Result<FolderComparison> comparison = compareFolders(o.estimateDir, o.truthDir, o.mask);
    if (!comparison) return fail(kExitBadInput, comparison.error().message);
    const std::string outDir = o.out.empty() ? o.estimateDir : o.out;
    if (Status s = prepareOutDir(outDir); !s) return fail(kExitBadInput, s.error().message);

    json lights = json::array();
    for (const LightComparison& light : comparison->lights) {
        const std::string heatMap =
            (std::filesystem::path(outDir) / ("error_" + std::to_string(light.index) + ".png")).string();
        if (Status s = writeHeatMapPng(heatMap, light.heatMap); !s) {
            return fail(kExitFailure, s.error().message);
        }
        json j = {{"index", light.index}};
        j.update(errorsJson(light.errors));
        j["heatMap"] = heatMap;
        lights.push_back(j);
    }
    json report;
    report["estimate"] = o.estimateDir;
    report["truth"] = o.truthDir;
    report["size"] = {comparison->width, comparison->height};
    report["mask"] = comparison->maskSource;
    report["lights"] = lights;
    report["allLights"] = errorsJson(comparison->allLights);
    report["warnings"] = comparison->warnings;
    report["definitions"] = definitionsJson();
    std::cout << report.dump(2) << "\n";
    for (const std::string& w : comparison->warnings) std::cerr << "shadow_compare: warning: " << w << "\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{
        "Compares the visibility_<i>.exr images of two render folders and prints the errors as "
        "JSON.\nA = ESTIMATE_DIR (images under test), B = TRUTH_DIR (reference); error = A - B."};
    app.add_option("ESTIMATE_DIR", o.estimateDir, "A: folder with the estimated visibility_<i>.exr")->required();
    app.add_option("TRUTH_DIR", o.truthDir, "B: folder with the true visibility_<i>.exr")->required();
    app.add_option("--out", o.out, "folder for the error_<i>.png heat maps (default: A)");
    app.add_option("--mask", o.mask,
                   "EXR whose A (or Y) channel > 0.5 marks receiver pixels (default: B's "
                   "position.exr, else A's, else every pixel)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "shadow_compare: " << e.what() << "\n(see shadow_compare --help)\n";
        return kExitBadInput;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        return fail(kExitFailure, e.what());
    }
}
