// Technique auto's edge counts (shaders/lit.frag.glsl, SG_COUNT_EDGES): on a counting frame the lit
// pass counts, at one pixel in each 2x2 block, the pixels each auto light's lookup reached, those
// its hard lookup leaves neither 0 nor 1 and those its technique does; a later frame's stats
// report them. Checked against the visibility the counting frame writes (with AOVs every pixel
// on geometry runs the lookup) and against a hard light's own visibility in the same map.
#include <gtest/gtest.h>
#include <shadow/auto_technique.h>
#include <shadow/frame_runner.h>
#include <shadow/scene.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "render/render_test_support.h"

namespace shadow::auto_edge_counts_test {
namespace {

struct Counted {
    std::uint32_t sampled = 0, mixed = 0;
};

/// Over the pixels the lit pass counts (even window x and y; image rows start at the top), the
/// geometry pixels and those of `visibility` neither 0 nor 1 (kVisibilityClassEpsilon).
Counted countImage(const FrameImages& images, const ImageF& visibility) {
    Counted c;
    for (int y = 0; y < visibility.height; ++y) {
        if ((visibility.height - 1 - y) % 2 != 0) continue;
        for (int x = 0; x < visibility.width; x += 2) {
            if (images.position.at(x, y, 3) <= 0.5f) continue;  // background
            ++c.sampled;
            const float v = visibility.at(x, y, 0);
            c.mixed += v > 1e-3f && v < 1.0f - 1e-3f ? 1u : 0u;
        }
    }
    return c;
}

struct Frame {
    test::RenderedFrame first;
    std::vector<Entity> lights;
    /// The counts read back with the next frame (the GPU done with the first's by then).
    std::vector<AutoEdgeCounts> counts;
};

/// The first frame of builtin:default at 160x90 with AOVs and the depth pre-pass (each pixel
/// shaded once), every light `auto` or, with `hard`, every light hard at 1024 texels; and the
/// edge counts the frame after it reports.
Frame firstFrame(bool hard) {
    test::glContext();
    Result<Scene> made = makeBuiltinScene("default");
    if (!made) throw std::runtime_error(made.error().message);
    Scene scene = std::move(*made);
    scene.world.view<Shadow>().each([hard](Entity, Shadow& s) {
        s.autoTechnique = !hard;
        if (hard) {
            s.technique = ShadowTechnique::Hard;
            s.mapSize = 1024;
        }
    });
    FrameRunner runner;
    RenderOptions options;
    options.width = 160;
    options.height = 90;
    options.depthPrepass = true;
    Frame f;
    f.first = test::renderFrame(runner, scene, options);
    f.lights = scene.lights;
    f.counts = test::renderFrame(runner, scene, options, 1.0 / 30.0).stats.edgeCounts;
    return f;
}

TEST(AutoEdgeCounts, TheLitPassCountsWhatItsVisibilityAndAHardLookupShow) {
    const Frame automatic = firstFrame(false);
    const Frame hard = firstFrame(true);
    const FrameImages& images = automatic.first.images;
    ASSERT_EQ(automatic.lights.size(), 3u);
    ASSERT_EQ(images.visibility.size(), 3u);
    // The first frame of every auto light counts; the frame after it reports them; a hard light
    // is never counted.
    ASSERT_EQ(automatic.counts.size(), 3u);
    EXPECT_TRUE(automatic.first.stats.edgeCounts.empty()) << "counts are read back a frame later";
    EXPECT_TRUE(hard.counts.empty());
    for (std::size_t i = 0; i < automatic.lights.size(); ++i) {
        const auto c = std::find_if(automatic.counts.begin(), automatic.counts.end(),
                                    [&](const AutoEdgeCounts& e) { return e.light == automatic.lights[i].bits(); });
        ASSERT_NE(c, automatic.counts.end()) << "light " << i;
        // Counted at the module's defaults.
        ASSERT_EQ(c->technique, ShadowTechnique::Pcss) << "light " << i;
        ASSERT_EQ(c->mapSize, 1024) << "light " << i;
        const Counted own = countImage(images, images.visibility[i]);
        ASSERT_GT(own.sampled, 1000u);
        // Every geometry pixel of the counted grid ran the lookup; the visibility AOV is half
        // precision, so a pixel within its rounding of the class bounds may fall either way.
        EXPECT_NEAR(c->sampled, own.sampled, 0.005 * own.sampled) << "light " << i;
        EXPECT_NEAR(c->soft, own.mixed, 2.0 + 0.02 * own.mixed) << "light " << i;
        EXPECT_GT(c->soft, 0u) << "light " << i;
        // The count's hard lookup is a hard light's in the same 1024 map.
        const Counted hardOwn = countImage(hard.first.images, hard.first.images.visibility[i]);
        EXPECT_GT(hardOwn.mixed, 0u) << "light " << i;
        EXPECT_NEAR(c->edge, hardOwn.mixed, 2.0 + 0.05 * hardOwn.mixed) << "light " << i;
    }
}

}  // namespace
}  // namespace shadow::auto_edge_counts_test
