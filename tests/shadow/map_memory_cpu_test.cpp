// What a light's maps take (engine/src/shadow/map_memory.cpp): the bytes the memory budget
// counts, worked out by hand for each kind of filter chain. The GL side allocates by the same
// functions (tests/shadow/shadow_system_test.cpp compares them with what stats.json reports).
#include <gtest/gtest.h>
#include <shadow/shadow_planner.h>

#include "shadow/map_memory.h"

#include <cstdint>

namespace shadow {
namespace {

constexpr std::int64_t kMiB = std::int64_t{1} << 20;

TEST(MapMemory, DepthAloneForTechniquesWithoutAChain) {
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Hard, 1024, 1, 32.0f), 4 * kMiB);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::PcssTextbook, 1024, 6, 32.0f), 24 * kMiB);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Hard, 16384, 1, 32.0f), 1024 * kMiB);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::None, 1024, 1, 32.0f), 0);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Hard, 0, 1, 32.0f), 0);
}

TEST(MapMemory, MinMaxPyramidIsAQuarterEdgeRg32fChain) {
    // PCF at 2048^2, radius 32: tiles of 4 texels, 512^2 at level 0; the widest region is
    // 2 (32 + 1.5) = 67 texels, the first level with tiles that wide is level 5 (128): 6 levels.
    EXPECT_EQ(chainLevels(ShadowTechnique::Pcf, 2048, 32.0f), 6);
    std::int64_t chain = 0;
    for (int edge = 512, level = 0; level < 6; ++level, edge /= 2) chain += std::int64_t{8} * edge * edge;
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Pcf, 2048, 1, 32.0f), 16 * kMiB + chain);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Pcss, 2048, 6, 32.0f), 6 * (16 * kMiB + chain));
}

TEST(MapMemory, MomentsChainsHoldLevelOneUpFourMomentsTwiceAsWide) {
    // VSM at 1024^2, radius 32: levels up to ceil(log2 32) + 1 = 6, RG32F, held from level 1
    // (512^2) down: the lookups take level 0 from a gather of the depth map, and the texture
    // holds no level 0 (three quarters of a full chain's bytes).
    std::int64_t vsm = 0;
    for (int edge = 512, level = 1; level < 6; ++level, edge /= 2) vsm += std::int64_t{8} * edge * edge;
    EXPECT_EQ(chainStoredFrom(FilterChainKind::Moments), 1);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Vsm, 1024, 1, 32.0f), 4 * kMiB + vsm);
    // MSM-soft's four moments: the same levels, twice as wide.
    EXPECT_EQ(chainStoredFrom(FilterChainKind::FourMoments), 1);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::MsmSoft, 1024, 1, 32.0f), 4 * kMiB + 2 * vsm);
    // A filter of at most a texel, or a map of one texel, still has the level the texture starts
    // at: a moment chain is two levels at least, the texture one (a 512^2 level 1, or 1^2).
    EXPECT_EQ(chainLevels(ShadowTechnique::Vsm, 1024, 1.0f), 2);
    EXPECT_EQ(chainLevels(ShadowTechnique::MsmSoft, 1, 32.0f), 2);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Vsm, 1024, 1, 1.0f), 4 * kMiB + 8 * 512 * 512);
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::MsmSoft, 1, 1, 32.0f), 4 + 16);
    // Hard-edged MSM gathers its one texel's moments from the depth map: no chain.
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Msm, 1024, 1, 32.0f), 4 * kMiB);
    // VSSM's summed-area table: one RGBA32F level whatever the radius.
    EXPECT_EQ(shadowMapBytes(ShadowTechnique::Vssm, 1024, 2, 256.0f), 2 * (4 * kMiB + 16 * kMiB));
}

}  // namespace
}  // namespace shadow
