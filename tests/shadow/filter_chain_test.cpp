// The filter chains (engine/src/shadow/filter_chain.cpp). The min/max depth pyramid: every texel
// of every level holds exactly the least and greatest stored depth of its tile of the map. The
// moments (VSM, VSSM): every texel holds the mean depth and mean squared depth of its tile; the
// four moments (MSM, MSM-soft) the means of z, z^2, z^3, z^4. The summed-area table (VSSM):
// exact integer sums of the quantised moments, and the region means read from it within the
// quantisation of the depths, where a float table would not be. A chain exists only for the
// techniques that read it, and follows the map when the map changes.
#include <shadow/shared_constants.h>

#include <gtest/gtest.h>

#include "gl/objects.h"
#include "shadow/filter_chain.h"
#include "render/render_test_support.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>

namespace shadow {
namespace {

/// The box of the last scene made (one per test).
Entity& boxOf(Scene&) {
    static Entity box;
    return box;
}

/// A spot light over a ground with a box and a sphere, so the map holds several depths.
Scene tiltedScene(ShadowTechnique technique, int mapSize) {
    Scene scene;
    test::addGround(scene, 6.0f);
    boxOf(scene) = test::addBox(scene, "box", {0.5, 0.6, -0.3}, {0.4, 0.6, 0.5});
    Shadow shadow = test::hardShadow(mapSize);
    shadow.technique = technique;
    addLight(scene, "spot", test::pointSizedLight(LightType::Spot, 0.6f), shadow, {-3.0, 5.0, 2.0},
             glm::normalize(glm::dvec3(3.0, -5.0, -2.0)));
    addCamera(scene, "camera", Camera{}, {0.0, 6.0, 8.0}, {0.0, 0.0, 0.0});
    return scene;
}

/// Level `level` of layer `layer` of the pyramid `texture` (RG pairs, rows bottom first).
/// Level `level` of `layer`, `channels` (2 or 4) floats per texel.
std::vector<float> readLevel(GLuint texture, int level, int layer, int size, int channels = 2) {
    std::vector<float> data(static_cast<std::size_t>(size) * size * channels);
    gl.GetTextureSubImage(texture, level, 0, 0, layer, size, size, 1, channels == 4 ? GL_RGBA : GL_RG, GL_FLOAT,
                          static_cast<GLsizei>(data.size() * sizeof(float)), data.data());
    return data;
}

void expectPyramidMatchesMap(FrameRunner& runner, int mapSize, const std::string& what) {
    const ShadowSystem& shadows = runner.shadows();
    const GLuint pyramid = shadows.maps().filterChainOf(0).name;
    ASSERT_NE(pyramid, 0u) << what;
    const float scale = shadows.frame().lights[0].layers[0].depthScale;
    std::vector<float> depth = shadows.maps().readLayerDepth(0, 0);  // metres, rows bottom first
    for (float& d : depth) d /= scale;                               // back to stored units
    int size = 1;  // level 0: the power of two of at least mapSize / SG_MINMAX_TILE texels
    while (size * SG_MINMAX_TILE < mapSize) size *= 2;
    // Levels up to the first whose tiles span the widest region the lookup asks for.
    const float maxFilterTexels = shadows.frame().lights[0].settings.maxFilterTexels;
    int levels = 1;
    for (int tile = SG_MINMAX_TILE; tile < 2.0f * (maxFilterTexels + 1.5f) && (size >> levels) > 0; tile *= 2) ++levels;
    int checked = 0;
    for (int level = 0; level < levels; ++level, size = std::max(1, size / 2)) {
        const std::vector<float> got = readLevel(pyramid, level, 0, size);
        const int tile = SG_MINMAX_TILE << level;
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                float lo = 1.0f, hi = 0.0f;
                for (int ty = y * tile; ty < std::min((y + 1) * tile, mapSize); ++ty) {
                    for (int tx = x * tile; tx < std::min((x + 1) * tile, mapSize); ++tx) {
                        const float d = depth[static_cast<std::size_t>(ty) * mapSize + tx];
                        lo = std::min(lo, d);
                        hi = std::max(hi, d);
                    }
                }
                if (x * tile >= mapSize || y * tile >= mapSize) continue;  // past the map's edge
                const std::size_t i = 2 * (static_cast<std::size_t>(y) * size + x);
                ASSERT_FLOAT_EQ(got[i], lo) << what << ": level " << level << " texel " << x << "," << y;
                ASSERT_FLOAT_EQ(got[i + 1], hi) << what << ": level " << level << " texel " << x << "," << y;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 1000) << what;
}

/// Renders the tilted scene with `technique` at a power-of-two map (256) and at one whose
/// tiles overhang the map and whose levels round down (200), then runs `expect` on its chain.
void forBothMapSizes(ShadowTechnique technique,
                     const std::function<void(FrameRunner&, int, const std::string&)>& expect) {
    test::glContext();
    for (int mapSize : {256, 200}) {
        Scene scene = tiltedScene(technique, mapSize);
        FrameRunner runner;
        // Whatever the texels per pixel of this small image: the chain is what is tested here.
        ShadowLimits limits = runner.shadows().planner().limits();
        limits.pyramidTexelsPerPixel = 1e9f;
        runner.shadows().planner().setLimits(limits);
        (void)test::renderFrame(runner, scene, 64, 48);
        expect(runner, mapSize, std::string(techniqueName(technique)) + ", map " + std::to_string(mapSize));
    }
}

TEST(MinMaxPyramid, EveryTexelHoldsTheRangeOfItsTile) {
    forBothMapSizes(ShadowTechnique::Pcss, expectPyramidMatchesMap);
}

TEST(MinMaxPyramid, TilesNoCasterDrewHoldTheFarRangeAndAreNotRead) {
    // The ground only receives: the box alone is drawn, and the pyramid reads the tiles its
    // bounds project to. At the power-of-two map and at the one whose tiles overhang its edge,
    // every level still holds each tile's range (the far depth's where nothing was drawn).
    test::glContext();
    for (int mapSize : {256, 200}) {
        Scene scene = tiltedScene(ShadowTechnique::Pcf, mapSize);
        scene.world.view<Mesh, Name>().each([](Entity, Mesh& mesh, const Name& name) {
            if (name.value == "ground") mesh.castShadows = false;
        });
        FrameRunner runner;
        ShadowLimits limits = runner.shadows().planner().limits();
        limits.pyramidTexelsPerPixel = 1e9f;
        runner.shadows().planner().setLimits(limits);
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 64, 48);
        const std::string what = "ground not casting, map " + std::to_string(mapSize);
        expectPyramidMatchesMap(runner, mapSize, what);
        // The texels read: the box's tiles, under half the map, and at least every texel it drew.
        const std::vector<float> depth = runner.shadows().maps().readLayerDepth(0, 0);
        const float far = runner.shadows().frame().lights[0].layers[0].depthScale;
        const long long drawn = std::count_if(depth.begin(), depth.end(), [far](float d) { return d < far; });
        const long long read = frame.stats.lights.at(0).pyramidTexelsRead;
        EXPECT_GT(drawn, 100) << what;
        EXPECT_GE(read, drawn) << what;
        EXPECT_LT(read, static_cast<long long>(mapSize) * mapSize / 2) << what;
    }
}

TEST(MinMaxPyramid, OnlyForTechniquesThatReadItAndRebuiltWhenTheMapChanges) {
    test::glContext();
    Scene scene = tiltedScene(ShadowTechnique::Hard, 256);
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, 64, 48);
    EXPECT_FALSE(runner.shadows().maps().filterChainOf(0)) << "hard shadows read no pyramid";

