// Compiling a GLSL text in the tests' context: the GL tests that check what a game's shader would
// compile (the technique files, the header's example, the host shader of the contract).
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <string>

#include "gl/gl_api.h"

namespace shadow::test {

/// A compiled shader object (the caller deletes it) and its info log, empty when it compiled.
struct CompiledShader {
    GLuint shader = 0;
    std::string log;
    [[nodiscard]] bool ok() const { return log.empty(); }
};

/// Compiles `source` as a shader of `stage` in the current context.
inline CompiledShader compileShader(GLenum stage, const std::string& source) {
    CompiledShader out;
    out.shader = gl.CreateShader(stage);
    const char* text = source.c_str();
    gl.ShaderSource(out.shader, 1, &text, nullptr);
    gl.CompileShader(out.shader);
    GLint ok = GL_FALSE;
    gl.GetShaderiv(out.shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        std::string log(8192, '\0');
        gl.GetShaderInfoLog(out.shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
        out.log = log.c_str();
        if (out.log.empty()) out.log = "(no info log)";
    }
    return out;
}

}  // namespace shadow::test
