// What the sample CLIs share: the exit codes of the CLI contract (docs/output_contract.md), the
// one-line failure message and the heap setting of the programs that render (their command
// lines: command_line.h). Header-only, so that shadow_compare, which links no sample library,
// shares it too.
#pragma once

#include <cstdlib>  // defines __GLIBC__ with glibc

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <iostream>
#include <string>

namespace shadow::samples {

/// Keeps up to 512 MiB of freed heap in the process instead of handing it back to the system
/// (glibc's trim threshold). llvmpipe allocates a draw's vertex buffers anew for every draw; in a
/// frame whose only pass is the lit one (no shadowed light), glibc gave them back at the end of
/// each frame and every page faulted in again on the next: about 20 ms a frame for the
/// 70 000-triangle bunny, which made an unshadowed light dearer than a shadowed one. A game that
/// embeds the module on llvmpipe sets its own allocator; README.md says so. No effect without
/// glibc.
inline void keepFreedHeap() {
#ifdef __GLIBC__
    (void)mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

inline constexpr int kExitFailure = 1;   ///< the program failed (OpenGL, the disk, ...)
inline constexpr int kExitBadInput = 2;  ///< bad arguments, files or settings: nothing written

/// Prints `program: message` on stderr and returns `code`.
inline int failAs(const char* program, int code, const std::string& message) {
    std::cerr << program << ": " << message << "\n";
    return code;
}

}  // namespace shadow::samples
