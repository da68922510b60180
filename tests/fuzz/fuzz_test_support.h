// What the GoogleTests replaying the fuzz targets' inputs share: the input files of a folder and
// their bytes.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

namespace shadow::fuzz_test {

/// The input files of `dir` (not hidden, not README.md) in name order; none when it is missing
/// (the callers fail on an empty list).
inline std::vector<std::filesystem::path> inputsIn(const std::filesystem::path& dir) {
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (e.is_regular_file() && name.front() != '.' && name != "README.md") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

/// The bytes of the file at `path`.
inline std::string bytesOf(const std::filesystem::path& path) {
    std::string bytes(std::filesystem::file_size(path), '\0');
    std::ifstream(path, std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return bytes;
}

}  // namespace shadow::fuzz_test
