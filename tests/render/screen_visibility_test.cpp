// The screen-space visibility stage (RenderOptions::screenVisibility): at full resolution it is
// the forward passes' visibility to the AOV's last bit; at half resolution its upsample keeps
// the error against the ray-traced truth where forward has it; many lights, cut-outs' absence,
// the AOVs and the choice Auto makes.
#include <gtest/gtest.h>
#include <shadow/metrics.h>
#include <shadow/reference.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "render/material_test_support.h"
#include "render/render_test_support.h"
#include "shadow/truth_test_support.h"
#include "render/screen_visibility.h"

namespace shadow::screen_visibility_test {
namespace {

using Rendered = test::RenderedFrame;

Rendered renderWith(Scene& scene, ScreenVisibility setting, int width, int height, FrameRunner& runner) {
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.screenVisibility = setting;
    return test::renderFrame(runner, scene, options);
}

/// `scene` forward and through the stage at `setting`, each through a runner of its own.
std::pair<Rendered, Rendered> forwardAndStage(Scene& scene, ScreenVisibility setting, int width, int height) {
    FrameRunner forward, screen;
    Rendered a = renderWith(scene, ScreenVisibility::Off, width, height, forward);
    return {std::move(a), renderWith(scene, setting, width, height, screen)};
}

Scene builtin(const char* name, ShadowTechnique technique) {
    Result<Scene> made = makeBuiltinScene(name);
    if (!made) throw std::runtime_error(made.error().message);
    Scene scene = std::move(*made);
    scene.world.view<Shadow>().each([&](Entity, Shadow& s) { s.technique = technique; });
    return scene;
}

/// Largest difference and the fraction of pixels differing by more than `tolerance`.
struct Difference {
    float largest = 0.0f;
    double over = 0.0;
};

/// `tolerance` is absolute, plus `relative` of b's value.
Difference difference(const ImageF& a, const ImageF& b, float tolerance, float relative = 0.0f) {
    Difference d;
    std::size_t over = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const float e = std::abs(a.pixels[i] - b.pixels[i]) - relative * std::abs(b.pixels[i]);
        d.largest = std::max(d.largest, e);
        if (e > tolerance) ++over;
    }
    d.over = static_cast<double>(over) / static_cast<double>(std::max<std::size_t>(a.pixels.size(), 1));
    return d;
}

// The stage at full resolution runs each light's technique at the surface the surface pass
// stored: the same functions at the same points as forward. Tolerance: the RGBA8 visibility
// target's rounding (half of 1/255) and the octahedral normal's float error; 99.5 % of pixels
// within 1/255, the rest (silhouette pixels whose triangle plane comes from a different
// derivative quad) anywhere.
TEST(ScreenVisibility, FullResolutionIsForwardForEveryTechniqueAndLightType) {
    for (const ShadowTechnique t : {ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss,
                                    ShadowTechnique::Vsm, ShadowTechnique::MsmSoft}) {
        test::glContext();
        Scene scene = builtin("bunny", t);  // a sun, a spot and a point light
        FrameRunner forward, screen;
        const Rendered a = renderWith(scene, ScreenVisibility::Off, 160, 90, forward);
        const Rendered b = renderWith(scene, ScreenVisibility::Full, 160, 90, screen);
        ASSERT_EQ(a.images.visibility.size(), b.images.visibility.size());
        for (std::size_t l = 0; l < a.images.visibility.size(); ++l) {
            const Difference d = difference(b.images.visibility[l], a.images.visibility[l], 1.0f / 255.0f);
            std::printf("[ measured ] %s light %zu: largest %.4f, over 1/255 on %.3f %% of pixels\n", techniqueName(t),
                        l, d.largest, 100.0 * d.over);
            EXPECT_LT(d.over, 0.005) << techniqueName(t) << " light " << l;
        }
        // Colour: the same shading from the same inputs, but the normals pass through the octahedral
        // encoding and derivatives differ at silhouettes: within 1 % on 99 % of pixels.
        const Difference c = difference(b.images.color, a.images.color, 1e-4f, 0.01f);
        std::printf("[ measured ] %s colour: over 1 %% on %.3f %% of pixels\n", techniqueName(t), 100.0 * c.over);
        EXPECT_LT(c.over, 0.01) << techniqueName(t) << ": colour";
        EXPECT_EQ(difference(b.images.position, a.images.position, 1e-4f).over, 0.0) << techniqueName(t);
    }
}

// Half resolution, upsampled along surfaces and refined at full resolution where the samples
// disagree: PCSS's error against the truth on the bunny's spot within 5 % of forward's (+0.002),
// and PCF's on a second scene (the plates).
TEST(ScreenVisibility, HalfResolutionKeepsTheErrorAgainstTheTruth) {
    struct Case {
        const char* scene;
        ShadowTechnique technique;
    };
    for (const Case c : {Case{"bunny-spot", ShadowTechnique::Pcss}, Case{"plates", ShadowTechnique::Pcss},
                         Case{"plates", ShadowTechnique::Pcf}}) {
        test::glContext();
        Scene scene = builtin(c.scene, c.technique);
        FrameRunner forward, screen;
        const Rendered a = renderWith(scene, ScreenVisibility::Off, 240, 135, forward);
        const Rendered b = renderWith(scene, ScreenVisibility::Half, 240, 135, screen);
        const std::optional<reference::ReferenceResult> truth =
            test::truthAt(scene, forward.lastCamera(), a.images, 64);
        ASSERT_TRUE(truth.has_value());
        const double ea = test::light0Errors(a.images, *truth).rmse, eb = test::light0Errors(b.images, *truth).rmse;
        std::printf("[ measured ] %s %s: RMSE forward %.4f, half %.4f\n", c.scene, techniqueName(c.technique), ea, eb);
        EXPECT_LE(eb, 1.05 * ea + 0.002) << c.scene << " " << techniqueName(c.technique);
    }
}

// Shadows narrower than the stage's blocks: thin posts and a bar under a spot whose disk
// emitter (2 cm) leaves their shadows 2-5 cm wide, about one pixel at 320x240, four pixels per
// block at quarter resolution, so most of each shadow falls between the samples, which agree
// on lit. Each technique reports at its samples the narrowest feature it found near
// (SG_STAGE_FEATURE: PCSS's and the moment methods' searches, sdf's closest misses, a search of
// the block for PCF), the pixels nearest a sample with a feature narrower than its block are
// recomputed at full resolution, and a sample is blended only into pixels whose triangle faces
// as its own (a post's face is not the ground at its foot). Of the pixels forward shows darker
// than 0.5, the share that reads lighter than 0.5 through the stage: under 1 % for PCSS, PCF
// and sdf, 8 % for VSSM and MSM-soft, whose visibility on the posts' own faces changes from
// pixel to pixel (without the reports and the normals: PCSS 22 %, PCF 10 %, sdf 29 %, VSSM 27 %,
// MSM-soft 27 %).
TEST(ScreenVisibility, ShadowsNarrowerThanTheBlocksAreRefined) {
    struct Case {
        ShadowTechnique technique;
        double missed;
    };
    for (const Case c :
         {Case{ShadowTechnique::Pcss, 0.01}, Case{ShadowTechnique::Pcf, 0.01}, Case{ShadowTechnique::Sdf, 0.01},
          Case{ShadowTechnique::Vssm, 0.08}, Case{ShadowTechnique::MsmSoft, 0.08}}) {
        const ShadowTechnique t = c.technique;
        test::glContext();
        Scene scene;
        test::addGround(scene, 6.0f);
        for (int i = 0; i < 5; ++i) {
            const double x = -1.0 + 0.5 * i, z = 0.3 * (i % 2);
            test::addBox(scene, "post" + std::to_string(i), {x, 0.5, z}, {0.02, 0.5, 0.02});
        }
        // A thin bar above the ground, lying across the others' shadows.
        test::addBox(scene, "bar", {0.0, 0.15, 1.0}, {1.2, 0.015, 0.015});
        Camera camera;
        addCamera(scene, "camera", camera, {0.0, 2.5, 4.0}, {0.0, 0.0, 0.5});
        Light spot = test::pointSizedLight(LightType::Spot, 1.2f);
        spot.radius = 0.02f;
        Shadow shadow = test::hardShadow(2048);
        shadow.technique = t;
        addLight(scene, "spot", spot, shadow, {0.4, 3.0, -1.5}, glm::normalize(glm::dvec3(-0.2, -1.0, 0.8)));
        FrameRunner forward, screen;
        const Rendered a = renderWith(scene, ScreenVisibility::Off, 320, 240, forward);
        const Rendered b = renderWith(scene, ScreenVisibility::Quarter, 320, 240, screen);
        const ImageF& va = a.images.visibility[0];
        const ImageF& vb = b.images.visibility[0];
        int dark = 0, missed = 0;
        for (std::size_t i = 0; i < va.pixels.size(); ++i) {
            if (va.pixels[i] >= 0.5f) continue;
            ++dark;
            missed += vb.pixels[i] > 0.5f ? 1 : 0;
        }
        std::printf("[ measured ] %s: %d of %d pixels dark forward read lit through the stage\n", techniqueName(t),
                    missed, dark);
        ASSERT_GT(dark, 300) << techniqueName(t);  // the thin shadows are on screen
        EXPECT_LT(missed, c.missed * dark) << techniqueName(t);
    }
}

/// A box above the ground under nine point lights in a ring, PCSS and hard by turns (`mapSize`
/// texels): two lit passes, groups of four, four and one.
Scene nineLightScene(int mapSize) {
    Scene scene;
    test::addGround(scene, 6.0f);
    test::addBox(scene, "box", {0.0, 1.2, 0.0}, {0.5, 0.3, 0.5});
    addCamera(scene, "camera", Camera{}, {0.0, 5.5, 5.5}, {0.0, 0.0, 0.0});
    for (int i = 0; i < 9; ++i) {
        const double angle = 6.283185307179586 * i / 9;
        Shadow shadow = test::hardShadow(mapSize);
        shadow.technique = i % 2 == 0 ? ShadowTechnique::Pcss : ShadowTechnique::Hard;
        addLight(scene, "light " + std::to_string(i), test::pointSizedLight(LightType::Point), shadow,
                 {1.2 * std::cos(angle), 3.2, 1.2 * std::sin(angle)}, {0, -1, 0});
    }
    return scene;
}

// Nine lights: two lit passes, each group of four with its own visibility layer; every light's
// AOV is its own (the stage at full resolution equals forward).
TEST(ScreenVisibility, ManyLightsInTwoPassesKeepTheirOwnVisibility) {
    test::glContext();
    Scene scene = nineLightScene(256);
    const auto [a, b] = forwardAndStage(scene, ScreenVisibility::Full, 120, 90);
    EXPECT_EQ(b.stats.mainPasses, 2);
    // Triangles drawn: forward, the scene by each of the two lit passes; through the stage, by
    // its surface pass alone (the lit passes are full-screen triangles).
    std::int64_t sceneTriangles = 0;
    scene.world.view<Mesh>().each(
        [&](Entity, const Mesh& m) { sceneTriangles += static_cast<std::int64_t>(m.data->indices.size() / 3); });
    EXPECT_EQ(a.stats.mainTriangles, 2 * sceneTriangles);
    EXPECT_EQ(b.stats.mainTriangles, sceneTriangles);
    ASSERT_EQ(b.images.visibility.size(), 9u);
    double shadowed = 0.0;
    for (std::size_t l = 0; l < 9; ++l) {
        const Difference d = difference(b.images.visibility[l], a.images.visibility[l], 1.0f / 255.0f);
        EXPECT_LT(d.over, 0.005) << "light " << l;
        for (const float v : b.images.visibility[l].pixels) shadowed += v < 0.5f ? 1.0 : 0.0;
    }
    EXPECT_GT(shadowed, 0.0);  // the lights do cast shadows: the comparison is not of ones
    const Difference c = difference(b.images.color, a.images.color, 1e-4f, 0.01f);
    std::printf("[ measured ] colour: over 1 %% on %.3f %% of pixels\n", 100.0 * c.over);
    EXPECT_LT(c.over, 0.01);
}

// Four lights in one group at quarter resolution, each with its shadow edges in its own part of
// the screen: the resolve sends each pixel's lights to the refine one by one (those whose samples
// disagree or report a feature narrower than the blocks), and the refine recomputes only those,
// keeping the resolve's value for the others. Every light's visibility stays within 0.25 of
// forward on 99 % of pixels (measured 0-0.03 % over; with each light's disagreement sent to
// the next light's refine 0.07-1.45 %, with no light marked 2.1-2.8 %: its edges left blocky).
TEST(ScreenVisibility, EachLightOfAGroupIsRefinedWhereItsOwnEdgesAre) {
    test::glContext();
    Scene scene;
    test::addGround(scene, 6.0f);
    for (int i = 0; i < 4; ++i) {
        const double x = -1.5 + 1.0 * i;
        test::addBox(scene, "post" + std::to_string(i), {x, 0.6, 0.2 * (i % 2)}, {0.08, 0.6, 0.08});
    }
    addCamera(scene, "camera", Camera{}, {0.0, 3.0, 4.5}, {0.0, 0.0, 0.3});
    const std::array<ShadowTechnique, 4> techniques{ShadowTechnique::Pcss, ShadowTechnique::Hard, ShadowTechnique::Pcf,
                                                    ShadowTechnique::Pcss};
    for (int i = 0; i < 4; ++i) {
        Shadow shadow = test::hardShadow(1024);
        shadow.technique = techniques[static_cast<std::size_t>(i)];
        Light spot = test::pointSizedLight(LightType::Spot, 1.0f);
        spot.radius = 0.01f;
        const double x = -1.5 + 1.0 * i;
        addLight(scene, "spot " + std::to_string(i), spot, shadow, {x + 0.3, 2.5, -1.0},
                 glm::normalize(glm::dvec3(-0.1, -1.0, 0.6)));
    }
    const auto [a, b] = forwardAndStage(scene, ScreenVisibility::Quarter, 320, 240);
    ASSERT_EQ(b.images.visibility.size(), 4u);
    for (std::size_t l = 0; l < 4; ++l) {
        const Difference d = difference(b.images.visibility[l], a.images.visibility[l], 0.25f);
        int dark = 0;
        for (const float v : a.images.visibility[l].pixels) dark += v < 0.5f ? 1 : 0;
        std::printf("[ measured ] light %zu (%s): %d dark pixels, over 0.25 on %.2f %% of pixels\n", l,
                    techniqueName(techniques[l]), dark, 100.0 * d.over);
        EXPECT_GT(dark, 200) << "light " << l;  // its shadows are on screen
        EXPECT_LT(d.over, 0.01) << "light " << l;
    }
    // The colour: where the lit pass leaves a light to its correction (its marked pixels), the
    // correction adds that light's shading as forward does.
    const Difference c = difference(b.images.color, a.images.color, 1e-4f, 0.05f);
    std::printf("[ measured ] colour: over 5 %% on %.3f %% of pixels\n", 100.0 * c.over);
    EXPECT_LT(c.over, 0.01);
}

// The same nine lights at quarter resolution: the groups of four refine light by light over
// one prior (resolve and refine group after group), the group of one as a whole. Every light
// within 0.25 of forward on 99.7 % of pixels (measured 0-0.06 % over; with each light's
// disagreement sent to the next light's refine, the hard lights 0.49-1.02 %).
// A light of the second pass that reaches part of the screen: the lit passes write every
// light's visibility AOV over the whole screen (as forward does, wherever there is geometry), so
// the stage computes it there too, not only within the pass's reach. Before, the AOV outside the
// reach held what another group had left in the stage's targets (one of the courtyard's lights
// read 0.40 RMSE off forward at full resolution).
TEST(ScreenVisibility, ALocalLightOfALaterPassHasItsVisibilityOverTheScreen) {
    test::glContext();
    Scene scene = nineLightScene(256);
    scene.world.view<Light, Name>().each([&](Entity, Light& l, const Name& n) {
        if (n.value == "light 8") l.range = 2.5f;  // the box's top: a pass of its own, part of the screen
    });
    for (const ScreenVisibility setting : {ScreenVisibility::Full, ScreenVisibility::Quarter}) {
        const auto [a, b] = forwardAndStage(scene, setting, 160, 120);
        EXPECT_EQ(b.stats.mainPasses, 2);
        ASSERT_EQ(b.images.visibility.size(), 9u);
        const Difference d = difference(b.images.visibility[8], a.images.visibility[8], 0.25f);
        // What the stage's targets held before light 8's pass: the first group's shadows.
        int dark = 0;
        for (const float v : a.images.visibility[0].pixels) dark += v < 0.5f ? 1 : 0;
        std::printf("[ measured ] %s: light 8 over 0.25 on %.2f %% of pixels (light 0: %d dark)\n",
                    setting == ScreenVisibility::Full ? "full" : "quarter", 100.0 * d.over, dark);
        EXPECT_GT(dark, 100);
        EXPECT_LT(d.over, setting == ScreenVisibility::Full ? 0.001 : 0.01);
    }
}

TEST(ScreenVisibility, ManyLightsAtQuarterResolutionKeepTheirOwnVisibility) {
    test::glContext();
    Scene scene = nineLightScene(512);
    const auto [a, b] = forwardAndStage(scene, ScreenVisibility::Quarter, 320, 240);
    EXPECT_EQ(b.stats.mainPasses, 2);
    ASSERT_EQ(b.images.visibility.size(), 9u);
    for (std::size_t l = 0; l < 9; ++l) {
        const Difference d = difference(b.images.visibility[l], a.images.visibility[l], 0.25f);
        int dark = 0;
        for (const float v : a.images.visibility[l].pixels) dark += v < 0.5f ? 1 : 0;
        std::printf("[ measured ] light %zu: %d dark pixels, over 0.25 on %.2f %% of pixels\n", l, dark,
                    100.0 * d.over);
        EXPECT_GT(dark, 100) << "light " << l;
        EXPECT_LT(d.over, 0.003) << "light " << l;
    }
}

/// A ground with every map (a metal/rough checker, a wavy normal map, occlusion, emission on a
/// stripe), a metal box on it, a PCSS spot and a hemisphere ambient.
Scene pbrScene() {
    Scene scene;
    Material ground = test::gltfMaterial({0.8f, 0.7f, 0.5f}, 1.0f, 1.0f);
    ground.metallicRoughnessMap.texture = test::makeTexture("metal-rough", 64, [](float u, float v) {
        const bool metal = (static_cast<int>(u * 4.0f) + static_cast<int>(v * 4.0f)) % 2 == 0;
        return glm::u8vec4(0, metal ? 90 : 200, metal ? 255 : 0, 255);
    });
    ground.normalMap.texture = test::makeTexture("waves", 64, [](float u, float) {
        const float slope = 0.5f * std::sin(u * 25.0f);
        const glm::vec3 n = glm::normalize(glm::vec3(slope, 0.0f, 1.0f)) * 0.5f + 0.5f;
        return glm::u8vec4(glm::round(n * 255.0f), 255);
    });
    ground.occlusionMap.texture = test::makeTexture("occlusion", 64, [](float, float v) {
        return glm::u8vec4(static_cast<std::uint8_t>(100 + 155 * v), 0, 0, 255);
    });
    ground.emissive = glm::vec3(0.3f, 0.1f, 0.0f);
    ground.emissiveMap.texture = test::makeTexture("stripe", 64, [](float u, float) {
        return std::abs(u - 0.8f) < 0.05f ? glm::u8vec4(255) : glm::u8vec4(0, 0, 0, 255);
    });
    ground.emissiveMap.uvTransform = textureTransform({0.0f, 0.0f}, 0.3f, {1.0f, 1.0f});
    addMeshInstance(scene.world, "ground", test::makeTexturedPlane(3.0f, 8), test::placed(glm::dvec3(0.0)), ground);
    Material metal = test::gltfMaterial({0.95f, 0.64f, 0.54f}, 1.0f, 0.3f);
    metal.doubleSided = false;
    addMeshInstance(scene.world, "box", makeBoxMesh(glm::vec3(0.4f)), test::placed({0.0, 0.4, 0.0}), metal);
    addCamera(scene, "camera", Camera{}, {0.0, 3.5, 4.5}, {0.0, 0.0, 0.0});
    Shadow shadow = test::hardShadow(512);
    shadow.technique = ShadowTechnique::Pcss;
    Light spot = test::pointSizedLight(LightType::Spot, 0.9f);
    spot.intensity = 60.0f;
    addLight(scene, "spot", spot, shadow, {1.0, 3.5, 1.0}, glm::normalize(glm::dvec3(-0.3, -1.0, -0.3)));
    return scene;
}

// The same PBR scene forward and through the stage at full resolution: the material comes out
// of the surface targets (lighting normal and emission in their own) as forward reads it from
// the textures. Visibility as in the test above; colour within 1 % on 99 % of pixels (the
// remaining ones at silhouettes).
TEST(ScreenVisibility, FullResolutionIsForwardForATexturedPbrMaterial) {
    test::glContext();
    Scene pbr = pbrScene();
    FrameRunner forward, screen;
    RenderOptions options;
    const glm::vec3 sky(0.05f, 0.07f, 0.1f), groundLight(0.02f, 0.015f, 0.01f);
    auto render = [&](Scene& scene, ScreenVisibility where, FrameRunner& runner) {
        options.width = 160;
        options.height = 90;
        options.aovs = true;
        options.screenVisibility = where;
        options.ambientSky = sky;
        options.ambientGround = groundLight;
        FrameStats stats = runner.runFrame(scene, 0.0, scene.cameras.at(0), options);
        return runner.renderer().readback(runner.lastCamera(), stats);
    };
    const FrameImages a = render(pbr, ScreenVisibility::Off, forward);
    const FrameImages b = render(pbr, ScreenVisibility::Full, screen);
    ASSERT_EQ(a.visibility.size(), 1u);
    const Difference v = difference(b.visibility[0], a.visibility[0], 1.0f / 255.0f);
    EXPECT_LT(v.over, 0.005);
    const Difference c = difference(b.color, a.color, 1e-4f, 0.01f);
    std::printf("[ measured ] PBR colour: largest %.4f, over 1 %% on %.3f %% of pixels\n", c.largest, 100.0 * c.over);
    EXPECT_LT(c.over, 0.01);
    // The maps show: without them most of the picture changes by more than 1 %.
    Scene plain = pbrScene();
    plain.world.view<Material>().each([](Entity, Material& m) { m = test::gltfMaterial(m.baseColor, 0.0f, 1.0f); });
    FrameRunner third;
    const FrameImages p = render(plain, ScreenVisibility::Full, third);
    EXPECT_GT(difference(b.color, p.color, 1e-4f, 0.01f).over, 0.3);
}

TEST(ScreenVisibility, AutoRunsTheStageWhereItMeasuredFaster) {
    using render::PassLights;
    auto passWith = [](std::initializer_list<int> techniques) {
        PassLights p;
        p.sceneLight.fill(-1);
        for (const int t : techniques) {
            p.variant.technique[static_cast<std::size_t>(p.variant.lights)] = static_cast<std::uint8_t>(t);
            ++p.variant.lights;
        }
        return p;
    };
    const std::vector<PassLights> onePcss{passWith({SG_TECH_PCSS})};
    const std::vector<PassLights> onePcf{passWith({SG_TECH_PCF, SG_TECH_HARD})};
    const std::vector<PassLights> twoSoft{passWith({SG_TECH_PCF, SG_TECH_HARD, SG_TECH_PCSS})};
    const std::vector<PassLights> sdf{passWith({SG_TECH_SDF})};
    const std::vector<PassLights> hard{passWith({SG_TECH_HARD, SG_TECH_HARD, SG_TECH_HARD})};
    const ShadowFrame frame;
    EXPECT_TRUE(render::screenStagePays(ScreenVisibility::Auto, frame, onePcss, 720));
    // One PCF light: forward below 720 rows, the stage at quarter resolution from them.
    EXPECT_FALSE(render::screenStagePays(ScreenVisibility::Auto, frame, onePcf, 719));
    EXPECT_TRUE(render::screenStagePays(ScreenVisibility::Auto, frame, onePcf, 720));
    EXPECT_TRUE(render::screenStagePays(ScreenVisibility::Auto, frame, twoSoft, 720));
    EXPECT_TRUE(render::screenStagePays(ScreenVisibility::Auto, frame, sdf, 720));
    EXPECT_FALSE(render::screenStagePays(ScreenVisibility::Auto, frame, hard, 720));
    // Small images stay forward: their penumbrae are too few pixels wide for half resolution.
    EXPECT_FALSE(render::screenStagePays(ScreenVisibility::Auto, frame, sdf, kMinStageHeight - 1));
    EXPECT_TRUE(render::screenStagePays(ScreenVisibility::Half, frame, sdf, 90));
    EXPECT_FALSE(render::screenStagePays(ScreenVisibility::Off, frame, sdf, 720));
    EXPECT_TRUE(render::screenStagePays(ScreenVisibility::Half, frame, onePcss, 720));
    // A light with contact shadows, which only the stage draws.
    ShadowFrame contact;
    contact.lights.resize(1);
    contact.lights[0].settings.contactShadows = true;
    contact.lights[0].settings.technique = ShadowTechnique::Hard;
    contact.lights[0].layers.resize(1);
    std::vector<PassLights> oneHard{passWith({SG_TECH_HARD})};
    oneHard[0].sceneLight[0] = 0;
    EXPECT_TRUE(render::screenStagePays(ScreenVisibility::Auto, contact, oneHard, 240));
    EXPECT_LT(render::contactLengthUniform(contact.lights[0]), 0.0f);  // automatic: pixels
    contact.lights[0].settings.contactLength = 0.25f;
    EXPECT_EQ(render::contactLengthUniform(contact.lights[0]), 0.25f);
    contact.lights[0].settings.contactShadows = false;
    EXPECT_FALSE(render::screenStagePays(ScreenVisibility::Auto, contact, oneHard, 240));
    // Auto's resolution: full for hard edges; for filtered ones half, quarter from 720 rows.
    EXPECT_EQ(render::visibilityDivisor(ScreenVisibility::Auto, twoSoft[0].variant, 1, 1, 720), 1);
    EXPECT_EQ(render::visibilityDivisor(ScreenVisibility::Auto, twoSoft[0].variant, 0, 3, 719), 2);
    EXPECT_EQ(render::visibilityDivisor(ScreenVisibility::Auto, twoSoft[0].variant, 0, 3, 720), 4);
    EXPECT_EQ(render::visibilityDivisor(ScreenVisibility::Quarter, hard[0].variant, 0, 3, 90), 4);
    EXPECT_EQ(render::visibilityDivisor(ScreenVisibility::Auto, twoSoft[0].variant, 0, 3, 240), 1);
}

/// Ground pixels in the cube's true shadow, and how many of them and of the lit ones (not next
/// to a shadowed pixel: edge pixels go either way) read as shadowed (visibility < 0.5).
struct ContactCount {
    int shadowed = 0, shadowedDark = 0, lit = 0, litDark = 0;
};

ContactCount countContact(const FrameImages& images, const test::AnalyticLight& sun, const DAabb& cube) {
    const int w = images.position.width, h = images.position.height;
    std::vector<int> truth(static_cast<std::size_t>(w) * h, -1);  // -1 not ground, 0 lit, 1 shadowed
    const std::array<DAabb, 1> boxes{cube};
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (!test::isGroundPixel(images, x, y)) continue;
            truth[static_cast<std::size_t>(y) * w + x] =
                test::analyticallyLit(sun, test::positionAt(images, x, y), boxes) ? 0 : 1;
        }
    }
    ContactCount c;
    for (int y = 1; y + 1 < h; ++y) {
        for (int x = 1; x + 1 < w; ++x) {
            const int t = truth[static_cast<std::size_t>(y) * w + x];
            if (t < 0) continue;
            const bool dark = images.visibility[0].at(x, y, 0) < 0.5f;
            if (t == 1) {
                ++c.shadowed;
                c.shadowedDark += dark ? 1 : 0;
                continue;
            }
            bool nearShadow = false;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx)
                    nearShadow = nearShadow || truth[static_cast<std::size_t>(y + dy) * w + x + dx] == 1;
            }
            if (nearShadow) continue;
            ++c.lit;
            c.litDark += dark ? 1 : 0;
        }
    }
    return c;
}