    scene.world.get<Shadow>(scene.lights[0]).technique = ShadowTechnique::Pcf;
    // Whatever the texels per pixel of this small image: the pyramid is what is tested here.
    ShadowLimits limits = runner.shadows().planner().limits();
    limits.pyramidTexelsPerPixel = 1e9f;
    runner.shadows().planner().setLimits(limits);
    (void)test::renderFrame(runner, scene, 64, 48);
    expectPyramidMatchesMap(runner, 256, "after switching to PCF");

    // Move the box: the layer is redrawn and its pyramid follows.
    scene.world.get<Transform>(boxOf(scene)).translation.x += 0.7;
    const test::RenderedFrame moved = test::renderFrame(runner, scene, 64, 48);
    EXPECT_EQ(moved.stats.shadowLayersDrawn, 1);
    expectPyramidMatchesMap(runner, 256, "after the box moved");
}

/// A PCF or PCSS light's lit pass without its pyramid (`ShadowLimits::pyramidTexelsPerPixel` 0:
/// too many texels per pixel) takes every tap, and the pyramid's region test only skips taps (and
/// PCSS's blocker search) whose answer it knows: the visibility is the same either way, and
/// without it no pyramid is built.
void expectTheSameVisibilityWithoutThePyramid(ShadowTechnique technique) {
    test::glContext();
    std::vector<ImageF> seen;
    for (const float texelsPerPixel : {1e9f, 0.0f}) {
        Scene scene = tiltedScene(technique, 256);
        scene.world.get<Shadow>(scene.lights[0]).pcfRadius = 0.12f;
        scene.world.get<Light>(scene.lights[0]).radius = 0.4f;  // PCSS's emitter: wide penumbrae
        FrameRunner runner;
        ShadowLimits limits = runner.shadows().planner().limits();
        limits.pyramidTexelsPerPixel = texelsPerPixel;
        runner.shadows().planner().setLimits(limits);
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 128, 96);
        const bool regionTest = texelsPerPixel > 0.0f;
        EXPECT_EQ(frame.stats.lights.at(0).regionTest, regionTest);
        const bool pyramidBuilt = std::any_of(frame.stats.passes.begin(), frame.stats.passes.end(),
                                              [](const auto& p) { return p.name.find("minmax") != std::string::npos; });
        EXPECT_EQ(pyramidBuilt, regionTest) << "a pyramid pass in the stats";
        seen.push_back(frame.images.visibility.at(0));
    }
    const ImageF& with = seen[0];
    const ImageF& without = seen[1];
    double worst = 0.0;
    int penumbra = 0;
    for (int y = 0; y < with.height; ++y) {
        for (int x = 0; x < with.width; ++x) {
            const float v = with.at(x, y, 0);
            if (v > 0.02f && v < 0.98f) ++penumbra;
            worst = std::max(worst, static_cast<double>(std::abs(v - without.at(x, y, 0))));
        }
    }
    std::printf("[ measured ] %s with and without its pyramid: %d penumbra pixels, largest difference %.3g\n",
                techniqueName(technique), penumbra, worst);
    EXPECT_GT(penumbra, 50) << "the frame has a penumbra to compare";
    EXPECT_LE(worst, 1e-6);
}

