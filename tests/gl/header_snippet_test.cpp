// Drift: the GLSL a public header shows a game compiles. The example at the top of
// engine/include/shadow/shadow_shaders.h (its indented `//     ` lines, less the placeholders) is
// read from the header itself and compiled after `shadowShaderSource()`'s text, as a game's
// fragment shader would hold it; so is the specialised call `ShadowShaderInputs` describes.
#include <gtest/gtest.h>
#include <shadow/shadow_shaders.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "render/render_test_support.h"

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

/// Compiles `source` as a fragment shader; the info log when it fails, empty when it compiles.
std::string compileFragment(const std::string& source) {
    const GLuint shader = gl.CreateShader(GL_FRAGMENT_SHADER);
    const char* text = source.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint ok = GL_FALSE;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    std::string log(8192, '\0');
    gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl.DeleteShader(shader);
    return ok == GL_TRUE ? std::string() : std::string(log.c_str());
}

TEST(HeaderSnippets, TheShaderContractsExampleCompilesAsWritten) {
    test::glContext();
    const std::vector<std::string> example =
        headerExample(std::string(SHADOW_SOURCE_DIR) + "/engine/include/shadow/shadow_shaders.h");
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
    EXPECT_EQ(compileFragment(source), "") << "shadow_shaders.h's example:\n" << body.str();
}

TEST(HeaderSnippets, TheSpecialisedCallOfTheShaderInputsCompiles) {
    test::glContext();
    const std::string source = "#version 450 core\n" + shadowShaderSource() + R"(
in vec3 csPosition;
in vec3 wsNormal;
in float viewDistance;
layout(location = 0) out vec4 outColor;
void main() {
    sg_Surface s = sg_surface(csPosition, wsNormal);
    const int slot = 0;
    float v = sg_shadowVisibility(slot, sg_slotLight(slot, SG_LIGHT_SPOT, SG_TECH_PCSS, SG_KERNEL_VOGEL), csPosition,
                                  s.normal, s.geoNormal, s.curvature, viewDistance);
    outColor = vec4(v);
}
)";
    EXPECT_EQ(compileFragment(source), "");
}

}  // namespace
}  // namespace shadow
