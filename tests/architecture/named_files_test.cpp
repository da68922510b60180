// Drift: every file of the repository that a comment, a document or a test names exists. A
// renamed or removed file leaves references behind (four files cited a shader split long ago);
// this reads every text file of the source tree and checks each repository path it names, and
// each shader file named by its bare name, against the tree. A file that names a missing one is
// named with its line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = fs::path(SHADOW_SOURCE_DIR);

/// Folders of the source tree whose text files are read (build and output folders are not).
const char* const kFolders[] = {"engine", "shaders", "samples", "tests", "benchmarks", "docs", "cmake", ".ci"};

bool isText(const fs::path& p) {
    static const std::set<std::string> kExtensions = {".cpp", ".h",   ".glsl",  ".md", ".sh",
                                                      ".py",  ".txt", ".cmake", ".in"};
    return kExtensions.count(p.extension().string()) > 0 || p.filename() == "CMakeLists.txt" ||
           p.parent_path().filename() == ".ci";
}

std::vector<fs::path> textFiles() {
    std::vector<fs::path> files = {kRoot / "README.md", kRoot / "BENCHMARKS.md", kRoot / "CMakeLists.txt"};
    for (const char* folder : kFolders) {
        if (!fs::exists(kRoot / folder)) continue;
        for (const auto& entry : fs::recursive_directory_iterator(kRoot / folder)) {
            const std::string rel = fs::relative(entry.path(), kRoot).generic_string();
            // The fuzzers' corpora are inputs, not prose; results are written by the benchmarks.
            if (rel.rfind("tests/fuzz/corpus", 0) == 0 || rel.rfind("tests/fuzz/regressions", 0) == 0 ||
                rel.rfind("benchmarks/results/tmp", 0) == 0) {
                continue;
            }
            if (entry.is_regular_file() && isText(entry.path())) files.push_back(entry.path());
        }
    }
    return files;
}

struct Missing {
    std::string where;  ///< file:line
    std::string named;
};

TEST(NamedFiles, EveryRepositoryPathAFileNamesExists) {
    // A path from a top-level folder of the repository, ending in a file name with an extension
    // (a `*` or a placeholder such as <i> or NAME makes it a pattern, not a file), and a shader
    // of the project's own (shadow_*.glsl) named without its folder. Folders the programs write
    // (a results/tmp/) are not the source tree's.
    static const std::regex kPath(
        R"((?:^|[\s`'"(\[])((?:engine|shaders|samples|tests|benchmarks|docs|cmake)/[A-Za-z0-9_./-]+\.(?:cpp|h|glsl|md|sh|py|gltf|json|txt|cmake)(?:\.in)?))");
    static const std::regex kShader(R"((?:^|[^A-Za-z0-9_./-])(shadow_[a-z0-9_]*\.glsl)\b)");
    std::vector<Missing> missing;
    int checked = 0;
    for (const fs::path& file : textFiles()) {
        std::ifstream in(file);
        std::string text;
        const std::string rel = fs::relative(file, kRoot).generic_string();
        for (int line = 1; std::getline(in, text); ++line) {
            for (auto it = std::sregex_iterator(text.begin(), text.end(), kPath); it != std::sregex_iterator(); ++it) {
                const std::string named = (*it)[1].str();
                if (named.find("/tmp/") != std::string::npos) continue;
                ++checked;
                if (!fs::exists(kRoot / named)) missing.push_back({rel + ":" + std::to_string(line), named});
            }
            for (auto it = std::sregex_iterator(text.begin(), text.end(), kShader); it != std::sregex_iterator();
                 ++it) {
                const std::string named = (*it)[1].str();
                ++checked;
                if (!fs::exists(kRoot / "shaders" / named))
                    missing.push_back({rel + ":" + std::to_string(line), named});
            }
        }
    }
    EXPECT_GT(checked, 200) << "the scan found almost no names: the patterns are broken";
    for (const Missing& m : missing) ADD_FAILURE() << m.where << " names " << m.named << ", which does not exist";
}

}  // namespace