TEST(MinMaxPyramid, APcfLightWithoutItsPyramidSeesWhatItSeesWithIt) {
    expectTheSameVisibilityWithoutThePyramid(ShadowTechnique::Pcf);
}

TEST(MinMaxPyramid, APcssLightWithoutItsPyramidSeesWhatItSeesWithIt) {
    expectTheSameVisibilityWithoutThePyramid(ShadowTechnique::Pcss);
}

/// The moments a chain level should hold, from the level below (level 0: from the stored depths)
/// as the builder makes them: 2x2 means (of a level of odd size, the last row and column are left
/// to the levels above' floor).
std::vector<double> momentsBelowAveraged(const std::vector<double>& below, int belowSize, int size, int channels) {
    const auto n = static_cast<std::size_t>(channels);
    std::vector<double> out(static_cast<std::size_t>(size) * size * n, 0.0);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            for (int k = 0; k < 4; ++k) {
                const int bx = std::min(2 * x + (k & 1), belowSize - 1);
                const int by = std::min(2 * y + (k >> 1), belowSize - 1);
                const std::size_t b = n * (static_cast<std::size_t>(by) * belowSize + bx);
                const std::size_t o = n * (static_cast<std::size_t>(y) * size + x);
                for (std::size_t c = 0; c < n; ++c) out[o + c] += 0.25 * below[b + c];
            }
        }
    }
    return out;
}

