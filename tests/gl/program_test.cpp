// Shader programs (engine/src/gl/program.cpp): include expansion with #line mapping, compiler
// logs rewritten to file names, errors that name the file, and every variant the engine builds
// compiling on the test context.
#include "gl/program.h"
#include "gl/technique_glsl.h"
#include "render/lit_programs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "gl/shader_sources.h"
#include "render/render_test_support.h"

namespace shadow {
namespace {

std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) out.push_back(line);
    return out;
}

/// 1-based line of `source` file `file` that contains `needle`; 0 when none does.
int lineContaining(const std::string& file, const std::string& needle) {
    const char* text = gpu::findShaderSource(file);
    if (text == nullptr) return 0;
    const std::vector<std::string> lines = linesOf(text);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].find(needle) != std::string::npos) return static_cast<int>(i) + 1;
    }
    return 0;
}

TEST(Program, ExpandShaderPutsVersionAndDefinesFirst) {
    const gpu::ExpandedSource src = gpu::expandShader("lit.frag.glsl", {"SG_TECH_PCF_ENABLED", "SG_FOO 3"});
    const std::vector<std::string> lines = linesOf(src.text);
    ASSERT_GE(lines.size(), 4u);
    EXPECT_EQ(lines[0], "#version 450 core");
    EXPECT_EQ(lines[1], "#define SG_TECH_PCF_ENABLED");
    EXPECT_EQ(lines[2], "#define SG_FOO 3");
    EXPECT_EQ(lines[3], "#line 1 0");
    ASSERT_FALSE(src.files.empty());
    EXPECT_EQ(src.files[0], "lit.frag.glsl");
}

TEST(Program, ExpandShaderInlinesEveryInclude) {
    const gpu::ExpandedSource src =
        gpu::expandShader("lit.frag.glsl", {"SG_TECH_PCSS_ENABLED"}, techniqueBit(ShadowTechnique::Pcss));
    for (const std::string& line : linesOf(src.text)) {
        EXPECT_EQ(line.find("#include"), std::string::npos) << "left unexpanded: " << line;
    }
    for (const char* f :
         {"shadow_visibility.glsl", "shadow_receiver.glsl", "shadow_bindings.glsl", "shadow_kernels.glsl",
          "shadow_filter.glsl", "shadow_pcss.glsl", "shadow_types.glsl", "shared_constants.h", "gpu_structs.h",
          "shadow_common.glsl", "lighting.glsl", "shadow_techniques.glsl (generated)"}) {
        EXPECT_NE(std::find(src.files.begin(), src.files.end(), f), src.files.end()) << f << " not in the file table";
    }
    // The text of an included file is there, and only the techniques asked for.
    EXPECT_NE(src.text.find("float sg_shadowVisibility("), std::string::npos);
    EXPECT_NE(src.text.find("float sg_pcssVisibility("), std::string::npos);
    EXPECT_EQ(src.text.find("float sg_vssmVisibility("), std::string::npos);
    EXPECT_EQ(src.text.find("float sg_pcfVisibility("), std::string::npos);
    EXPECT_NE(src.text.find("#define SG_MAX_LIGHTS_PER_PASS 8"), std::string::npos);
}

// Each file is expanded once, wherever it is included from (as if every file had #pragma once):
// the text a game gets grows with the files it needs, not with the include graph's paths.
TEST(Program, ExpandShaderExpandsEachFileOnce) {
    const gpu::ExpandedSource src = gpu::expandShader("lit.frag.glsl", {}, kAllShadowTechniques);
    for (std::size_t i = 0; i < src.files.size(); ++i) {
        EXPECT_EQ(std::count(src.files.begin(), src.files.end(), src.files[i]), 1) << src.files[i];
        const std::string start = "#line 1 " + std::to_string(i) + "\n";
        std::size_t starts = 0;
        for (std::size_t at = src.text.find(start); at != std::string::npos; at = src.text.find(start, at + 1))
            ++starts;
        EXPECT_EQ(starts, 1u) << src.files[i];
    }
    EXPECT_EQ(std::count(src.files.begin(), src.files.end(), "shadow_receiver.glsl"), 1);
}

// Every line of the expansion must be the line of the file its #line directive says: a compiler
// message at F:N then points at the right source line.
TEST(Program, ExpandShaderLineDirectivesMapEveryLineToItsSource) {
    const unsigned techniques = techniqueBit(ShadowTechnique::Hard) | techniqueBit(ShadowTechnique::Vssm);
    for (const char* file : {"lit.frag.glsl", "lit.vert.glsl", "shadow_depth.frag.glsl", "shadow_depth.vert.glsl"}) {
        const gpu::ExpandedSource src = gpu::expandShader(file, {"SG_TECH_HARD_ENABLED"}, techniques);
        int currentFile = -1;
        int currentLine = 0;
        int checked = 0;
        int directives = 0;
        for (const std::string& line : linesOf(src.text)) {
            int n = 0;
            int f = 0;
            if (std::sscanf(line.c_str(), "#line %d %d", &n, &f) == 2) {
                ASSERT_GE(f, 0);
                ASSERT_LT(static_cast<std::size_t>(f), src.files.size()) << line;
                currentFile = f;
                currentLine = n;
                ++directives;
                continue;
            }
            if (currentFile < 0) continue;  // #version and the defines
            const std::string& name = src.files[static_cast<std::size_t>(currentFile)];
            const std::vector<std::string> source =
                linesOf(name == "shadow_techniques.glsl (generated)" ? gpu::techniquesGlsl(techniques).c_str()
                                                                     : gpu::findShaderSource(name));
            ASSERT_GE(currentLine, 1);
            ASSERT_LE(static_cast<std::size_t>(currentLine), source.size())
                << file << ": line " << currentLine << " past the end of "
                << src.files[static_cast<std::size_t>(currentFile)];
            EXPECT_EQ(line, source[static_cast<std::size_t>(currentLine - 1)])
                << file << ": expanded line claims to be " << src.files[static_cast<std::size_t>(currentFile)] << ":"
                << currentLine;
            ++currentLine;
            ++checked;
        }
        EXPECT_GT(checked, 10) << file;
        EXPECT_GE(directives, 1) << file;
    }
}

