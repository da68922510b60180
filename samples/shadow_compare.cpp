// shadow_compare: error of one render folder's visibility against another's.
//
//   shadow_compare ESTIMATE_DIR TRUTH_DIR [--out DIR] [--mask FILE]
//
// ESTIMATE_DIR (A) holds the images under test, e.g. shadow_render --technique pcss output;
// TRUTH_DIR (B) the reference, e.g. the ray-traced visibility. A folder a tool wrote holds the
// record of its run, stats.json (shadow_render) or reference.json (shadow_reference; the newer
// of the two when both are there): the lights compared are exactly those B's record names, each
// must be named by A's record too (when A has one) and its visibility_<i>.exr must exist in
// both. A file the comparison reads from a folder with a record must have been written by that
// run: not before its startTime, not after the record itself (kRunClockSlack either way);
// otherwise it is an earlier run's, left behind, and the comparison is refused. A folder without
// a record (images made by hand) compares every visibility_<i>.exr of B, with a warning. Receiver pixels are those of B's position.exr (A = 1), else A's, else every
// pixel; --mask overrides (--mask lit: each light over B's lit_<i>.exr, where the reference
// says it shades the surface). Prints one JSON document to stdout: per light and for all lights
// pooled, RMSE, MAE, p99 |error|, the fraction with |error| > 0.1, penumbra RMSE, false shadow
// in lit pixels, light leaking in the umbra and the pixel counts (definitions in
// shadow/metrics.h, echoed in the JSON's "definitions"). Writes a signed-error heat map
// error_<i>.png per light into --out (default: ESTIMATE_DIR): blue = estimate too dark, red =
// too light, white = exact, grey = not a receiver, black = NaN/Inf.
// A NaN/Inf estimate pixel scores |error| = 1 and is counted in "nonFinite"; a NaN/Inf truth
// pixel is bad input. Bad input (folders, files, records, sizes, unreadable EXR, stale files):
// one message, exit code 2.
#include <shadow/metrics.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "cli_common.h"
#include "command_line.h"

namespace {

using namespace shadow;
/// Keys in the order written, so a report reads index, headline numbers, then counts.
using json = nlohmann::ordered_json;

using samples::kExitBadInput;
using samples::kExitFailure;

struct Options {
    std::string estimateDir;
    std::string truthDir;
    std::string out;  ///< empty: estimateDir
    std::string mask;
};

int fail(int code, const std::string& message) { return samples::failAs("shadow_compare", code, message); }

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
            {"receivers", "mask > 0.5"},
            {"nonFinite", "receivers with a NaN/Inf estimate, scored |error| = 1 (the far end of [0, 1])"},
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

namespace fs = std::filesystem;

/// How far a file's time may lie outside its run (file times come from a coarse clock, and a
/// copy may round them to whole seconds).
constexpr double kRunClockSlack = 2.0;

/// What a tool wrote about its run into its folder.
struct RunRecord {
    std::string path;                 ///< stats.json or reference.json
    double writtenAt = 0.0;           ///< the record's own modification time (Unix seconds)
    std::optional<double> startTime;  ///< absent in records older than the field
    std::vector<int> lights;          ///< the `<i>` of every visibility_<i>.exr it names
};

double unixSeconds(fs::file_time_type t) {
    const auto sys = std::chrono::file_clock::to_sys(t);
    return std::chrono::duration<double>(sys.time_since_epoch()).count();
}

/// The run record of `dir`, if it has one; errors name the record.
Result<std::optional<RunRecord>> readRunRecord(const std::string& dir) {
    std::optional<fs::path> newest;
    fs::file_time_type newestTime;
    for (const char* name : {"stats.json", "reference.json"}) {
        const fs::path p = fs::path(dir) / name;
        std::error_code ec;
        if (!fs::is_regular_file(p, ec)) continue;
        const fs::file_time_type t = fs::last_write_time(p, ec);
        if (ec) return Error{ErrorCode::FileUnreadable, p.string() + ": " + ec.message()};
        if (!newest || t > newestTime) {
            newest = p;
            newestTime = t;
        }
    }
    if (!newest) return std::optional<RunRecord>{};
    RunRecord record;
    record.path = newest->string();
    record.writtenAt = unixSeconds(newestTime);
    std::ifstream in(*newest);
    const json j = json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded() || !j.is_object()) return Error{ErrorCode::MalformedFile, record.path + ": not a JSON object"};
    if (j.contains("startTime") && j["startTime"].is_number()) record.startTime = j["startTime"].get<double>();
    if (!j.contains("lights") || !j["lights"].is_array())
        return Error{ErrorCode::MalformedFile, record.path + ": no \"lights\" array"};
    for (std::size_t k = 0; k < j["lights"].size(); ++k) {
        const json& light = j["lights"][k];
        if (!light.is_object() || !light.contains("index") || !light["index"].is_number_unsigned() ||
            light["index"].get<std::uint64_t>() > 1000000) {
            return Error{ErrorCode::MalformedFile,
                         record.path + ": lights[" + std::to_string(k) + "] has no valid \"index\""};
        }
        record.lights.push_back(light["index"].get<int>());
    }
    return std::optional<RunRecord>{std::move(record)};
}

