// The main pass's programs (engine/src/render/lit_programs.cpp): a variant's label and defines
// (per-slot constants, the techniques the planner found, AOVs and debug views), and the cache
// that builds each variant once.
#include <gtest/gtest.h>
#include <shadow/shadow_shaders.h>

#include "render/lit_programs.h"

#include <algorithm>
#include <string>
#include <vector>

#include "render/render_test_support.h"

namespace shadow::render {
namespace {

bool has(const std::vector<std::string>& defines, const std::string& define) {
    return std::find(defines.begin(), defines.end(), define) != defines.end();
}

/// A spot with PCSS in slot 0 and a point light with hard shadows in slot 1.
LitVariant twoLights() {
    LitVariant v;
    v.lights = 2;
    v.type[0] = SG_LIGHT_SPOT;
    v.technique[0] = SG_TECH_PCSS;
    v.kernel[0] = SG_KERNEL_POISSON;
    v.type[1] = SG_LIGHT_POINT;
    v.technique[1] = SG_TECH_HARD;
    return v;
}

TEST(LitPrograms, LabelNamesEachSlotsTypeAndTechnique) {
    LitVariant v = twoLights();
    EXPECT_EQ(variantLabel(v), "Main/Lit[spot:pcss,point:hard]");
    v.aovs = true;
    EXPECT_EQ(variantLabel(v), "Main/Lit[spot:pcss,point:hard,AOV]");
    EXPECT_EQ(variantLabel(LitVariant{}), "Main/Lit[]");
}

TEST(LitPrograms, DefinesHoldEverySlotAndOnlyItsTechniques) {
    const LitVariant v = twoLights();
    const std::vector<std::string> d = variantDefines(v);
    EXPECT_TRUE(has(d, "SG_PASS_LIGHTS 2"));
    // Two unlike lights: a group each, its configuration compile-time constants.
    EXPECT_TRUE(has(d, "SG_PASS_GROUPS 2"));
    EXPECT_TRUE(has(d, "SG_GROUP0_TYPE " + std::to_string(SG_LIGHT_SPOT)));
    EXPECT_TRUE(has(d, "SG_GROUP0_TECH " + std::to_string(SG_TECH_PCSS)));
    EXPECT_TRUE(has(d, "SG_GROUP0_KERNEL " + std::to_string(SG_KERNEL_POISSON)));
    EXPECT_TRUE(has(d, "SG_GROUP0_VISIBILITY sg_pcssLightVisibility"));
    EXPECT_TRUE(has(d, "SG_GROUP1_TECH " + std::to_string(SG_TECH_HARD)));
    EXPECT_TRUE(has(d, "SG_GROUP1_FIRST 1"));
    // Unused groups are constants too: no light, no shadow.
    EXPECT_TRUE(has(d, "SG_GROUP7_TECH " + std::to_string(SG_TECH_NONE)));
    // The code compiled is the techniques of the pass's own lights, and only those.
    EXPECT_EQ(variantTechniques(v), techniqueBit(ShadowTechnique::Pcss) | techniqueBit(ShadowTechnique::Hard));
    EXPECT_TRUE(has(d, "SG_TECH_PCSS_ENABLED"));
    EXPECT_TRUE(has(d, "SG_TECH_HARD_ENABLED"));
    EXPECT_FALSE(has(d, "SG_TECH_VSM_ENABLED"));
    EXPECT_FALSE(has(d, "SG_TECH_PCF_ENABLED"));
    EXPECT_FALSE(has(d, "SG_WRITE_AOVS"));
    EXPECT_FALSE(has(d, "SG_ISOLATE_LOOPS"));
}

// More than four shadowed lights: lights alike share a group (one loop over their slots).
TEST(LitPrograms, LightsAlikeShareAGroupInAPassOfMany) {
    LitVariant v;
    v.lights = 6;
    for (std::size_t i = 0; i < 6; ++i) {
        v.type[i] = i < 4 ? SG_LIGHT_SPOT : SG_LIGHT_POINT;
        v.technique[i] = SG_TECH_PCF;
    }
    const std::vector<std::string> d = variantDefines(v);
    EXPECT_TRUE(has(d, "SG_PASS_GROUPS 2"));
    EXPECT_TRUE(has(d, "SG_GROUP0_COUNT 4"));
    EXPECT_TRUE(has(d, "SG_GROUP0_SLOTS int[](0, 1, 2, 3)"));
    EXPECT_TRUE(has(d, "SG_GROUP1_COUNT 2"));
    EXPECT_TRUE(has(d, "SG_GROUP1_SLOTS int[](4, 5)"));
    // Four lights alike stay a group each: straight-line code.
    v.lights = 4;
    EXPECT_TRUE(has(variantDefines(v), "SG_PASS_GROUPS 4"));
}

// Loops in sequence are counted from the technique table: past kMaxLoopsInSequence the program
// isolates them (shadow_bindings.glsl).
TEST(LitPrograms, ManyLoopsInSequenceAreIsolated) {
    LitVariant v;
    v.lights = 3;
    for (std::size_t i = 0; i < 3; ++i) {
        v.type[i] = SG_LIGHT_POINT;  // PCSS: 2 loops, and the centre tap's face crossing
        v.technique[i] = SG_TECH_PCSS;
        v.kernel[i] = static_cast<std::uint8_t>(i);  // unlike: straight-line each
    }
    EXPECT_TRUE(has(variantDefines(v), "SG_ISOLATE_LOOPS"));  // 9 loops
    v.lights = 2;
    EXPECT_FALSE(has(variantDefines(v), "SG_ISOLATE_LOOPS"));  // 6 loops
}

TEST(LitPrograms, TheCacheBuildsEachVariantOnce) {
    test::glContext();
    LitProgramCache cache;
    int compiled = 0;
    const LitVariant v = twoLights();
    LitProgram& first = cache.get(v, compiled);
    EXPECT_EQ(compiled, 1);
    EXPECT_NE(first.program.get(), 0u);
    EXPECT_GE(first.mesh.clipFromCs, 0) << "the vertex shader's uniforms are found";
    EXPECT_GE(first.material.albedo, 0);
    LitProgram& again = cache.get(v, compiled);
    EXPECT_EQ(compiled, 1) << "a variant seen before is not built again";
    EXPECT_EQ(&again, &first);
    LitVariant aov = v;
    aov.aovs = true;
    EXPECT_NE(cache.get(aov, compiled).program.get(), first.program.get());
    LitVariant otherTechnique = v;
    otherTechnique.technique[1] = SG_TECH_PCF;
    (void)cache.get(otherTechnique, compiled);
    EXPECT_EQ(compiled, 3) << "another technique in a slot is another program";
    EXPECT_EQ(cache.size(), 3u);

    const DepthPrepassProgram prepass = buildDepthPrepass(false);
    EXPECT_NE(prepass.program.get(), 0u);
    EXPECT_GE(prepass.mesh.clipFromCs, 0);
    EXPECT_LT(prepass.alphaCutoff, 0) << "the opaque pre-pass has no alpha test";
    const DepthPrepassProgram cutout = buildDepthPrepass(true);
    EXPECT_NE(cutout.program.get(), 0u);
    EXPECT_GE(cutout.alphaCutoff, 0) << "the alpha-tested pre-pass reads the cutoff";
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace shadow::render
