// Helpers every test binary may use: a fresh temporary folder per test, running one of the
// project's programs with its output captured, and finding warnings by code and element.
// Header-only: test sources are globbed per folder.
#pragma once

#include <shadow/components.h>
#include <shadow/image_io.h>
#include <shadow/warnings.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace shadow {

/// How GoogleTest prints a `Warning` in a failure: code, element and message.
inline void PrintTo(const Warning& w, std::ostream* os) {
    *os << warningCodeName(w.code) << " [" << w.element << "] " << w.message;
}

}  // namespace shadow

namespace shadow::test {

/// The techniques of `techniques` this build offers, in order: pcss-textbook only in builds with
/// SHADOW_BASELINE_TECHNIQUES (elsewhere a light asking for it gets PCSS and a warning).
template <typename Range = std::initializer_list<ShadowTechnique>>
std::vector<ShadowTechnique> offered(const Range& techniques) {
    std::vector<ShadowTechnique> out;
    for (ShadowTechnique t : techniques) {
        if (techniqueAvailable(t)) out.push_back(t);
    }
    return out;
}

/// How many of `warnings` have `code` and name `element`.
[[nodiscard]] inline long countWarnings(const std::vector<Warning>& warnings, WarningCode code,
                                        std::string_view element) {
    return std::count_if(warnings.begin(), warnings.end(),
                         [&](const Warning& w) { return w.code == code && w.element == element; });
}

/// Whether some warning has `code` and names `element`.
[[nodiscard]] inline bool hasWarning(const std::vector<Warning>& warnings, WarningCode code, std::string_view element) {
    return countWarnings(warnings, code, element) > 0;
}

/// Every warning, one per line, for a failure message.
[[nodiscard]] inline std::string describe(const std::vector<Warning>& warnings) {
    std::ostringstream out;
    for (const Warning& w : warnings) {
        PrintTo(w, &out);
        out << "\n";
    }
    return out.str();
}

/// A fresh folder under $SHADOW_TEST_TMP (or the system temp folder), removed afterwards.
class TempDir {
public:
    /// `prefix` names the folder after the test file, for a reader of a leftover folder.
    explicit TempDir(const std::string& prefix = "shadow_test") {
        static std::atomic<int> counter{0};
        namespace fs = std::filesystem;
        const char* root = std::getenv("SHADOW_TEST_TMP");
        const fs::path base = root != nullptr && *root != '\0' ? fs::path(root) : fs::temp_directory_path();
        path_ = base / (prefix + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }
    [[nodiscard]] std::string operator/(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

/// The exit code of the project's command-line programs on bad input (arguments, files).
constexpr int kExitBadInput = 2;

/// The whole content of the file at `path`; throws std::filesystem::filesystem_error when there is
/// none (the test fails naming it).
inline std::string readBytes(const std::filesystem::path& path) {
    std::string bytes(std::filesystem::file_size(path), '\0');
    std::ifstream(path, std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return bytes;
}

/// A one-channel `width` x `height` image holding `values`, row by row.
inline ImageF imageOf(int width, int height, const std::vector<float>& values) {
    ImageF image = makeImage(width, height, 1);
    image.pixels = values;
    return image;
}

/// `s` quoted for the POSIX shell.
inline std::string shellQuoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

#ifdef SHADOW_SOURCE_DIR
/// `relative` (e.g. "README.md") under the source tree, which the test programs that read it
/// name in SHADOW_SOURCE_DIR. Appended, not `std::string(SHADOW_SOURCE_DIR) + "/..."`: at -O1,
/// file by file, GCC 12 reports that as a copy out of bounds (-Warray-bounds, a false positive).
inline std::string sourcePath(const char* relative) {
    std::string path = SHADOW_SOURCE_DIR;
    path.append("/").append(relative);
    return path;
}
#endif

/// The outcome of running a program.
struct ProcessRun {
    int exitCode = -1;   ///< -1 when the process did not exit normally (a crash)
    std::string output;  ///< stdout and stderr
};

/// Runs `program` (a path, quoted here) with `args` (already quoted where needed) through the
/// shell, capturing stdout and stderr in `logPath`.
inline ProcessRun runProgram(const std::string& program, const std::string& args, const std::string& logPath) {
    const std::string command = shellQuoted(program) + " " + args + " > " + shellQuoted(logPath) + " 2>&1";
    const int raw = std::system(command.c_str());
    ProcessRun run;
    run.exitCode = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream in(logPath);
    std::ostringstream text;
    text << in.rdbuf();
    run.output = text.str();
    return run;
}

}  // namespace shadow::test
