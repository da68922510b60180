// shadowShaderSource (shadow/shadow_shaders.h): the text a game puts into its own shader shares
// the game's namespace, so every name it declares carries the module's prefix (sg_ or SG_).
#include <shadow/shadow_shaders.h>

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>

namespace shadow {
namespace {

/// `text` without // comments.
std::string withoutComments(const std::string& text) {
    static const std::regex comment("//[^\n]*");
    return std::regex_replace(text, comment, "");
}

/// Every name `text` declares: macros, structs, uniform blocks, functions, and variables and
/// constants at file scope (a line that starts with a type or a qualifier at the left margin).
std::set<std::string> declaredNames(const std::string& text) {
    std::set<std::string> names;
    const std::string code = withoutComments(text);
    const std::vector<std::regex> patterns{
        std::regex(R"((?:^|\n)\s*#\s*define\s+(\w+))"),
        std::regex(R"(\bstruct\s+(\w+))"),
        std::regex(R"(\buniform\s+(\w+)\s*\{)"),
        // At the left margin: a return type, the name, "(": a function.
        std::regex(R"(\n(?:\w+)\s+(\w+)\s*\()"),
        // At the left margin: const or a type, then the name and "=" or ";": a global.
        std::regex(R"(\n(?:const\s+)?(?:float|int|uint|bool|vec[234]|ivec[234]|uvec[234]|mat[234])\s+(\w+)\s*[=;\[])"),
        // Samplers.
        std::regex(R"(\buniform\s+\w*sampler\w*\s+(\w+))"),
    };
    for (const std::regex& p : patterns) {
        for (auto it = std::sregex_iterator(code.begin(), code.end(), p); it != std::sregex_iterator(); ++it) {
            names.insert((*it)[1].str());
        }
    }
    // The shared records, declared as SG_STRUCT(name): struct sg_##name.
    static const std::regex shared(R"(\bSG_STRUCT\((\w+)\))");
    for (auto it = std::sregex_iterator(code.begin(), code.end(), shared); it != std::sregex_iterator(); ++it) {
        if ((*it)[1].str() != "name") names.insert("sg_" + (*it)[1].str());
    }
    // The members of uniform blocks are names at file scope.
    static const std::regex block(R"(\buniform\s+\w+\s*\{([^}]*)\})");
    static const std::regex member(R"((\w+)\s*(?:\[[^\]]*\])?\s*;)");
    for (auto it = std::sregex_iterator(code.begin(), code.end(), block); it != std::sregex_iterator(); ++it) {
        const std::string body = (*it)[1].str();
        for (auto m = std::sregex_iterator(body.begin(), body.end(), member); m != std::sregex_iterator(); ++m) {
            names.insert((*m)[1].str());
        }
    }
    return names;
}

TEST(ShaderSource, EveryNameAGameShaderGetsCarriesThePrefix) {
    const std::string text = shadowShaderSource({}, kAllShadowTechniques);
    const std::set<std::string> names = declaredNames(text);
    EXPECT_GT(names.size(), 60u);  // the patterns do find the declarations
    for (const std::string& name : names) {
        const bool prefixed = name.rfind("sg_", 0) == 0 || name.rfind("SG_", 0) == 0;
        EXPECT_TRUE(prefixed) << name;
    }
    // The public entry points are among them.
    for (const char* name : {"sg_lightVisibility", "sg_surface", "sg_Surface", "sg_LightBlock", "sg_GpuLight"}) {
        EXPECT_EQ(names.count(name), 1u) << name;
    }
}

// The patterns are not blind: unprefixed declarations of each kind are found.
TEST(ShaderSource, DeclaredNamesFindsEveryKindOfDeclaration) {
    const std::set<std::string> names = declaredNames(
        "\n#define FOO 1\nstruct Receiver {\n    float x;\n};\nfloat rotate(vec2 p) {\n    return 0.0;\n}\n"
        "const float kSlope = 1.0;\nlayout(std140) uniform LightBlock {\n    vec4 lights[8];\n};\n"
        "layout(binding = 0) uniform sampler2D depthMap;\n");
    for (const char* name : {"FOO", "Receiver", "rotate", "kSlope", "LightBlock", "lights", "depthMap"}) {
        EXPECT_EQ(names.count(name), 1u) << name;
    }
}

}  // namespace
}  // namespace shadow
