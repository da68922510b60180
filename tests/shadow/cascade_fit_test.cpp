// Cascades fitted to the receivers visible on screen (engine/src/shadow/light_projection.cpp), as
// rendered: the debug cascade view (--debug cascade) of builtin:default and of a wide sun scene,
// in which every cascade must colour a share of the receiver pixels; and a still camera whose
// cascades are reused frame after frame. The planner's side, against brute force, is in
// cascade_fit_cpu_test.cpp.
#include <gtest/gtest.h>
#include <shadow/renderer.h>
#include <shadow/shadow_system.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "render/render_test_support.h"

namespace shadow {
namespace {

/// Least share of the receiver pixels each cascade must colour. Measured at 320x180 with the
/// cascades fitted to the visible receivers: builtin:default 60.9 / 31.9 / 7.2 %, the wide sun
/// 72.2 / 19.4 / 8.5 %. Splitting the distances to the receivers' bounding box instead gave
/// 4.1 / 76.7 / 19.3 % and 72.5 / 22.0 / 5.5 % (640x360, shadow_render --debug cascade).
constexpr double kMinCascadeShare = 0.05;

/// A 400 m ground, eight 2 m boxes in a row going away, a sun with three cascades (PCF, 1024^2,
/// angular radius 0.01) and a camera 10 m up looking 10 degrees down toward the horizon: a wide
/// view over a ground that ends just below the horizon.
Scene wideSunScene() {
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(200.0f, 4), test::placed(glm::dvec3(0.0)));
    for (int i = 0; i < 8; ++i) test::addBox(scene, "box", {3.0 * (i % 3) - 3.0, 1.0, -8.0 * i}, glm::dvec3(1.0));
    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.01f;
    Shadow shadow = test::hardShadow(1024);
    shadow.technique = ShadowTechnique::Pcf;
    shadow.cascades = 3;
    addLight(scene, "sun", sun, shadow, {0, 50, 0}, glm::normalize(glm::dvec3(0.4, -1.0, 0.3)));
    Camera lens;
    lens.yfov = 0.8f;
    lens.znear = 0.1f;
    lens.zfar = 1000.0f;
    const glm::dvec3 eye(0.0, 10.0, 20.0);
    addCamera(scene, "camera", lens, eye, eye + glm::dvec3(0.0, -std::sin(0.175), -std::cos(0.175)));
    return scene;
}

/// The index of the first directional light of `scene`.
int sunIndex(const Scene& scene) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.world.tryGet<Light>(scene.lights[i]);
        if (light != nullptr && light->type == LightType::Directional) return static_cast<int>(i);
    }
    return -1;
}

/// Share of the covered pixels of the debug cascade view that each cascade colours: the view
/// tints cascade 0 red, 1 green, 2 and later blue (0.8 of the channel, plus 0.2 x visibility).
std::array<double, 3> cascadeShares(Scene& scene, int width, int height) {
    test::glContext();
    FrameRunner runner;
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.aovs = true;
    options.debugView = DebugView::Cascade;
    options.debugLight = sunIndex(scene);
    FrameStats stats = runner.runFrame(scene, 0.0, scene.cameras.at(0), options);
    const FrameImages images = runner.renderer().readback(runner.lastCamera(), stats);
    std::array<double, 3> shares{};
    double covered = 0.0;
    for (int y = 0; y < images.color.height; ++y) {
        for (int x = 0; x < images.color.width; ++x) {
            if (images.position.at(x, y, 3) < 0.5f) continue;
            int strongest = 0;
            for (int c = 1; c < 3; ++c) {
                if (images.color.at(x, y, c) > images.color.at(x, y, strongest)) strongest = c;
            }
            shares[static_cast<std::size_t>(strongest)] += 1.0;
            covered += 1.0;
        }
    }
    for (double& s : shares) s = covered > 0.0 ? s / covered : 0.0;
    return shares;
}

void expectEveryCascadeShows(Scene& scene, const std::string& what) {
    ASSERT_GE(sunIndex(scene), 0) << what;
    const std::array<double, 3> shares = cascadeShares(scene, 320, 180);
    std::printf("[ measured ] %s: receiver pixels per cascade %.1f / %.1f / %.1f %%\n", what.c_str(), 100.0 * shares[0],
                100.0 * shares[1], 100.0 * shares[2]);
    for (std::size_t k = 0; k < shares.size(); ++k) {
        EXPECT_GE(shares[k], kMinCascadeShare) << what << ": cascade " << k;
    }
}

TEST(CascadeFit, DefaultSceneEveryCascadeColoursReceiverPixels) {
    Result<Scene> made = makeBuiltinScene("default");
    ASSERT_TRUE(made) << made.error().message;
    Scene scene = std::move(made).value();
    expectEveryCascadeShows(scene, "builtin:default");
}

TEST(CascadeFit, WideSunEveryCascadeColoursReceiverPixels) {
    Scene scene = wideSunScene();
    expectEveryCascadeShows(scene, "wide sun");
}

TEST(CascadeFit, StillCameraReusesEveryCascade) {
    Scene scene = wideSunScene();
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame first = test::renderFrame(runner, scene, 160, 90);
    const std::vector<ShadowLayerPlan> before = runner.shadows().frame().lights.at(0).layers;
    const test::RenderedFrame second = test::renderFrame(runner, scene, 160, 90);
    const std::vector<ShadowLayerPlan>& after = runner.shadows().frame().lights.at(0).layers;
    ASSERT_EQ(before.size(), 3u);
    ASSERT_EQ(after.size(), before.size());
    for (std::size_t k = 0; k < before.size(); ++k) {
        EXPECT_EQ(after[k].splitFar, before[k].splitFar) << "cascade " << k;
        EXPECT_EQ(after[k].lightFromWorld, before[k].lightFromWorld) << "cascade " << k;
        EXPECT_EQ(after[k].clipFromLight, before[k].clipFromLight) << "cascade " << k;
    }
    EXPECT_EQ(first.stats.shadowLayersDrawn, 3);
    EXPECT_EQ(second.stats.shadowLayersDrawn, 0);
    EXPECT_EQ(second.stats.shadowLayersReused, 3);
}

}  // namespace
}  // namespace shadow
