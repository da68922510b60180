// Drift: the GLSL a public header shows a game compiles. The example at the top of
// engine/include/shadow/shadow_shaders.h (its indented `//     ` lines, less the placeholders) is
// read from the header itself and compiled after `shadowShaderSource()`'s text, as a game's
// fragment shader would hold it; so is the specialised call `ShadowShaderInputs`' comment writes,
// read from the header as well.
#include <gtest/gtest.h>
#include <shadow/shadow_shaders.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "gl/gl_test_support.h"
#include "render/render_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

/// The indented code lines (`//     `) of the first comment block of `path`, without the
/// placeholder lines (`<...>`, `...`).
std::vector<std::string> headerExample(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::vector<std::string> code;
    while (std::getline(in, line)) {
        if (line.rfind("//", 0) != 0) break;  // the first comment block only
        if (line.rfind("//     ", 0) != 0) continue;
        const std::string text = line.substr(7);
        if (text.find('<') != std::string::npos || text.rfind("...", 0) == 0) continue;
        code.push_back(text);
    }
    return code;
}

/// The code between the backquotes of `path`'s doc comment that start with `opening` (a call
/// written across comment lines: their `///` and the indents dropped).
std::string backquotedCall(const std::string& path, const std::string& opening) {
    std::ifstream in(path);
    std::ostringstream text;
    std::string line;
    while (std::getline(in, line)) {
        const std::size_t slashes = line.find("///");
        if (slashes != std::string::npos) text << line.substr(slashes + 3) << ' ';
    }
    const std::string all = text.str();
    const std::size_t start = all.find("`" + opening);
    if (start == std::string::npos) return {};
    const std::size_t end = all.find('`', start + 1);
    std::string call = all.substr(start + 1, end - start - 1);
    std::string squeezed;  // runs of blanks (the comment's line breaks) as one
    for (char c : call) {
        if (c == ' ' && !squeezed.empty() && squeezed.back() == ' ') continue;
        squeezed += c;
    }
    return squeezed;
}

TEST(HeaderSnippets, TheShaderContractsExampleCompilesAsWritten) {
    test::glContext();
    const std::vector<std::string> example = headerExample(test::sourcePath("engine/include/shadow/shadow_shaders.h"));
    ASSERT_GE(example.size(), 2u) << "the header's example was not found";
    std::ostringstream body;
    for (const std::string& line : example) body << "    " << line << "\n";
    const std::string source = "#version 450 core\n" + shadowShaderSource() + R"(
#line 1 9999
in vec3 csPosition;
in vec3 wsNormal;
in float viewDistance;
uniform int slot;
layout(location = 0) out vec4 outColor;
void main() {
)" + body.str() + R"(    outColor = vec4(v);
}
)";
    const test::CompiledShader compiled = test::compileShader(GL_FRAGMENT_SHADER, source);
    EXPECT_TRUE(compiled.ok()) << compiled.log << "shadow_shaders.h's example:\n" << body.str();
    gl.DeleteShader(compiled.shader);
}

TEST(HeaderSnippets, TheSpecialisedCallOfTheShaderInputsCompiles) {
    test::glContext();
    const std::string call =
        backquotedCall(test::sourcePath("engine/include/shadow/shadow_shaders.h"), "sg_shadowVisibility(");
    ASSERT_FALSE(call.empty()) << "ShadowShaderInputs' specialised call was not found";
    // Its names as a game's shader would have them: the surface, and the slot's configuration as
    // compile-time constants.
    const std::string source = "#version 450 core\n" + shadowShaderSource() + R"(
in vec3 csPosition;
in vec3 wsNormal;
in float viewDistance;
layout(location = 0) out vec4 outColor;
void main() {
    sg_Surface s = sg_surface(csPosition, wsNormal);
    const int slot = 0, type = SG_LIGHT_SPOT, technique = SG_TECH_PCSS, kernel = SG_KERNEL_VOGEL;
    float v = )" + call + R"(;
    outColor = vec4(v);
}
)";
    const test::CompiledShader compiled = test::compileShader(GL_FRAGMENT_SHADER, source);
    EXPECT_TRUE(compiled.ok()) << compiled.log << "the call: " << call;
    gl.DeleteShader(compiled.shader);
}

}  // namespace
}  // namespace shadow
