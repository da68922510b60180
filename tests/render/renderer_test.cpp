// The forward renderer: lights in passes of eight, visibility per light, shader variants per
// technique set, and the position and depth AOVs against the camera's geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "render/material_test_support.h"
#include "render/render_test_support.h"

namespace shadow::renderer_test {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;
const glm::dvec3 kBoxCenter{0.0, 1.2, 0.0};
const glm::dvec3 kBoxHalf{0.5, 0.3, 0.5};

/// A ground, a floating box, and a camera looking down at them.
Scene boxOverGround() {
    Scene scene;
    test::addGround(scene, 6.0f);
    test::addBox(scene, "box", kBoxCenter, kBoxHalf);
    addCamera(scene, "camera", Camera{}, {0.0, 5.5, 5.5}, {0.0, 0.0, 0.0});
    return scene;
}

/// `count` point lights in a ring above the box, each throwing the box's shadow another way.
std::vector<glm::dvec3> ringOfLights(Scene& scene, int count, int mapSize) {
    std::vector<glm::dvec3> positions;
    for (int i = 0; i < count; ++i) {
        const double angle = 6.283185307179586 * i / count;
        const glm::dvec3 p(1.2 * std::cos(angle), 3.2, 1.2 * std::sin(angle));
        addLight(scene, "light " + std::to_string(i), test::pointSizedLight(LightType::Point),
                 test::hardShadow(mapSize), p, {0, -1, 0});
        positions.push_back(p);
    }
    return positions;
}

/// Compares light `i`'s visibility with the ray-cast shadow of the box over the ground.
struct ShadowAgreement {
    int ground = 0;
    int shadowed = 0;
    int mismatches = 0;
};

ShadowAgreement agreement(const FrameImages& images, std::size_t light, const glm::dvec3& position) {
    ShadowAgreement a;
    const test::AnalyticLight analytic{LightType::Point, position, {0, -1, 0}};
    const std::array<DAabb, 1> boxes{test::boxBounds(kBoxCenter, kBoxHalf)};
    for (int y = 0; y < images.position.height; ++y) {
        for (int x = 0; x < images.position.width; ++x) {
            if (!test::isGroundPixel(images, x, y)) continue;
            ++a.ground;
            const bool lit = test::analyticallyLit(analytic, test::positionAt(images, x, y), boxes);
            a.shadowed += lit ? 0 : 1;
            if ((images.visibility[light].at(x, y, 0) > 0.5f) != lit) ++a.mismatches;
        }
    }
    return a;
}

/// What the default material of the ground (normal +Y) at pixel (x, y) reflects of the default
/// uniform ambient, seen from `eye` (shaders/lighting.glsl's ambientShading in closed form).
double groundAmbient(const FrameImages& images, int x, int y, const glm::dvec3& eye) {
    const Material m;
    const double nDotV = glm::normalize(eye - test::positionAt(images, x, y)).y;
    return test::ambientClosedForm(m.albedo.x, m.specular.x, m.shininess, nDotV, RenderOptions{}.ambientSky.x);
}

TEST(Renderer, SceneWithoutLightsRendersAmbientOnly) {
    test::glContext();  // before any engine object: they need a current context
    Scene scene = boxOverGround();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    test::expectSaneAovs(frame.images);
    EXPECT_TRUE(frame.images.visibility.empty());
    EXPECT_EQ(frame.stats.mainPasses, 1);
    const glm::dvec3 eye = runner.lastCamera().wsPosition;
    int covered = 0;
    int wrong = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const bool geometry = frame.images.position.at(x, y, 3) > 0.5f;
            covered += geometry ? 1 : 0;
            // The ground's in closed form; the box's faces between no specular and all of it.
            const bool ground = test::isGroundPixel(frame.images, x, y);
            const double want = ground ? groundAmbient(frame.images, x, y, eye) : 0.0;
            for (int c = 0; c < 3; ++c) {
                const float got = frame.images.color.at(x, y, c);
                if (ground || !geometry) {
                    if (std::abs(got - want) > 1e-5 + 1e-4 * want) ++wrong;
                } else if (got < 0.9 * RenderOptions{}.ambientSky.x * Material{}.albedo.x || got > 0.04f) {
                    ++wrong;
                }
            }
        }
    }
    EXPECT_GT(covered, kWidth * kHeight / 4);
    EXPECT_EQ(wrong, 0) << "colour must be the ambient's on geometry and 0 elsewhere";
}

