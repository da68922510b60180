// The shadow terminator of smooth-shaded low-poly meshes: a UV sphere of 360 triangles with
// interpolated normals, under a sun and a spot, against the ray-traced truth (shadow rays from the
// triangles themselves). Where the interpolated normal leaves the triangle's plane, a filter that
// lays its taps on the plane of the shading normal compares them with depths the triangles never
// had, and the lit side shows facet-shaped acne. At their defaults PCF and PCSS must do no worse
// than hard shadows there.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/soft_test_support.h"
#include "shadow/truth_test_support.h"
#include "test_support.h"

namespace shadow::test::terminator_test {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

/// A low-poly smooth sphere (20 segments, 10 rings: 360 triangles) 1 m in radius standing on a
/// ground, lit by `type` from above and to the side; light 0 is the light (its technique set by
/// renderAgainstTruth).
Scene lowPolySphere(LightType type) {
    Scene scene;
    addGround(scene, 6.0f);
    addMeshInstance(scene.world, "sphere", makeSphereMesh(1.0f, 20, 10), placed({0.0, 1.05, 0.0}));
    Light light = pointSizedLight(type, 0.6f);
    if (type == LightType::Directional)
        light.angularRadius = 0.02f;
    else
        light.radius = 0.1f;
    const glm::dvec3 direction = glm::normalize(glm::dvec3(-0.8, -1.0, -0.3));
    addLight(scene, "light", light, shadowWith(ShadowTechnique::Hard, 1024),
             -6.0 * direction + glm::dvec3(0.0, 1.0, 0.0), direction);
    addCamera(scene, "camera", Camera{}, {2.5, 2.6, 4.0}, {0.0, 0.9, 0.0});
    return scene;
}

/// RMSE of light 0's visibility against the traced truth over the pixels the light shades, for
/// hard, PCF and PCSS: the filters must err no more than hard shadows.
void expectFiltersNoWorseThanHard(LightType type) {
    const std::vector<ShadowTechnique> techniques{ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss};
    Scene scene = lowPolySphere(type);
    const std::vector<AgainstTruth> errors = renderAgainstTruth(scene, kWidth, kHeight, 64, techniques);
    const double hard = errors.at(0).errors.rmse;
    std::printf("[ measured ] low-poly sphere, %s, hard: RMSE %.4f\n", lightTypeName(type), hard);
    for (std::size_t i = 1; i < techniques.size(); ++i) {
        const double filtered = errors.at(i).errors.rmse;
        const char* name = techniqueName(techniques[i]);
        std::printf("[ measured ] low-poly sphere, %s, %s: RMSE %.4f\n", lightTypeName(type), name, filtered);
        EXPECT_LE(filtered, hard * 1.02 + 1e-3)
            << lightTypeName(type) << ", " << name << ": RMSE " << filtered << " against hard's " << hard;
    }
}

TEST(Terminator, PcfAndPcssAtTheirDefaultsAreNoWorseThanHardOnALowPolySmoothSphereUnderASun) {
    expectFiltersNoWorseThanHard(LightType::Directional);
}

TEST(Terminator, PcfAndPcssAtTheirDefaultsAreNoWorseThanHardOnALowPolySmoothSphereUnderASpot) {
    expectFiltersNoWorseThanHard(LightType::Spot);
}

// The bunny's surface is a fur of small triangles whose creases rise above any one triangle's
// plane within PCF's radius: taps there shadowed their own receiver (RMSE 0.0496 / 0.0510 /
// 0.0403 against hard's 0.0387 / 0.0487 / 0.0321 at 320x240 before PCF's reach bias). Each of
// its three lights (a PCSS sun, a PCF spot, a hard bulb) set to each technique at its defaults.
TEST(Terminator, PcfAndPcssAtTheirDefaultsAreNoWorseThanHardOnTheBunny) {
    if (!std::filesystem::exists(kBunnyObjPath)) GTEST_SKIP() << "no " << kBunnyObjPath;
    glContext();
    std::optional<reference::ReferenceResult> truth;
    std::vector<double> hard;
    for (ShadowTechnique t : {ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss}) {
        Result<Scene> scene = makeBuiltinScene("bunny");
        ASSERT_TRUE(scene) << scene.error().message;
        scene->world.view<Shadow>().each([&](Entity, Shadow& s) { s.technique = t; });
        FrameRunner runner;
        const RenderedFrame frame = renderFrame(runner, *scene, 2 * kWidth, 2 * kHeight);
        if (!truth) truth = truthAt(*scene, runner.lastCamera(), frame.images, 64);
        ASSERT_TRUE(truth);
        for (std::size_t i = 0; i < frame.images.visibility.size(); ++i) {
            const double rmse = lightErrors(frame.images, *truth, i).rmse;
            std::printf("[ measured ] bunny, light %zu, %s: RMSE %.4f\n", i, techniqueName(t), rmse);
            if (t == ShadowTechnique::Hard) {
                hard.push_back(rmse);
                continue;
            }
            EXPECT_LE(rmse, hard.at(i) * 1.02 + 1e-3)
                << "light " << i << ", " << techniqueName(t) << ": RMSE " << rmse << " against hard's " << hard.at(i);
        }
    }
}

}  // namespace
}  // namespace shadow::test::terminator_test