/// Largest difference allowed between a moment the GPU averaged in float and the same mean in
/// double: a few float ulps of moments below 1, over up to 8 levels of 2x2 means. A level above
/// 0 is one bilinear fetch at the corner of each 2x2 block, (2x + 1) / size: exact weights of 1/2
/// when the size is a power of two; otherwise the coordinate's rounding moves the weights by
/// about 1e-7 (2x + 1), which a moment carries times the difference between neighbours (below 1).
double momentTolerance(int mapSize) { return (mapSize & (mapSize - 1)) == 0 ? 1e-6 : 1e-5; }

void expectMomentsMatchMap(FrameRunner& runner, int mapSize, const std::string& what) {
    const ShadowSystem& shadows = runner.shadows();
    const GLuint chain = shadows.maps().filterChainOf(0).name;
    ASSERT_NE(chain, 0u) << what;
    const float scale = shadows.frame().lights[0].layers[0].depthScale;
    std::vector<float> depth = shadows.maps().readLayerDepth(0, 0);  // metres, rows bottom first
    const std::optional<FilterChainKind> kind = filterChainOf(shadows.frame().lights[0].technique());
    ASSERT_TRUE(kind && *kind != FilterChainKind::MinMax) << what;
    const int channels = *kind == FilterChainKind::FourMoments ? 4 : 2;
    std::vector<double> expected;
    for (float stored : depth) {
        const double z = stored / scale;  // back to stored units, as the GPU rounds it
        for (int c = 0; c < channels; ++c)
            expected.push_back(std::pow(static_cast<double>(static_cast<float>(z)), c + 1));
    }
    const int levels = FilterChain::levelsFor(shadows.frame().lights[0].technique(), mapSize,
                                              shadows.frame().lights[0].settings.maxFilterTexels);
    ASSERT_GT(levels, 1) << what;
    // The levels below the layer's first level and above its last are neither built nor read.
    const int first = shadows.frame().lights[0].layers[0].chainFirstLevel;
    const int last = shadows.frame().lights[0].layers[0].chainLastLevel;
    ASSERT_LE(first, last) << what;
    ASSERT_LT(last, levels) << what;
    int size = mapSize;
    double worst = 0.0;
    for (int level = 0; level <= last; ++level) {
        if (level > 0) {
            const int next = std::max(1, size / 2);
            expected = momentsBelowAveraged(expected, size, next, channels);
            size = next;
        }
        if (level < first) continue;
        // The texture holds the chain from chainStoredFrom up (four moments: from level 1).
        const std::vector<float> got = readLevel(chain, level - chainStoredFrom(*kind), 0, size, channels);
        for (std::size_t i = 0; i < got.size(); ++i) worst = std::max(worst, std::abs(got[i] - expected[i]));
    }
    std::printf("[ measured ] %s: levels %d to %d of %d, largest |moment - double mean| %.3g\n", what.c_str(), first,
                last, levels, worst);
    EXPECT_LT(worst, momentTolerance(mapSize)) << what;
}

TEST(FilterChain, MomentsHoldTheMeanDepthAndSquareOfEachTile) {
    forBothMapSizes(ShadowTechnique::Vsm, expectMomentsMatchMap);
}

