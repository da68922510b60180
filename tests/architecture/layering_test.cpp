// The layering rules of docs/architecture.md, read from the source tree: which folder of
// engine/ may include which. A file that breaks a rule is named with its line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kEngine = fs::path(SHADOW_SOURCE_DIR) / "engine";

struct Include {
    fs::path file;  ///< relative to engine/
    int line = 0;
    std::string target;  ///< the text between the quotes or angle brackets
    bool quoted = false;
};

/// Every `#include` of every source and header under engine/<folder>.
std::vector<Include> includesUnder(const std::string& folder) {
    static const std::regex kInclude(R"(^\s*#\s*include\s*([<"])([^">]+)[">])");
    std::vector<Include> out;
    for (const auto& entry : fs::recursive_directory_iterator(kEngine / folder)) {
        const std::string ext = entry.path().extension().string();
        if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
        std::ifstream in(entry.path());
        std::string text;
        for (int line = 1; std::getline(in, text); ++line) {
            std::smatch m;
            if (std::regex_search(text, m, kInclude)) {
                out.push_back({fs::relative(entry.path(), kEngine), line, m[2].str(), m[1].str() == "\""});
            }
        }
    }
    return out;
}

std::string where(const Include& inc) {
    return inc.file.string() + ":" + std::to_string(inc.line) + " includes " + inc.target;
}

/// Private headers are included as "folder/file.h", relative to engine/src.
bool privateIn(const Include& inc, const std::string& folder) {
    return inc.quoted && inc.target.rfind(folder + "/", 0) == 0 && fs::exists(kEngine / "src" / inc.target);
}

void expectNoPrivateInclude(const std::string& from, const std::vector<std::string>& forbidden) {
    const std::vector<Include> includes = includesUnder(from);
    ASSERT_FALSE(includes.empty()) << "no include found under engine/" << from << ": the test reads the wrong tree";
    for (const Include& inc : includes) {
        for (const std::string& folder : forbidden) {
            EXPECT_FALSE(privateIn(inc, folder)) << where(inc) << ": " << from << " may not reach src/" << folder;
        }
    }
}

TEST(Layering, ShadowPartsNeverReachTheRenderer) { expectNoPrivateInclude("src/shadow", {"render"}); }

TEST(Layering, TheRendererReadsTheShadowPartsOnlyThroughPublicHeaders) {
    expectNoPrivateInclude("src/render", {"shadow"});
}

TEST(Layering, CoreIsBelowShadowAndRender) { expectNoPrivateInclude("src/core", {"shadow", "render"}); }

TEST(Layering, GlIsBelowEverything) { expectNoPrivateInclude("src/gl", {"core", "shadow", "render", "scene"}); }

TEST(Layering, PublicHeadersIncludeNoPrivateHeaderAndNoGlHeader) {
    static const std::regex kGlHeader(R"(^(GL|GLES\d*|EGL|KHR|glad|epoxy)/)");
    for (const Include& inc : includesUnder("include/shadow")) {
        if (inc.quoted) {
            EXPECT_TRUE(fs::exists(kEngine / "include/shadow" / inc.target))
                << where(inc) << ": a public header includes only public headers";
        }
        EXPECT_FALSE(std::regex_search(inc.target, kGlHeader)) << where(inc) << ": no GL types in the public API";
    }
}

TEST(Layering, OnlyTheReferenceLibraryIncludesTheTracer) {
    for (const char* folder : {"src/scene", "src/gl", "src/core", "src/shadow", "src/render", "src/io"}) {
        for (const Include& inc : includesUnder(folder)) {
            EXPECT_FALSE(privateIn(inc, "reference")) << where(inc);
            EXPECT_NE(inc.target, "shadow/reference.h") << where(inc);
        }
    }
}

// The rules above must be able to fail: a private include of the renderer is recognised.
TEST(Layering, TheCheckRecognisesAPrivateInclude) {
    const Include inc{"src/shadow/x.cpp", 1, "render/light_packing.h", true};
    EXPECT_TRUE(privateIn(inc, "render"));
    const Include publicOne{"src/render/x.cpp", 1, "shadow/shadow_maps.h", false};
    EXPECT_FALSE(privateIn(publicOne, "shadow"));
}

}  // namespace
