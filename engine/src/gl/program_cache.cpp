#include "gl/program_cache.h"

#include <shadow/program_cache.h>

#include "gl/gl_api.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <system_error>
#include <unistd.h>

namespace shadow {
namespace {

struct CacheState {
    std::mutex mutex;
    std::filesystem::path directory;  ///< empty: off
    ProgramCacheStats stats;
};

CacheState& state() {
    static CacheState s;
    return s;
}

/// FNV-1a, 64 bits, continued from `h`.
std::uint64_t fnv1a(std::string_view text, std::uint64_t h) {
    for (const char c : text) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ull;
    }
    return h;
}

constexpr std::array<char, 4> kMagic{'S', 'G', 'P', 'B'};
/// A binary larger than this is not a program of this module: refused without reading it.
constexpr std::uint64_t kMaxBinaryBytes = std::uint64_t{64} << 20;

struct Header {
    std::array<char, 4> magic{};
    std::uint32_t format = 0;
    std::uint64_t bytes = 0;
    std::uint64_t check = 0;  ///< a second hash of the key, against collisions and mixed-up files
};

std::string driverString(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(gl.GetString(name));
    return s != nullptr ? s : "";
}

}  // namespace

Status setProgramBinaryCache(const std::string& directory) {
    CacheState& s = state();
    const std::lock_guard lock(s.mutex);
    s.directory.clear();
    s.stats = {};
    if (directory.empty()) return Ok{};
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (!std::filesystem::is_directory(directory, error)) {
        return Error{ErrorCode::FileUnwritable,
                     "program binary cache: " + directory + " is not a folder that can be created"};
    }
    s.directory = directory;
    return Ok{};
}

ProgramCacheStats programCacheStats() {
    CacheState& s = state();
    const std::lock_guard lock(s.mutex);
    return s.stats;
}

namespace gpu {

std::string programKey(const std::string& label, const std::vector<const std::string*>& stages) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (GLenum name : {GL_VENDOR, GL_RENDERER, GL_VERSION}) h = fnv1a(driverString(name) + '\n', h);
    h = fnv1a(label + '\n', h);
    for (const std::string* stage : stages) h = fnv1a(*stage + '\n', fnv1a(std::to_string(stage->size()), h));
    std::array<char, 17> hex{};
    std::snprintf(hex.data(), hex.size(), "%016llx", static_cast<unsigned long long>(h));
    return hex.data();
}

namespace {

std::filesystem::path cacheDirectory() {
    CacheState& s = state();
    const std::lock_guard lock(s.mutex);
    return s.directory;
}

void count(int ProgramCacheStats::*counter) {
    CacheState& s = state();
    const std::lock_guard lock(s.mutex);
    ++(s.stats.*counter);
}

std::uint64_t checkOf(const std::string& key) { return fnv1a(key, 0x84222325cbf29ce4ull); }

}  // namespace

std::optional<Program> loadCachedProgram(const std::string& key) {
    const std::filesystem::path dir = cacheDirectory();
    if (dir.empty()) return std::nullopt;
    const std::filesystem::path path = dir / (key + ".glbin");
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    Header header;
    if (!in.read(reinterpret_cast<char*>(&header), sizeof header) || header.magic != kMagic ||
        header.check != checkOf(key) || header.bytes == 0 || header.bytes > kMaxBinaryBytes) {
        count(&ProgramCacheStats::rejected);
        return std::nullopt;
    }
    std::vector<char> binary(header.bytes);
    if (!in.read(binary.data(), static_cast<std::streamsize>(binary.size()))) {
        count(&ProgramCacheStats::rejected);
        return std::nullopt;
    }
    Program program(gl.CreateProgram());
    gl.ProgramBinary(program.get(), header.format, binary.data(), static_cast<GLsizei>(binary.size()));
    GLint linked = GL_FALSE;
    gl.GetProgramiv(program.get(), GL_LINK_STATUS, &linked);
    // A refused binary (a driver update changed its format) sets an error on some drivers.
    while (gl.GetError() != GL_NO_ERROR) {}
    if (linked != GL_TRUE) {
        count(&ProgramCacheStats::rejected);
        return std::nullopt;
    }
    count(&ProgramCacheStats::loaded);
    return program;
}

void markRetrievable(const Program& program) {
    if (!cacheDirectory().empty()) gl.ProgramParameteri(program.get(), GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
}

void storeCachedProgram(const std::string& key, const Program& program) {
    const std::filesystem::path dir = cacheDirectory();
    if (dir.empty()) return;
    GLint length = 0;
    gl.GetProgramiv(program.get(), GL_PROGRAM_BINARY_LENGTH, &length);
    if (length <= 0) return;
    std::vector<char> binary(static_cast<std::size_t>(length));
    GLenum format = 0;
    GLsizei written = 0;
    gl.GetProgramBinary(program.get(), length, &written, &format, binary.data());
    if (written <= 0) return;
    Header header;
    header.magic = kMagic;
    header.format = format;
    header.bytes = static_cast<std::uint64_t>(written);
    header.check = checkOf(key);
    const std::filesystem::path path = dir / (key + ".glbin");
    const std::filesystem::path temporary = dir / (key + ".tmp" + std::to_string(::getpid()));
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(&header), sizeof header);
        out.write(binary.data(), written);
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            return;
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        return;
    }
    count(&ProgramCacheStats::stored);
}

}  // namespace gpu
}  // namespace shadow