TEST(FilterChain, AVsmChainStartsAtTheFirstLevelItsLookupsRead) {
    // A filter radius of many texels at the farthest receiver: the lookups read nothing below
    // level log2 of it, and the chain is drawn from the depth map at that level (its tiles' means
    // of 2^k x 2^k texels by gathers), for a map size of odd levels too.
    test::glContext();
    for (int mapSize : {256, 200}) {
        Scene scene = tiltedScene(ShadowTechnique::Vsm, mapSize);
        Shadow& shadow = scene.world.get<Shadow>(scene.lights[0]);
        shadow.pcfRadius = 0.5f;
        FrameRunner runner;
        (void)test::renderFrame(runner, scene, 64, 48);
        const ShadowLayerPlan& layer = runner.shadows().frame().lights[0].layers[0];
        // The spot's texel at the farthest receiver corner (the ground's), as the planner bounds it.
        const double texel = 2.0 / (layer.clipFromLight[0][0] * mapSize) *
                             glm::distance(glm::dvec3(-3.0, 5.0, 2.0), glm::dvec3(6.0, 0.0, -6.0));
        const int expectedFirst = static_cast<int>(std::floor(std::log2(0.5 / (1.05 * texel))));
        std::printf("[ measured ] vsm, map %d, radius 0.5 m: first level %d (texel at the farthest receiver %.4f m)\n",
                    mapSize, layer.chainFirstLevel, texel);
        EXPECT_EQ(layer.chainFirstLevel, expectedFirst) << "map " << mapSize;
        EXPECT_GE(layer.chainFirstLevel, 2) << "map " << mapSize;
        expectMomentsMatchMap(runner, mapSize, "vsm from its first level, map " + std::to_string(mapSize));
        // A radius below a texel reads level 0 again, from the depth map: the chain is built from
        // level 1 (the first its texture holds).
        shadow.pcfRadius = 0.001f;
        (void)test::renderFrame(runner, scene, 64, 48);
        EXPECT_EQ(runner.shadows().frame().lights[0].layers[0].chainFirstLevel, 1);
        expectMomentsMatchMap(runner, mapSize, "vsm down to level 1 again, map " + std::to_string(mapSize));
    }
}

TEST(FilterChain, FourMomentsHoldTheMeansOfTheFirstFourPowersOfEachTile) {
    forBothMapSizes(ShadowTechnique::MsmSoft, expectMomentsMatchMap);
}

/// One unit of the table's fixed point (2^-24 of the stored range) and its limbs' modulus.
constexpr double kSatUnit = 16777216.0;
constexpr std::uint64_t kLimb = 1ull << 24;

/// Sum of the quantised moment `m` (0: z, 1: z^2) over texels [x0, x1) x [y0, y1) from the table
/// texels `t` (4 limbs each) as the lit pass takes it: the corners' limbs combined in integers,
/// the result modulo 2^48 brought near [0, 2^47).
double tableRectSum(const std::vector<float>& t, int size, int x0, int x1, int y0, int y1, int m) {
    const auto lattice = [&](int x, int y, int limb) -> std::int64_t {
        if (x <= 0 || y <= 0) return 0;
        return static_cast<std::int64_t>(t[4 * (static_cast<std::size_t>(y - 1) * size + (x - 1)) + 2 * m + limb]);
    };
    std::array<std::int64_t, 2> limbs{};
    for (int limb = 0; limb < 2; ++limb)
        limbs[limb] = lattice(x1, y1, limb) - lattice(x0, y1, limb) - lattice(x1, y0, limb) + lattice(x0, y0, limb);
    std::int64_t hi = limbs[1] & static_cast<std::int64_t>(kLimb - 1);
    if (hi >= static_cast<std::int64_t>(kLimb / 2)) hi -= static_cast<std::int64_t>(kLimb);
    return static_cast<double>(hi) * kSatUnit + static_cast<double>(limbs[0]);
}

