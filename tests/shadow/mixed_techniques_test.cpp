// Mixed techniques: in one frame each light is sampled with its own technique (a PCSS sun, a
// PCF spot and a hard bulb), told apart by the share of ground pixels in penumbra, before and
// after every light is forced to hard. Visibility is read from the per-light AOVs.
#include <gtest/gtest.h>
#include <shadow/shadow_system.h>

#include <array>
#include <cstdio>

#include "shadow/soft_test_support.h"

namespace shadow {
namespace {

using test::countGround;
using test::GroundCounts;

/// Fraction of ground pixels in (0.05, 0.95) allowed for a hard light (edge pixels only): three
/// times the largest measured by `shadow_gl_tests --gtest_filter=Mixed.EachLightUsesItsOwnTechnique`
/// on llvmpipe (LLVM 15.0.6): 0.00168 (the sun forced to hard; spot 0.00113, bulb 0.00044).
constexpr double kMaxHardPenumbraFraction = 0.005;
/// Fraction a soft light must exceed: measured 0.033 (PCSS sun) and 0.050 (PCF spot) against
/// 0.0004-0.0017 for the same lights forced to hard.
constexpr double kMinSoftPenumbraFraction = 0.02;

TEST(Mixed, EachLightUsesItsOwnTechnique) {
    Scene scene;
    test::addGround(scene, 6.0f);
    // Floating boxes (1.3 m above the ground) so every technique has room for a penumbra.
    const glm::dvec3 half{0.6, 0.2, 0.6};
    test::addBox(scene, "sun box", {-2.5, 1.5, -1.0}, half);
    test::addBox(scene, "spot box", {2.5, 1.5, -1.5}, half);
    test::addBox(scene, "bulb box", {0.0, 1.5, 2.0}, half);

    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.1f;
    addLight(scene, "sun", sun, test::shadowWith(ShadowTechnique::Pcss, 1024), {0, 10, 0},
             glm::normalize(glm::dvec3(0.4, -1.0, 0.3)));

    Light spot = test::pointSizedLight(LightType::Spot, 0.6f);
    Shadow pcf = test::shadowWith(ShadowTechnique::Pcf, 1024);
    pcf.pcfRadius = 0.15f;
    const glm::dvec3 spotPosition{2.8, 5.0, -1.2};
    const glm::dvec3 spotDirection = glm::normalize(glm::dvec3(2.3, 0.0, -2.0) - spotPosition);
    addLight(scene, "spot", spot, pcf, spotPosition, spotDirection);

    Light bulb = test::pointSizedLight(LightType::Point);
    bulb.radius = 0.05f;
    addLight(scene, "bulb", bulb, test::shadowWith(ShadowTechnique::Hard, 1024), {0.0, 3.5, 2.4}, {0, -1, 0});
    addCamera(scene, "camera", Camera{}, {0.0, 10.0, 10.0}, {0.0, 0.0, 0.0});

    test::glContext();
    FrameRunner runner;
    auto penumbraFractions = [&] {
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 192);
        test::expectSaneAovs(frame.images);
        std::array<double, 3> f{};
        for (std::size_t i = 0; i < 3; ++i) {
            const GroundCounts c = countGround(frame.images, i, [&](const glm::dvec3& p) {
                return i != 1 || test::insideCone(p, spotPosition, spotDirection, 0.58);
            });
            EXPECT_GT(c.dark, c.ground / 100) << "light " << i << " casts (almost) no shadow in view";
            f[i] = c.penumbraFraction();
        }
        return f;
    };
    const std::array<double, 3> own = penumbraFractions();
    for (Entity light : scene.lights) scene.world.get<Shadow>(light).technique = ShadowTechnique::Hard;
    const std::array<double, 3> allHard = penumbraFractions();
    std::printf(
        "[ measured ] penumbra fraction own technique: sun/pcss %.5f, spot/pcf %.5f, bulb/hard "
        "%.5f\n",
        own[0], own[1], own[2]);
    std::printf("[ measured ] penumbra fraction all hard:      sun %.5f, spot %.5f, bulb %.5f\n", allHard[0],
                allHard[1], allHard[2]);

    EXPECT_LT(own[2], kMaxHardPenumbraFraction) << "the hard light is not binary";
    for (std::size_t i = 0; i < 2; ++i) {
        // A soft technique: a penumbra band several times wider than a hard edge's.
        EXPECT_GT(own[i], kMinSoftPenumbraFraction) << "light " << i << " shows no soft penumbra";
        EXPECT_LT(allHard[i], kMaxHardPenumbraFraction) << "light " << i << " forced to hard is not binary";
        EXPECT_LT(allHard[i], 0.5 * own[i]) << "light " << i << ": forcing hard did not sharpen it";
    }
    // The hard light did not change.
    EXPECT_NEAR(allHard[2], own[2], 1e-9);
}

}  // namespace
}  // namespace shadow
