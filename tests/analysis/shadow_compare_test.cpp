// The shadow_compare CLI (samples/shadow_compare.cpp): JSON on stdout with the expected
// numbers, error_<i>.png heat maps, and bad input answered by one message and exit code 2.
//
// shadow_core_tests has no SHADOW_BIN_DIR: the programs live beside the test executable
// (build/bin), found through /proc/self/exe. Build the shadow_compare target before running.
#include <gtest/gtest.h>

#include <memory>

#include "test_support.h"
#include <shadow/image_io.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace shadow {
namespace {

namespace fs = std::filesystem;

using test::kExitBadInput;

fs::path compareBinary() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path("shadow_compare") : self.parent_path() / "shadow_compare";
}

using test::shellQuoted;

std::string readText(const std::string& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

struct CliRun {
    int exitCode = -1;  ///< -1 when the process did not exit normally (a crash)
    std::string out;
    std::string err;
};

using test::imageOf;

/// A fresh directory per test under $SHADOW_TEST_TMP (or the system temp dir), removed after.
class ShadowCompareCli : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_TRUE(fs::exists(compareBinary())) << compareBinary() << " is missing: build the shadow_compare target";
        tmp_ = std::make_unique<test::TempDir>("shadow_compare_test");
        dir_ = tmp_->path();
        estimate_ = (dir_ / "est").string();
        truth_ = (dir_ / "truth").string();
        fs::create_directories(estimate_);
        fs::create_directories(truth_);
    }
    void TearDown() override { tmp_.reset(); }

    /// Runs shadow_compare with `args` (quoted by the caller where needed).
    [[nodiscard]] CliRun run(const std::string& args) const {
        const std::string outFile = (dir_ / "stdout.txt").string();
        const std::string errFile = (dir_ / "stderr.txt").string();
        const std::string command = shellQuoted(compareBinary().string()) + " " + args + " > " + shellQuoted(outFile) +
                                    " 2> " + shellQuoted(errFile);
        const int raw = std::system(command.c_str());
        CliRun r;
        r.exitCode = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
        r.out = readText(outFile);
        r.err = readText(errFile);
        return r;
    }

    static void writeVisibility(const std::string& dir, int index, const ImageF& image) {
        const std::string file = dir + "/visibility_" + std::to_string(index) + ".exr";
        ASSERT_TRUE(writeExr(file, image, {"Y"}).ok()) << file;
    }

    /// Two 2x2 lights; truth's position.exr covers pixels 0-2.
    ///   light 0: e = 0, -0.75 (acne), +0.5      light 1: e = 0, +1 (leak), 0
    void writeTwoLights() {
        writeVisibility(truth_, 0, imageOf(2, 2, {1, 1, 0, 0.5f}));
        writeVisibility(truth_, 1, imageOf(2, 2, {0, 0, 0.5f, 0}));
        writeVisibility(estimate_, 0, imageOf(2, 2, {1, 0.25f, 0.5f, 9}));
        writeVisibility(estimate_, 1, imageOf(2, 2, {0, 1, 0.5f, 0}));
        ImageF position = makeImage(2, 2, 4);
        for (int i = 0; i < 3; ++i) position.pixels[static_cast<std::size_t>(4 * i + 3)] = 1.0f;
        ASSERT_TRUE(writeExr(truth_ + "/position.exr", position, {"R", "G", "B", "A"}).ok());
    }

    /// A run record as shadow_render (stats.json) or shadow_reference (reference.json) writes
    /// it: the lights it names and the run's start.
    static void writeRecord(const std::string& file, const std::vector<int>& lights, double startTime) {
        nlohmann::json j;
        j["startTime"] = startTime;
        j["lights"] = nlohmann::json::array();
        for (int i : lights) {
            j["lights"].push_back({{"index", i}, {"visibility", "visibility_" + std::to_string(i) + ".exr"}});
        }
        std::ofstream(file) << j.dump(2);
    }

    static double now() {
        return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    }

    /// Moves `file`'s modification time `seconds` into the past.
    static void age(const std::string& file, int seconds) {
        fs::last_write_time(file, fs::last_write_time(file) - std::chrono::seconds(seconds));
    }

    std::unique_ptr<test::TempDir> tmp_;  // removes the folder
    fs::path dir_;
    std::string estimate_;
    std::string truth_;
};

