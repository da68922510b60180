// The technique table (shadow/techniques.h) and what is made from it or checked against it: the
// installed shadow_techniques.glsl, each technique's GLSL file and functions, shared GLSL that
// names no technique, the README's table, and a game's loader that expands each file once.
#include "gl/technique_glsl.h"

#include <shadow/components.h>
#include <shadow/shadow_shaders.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "gl/shader_sources.h"
#include "gl/gl_test_support.h"
#include "render/render_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<ShadowTechnique> allTechniques() {
    std::vector<ShadowTechnique> all;
    for (int t = 0; t < kShadowTechniqueCount; ++t) all.push_back(static_cast<ShadowTechnique>(t));
    return all;
}

// The checked-in copy is what the table writes; SHADOW_WRITE_TECHNIQUES_GLSL=1 rewrites it.
TEST(TechniqueGlsl, InstalledFileIsTheOneTheTableWrites) {
    const std::string path = test::sourcePath("shaders/shadow_techniques.glsl");
    const std::string expected = gpu::installedTechniquesGlsl();
    if (const char* write = std::getenv("SHADOW_WRITE_TECHNIQUES_GLSL");
        write != nullptr && std::string(write) == "1") {
        std::ofstream(path) << expected;
    }
    EXPECT_EQ(readFile(path), expected) << "shaders/shadow_techniques.glsl is out of step with the technique table; "
                                           "rerun with SHADOW_WRITE_TECHNIQUES_GLSL=1";
}

TEST(TechniqueGlsl, EveryTechniqueHasItsFileWithPolicyAndVisibility) {
    for (ShadowTechnique t : allTechniques()) {
        if (t == ShadowTechnique::None) {
            EXPECT_STREQ(gpu::techniqueGlslFile(t), "");
            continue;
        }
        const char* text = gpu::findShaderSource(gpu::techniqueGlslFile(t));
        ASSERT_NE(text, nullptr) << techniqueName(t) << ": " << gpu::techniqueGlslFile(t);
        const std::string function = gpu::slotVisibilityFunction(t);  // sg_<stem>LightVisibility
        const std::string stem = function.substr(0, function.size() - std::string("LightVisibility").size());
        EXPECT_NE(std::string(text).find("sg_ReceiverPolicy " + stem + "Policy()"), std::string::npos) << stem;
        EXPECT_NE(std::string(text).find("float " + stem + "Visibility(int slot, sg_GpuLight L, sg_Receiver r)"),
                  std::string::npos)
            << stem;
        // A technique's file includes shared pieces only, never another technique's file.
        for (ShadowTechnique other : allTechniques()) {
            if (other == t || other == ShadowTechnique::None) continue;
            EXPECT_EQ(std::string(text).find(std::string("#include \"") + gpu::techniqueGlslFile(other)),
                      std::string::npos)
                << techniqueName(t) << " includes " << gpu::techniqueGlslFile(other);
        }
    }
}

// Shared code branches on no particular technique: what a technique needs of the receiver it
// says through its policy.
TEST(TechniqueGlsl, SharedCodeNamesNoTechnique) {
    const std::regex named(R"(SG_TECH_(?!NONE\b)[A-Z_]+)");
    int checked = 0;
    for (const gpu::ShaderSource& file : gpu::embeddedShaderSources()) {
        const std::string name = file.name;
        bool technique = false;
        for (ShadowTechnique t : allTechniques()) technique = technique || name == gpu::techniqueGlslFile(t);
        if (technique || name == "shadow_techniques.glsl" || name == "shared_constants.h") continue;
        if (name.rfind("shadow_", 0) != 0) continue;
        EXPECT_FALSE(std::regex_search(std::string(file.text), named)) << name << " names a technique";
        ++checked;
    }
    EXPECT_GE(checked, 10);
}

// The README's table lists every technique of this build with the table's own description.
TEST(TechniqueGlsl, ReadmeTableIsTheTechniqueTable) {
    const std::string readme = readFile(test::sourcePath("README.md"));
    const std::size_t begin = readme.find("<!-- techniques:begin -->");
    const std::size_t end = readme.find("<!-- techniques:end -->");
    ASSERT_NE(begin, std::string::npos);
    ASSERT_NE(end, std::string::npos);
    std::string expected = "| technique | what it does |\n|---|---|\n";
    for (ShadowTechnique t : allTechniques()) {
        expected += std::string("| `") + techniqueName(t) + "` | " + techniqueDescription(t) + " |\n";
    }
    const std::size_t tableStart = readme.find('\n', begin) + 1;
    EXPECT_EQ(readme.substr(tableStart, end - tableStart), expected);
}

