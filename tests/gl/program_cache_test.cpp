// The program binary cache (shadow/program_cache.h): a program built once is taken from the
// folder the next time, renders the same, and a damaged or foreign file is rebuilt, never used.
#include "gl/program_cache.h"

#include <shadow/program_cache.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gl/program.h"
#include "render/lit_programs.h"
#include "render/render_test_support.h"

namespace shadow {
namespace {

std::filesystem::path freshFolder(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(std::getenv("SHADOW_TEST_TMP") != nullptr
                                                                ? std::getenv("SHADOW_TEST_TMP")
                                                                : std::filesystem::temp_directory_path().string()) /
                                      name;
    std::filesystem::remove_all(dir);
    return dir;
}

gpu::ProgramDesc pcssSpot() {
    render::LitVariant v;
    v.lights = 1;
    v.type[0] = SG_LIGHT_SPOT;
    v.technique[0] = SG_TECH_PCSS;
    return {"Test/CachedLit", "lit.vert.glsl", "lit.frag.glsl", render::variantDefines(v),
            render::variantTechniques(v)};
}

/// The binary files in `dir`.
std::vector<std::filesystem::path> binaries(const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> out;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.path().extension() == ".glbin") out.push_back(e.path());
    }
    return out;
}

class ProgramCache : public ::testing::Test {
protected:
    void SetUp() override { test::glContext(); }
    void TearDown() override { EXPECT_TRUE(setProgramBinaryCache("").ok()); }
};

/// The key `buildProgram(desc)` files its program under.
std::string keyOf(const gpu::ProgramDesc& desc) {
    const gpu::ExpandedSource v = gpu::expandShader(desc.vertexFile, desc.defines, desc.techniques);
    const gpu::ExpandedSource f = gpu::expandShader(desc.fragmentFile, desc.defines, desc.techniques);
    return gpu::programKey(desc.label, {&v.text, &f.text});
}

// Mesa makes program binaries only with its own shader cache on (MESA_SHADER_CACHE_DISABLE unset):
// a driver that gives none leaves the folder empty and builds every program as without the
// cache; one that gives them serves the second build from the folder.
// (tests/samples/shadow_render_test.cpp runs the cache end to end: the second run loads every
// program.)
TEST_F(ProgramCache, SecondBuildLoadsWhatTheDriverGaveAndNothingElse) {
    const std::filesystem::path dir = freshFolder("program_cache_none");
    ASSERT_TRUE(setProgramBinaryCache(dir.string()).ok());
    const gpu::Program program = gpu::buildProgram(pcssSpot());
    GLint length = -1;
    gl.GetProgramiv(program.get(), GL_PROGRAM_BINARY_LENGTH, &length);
    EXPECT_EQ(programCacheStats().stored, length > 0 ? 1 : 0);
    EXPECT_EQ(binaries(dir).size(), length > 0 ? 1u : 0u);
    // Where the driver gives one, the second build loads it: the same program.
    const gpu::Program second = gpu::buildProgram(pcssSpot());
    EXPECT_EQ(programCacheStats().loaded, length > 0 ? 1 : 0);
    GLint a = 0, b = 0;
    gl.GetProgramiv(program.get(), GL_ACTIVE_UNIFORMS, &a);
    gl.GetProgramiv(second.get(), GL_ACTIVE_UNIFORMS, &b);
    EXPECT_EQ(a, b);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A file under the program's key that is not the driver's binary (a driver update, a damaged
// disk, someone else's file) is refused, the program rebuilt, and no GL error left behind.
TEST_F(ProgramCache, ForeignOrDamagedBinaryIsRefusedAndTheProgramRebuilt) {
    const std::filesystem::path dir = freshFolder("program_cache_damaged");
    ASSERT_TRUE(setProgramBinaryCache(dir.string()).ok());
    const std::string key = keyOf(pcssSpot());
    struct {
        char magic[4] = {'S', 'G', 'P', 'B'};
        std::uint32_t format = 0x1234;
        std::uint64_t bytes = 64;
        std::uint64_t check = 0;
    } header;
    {
        std::ofstream out(dir / (key + ".glbin"), std::ios::binary);
        out.write(reinterpret_cast<const char*>(&header), sizeof header);
        out << std::string(64, 'x');
    }
    const gpu::Program rebuilt = gpu::buildProgram(pcssSpot());
    GLint linked = GL_FALSE;
    gl.GetProgramiv(rebuilt.get(), GL_LINK_STATUS, &linked);
    EXPECT_EQ(linked, GL_TRUE);
    EXPECT_EQ(programCacheStats().rejected, 1);
    EXPECT_EQ(programCacheStats().loaded, 0);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    // A truncated file.
    std::filesystem::resize_file(dir / (key + ".glbin"), 10);
    (void)gpu::buildProgram(pcssSpot());
    EXPECT_EQ(programCacheStats().rejected, 2);
}

TEST_F(ProgramCache, KeyFollowsEverySourceAndTheLabel) {
    const std::string a = "void main() {}", b = "void main() { }";
    EXPECT_EQ(gpu::programKey("x", {&a}), gpu::programKey("x", {&a}));
    EXPECT_NE(gpu::programKey("x", {&a}), gpu::programKey("x", {&b}));
    EXPECT_NE(gpu::programKey("x", {&a}), gpu::programKey("y", {&a}));
    EXPECT_NE(gpu::programKey("x", {&a, &b}), gpu::programKey("x", {&b, &a}));
}

TEST_F(ProgramCache, AFileInPlaceOfTheFolderIsRefusedAndTheCacheStaysOff) {
    const std::filesystem::path dir = freshFolder("program_cache_file");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "not_a_folder") << "x";
    const Status s = setProgramBinaryCache((dir / "not_a_folder").string());
    EXPECT_FALSE(s.ok());
    (void)gpu::buildProgram(pcssSpot());
    EXPECT_EQ(programCacheStats().stored, 0);
}

}  // namespace
}  // namespace shadow