TEST_F(ShadowCompareCli, PrintsJsonWithTheExpectedNumbersAndWritesHeatMaps) {
    writeTwoLights();
    const std::string heatDir = (dir_ / "heat").string();
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_) + " --out " + shellQuoted(heatDir));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << "stdout is not JSON:\n" << r.out;

    ASSERT_EQ(j["lights"].size(), 2u);
    const nlohmann::json& l0 = j["lights"][0];
    EXPECT_EQ(l0["index"], 0);
    EXPECT_DOUBLE_EQ(l0["rmse"].get<double>(), std::sqrt((0.5625 + 0.25) / 3.0));
    EXPECT_DOUBLE_EQ(l0["mae"].get<double>(), (0.75 + 0.5) / 3.0);
    EXPECT_DOUBLE_EQ(l0["p99"].get<double>(), 0.75);
    EXPECT_DOUBLE_EQ(l0["fractionOver0_1"].get<double>(), 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(l0["acneFraction"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(l0["acneMeanDarkening"].get<double>(), 0.75 / 2.0);
    EXPECT_EQ(l0["counts"]["receivers"], 3);
    EXPECT_EQ(l0["counts"]["lit"], 2);

    const nlohmann::json& l1 = j["lights"][1];
    EXPECT_EQ(l1["index"], 1);
    EXPECT_DOUBLE_EQ(l1["leakFraction"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(l1["leakMeanLightening"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(l1["penumbraRmse"].get<double>(), 0.0);
    EXPECT_EQ(l1["counts"]["penumbra"], 1);

    const nlohmann::json& all = j["allLights"];
    EXPECT_DOUBLE_EQ(all["rmse"].get<double>(), std::sqrt((0.5625 + 0.25 + 1.0) / 6.0));
    EXPECT_DOUBLE_EQ(all["leakFraction"].get<double>(), 1.0 / 3.0);
    EXPECT_EQ(all["counts"]["valid"], 6);
    EXPECT_EQ(all["counts"]["nonFinite"], 0);
    EXPECT_EQ(j["size"], nlohmann::json::array({2, 2}));

    EXPECT_TRUE(fs::is_regular_file(heatDir + "/error_0.png"));
    EXPECT_TRUE(fs::is_regular_file(heatDir + "/error_1.png"));
    EXPECT_FALSE(fs::exists(estimate_ + "/error_0.png"));
}

TEST_F(ShadowCompareCli, HeatMapsGoToTheEstimateFolderByDefault) {
    writeTwoLights();
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::is_regular_file(estimate_ + "/error_0.png"));
    EXPECT_TRUE(fs::is_regular_file(estimate_ + "/error_1.png"));
}

TEST_F(ShadowCompareCli, MissingFolderExitsTwoWithOneMessage) {
    writeTwoLights();
    const std::string nowhere = (dir_ / "nowhere").string();
    const CliRun r = run(shellQuoted(nowhere) + " " + shellQuoted(truth_));
    EXPECT_EQ(r.exitCode, kExitBadInput);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(nowhere), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(ShadowCompareCli, MissingEstimateLightExitsTwo) {
    writeTwoLights();
    fs::remove(estimate_ + "/visibility_1.exr");
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    EXPECT_EQ(r.exitCode, kExitBadInput);
    EXPECT_NE(r.err.find("visibility_1.exr"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(estimate_ + "/error_0.png"));
}

TEST_F(ShadowCompareCli, NaNEstimateScoresTheWorstErrorNotZero) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    writeVisibility(truth_, 0, imageOf(2, 2, {1, 0, 1, 0}));
    writeVisibility(estimate_, 0, imageOf(2, 2, {nan, nan, nan, nan}));
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.out;
    EXPECT_DOUBLE_EQ(j["allLights"]["rmse"].get<double>(), 1.0);
    EXPECT_EQ(j["allLights"]["counts"]["nonFinite"], 4);
    EXPECT_EQ(j["lights"][0]["counts"]["nonFinite"], 4);
}

TEST_F(ShadowCompareCli, NaNTruthExitsTwoNamingTheFileAndPixel) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    writeVisibility(truth_, 0, imageOf(2, 2, {1, 0, nan, 0}));
    writeVisibility(estimate_, 0, imageOf(2, 2, {1, 0, 1, 0}));
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    EXPECT_EQ(r.exitCode, kExitBadInput) << r.out;
    EXPECT_NE(r.err.find(truth_ + "/visibility_0.exr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(0, 1)"), std::string::npos) << r.err;
}

TEST_F(ShadowCompareCli, ComparesExactlyTheLightsTheRunRecordsName) {
    writeTwoLights();
    // An earlier run left a third light in both folders; the records of the last runs name two.
    writeVisibility(truth_, 2, imageOf(2, 2, {0, 0, 0, 0}));
    writeVisibility(estimate_, 2, imageOf(2, 2, {1, 1, 1, 1}));
    const double start = now() - 1.0;
    writeRecord(truth_ + "/reference.json", {0, 1}, start);
    writeRecord(estimate_ + "/stats.json", {0, 1}, start);
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.out;
    ASSERT_EQ(j["lights"].size(), 2u);
    EXPECT_EQ(j["lights"][1]["index"], 1);
    EXPECT_EQ(j["allLights"]["counts"]["valid"], 6);
}

TEST_F(ShadowCompareCli, NamedLightMissingExitsTwo) {
    writeTwoLights();
    writeRecord(truth_ + "/reference.json", {0, 1, 2}, now() - 1.0);
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    EXPECT_EQ(r.exitCode, kExitBadInput) << r.out;
    EXPECT_NE(r.err.find(truth_ + "/visibility_2.exr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;

    // The estimate's record must name every light of the truth's.
    writeVisibility(truth_, 2, imageOf(2, 2, {0, 0, 0, 0}));
    writeVisibility(estimate_, 2, imageOf(2, 2, {0, 0, 0, 0}));
    writeRecord(estimate_ + "/stats.json", {0, 1}, now() - 1.0);
    const CliRun named = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    EXPECT_EQ(named.exitCode, kExitBadInput) << named.out;
    EXPECT_NE(named.err.find("stats.json"), std::string::npos) << named.err;
    EXPECT_NE(named.err.find("light 2"), std::string::npos) << named.err;
}

TEST_F(ShadowCompareCli, FileOfAnEarlierRunExitsTwo) {
    writeTwoLights();
    writeRecord(truth_ + "/reference.json", {0, 1}, now() - 1.0);
    writeRecord(estimate_ + "/stats.json", {0, 1}, now() - 1.0);
    age(estimate_ + "/visibility_1.exr", 3600);  // named by the run, but written an hour before it
    const CliRun r = run(shellQuoted(estimate_) + " " + shellQuoted(truth_));
    EXPECT_EQ(r.exitCode, kExitBadInput) << r.out;
    EXPECT_NE(r.err.find(estimate_ + "/visibility_1.exr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("earlier run"), std::string::npos) << r.err;
}

TEST_F(ShadowCompareCli, HelpNamesTheArgumentOrder) {
    const CliRun r = run("--help");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("ESTIMATE_DIR"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("TRUTH_DIR"), std::string::npos) << r.out;
    const CliRun none = run("");
    EXPECT_EQ(none.exitCode, kExitBadInput);
}

}  // namespace
}  // namespace shadow