TEST(Renderer, NineLightsRenderInTwoPassesWithAVisibilityEach) {
    test::glContext();  // before any engine object: they need a current context
    Scene scene = boxOverGround();
    const std::vector<glm::dvec3> positions = ringOfLights(scene, 9, 512);
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    test::expectSaneAovs(frame.images);
    EXPECT_EQ(frame.stats.mainPasses, 2);
    ASSERT_EQ(frame.images.visibility.size(), 9u);
    for (std::size_t i = 0; i < 9; ++i) {
        const ImageF& v = frame.images.visibility[i];
        EXPECT_EQ(v.width, kWidth);
        EXPECT_EQ(v.height, kHeight);
        EXPECT_EQ(v.channels, 1);
        // Each light's AOV holds that light's own shadow: the box seen from its position. Edge
        // pixels may go either way; 2 % of the ground is far more than the edges cover here.
        const ShadowAgreement a = agreement(frame.images, i, positions[i]);
        std::printf("[ measured ] light %zu: shadowed %.2f %% of %d ground px, mismatches %.3f %%\n", i,
                    100.0 * a.shadowed / std::max(a.ground, 1), a.ground, 100.0 * a.mismatches / std::max(a.ground, 1));
        EXPECT_GT(a.shadowed, 0.02 * a.ground) << "light " << i;
        EXPECT_LT(a.mismatches, 0.02 * a.ground) << "light " << i << ": visibility is not this light's shadow";
    }
}

// Lights 0-7 are dark; only light 8, shaded by the second pass, adds light. The second pass
// must add onto the first (ambient) rather than replace it.
TEST(Renderer, LightsBeyondTheFirstPassAddTheirLight) {
    test::glContext();  // before any engine object: they need a current context
    Scene scene = boxOverGround();
    ringOfLights(scene, 9, 512);
    for (std::size_t i = 0; i < 8; ++i) scene.world.get<Light>(scene.lights[i]).intensity = 0.0f;
    // Bright enough that its diffuse term is 10x the ambient even at the far corners.
    scene.world.get<Light>(scene.lights[8]).intensity = 200.0f;
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    ASSERT_EQ(frame.images.visibility.size(), 9u);
    const glm::dvec3 eye = runner.lastCamera().wsPosition;
    int lit = 0;
    int shadowed = 0;
    int brightInShadow = 0;
    int darkInLight = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (!test::isGroundPixel(frame.images, x, y)) continue;
            const float v = frame.images.visibility[8].at(x, y, 0);
            const float c = frame.images.color.at(x, y, 1);
            const double ambient = groundAmbient(frame.images, x, y, eye);
            if (v == 0.0f) {
                ++shadowed;
                if (std::abs(c - ambient) > 1e-4) ++brightInShadow;
            } else if (v == 1.0f) {
                ++lit;
                if (c < 2.0f * ambient) ++darkInLight;
            }
        }
    }
    EXPECT_GT(shadowed, 100);
    EXPECT_GT(lit, 100);
    EXPECT_EQ(brightInShadow, 0) << "in light 8's shadow only the first pass's ambient remains";
    EXPECT_EQ(darkInLight, 0) << "light 8 (second pass) adds nothing";
}

TEST(Renderer, SteadyStateCompilesNothingAndRedrawsNoLayer) {
    test::glContext();  // before any engine object: they need a current context
    Scene scene = boxOverGround();
    ringOfLights(scene, 2, 256);
    FrameRunner runner;
    const test::RenderedFrame first = test::renderFrame(runner, scene, kWidth, kHeight);
    EXPECT_GE(first.stats.programsCompiled, 1);
    EXPECT_GT(first.stats.shadowLayersDrawn, 0);
    const test::RenderedFrame second = test::renderFrame(runner, scene, kWidth, kHeight);
    EXPECT_EQ(second.stats.programsCompiled, 0);
    EXPECT_EQ(second.stats.shadowLayersDrawn, 0);
    EXPECT_EQ(second.stats.shadowLayersReused, 12);
    // Reused layers must still shadow the same pixels.
    ASSERT_EQ(second.images.visibility.size(), 2u);
    EXPECT_EQ(second.images.visibility[0].pixels, first.images.visibility[0].pixels);
}