// A 3 cm cube on the ground under a sun whose one cascade covers 200 m (a 1024^2 map: 20 cm
// texels): the map cannot hold its shadow; contact shadows draw at least half of its true
// footprint, and darken under 0.1 % of the open ground. Without them (the control) the shadow
// is missing, which is what makes the first check able to fail.
TEST(ContactShadows, ASmallCubeUnderAWideSunCastsItsShadow) {
    test::glContext();
    const glm::dvec3 center{0.0, 0.015, 0.0}, half{0.015, 0.015, 0.015};
    const glm::dvec3 sunDirection = glm::normalize(glm::dvec3(1.0, -1.2, -0.6));
    for (const bool contact : {false, true}) {
        Scene scene;
        test::addGround(scene, 100.0f);
        test::addBox(scene, "cube", center, half);
        Camera camera;
        camera.znear = 0.01f;
        // Close to the cube, looking along the ground: the cascade spans the whole 200 m.
        addCamera(scene, "camera", camera, {0.1, 0.05, 0.12}, {0.0, 0.01, 0.0});
        Shadow shadow = test::hardShadow(1024);
        shadow.shadowDistance = 200.0f;
        shadow.contactShadows = contact;
        addLight(scene, "sun", test::pointSizedLight(LightType::Directional), shadow, {0.0, 10.0, 0.0}, sunDirection);
        FrameRunner runner;
        const Rendered frame = renderWith(scene, ScreenVisibility::Auto, 160, 120, runner);
        const ContactCount c =
            countContact(frame.images, {LightType::Directional, {}, sunDirection}, test::boxBounds(center, half));
        std::printf("[ measured ] contact %s: %d of %d shadowed ground px dark, %d of %d lit px dark\n",
                    contact ? "on" : "off", c.shadowedDark, c.shadowed, c.litDark, c.lit);
        ASSERT_GT(c.shadowed, 50);  // the shadow is on screen and many pixels wide
        if (contact) {
            EXPECT_GE(c.shadowedDark, c.shadowed / 2);
            EXPECT_LT(c.litDark, c.lit / 1000 + 1);
        } else {
            EXPECT_LT(c.shadowedDark, c.shadowed / 2);
        }
    }
}