/// Refuses `file` when its time says it is not of `record`'s run.
Status checkOfRun(const RunRecord& record, const std::string& file) {
    std::error_code ec;
    const fs::file_time_type t = fs::last_write_time(file, ec);
    if (ec) return Error{ErrorCode::FileUnreadable, file + ": " + ec.message()};
    const double at = unixSeconds(t);
    if (record.startTime && at < *record.startTime - kRunClockSlack) {
        return Error{ErrorCode::MismatchedInputs,
                     file + ": older than the run of " + record.path +
                         " (a file an earlier run left in the folder; render into an empty folder)"};
    }
    if (at > record.writtenAt + kRunClockSlack) {
        return Error{ErrorCode::MismatchedInputs,
                     file + ": newer than " + record.path + " (written by a later run that did not finish)"};
    }
    return Ok{};
}

std::string visibilityPath(const std::string& dir, int index) {
    return (fs::path(dir) / ("visibility_" + std::to_string(index) + ".exr")).string();
}

/// The lights to compare, from the folders' run records, with every file of a recorded run
/// checked to belong to it; `warnings` gets what is worth telling.
Result<std::vector<int>> lightsToCompare(const std::string& estimateDir, const std::string& truthDir,
                                         const std::string& maskPath, std::vector<std::string>& warnings) {
    Result<std::optional<RunRecord>> estimate = readRunRecord(estimateDir);
    if (!estimate) return estimate.error();
    Result<std::optional<RunRecord>> truth = readRunRecord(truthDir);
    if (!truth) return truth.error();
    std::vector<int> lights;
    if (*truth) {
        lights = (*truth)->lights;
        if (lights.empty()) return Error{ErrorCode::MismatchedInputs, (*truth)->path + ": names no lights to compare"};
    } else {
        warnings.push_back(truthDir + ": no stats.json or reference.json; comparing every visibility_<i>.exr in it");
    }
    if (*estimate && *truth) {
        const std::vector<int>& named = (*estimate)->lights;
        for (int i : lights) {
            if (std::find(named.begin(), named.end(), i) == named.end()) {
                return Error{ErrorCode::MismatchedInputs, (*estimate)->path + ": names no light " + std::to_string(i) +
                                                              " (" + (*truth)->path + " does)"};
            }
        }
        for (int i : named) {
            if (std::find(lights.begin(), lights.end(), i) == lights.end()) {
                warnings.push_back((*estimate)->path + ": light " + std::to_string(i) + " is not in " + (*truth)->path +
                                   "; not compared");
            }
        }
    }
    for (const auto& [dir, record] : {std::pair{estimateDir, &*estimate}, std::pair{truthDir, &*truth}}) {
        if (!record->has_value()) continue;
        for (int i : lights.empty() ? (*record)->lights : lights) {
            const std::string file = visibilityPath(dir, i);
            std::error_code ec;
            if (!fs::is_regular_file(file, ec)) {
                return Error{ErrorCode::FileUnreadable,
                             file + ": missing (" + (*record)->path + " names light " + std::to_string(i) + ")"};
            }
            if (Status s = checkOfRun(**record, file); !s) return s.error();
        }
        const std::string position = (fs::path(dir) / "position.exr").string();
        std::error_code ec;
        if (maskPath.empty() && fs::is_regular_file(position, ec)) {
            if (Status s = checkOfRun(**record, position); !s) return s.error();
        }
    }
    return lights;
}

/// Creates `dir` if needed; the error names it.
Status prepareOutDir(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return Error{ErrorCode::FileUnreadable, "--out " + dir + ": cannot create folder: " + ec.message()};
    if (!fs::is_directory(dir, ec)) return Error{ErrorCode::FileUnwritable, "--out " + dir + ": not a folder"};
    return Ok{};
}

int run(const Options& o) {
    std::vector<std::string> warnings;
    Result<std::vector<int>> compared = lightsToCompare(o.estimateDir, o.truthDir, o.mask, warnings);
    if (!compared) return fail(kExitBadInput, compared.error().message);
    Result<FolderComparison> comparison = compareFolders(o.estimateDir, o.truthDir, o.mask, *compared);
    if (!comparison) return fail(kExitBadInput, comparison.error().message);
    comparison->warnings.insert(comparison->warnings.begin(), warnings.begin(), warnings.end());
    const std::string outDir = o.out.empty() ? o.estimateDir : o.out;
    if (Status s = prepareOutDir(outDir); !s) return fail(kExitBadInput, s.error().message);

    json lights = json::array();
    for (const LightComparison& light : comparison->lights) {
        const std::string heatMap = (fs::path(outDir) / ("error_" + std::to_string(light.index) + ".png")).string();
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
    samples::CommandLine app{
        "Compares the visibility_<i>.exr images of two render folders and prints the errors as "
        "JSON.\nA = ESTIMATE_DIR (images under test), B = TRUTH_DIR (reference); error = A - B."};
    app.add("ESTIMATE_DIR", o.estimateDir, "A: folder with the estimated visibility_<i>.exr").required();
    app.add("TRUTH_DIR", o.truthDir, "B: folder with the true visibility_<i>.exr").required();
    app.add("--out", o.out, "folder for the error_<i>.png heat maps (default: A)");
    app.add("--mask", o.mask,
            "EXR whose A (or Y) channel > 0.5 marks receiver pixels (default: B's "
            "position.exr, else A's, else every pixel); the word lit: each light over B's lit_<i>.exr");
    if (const std::optional<int> exit = app.parse(argc, argv, "shadow_compare")) return *exit;
    try {
        return run(o);
    } catch (const std::exception& e) {
        return fail(kExitFailure, e.what());
    }
}