/// The table: texel (x, y) holds, two 24-bit limbs per moment, the sums modulo 2^48 of z and z^2
/// rounded to units of 2^-24, over the map texels [0, x] x [0, y]: checked bit for bit against
/// the stored depths. Then the error the table adds to a region's mean: squares of half-width 1
/// to 64 texels all over the layer, their means from four corners against the double means of
/// the stored depths, beside the same from a float table (what the table's integers avoid).
void expectSummedAreaMatchesMap(FrameRunner& runner, int mapSize, const std::string& what) {
    const ShadowSystem& shadows = runner.shadows();
    const GLuint table = shadows.maps().filterChainOf(0).name;
    ASSERT_NE(table, 0u) << what;
    std::vector<float> stored(static_cast<std::size_t>(mapSize) * mapSize);  // bit for bit
    gl.GetTextureSubImage(shadows.maps().textureOf(0).name, 0, 0, 0, 0, mapSize, mapSize, 1, GL_DEPTH_COMPONENT,
                          GL_FLOAT, static_cast<GLsizei>(stored.size() * sizeof(float)), stored.data());
    const std::vector<float> got = readLevel(table, 0, 0, mapSize, 4);
    const auto n = static_cast<std::size_t>(mapSize);
    // The table holds the moments of w = min(z s, 1) (ShadowLayerPlan::momentScale).
    const float scale = shadows.frame().lights[0].layers[0].momentScale;
    std::printf("[ measured ] %s: moment scale %g\n", what.c_str(), scale);
    const auto scaled = [&](std::size_t i) { return std::clamp(stored[i] * scale, 0.0f, 1.0f); };
    std::vector<std::array<std::uint64_t, 2>> sums(n * n);  // exact prefix sums
    std::vector<std::array<float, 2>> floatSums(n * n);     // the same summed in float
    int mismatches = 0;
    double depthSpread = 0.0;
    for (std::size_t y = 0; y < n; ++y) {
        for (std::size_t x = 0; x < n; ++x) {
            const float z = scaled(y * n + x);
            const std::array<float, 2> moments{z, z * z};
            depthSpread = std::max(depthSpread, std::abs(static_cast<double>(z) - scaled(0)));
            for (std::size_t m = 0; m < 2; ++m) {
                const auto q = static_cast<std::uint64_t>(moments[m] * static_cast<float>(kSatUnit) + 0.5f);
                const std::uint64_t left = x > 0 ? sums[y * n + x - 1][m] : 0;
                const std::uint64_t below = y > 0 ? sums[(y - 1) * n + x][m] : 0;
                const std::uint64_t diagonal = x > 0 && y > 0 ? sums[(y - 1) * n + x - 1][m] : 0;
                sums[y * n + x][m] = q + left + below - diagonal;
                const float fl = x > 0 ? floatSums[y * n + x - 1][m] : 0.0f;
                const float fb = y > 0 ? floatSums[(y - 1) * n + x][m] : 0.0f;
                const float fd = x > 0 && y > 0 ? floatSums[(y - 1) * n + x - 1][m] : 0.0f;
                floatSums[y * n + x][m] = moments[m] + fl + fb - fd;
                const std::uint64_t s = sums[y * n + x][m] % (kLimb * kLimb);
                const float lo = got[4 * (y * n + x) + 2 * m];
                const float hi = got[4 * (y * n + x) + 2 * m + 1];
                if (lo != static_cast<float>(s % kLimb) || hi != static_cast<float>(s / kLimb)) {
                    if (++mismatches <= 3)
                        ADD_FAILURE() << what << ": texel " << x << "," << y << " moment " << m << " limbs " << lo
                                      << "," << hi << ", expected " << s % kLimb << "," << s / kLimb;
                }
            }
        }
    }
    EXPECT_EQ(mismatches, 0) << what;
    ASSERT_GT(depthSpread, 0.01) << what << ": the layer should hold several depths";

    double worstTable = 0.0, worstFloat = 0.0;
    for (int half : {1, 2, 4, 8, 16, 32, 64}) {
        for (int cy = half; cy + half <= mapSize; cy += 7) {
            for (int cx = half; cx + half <= mapSize; cx += 11) {
                const int x0 = cx - half, x1 = cx + half, y0 = cy - half, y1 = cy + half;
                const double area = 4.0 * half * half;
                for (int m = 0; m < 2; ++m) {
                    double exact = 0.0;
                    for (int y = y0; y < y1; ++y)
                        for (int x = x0; x < x1; ++x) {
                            const double z = scaled(static_cast<std::size_t>(y) * n + x);
                            exact += m == 0 ? z : static_cast<double>(static_cast<float>(z * z));
                        }
                    exact /= area;
                    const double fromTable = tableRectSum(got, mapSize, x0, x1, y0, y1, m) / (area * kSatUnit);
                    worstTable = std::max(worstTable, std::abs(fromTable - exact));
                    const auto fsum = [&](int x, int y) {
                        return x <= 0 || y <= 0 ? 0.0f
                                                : floatSums[static_cast<std::size_t>(y - 1) * n + (x - 1)]
                                                           [static_cast<std::size_t>(m)];
                    };
                    const float floatTable =
                        (fsum(x1, y1) - fsum(x0, y1) - fsum(x1, y0) + fsum(x0, y0)) / static_cast<float>(area);
                    worstFloat = std::max(worstFloat, std::abs(floatTable - exact));
                }
            }
        }
    }
    std::printf(
        "[ measured ] %s: largest |region mean - double mean|, squares of 2-128 texels: table %.3g, "
        "a float table %.3g\n",
        what.c_str(), worstTable, worstFloat);
    // Rounding to 2^-24 per texel (half a unit), then one float rounding of the sum: a few units.
    EXPECT_LT(worstTable, 4.0 / kSatUnit) << what;
}