TEST(Renderer, LightWithTechniqueNoneHasVisibilityOneEverywhere) {
    test::glContext();  // before any engine object: they need a current context
    Scene scene = boxOverGround();
    Shadow none = test::hardShadow();
    none.technique = ShadowTechnique::None;
    // One light never had a Shadow component; the other has one switched to None.
    addLight(scene, "unshadowed", test::pointSizedLight(LightType::Point), none, {0.3, 3.2, 0.2}, {0, -1, 0});
    const Entity off = addLight(scene, "switched off", test::pointSizedLight(LightType::Spot), test::hardShadow(),
                                {-0.3, 3.5, 0.0}, {0, -1, 0});
    scene.world.get<Shadow>(off).technique = ShadowTechnique::None;
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    test::expectSaneAovs(frame.images);
    ASSERT_EQ(frame.images.visibility.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        int notOne = 0;
        for (float v : frame.images.visibility[i].pixels) notOne += v == 1.0f ? 0 : 1;
        EXPECT_EQ(notOne, 0) << "light " << i;
    }
    for (const ShadowLightPlan& light : runner.shadows().frame().lights) {
        EXPECT_FALSE(light.hasMap()) << light.name << ": no shadow map for technique None";
    }
}

/// The label of the program the renderer left bound, or "" when none is bound.
std::string boundProgramLabel() {
    GLint program = 0;
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &program);
    if (program == 0) return "";
    auto getLabel = reinterpret_cast<PFNGLGETOBJECTLABELPROC>(test::glContext().loader()("glGetObjectLabel"));
    if (getLabel == nullptr) return "";
    std::array<char, 256> label{};
    GLsizei length = 0;
    getLabel(GL_PROGRAM, static_cast<GLuint>(program), static_cast<GLsizei>(label.size()), &length, label.data());
    return std::string(label.data(), static_cast<std::size_t>(length));
}

// The variant is compiled for the set of techniques in use: a PCF-only frame builds no PCSS
// code, a new set builds once, and a set seen before is reused.
TEST(Renderer, CompilesOnlyTheTechniquesInUse) {
    test::glContext();  // before any engine object: they need a current context
    Scene scene = boxOverGround();
    Shadow pcf = test::hardShadow(256);
    pcf.technique = ShadowTechnique::Pcf;
    addLight(scene, "a", test::pointSizedLight(LightType::Spot), pcf, {0.5, 3.5, 0}, {0, -1, 0});
    const Entity b = addLight(scene, "b", test::pointSizedLight(LightType::Spot), pcf, {-0.5, 3.5, 0}, {0, -1, 0});
    FrameRunner runner;

    const test::RenderedFrame f1 = test::renderFrame(runner, scene, kWidth, kHeight);
    // The shadow passes' two (the depth pass, PCF's min/max pyramid) and one lit program.
    EXPECT_EQ(f1.stats.programsCompiled, 3);
    const std::string pcfLabel = boundProgramLabel();
    if (!pcfLabel.empty()) {
        EXPECT_NE(pcfLabel.find(":pcf"), std::string::npos) << pcfLabel;
        EXPECT_EQ(pcfLabel.find(":pcss"), std::string::npos) << pcfLabel;
        EXPECT_EQ(pcfLabel.find(":hard"), std::string::npos) << pcfLabel;
    }
    EXPECT_EQ(test::renderFrame(runner, scene, kWidth, kHeight).stats.programsCompiled, 0);

    scene.world.get<Shadow>(b).technique = ShadowTechnique::Pcss;
    EXPECT_EQ(test::renderFrame(runner, scene, kWidth, kHeight).stats.programsCompiled, 1)
        << "new configuration {spot:pcf, spot:pcss}";
    const std::string bothLabel = boundProgramLabel();
    if (!bothLabel.empty()) {
        EXPECT_NE(bothLabel.find(":pcf"), std::string::npos) << bothLabel;
        EXPECT_NE(bothLabel.find(":pcss"), std::string::npos) << bothLabel;
    }

    scene.world.get<Shadow>(b).technique = ShadowTechnique::Pcf;
    EXPECT_EQ(test::renderFrame(runner, scene, kWidth, kHeight).stats.programsCompiled, 0) << "{PCF} is cached";
    std::printf("[ measured ] labels: '%s', '%s'\n", pcfLabel.c_str(), bothLabel.c_str());
}

