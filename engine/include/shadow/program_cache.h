// A cache of the module's linked shader programs on disk (GL_ARB_get_program_binary, core since
// OpenGL 4.1), for a game that wants its second start to skip compiling and linking them.
//
// Off by default. When a folder is set, every program the module builds (lit variants, the
// shadow mask, the depth pass, the filter chains' compute passes) is first looked up there by a
// key of its full source text, its label and the driver (GL_VENDOR, GL_RENDERER, GL_VERSION):
// a changed shader, a new engine or another driver never loads a stale binary. A binary the
// driver refuses (its format changed with an update) is rebuilt and written again. Files are
// written whole (to a temporary name, then renamed), so a crash never leaves half a binary.
//
// What it saves depends on the driver: a GPU driver's binary is machine code; Mesa's llvmpipe
// keeps its optimised intermediate code in the binary and still generates machine code at a
// program's first draw (BENCHMARKS.md, compile time, measures both parts).
#pragma once

#include <shadow/result.h>

#include <string>

namespace shadow {

/// Sets the folder of the program binary cache (created if missing); "" turns the cache off.
/// Fails, leaving the cache off, when the folder cannot be created or is not a folder.
/// Process-wide: it applies to every program built afterwards, in any context.
[[nodiscard]] Status setProgramBinaryCache(const std::string& directory);

/// What the cache did since the process started (or since `setProgramBinaryCache`).
struct ProgramCacheStats {
    int loaded = 0;    ///< programs taken from the cache
    int stored = 0;    ///< programs built and written to it
    int rejected = 0;  ///< binaries the driver refused (rebuilt and written again)
};

/// The counters of the cache.
[[nodiscard]] ProgramCacheStats programCacheStats();

}  // namespace shadow