TEST(FilterChain, SummedAreaTableHoldsExactSumsAndExactRegionMeans) {
    forBothMapSizes(ShadowTechnique::Vssm, expectSummedAreaMatchesMap);
    // An odd edge: the rows' pass reads two rows and two columns per gather, the last of each
    // alone.
    test::glContext();
    Scene scene = tiltedScene(ShadowTechnique::Vssm, 75);
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, 64, 48);
    expectSummedAreaMatchesMap(runner, 75, "vssm, map 75");
}

TEST(FilterChain, SummedAreaTableScalesALongRangeLightsDepthsToItsCasters) {
    // A range of 10 km over a scene 10 m deep: the casters' stored depths are below 10^-3, and
    // the table holds them scaled by a power of two of at least 2^8.
    test::glContext();
    Scene scene = tiltedScene(ShadowTechnique::Vssm, 256);
    scene.world.get<Light>(scene.lights[0]).range = 1e4f;
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, 64, 48);
    EXPECT_GE(runner.shadows().frame().lights[0].layers[0].momentScale, 256.0f);
    expectSummedAreaMatchesMap(runner, 256, "vssm, range 10 km");
}

TEST(FilterChain, LevelsReachTheWidestRegionTheTechniqueReads) {
    // Moments: a trilinear fetch at log2(radius) reads up to level ceil(log2(maxFilterTexels)).
    EXPECT_EQ(FilterChain::levelsFor(ShadowTechnique::Vsm, 2048, 32.0f), 6);
    EXPECT_EQ(FilterChain::levelsFor(ShadowTechnique::MsmSoft, 2048, 20.0f), 6);
    EXPECT_EQ(FilterChain::levelsFor(ShadowTechnique::MsmSoft, 16, 256.0f), 5);  // all the map has
    // VSSM's summed-area table is one level whatever the width.
    EXPECT_EQ(FilterChain::levelsFor(ShadowTechnique::Vssm, 2048, 256.0f), 1);
    // Hard-edged MSM reads one texel, whose moments it takes from the depth map itself: no chain.
    EXPECT_FALSE(filterChainOf(ShadowTechnique::Msm));
    // The pyramid: tiles of 4 texels at level 0, up to the first as wide as 2 (32 + 1.5) texels.
    EXPECT_EQ(FilterChain::levelsFor(ShadowTechnique::Pcss, 2048, 32.0f), 6);
}

TEST(FilterChain, TheChainFollowsTheTechnique) {
    test::glContext();
    Scene scene = tiltedScene(ShadowTechnique::Vsm, 256);
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, 64, 48);
    expectMomentsMatchMap(runner, 256, "vsm");
    scene.world.get<Transform>(boxOf(scene)).translation.x += 0.7;  // redrawn: the moments follow
    (void)test::renderFrame(runner, scene, 64, 48);
    expectMomentsMatchMap(runner, 256, "vsm after the box moved");
    scene.world.get<Shadow>(scene.lights[0]).technique = ShadowTechnique::Pcss;
    (void)test::renderFrame(runner, scene, 64, 48);
    expectPyramidMatchesMap(runner, 256, "after switching from VSM to PCSS");
    scene.world.get<Shadow>(scene.lights[0]).technique = ShadowTechnique::Hard;
    (void)test::renderFrame(runner, scene, 64, 48);
    EXPECT_FALSE(runner.shadows().maps().filterChainOf(0)) << "hard shadows read no chain";
    scene.world.get<Shadow>(scene.lights[0]).technique = ShadowTechnique::Msm;
    (void)test::renderFrame(runner, scene, 64, 48);
    EXPECT_FALSE(runner.shadows().maps().filterChainOf(0)) << "msm gathers its moments from the depth map";
}

}  // namespace
}  // namespace shadow