// The renderer owns its mesh cache and collects it: the shadow maps draw from the same cache
// (FrameRunner hands it to them) and never collect it.
TEST(Renderer, CollectsTheMeshCacheItOwns) {
    test::glContext();
    Scene scene = boxOverGround();
    ringOfLights(scene, 1, 256);
    const Entity extra = test::addBox(scene, "extra", {2.0, 0.5, 0.0}, {0.2, 0.5, 0.2});
    FrameRunner runner;
    (void)test::renderFrame(runner, scene, kWidth, kHeight);
    EXPECT_EQ(runner.renderer().meshes().size(), 3u);  // ground, box, extra
    scene.world.destroy(extra);                        // its MeshData dies with its only instance
    (void)test::renderFrame(runner, scene, kWidth, kHeight);
    EXPECT_EQ(runner.renderer().meshes().size(), 2u);
    EXPECT_EQ(runner.shadows().meshes().size(), 0u) << "the system's own cache is not the one drawn from";
}

/// Camera ray through the centre of pixel (x, y), (0, 0) the top-left, in world space.
glm::dvec3 pixelRay(const CameraView& view, int x, int y, int width, int height) {
    const double ndcX = 2.0 * (x + 0.5) / width - 1.0;
    const double ndcY = 1.0 - 2.0 * (y + 0.5) / height;
    const double ty = std::tan(0.5 * static_cast<double>(view.yfov));
    const double tx = ty * static_cast<double>(view.aspect);
    const glm::dmat3 worldFromView(glm::inverse(view.viewFromWorld));
    return glm::normalize(worldFromView * glm::dvec3(ndcX * tx, ndcY * ty, -1.0));
}

// A ground far larger than the view with its edge and the sky in sight; every pixel is checked
// against the intersection of its camera ray with y = 0.
TEST(Renderer, PositionAndDepthAovsMatchTheCameraRayHitOnTheGround) {
    test::glContext();  // before any engine object: they need a current context
    constexpr double kHalf = 30.0;
    Scene scene;
    test::addGround(scene, static_cast<float>(kHalf));
    Camera camera;
    camera.znear = 0.1f;
    camera.zfar = 200.0f;
    addCamera(scene, "camera", camera, {1.0, 2.5, 6.0}, {0.3, 0.0, -4.0});
    addLight(scene, "sun", test::pointSizedLight(LightType::Directional), test::hardShadow(256), {0, 10, 0},
             {0.3, -1.0, 0.2});
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, kWidth, kHeight);
    test::expectSaneAovs(frame.images);
    const CameraView view = runner.lastCamera();
    ASSERT_FLOAT_EQ(view.aspect, static_cast<float>(kWidth) / kHeight);

    int hits = 0;
    int misses = 0;
    double worstPosition = 0.0;
    double worstDepth = 0.0;
    int coverageWrong = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::dvec3 dir = pixelRay(view, x, y, kWidth, kHeight);
            const bool covered = frame.images.position.at(x, y, 3) > 0.5f;
            const double t = dir.y < 0.0 ? -view.wsPosition.y / dir.y : -1.0;
            const glm::dvec3 hit = view.wsPosition + t * dir;
            const bool onGround = t > 0.0 && std::abs(hit.x) < kHalf && std::abs(hit.z) < kHalf;
            // Leave out the pixels a rasteriser may decide either way: along the ground's edge and
            // at the horizon, where a pixel spans metres of ground.
            const bool ambiguous =
                t > 100.0 ||
                (t > 0.0 && (std::abs(std::abs(hit.x) - kHalf) < 0.5 || std::abs(std::abs(hit.z) - kHalf) < 0.5));
            if (ambiguous) continue;
            if (covered != onGround) {
                ++coverageWrong;
                continue;
            }
            if (!onGround) {
                ++misses;
                EXPECT_EQ(frame.images.depth.at(x, y, 0), 0.0f) << "background depth at " << x << "," << y;
                continue;
            }
            ++hits;
            worstPosition = std::max(worstPosition, glm::distance(test::positionAt(frame.images, x, y), hit));
            worstDepth = std::max(worstDepth, std::abs(frame.images.depth.at(x, y, 0) - t));
        }
    }
    std::printf("[ measured ] %d ground px, %d background px: position error %.2e m, depth error %.2e m\n", hits,
                misses, worstPosition, worstDepth);
    EXPECT_GT(hits, kWidth * kHeight / 3);
    EXPECT_GT(misses, kWidth * 4) << "the sky must be in view";
    EXPECT_EQ(coverageWrong, 0);
    EXPECT_LT(worstPosition, 1e-3) << "position AOV (m)";
    EXPECT_LT(worstDepth, 1e-3) << "depth AOV: distance from the camera (m)";
}

}  // namespace
}  // namespace shadow::renderer_test