TEST(Program, ExpandShaderLineAfterIncludeResumesTheIncludingFile) {
    const gpu::ExpandedSource src = gpu::expandShader("lit.frag.glsl", {});
    const int include = lineContaining("lit.frag.glsl", "#include \"shadow_visibility.glsl\"");
    ASSERT_GT(include, 0);
    EXPECT_NE(src.text.find("#line " + std::to_string(include + 1) + " 0\n"), std::string::npos);
}

TEST(Program, ExpandShaderThrowsNamingAMissingFile) {
    try {
        (void)gpu::expandShader("no_such_shader.glsl", {});
        FAIL() << "expected GlError";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("no_such_shader.glsl"), std::string::npos) << e.what();
    }
}

TEST(Program, MapShaderLogReplacesFileNumbersByNames) {
    EXPECT_EQ(gpu::mapShaderLog("0:12(5): error: x\n1:3(1): error: y", {"a.glsl", "b.glsl"}),
              "a.glsl:12(5): error: x\nb.glsl:3(1): error: y");
    // NVIDIA's "F(L) : " form.
    EXPECT_EQ(gpu::mapShaderLog("1(7) : error C0000: z", {"a.glsl", "b.glsl"}), "b.glsl(7) : error C0000: z");
    // A number outside the table is kept, not invented.
    EXPECT_EQ(gpu::mapShaderLog("5:1(1): error: w", {"a.glsl"}), "5:1(1): error: w");
}

TEST(Program, BuildProgramWithMissingFileThrowsNamingIt) {
    test::glContext();
    try {
        (void)gpu::buildProgram({"Test/missing", "nonexistent.vert.glsl", "lit.frag.glsl", {}});
        FAIL() << "expected GlError";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("nonexistent.vert.glsl"), std::string::npos) << e.what();
    }
}

// A compile error inside an included file is reported with that file's name and line.
TEST(Program, CompileErrorNamesTheIncludedFileAndLine) {
    test::glContext();
    const int line = lineContaining("shadow_kernels.glsl", "const float sg_kGoldenAngle");
    ASSERT_GT(line, 0);
    render::LitVariant pcf;
    pcf.lights = 1;
    pcf.technique[0] = SG_TECH_PCF;
    std::vector<std::string> defines = render::variantDefines(pcf);
    defines.emplace_back("sg_kGoldenAngle )");  // turns "const float sg_kGoldenAngle = ..." into a syntax error
    try {
        (void)gpu::buildProgram(
            {"Test/broken", "lit.vert.glsl", "lit.frag.glsl", defines, render::variantTechniques(pcf)});
        FAIL() << "expected GlError";
    } catch (const GlError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("Test/broken"), std::string::npos) << what;
        EXPECT_NE(what.find("shadow_kernels.glsl:" + std::to_string(line) + "("), std::string::npos) << what;
    }
}

// Every light type with every technique and kernel in some slot, with and without AOVs, and
// with a debug view: the configurations the renderer can ask for.
TEST(Program, EveryLitVariantAndTheDepthProgramCompile) {
    test::glContext();
    std::vector<render::LitVariant> variants;
    for (int type : {SG_LIGHT_DIRECTIONAL, SG_LIGHT_SPOT, SG_LIGHT_POINT}) {
        render::LitVariant v;
        v.lights = SG_MAX_LIGHTS_PER_PASS;
        for (int slot = 0; slot < v.lights; ++slot) {
            const auto i = static_cast<std::size_t>(slot);
            v.type[i] = static_cast<std::uint8_t>(slot < 5 ? type : (type + slot) % 3);
            v.technique[i] = static_cast<std::uint8_t>(slot % (SG_TECH_PCSS_TEXTBOOK + 1));
            v.kernel[i] = static_cast<std::uint8_t>(slot % 3);
        }
        variants.push_back(v);
        v.aovs = true;
        variants.push_back(v);
        v.debugView = SG_DEBUG_PENUMBRA;
        v.debugSlot = 3;
        variants.push_back(v);
    }
    variants.emplace_back();  // no light at all: ambient and AOVs only
    for (const render::LitVariant& v : variants) {
        const std::string label = render::variantLabel(v);
        try {
            const gpu::Program program = gpu::buildProgram(
                {label, "lit.vert.glsl", "lit.frag.glsl", render::variantDefines(v), render::variantTechniques(v)});
            EXPECT_NE(program.get(), 0u) << label;
        } catch (const GlError& e) {
            ADD_FAILURE() << label << ": " << e.what();
        }
    }
    try {
        const gpu::Program prepass =
            gpu::buildProgram({"Test/DepthPrepass", "lit.vert.glsl", "depth_prepass.frag.glsl", {}});
        EXPECT_NE(prepass.get(), 0u);
    } catch (const GlError& e) {
        ADD_FAILURE() << "depth pre-pass: " << e.what();
    }
    try {
        const gpu::Program depth =
            gpu::buildProgram({"Test/Depth", "shadow_depth.vert.glsl", "shadow_depth.frag.glsl", {}});
        EXPECT_NE(depth.get(), 0u);
    } catch (const GlError& e) {
        ADD_FAILURE() << "shadow_depth: " << e.what();
    }
}

}  // namespace
}  // namespace shadow