TEST(TechniqueGlsl, NamesAndDefinesFollowTheTable) {
    std::vector<std::string> defines;
    gpu::appendTechniqueDefines(~0u, defines);
    EXPECT_EQ(defines.size(), static_cast<std::size_t>(kShadowTechniqueCount - 1));  // None has none
    for (ShadowTechnique t : allTechniques()) {
        EXPECT_EQ(techniqueFromName(techniqueName(t)), techniqueAvailable(t) ? std::optional(t) : std::nullopt);
        EXPECT_EQ(techniqueFromAnyName(techniqueName(t)), t) << "a scene names a technique of any build";
        if (techniqueAvailable(t)) {
            EXPECT_NE(techniqueNameList().find(techniqueName(t)), std::string::npos);
        }
    }
    // A game's techniques are the public ones: the baseline is never among them.
    EXPECT_EQ(kAllShadowTechniques & techniqueBit(ShadowTechnique::PcssTextbook), 0u);
    EXPECT_EQ(shadowShaderSource({}, ~0u).find("sg_pcssTextbookVisibility"), std::string::npos);
    EXPECT_EQ(techniqueFromName("no-such-technique"), std::nullopt);
    EXPECT_EQ(techniqueFromAnyName("no-such-technique"), std::nullopt);
}

/// Expands `#include`s from the installed shader folder as a simple game loader does: each file
/// once, by name, with no notion of the preprocessor's conditions.
// NOLINTNEXTLINE(misc-no-recursion)
std::string expandOnce(const std::string& file, std::vector<std::string>& seen) {
    if (std::find(seen.begin(), seen.end(), file) != seen.end()) return "";
    seen.push_back(file);
    const char* text = gpu::findShaderSource(file);
    if (text == nullptr) return "#error missing " + file + "\n";
    std::istringstream lines(text);
    std::string line, out;
    static const std::regex include(R"re(^\s*#\s*include\s*"([^"]+)"\s*$)re");
    std::smatch m;
    while (std::getline(lines, line)) {
        out += std::regex_match(line, m, include) ? expandOnce(m[1].str(), seen) : line + "\n";
    }
    return out;
}

// A game that expands the installed files itself, each once, gets a shader that compiles for any
// one technique it enables: the shared files come before the conditional ones.
TEST(TechniqueGlsl, InstalledFilesCompileThroughALoaderThatIncludesEachFileOnce) {
    test::glContext();
    for (ShadowTechnique t : allTechniques()) {
        if (t == ShadowTechnique::None || (kAllShadowTechniques & techniqueBit(t)) == 0) continue;
        std::vector<std::string> defines;
        gpu::appendTechniqueDefines(techniqueBit(t), defines);
        std::string text = "#version 450 core\n";
        for (const std::string& d : defines) text += "#define " + d + "\n";
        std::vector<std::string> seen;
        text += expandOnce("shadow.glsl", seen);
        text += R"(
in vec3 vCsPosition;
in vec3 vNormal;
layout(location = 0) out vec4 outColor;
void main() {
    sg_Surface s = sg_surface(vCsPosition, vNormal);
    outColor = vec4(sg_lightVisibility(0, vCsPosition, s, 1.0));
}
)";
        const test::CompiledShader compiled = test::compileShader(GL_FRAGMENT_SHADER, text);
        EXPECT_TRUE(compiled.ok()) << techniqueName(t) << ": " << compiled.log;
        gl.DeleteShader(compiled.shader);
    }
}

// What a game's shader gets is the code of the techniques it asks for: a few tens of kilobytes
// for one, not every technique's. (Every technique's text holds the screen-space stage's feature
// reports too, 2 kB under #ifdef SG_STAGE_FEATURES, which a game's shader compiles out.)
TEST(TechniqueGlsl, GameShaderTextGrowsWithTheTechniquesAskedFor) {
    const std::size_t hard = shadowShaderSource({}, techniqueBit(ShadowTechnique::Hard)).size();
    const std::size_t all = shadowShaderSource({}, kAllShadowTechniques).size();
    std::printf("[ glsl     ] game shader text: hard %zu bytes, every technique %zu bytes\n", hard, all);
    for (ShadowTechnique t : allTechniques()) {
        if ((kAllShadowTechniques & techniqueBit(t)) == 0) continue;
        const std::string text = shadowShaderSource({}, techniqueBit(t));
        EXPECT_LT(text.size(), all) << techniqueName(t);
        EXPECT_NE(text.find(gpu::slotVisibilityFunction(t)), std::string::npos) << techniqueName(t);
    }
    EXPECT_LT(all, 68u * 1024u);
}

}  // namespace
}  // namespace shadow