// A second scene, not the one the march was tuned on: contact shadows on the bunny's spot (a
// scanned, bumpy mesh on a ground) must not add error against the truth where the map already
// holds the shadow: RMSE within 5 % (+0.002) of the same stage (half resolution) without them.
TEST(ContactShadows, AddNoErrorWhereTheMapHoldsTheShadow) {
    test::glContext();
    double rmse[2] = {0.0, 0.0};
    for (const bool contact : {false, true}) {
        Scene scene = builtin("bunny-spot", ShadowTechnique::Pcss);
        scene.world.view<Shadow>().each([&](Entity, Shadow& s) { s.contactShadows = contact; });
        FrameRunner runner;
        const Rendered frame = renderWith(scene, ScreenVisibility::Half, 240, 135, runner);
        const std::optional<reference::ReferenceResult> truth =
            test::truthAt(scene, runner.lastCamera(), frame.images, 64);
        ASSERT_TRUE(truth.has_value());
        const VisibilityErrors e = test::light0Errors(frame.images, *truth);
        rmse[contact ? 1 : 0] = e.rmse;
        std::printf("[ measured ] bunny-spot pcss, contact %s: RMSE %.4f, acne %.4f %%\n", contact ? "on" : "off",
                    e.rmse, 100.0 * e.acneFraction);
    }
    EXPECT_LE(rmse[1], 1.05 * rmse[0] + 0.002);
}

TEST(ScreenVisibility, SettingNamesRoundTrip) {
    for (const ScreenVisibility v : {ScreenVisibility::Off, ScreenVisibility::Auto, ScreenVisibility::Full,
                                     ScreenVisibility::Half, ScreenVisibility::Quarter}) {
        EXPECT_EQ(parseScreenVisibility(screenVisibilityName(v)), v);
    }
    EXPECT_FALSE(parseScreenVisibility("halfway").has_value());
    EXPECT_FALSE(parseScreenVisibility("").has_value());
}

}  // namespace
}  // namespace shadow::screen_visibility_test
