// Cascades fitted to the receivers visible on screen (engine/src/shadow/light_projection.cpp), as
// rendered: the debug cascade view (--debug cascade) of builtin:default and of a wide sun scene,
// in which every cascade must colour a share of the receiver pixels; and a still camera whose
// cascades are reused frame after frame. The planner's side, against brute force, is in
// cascade_fit_cpu_test.cpp.
#include <gtest/gtest.h>
#include <shadow/renderer.h>
#include <shadow/shadow_system.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

/// Least share of the receiver pixels each of n cascades must colour: 0.15 / n (5 % of three,
/// 3.75 % of four; a far cascade holds few pixels by perspective). Measured at 320x180 with the
/// cascades fitted to the visible receivers: builtin:default 60.9 / 31.9 / 7.2 %, the wide sun
/// 72.2 / 19.4 / 8.5 %, the sunfield sample (four, within their reach) 67.2 / 17.1 / 11.0 /
/// 4.6 %. Splitting the distances to the receivers' bounding box instead gave 4.1 / 76.7 /
/// 19.3 % and 72.5 / 22.0 / 5.5 % (640x360, shadow_render --debug cascade).
constexpr double kMinCascadeShareTimesCascades = 0.15;

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

/// Share of the covered pixels within the last cascade's view depth of the debug cascade view
/// that each of the sun's `cascades`
/// colours: the view tints cascade 0 red, 1 green, 2 blue, 3 yellow (0.8 of the channels, plus
/// 0.2 x visibility on all three, which taking the smallest channel away removes).
std::vector<double> cascadeShares(Scene& scene, int width, int height, int cascades) {
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
    // Pixels within the cascades' reach only (a sky dome or ground past the shadow distance is
    // in none of them).
    const CameraView& view = runner.lastCamera();
    const glm::dvec3 forward = -glm::dvec3(glm::transpose(view.viewFromWorld)[2]);
    const double reach =
        runner.shadows().frame().lights.at(static_cast<std::size_t>(sunIndex(scene))).layers.back().splitFar;
    const std::array<glm::vec3, 4> palette{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1),
                                           glm::vec3(1, 1, 0)};
    std::vector<double> shares(static_cast<std::size_t>(cascades), 0.0);
    double covered = 0.0;
    for (int y = 0; y < images.color.height; ++y) {
        for (int x = 0; x < images.color.width; ++x) {
            if (images.position.at(x, y, 3) < 0.5f) continue;
            const glm::dvec3 p(images.position.at(x, y, 0), images.position.at(x, y, 1), images.position.at(x, y, 2));
            if (glm::dot(p - view.wsPosition, forward) > reach) continue;
            glm::vec3 c(images.color.at(x, y, 0), images.color.at(x, y, 1), images.color.at(x, y, 2));
            c -= glm::vec3(std::min({c.x, c.y, c.z}));
            std::size_t nearest = 0;
            for (std::size_t k = 1; k < shares.size(); ++k) {
                if (glm::distance(c, 0.8f * palette[k]) < glm::distance(c, 0.8f * palette[nearest])) nearest = k;
            }
            shares[nearest] += 1.0;
            covered += 1.0;
        }
    }
    for (double& s : shares) s = covered > 0.0 ? s / covered : 0.0;
    return shares;
}

void expectEveryCascadeShows(Scene& scene, const std::string& what, int cascades = 3) {
    ASSERT_GE(sunIndex(scene), 0) << what;
    const std::vector<double> shares = cascadeShares(scene, 320, 180, cascades);
    std::string figures;
    for (double s : shares) figures += (figures.empty() ? "" : " / ") + std::to_string(100.0 * s).substr(0, 4);
    std::printf("[ measured ] %s: receiver pixels per cascade %s %%\n", what.c_str(), figures.c_str());
    for (std::size_t k = 0; k < shares.size(); ++k) {
        EXPECT_GE(shares[k], kMinCascadeShareTimesCascades / cascades) << what << ": cascade " << k;
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

// The sample scene of a sun over 300 m (samples/scenes/sunfield.gltf, four cascades), a scene
// the fit was not tuned on.
TEST(CascadeFit, SunfieldSampleEveryCascadeColoursReceiverPixels) {
    Result<Scene> loaded = loadGltf(test::sourcePath("samples/scenes/sunfield.gltf"));
    ASSERT_TRUE(loaded) << loaded.error().message;
    Scene scene = std::move(loaded).value();
    expectEveryCascadeShows(scene, "sunfield", 4);
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
