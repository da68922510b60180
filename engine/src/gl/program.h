// Shader programs built from the embedded GLSL with `#define` variants.
//
// Sources may `#include "file"` other files of shaders/. The builder expands includes and
// emits `#line N F` directives, F indexing the file table, so that a compiler message such as
// `0:12(5): error` is reported as `shadow_receiver.glsl:12(5): error`.
#pragma once

#include "gl/objects.h"

#include <cstdint>
#include <string>
#include <vector>

namespace shadow::gpu {

/// What to build: a vertex and a fragment shader file of shaders/ and the defines of the variant.
struct ProgramDesc {
    std::string label;                 ///< object label, e.g. "Main/Lit[PCF,PCSS]"
    std::string vertexFile;            ///< e.g. "lit.vert.glsl"
    std::string fragmentFile;          ///< e.g. "lit.frag.glsl"
    std::vector<std::string> defines;  ///< "NAME" or "NAME VALUE"
    /// `techniqueBit`s of the techniques shadow_techniques.glsl compiles in, when a file includes it.
    unsigned techniques = 0;
};

/// Compiles and links; throws `GlError` naming the file and line of the first error.
Program buildProgram(const ProgramDesc& desc);
/// How many programs this process has built (compiled or loaded from the program cache): a pass
/// that builds its programs as it first needs them counts its frame's share into
/// `FrameStats::programsCompiled` as the difference across the frame.
[[nodiscard]] std::uint64_t programsBuilt();

/// Compiles and links the compute shader `file`; throws `GlError` like `buildProgram`.
Program buildComputeProgram(const std::string& label, const std::string& file, const std::vector<std::string>& defines);

/// One preprocessed shader stage: the text handed to GL and the file table for messages.
struct ExpandedSource {
    std::string text;
    std::vector<std::string> files;  ///< index = the file number of `#line`
};

/// Compiles and links two expanded stages (the first file of each names it in messages), labels
/// the program `label`; throws `GlError` naming the file and line of the first error.
Program linkProgram(const std::string& label, const ExpandedSource& vertex, const ExpandedSource& fragment);

/// Compiles and links one expanded compute stage (its first file names it in messages), labels
/// the program `label`; throws `GlError` naming the file and line of the first error.
Program linkComputeProgram(const std::string& label, const ExpandedSource& compute);

/// Expands `#include`s of `file` below a `#version` line and the defines, each file once (as if
/// every file had `#pragma once`); `#include "shadow_techniques.glsl"` expands to the dispatch
/// over `techniques` (gl/technique_glsl.h). Throws `GlError` for a missing file, an include
/// cycle or an `#include` under a condition other than its file's include guard.
ExpandedSource expandShader(const std::string& file, const std::vector<std::string>& defines, unsigned techniques = 0);

/// The same without the `#version` line, for a text that goes into another shader (the public
/// shadow GLSL): file number 0 is the host's own source, named `hostName` in the file table, and
/// the expanded files count from 1. Comment-only lines are left empty (the files in the
/// repository and the installed package have them; line numbers stay those of the files).
ExpandedSource expandShaderBody(const std::string& file, const std::vector<std::string>& defines,
                                const std::string& hostName, unsigned techniques = 0);

/// Rewrites `F:LINE(COL)` prefixes of a compiler log into `name:LINE(COL)`.
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files);

}  // namespace shadow::gpu
