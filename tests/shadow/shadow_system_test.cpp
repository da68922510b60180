// The shadow system split by job (engine/src/shadow/shadow_system.cpp and the parts it owns:
// ShadowPlanner, ShadowMaps, ShadowShaderContract, ShadowMask): a game that uses the parts apart
// gets what the facade gives, each part reads what it is handed as const, and the map memory
// stats.json reports is what the memory budget counts.
#include <gtest/gtest.h>
#include <shadow/shader_contract.h>
#include <shadow/shadow_maps.h>
#include <shadow/shadow_mask.h>
#include <shadow/shadow_planner.h>
#include <shadow/shadow_system.h>

#include <algorithm>
#include <array>
#include <functional>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "gl/gl_api.h"
#include "render/render_test_support.h"
#include "test_support.h"

namespace shadow::shadow_system_test {
namespace {

// The parts take what they read as const: a frame, maps and a world handed to them cannot be
// changed through them.
static_assert(std::is_invocable_v<decltype(&ShadowPlanner::prepare), ShadowPlanner&, const World&, const CameraView&,
                                  const std::vector<Entity>&>);
static_assert(std::is_invocable_v<decltype(&ShadowMaps::render), ShadowMaps&, const ShadowFrame&, const World&,
                                  MeshCache&, FrameStats&>);
static_assert(std::is_invocable_v<decltype(&ShadowShaderContract::inputs), ShadowShaderContract&, const ShadowFrame&,
                                  const ShadowMaps&, std::span<const int>, const glm::dvec3&>);
static_assert(std::is_invocable_v<decltype(&ShadowMask::render), ShadowMask&, const ShadowFrame&, const ShadowMaps&,
                                  std::span<const int>, const ShadowMaskRequest&, FrameStats&>);

constexpr int kWidth = 64;
constexpr int kHeight = 48;

/// The visibility mask of lights 0-2 over `depth` (window depth, rows bottom first).
std::vector<float> maskOf(const std::function<void(const ShadowMaskRequest&, FrameStats&)>& render,
                          const CameraView& camera, const std::vector<float>& windowDepth) {
    GLuint depth = 0, target = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
    gl.TextureStorage2D(depth, 1, GL_R32F, kWidth, kHeight);
    auto upload = reinterpret_cast<PFNGLTEXTURESUBIMAGE2DPROC>(test::glContext().loader()("glTextureSubImage2D"));
    upload(depth, 0, 0, 0, kWidth, kHeight, GL_RED, GL_FLOAT, windowDepth.data());
    gl.CreateTextures(GL_TEXTURE_2D, 1, &target);
    gl.TextureStorage2D(target, 1, GL_RGBA32F, kWidth, kHeight);
    ShadowMaskRequest request;
    request.depthTexture = GlTexture{depth};
    request.target = GlTexture{target};
    request.width = kWidth;
    request.height = kHeight;
    request.camera = camera;
    FrameStats stats;
    render(request, stats);
    std::vector<float> pixels(std::size_t{kWidth} * kHeight * 4);
    gl.GetTextureSubImage(target, 0, 0, 0, 0, kWidth, kHeight, 1, GL_RGBA, GL_FLOAT,
                          static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
    gl.DeleteTextures(1, &depth);
    gl.DeleteTextures(1, &target);
    return pixels;
}

TEST(ShadowSystem, ThePartsUsedApartGiveWhatTheFacadeGives) {
    test::glContext();
    Scene scene = test::threeLightScene();
    FrameRunner view;  // the scene's depth, for the masks
    const test::RenderedFrame seen = test::renderFrame(view, scene, kWidth, kHeight);
    const CameraView camera = view.lastCamera();
    const std::vector<float> depth = test::windowDepth(seen.images.position, camera);
    const std::array<int, 3> lights{0, 1, 2};

    ShadowSystem facade;
    facade.prepare(scene.world, camera, scene.lights);
    FrameStats facadeStats;
    facade.render(scene.world, facadeStats);

    // A game's own assembly: its planner with the context's limits, maps, contract, mask, cache.
    const World& world = scene.world;
    ShadowPlanner planner;
    planner.setLimits(facade.planner().limits());
    ShadowMaps maps;
    ShadowShaderContract contract;
    ShadowMask mask;
    MeshCache meshes;
    const ShadowFrame& frame = planner.prepare(world, camera, scene.lights);
    FrameStats partStats;
    maps.render(frame, world, meshes, partStats);
    meshes.collect();

    ASSERT_EQ(frame.lights.size(), facade.frame().lights.size());
    int layers = 0;
    for (std::size_t i = 0; i < frame.lights.size(); ++i) {
        ASSERT_EQ(maps.layersOf(i), facade.maps().layersOf(i));
        for (int k = 0; k < maps.layersOf(i); ++k, ++layers) {
            EXPECT_EQ(maps.readLayerDepth(i, k), facade.maps().readLayerDepth(i, k)) << "light " << i << " layer " << k;
        }
        EXPECT_NE(maps.textureOf(i), facade.maps().textureOf(i)) << "each owns its maps";
    }
    EXPECT_GT(layers, 6);
    EXPECT_EQ(partStats.shadowLayersDrawn, facadeStats.shadowLayersDrawn);
    EXPECT_EQ(maps.textureOfLight(scene.lights[1]), maps.textureOf(1));

    const ShadowShaderInputs partInputs = contract.inputs(frame, maps, lights, camera.wsPosition);
    const ShadowShaderInputs& facadeInputs = facade.shaderInputs(lights, camera.wsPosition);
    EXPECT_EQ(partInputs.techniques, facadeInputs.techniques);
    EXPECT_EQ(partInputs.type, facadeInputs.type);
    EXPECT_EQ(partInputs.technique, facadeInputs.technique);
    for (std::size_t s = 0; s < lights.size(); ++s) EXPECT_EQ(partInputs.depthArray[s], maps.textureOf(s));
    EXPECT_NE(partInputs.lightBuffer, facadeInputs.lightBuffer) << "each contract owns its buffers";

    const std::vector<float> partMask =
        maskOf([&](const ShadowMaskRequest& r, FrameStats& stats) { mask.render(frame, maps, lights, r, stats); },
               camera, depth);
    const std::vector<float> facadeMask = maskOf(
        [&](const ShadowMaskRequest& r, FrameStats& stats) { facade.renderMask(lights, r, stats); }, camera, depth);
    EXPECT_EQ(partMask, facadeMask);
    EXPECT_TRUE(std::any_of(partMask.begin(), partMask.end(), [](float v) { return v < 0.5f; })) << "no shadow";
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(ShadowSystem, MapMemoryInTheStatsIsWhatTheBudgetCounts) {
    // stats.json's mapBytes + filterChainBytes per light, as allocated, equal the planner's
    // shadowMapBytes: the budget counts what the maps take.
    test::glContext();
    for (const ShadowTechnique technique : test::offered(
             {ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss, ShadowTechnique::PcssTextbook,
              ShadowTechnique::Vsm, ShadowTechnique::Vssm, ShadowTechnique::Msm, ShadowTechnique::MsmSoft})) {
        Scene scene = test::threeLightScene();
        scene.world.view<Shadow>().each([&](Entity, Shadow& s) { s.technique = technique; });
        FrameRunner runner;
        const test::RenderedFrame rendered = test::renderFrame(runner, scene, 32, 24);
        const ShadowFrame& frame = runner.shadows().frame();
        ASSERT_EQ(rendered.stats.lights.size(), frame.lights.size());
        for (std::size_t i = 0; i < frame.lights.size(); ++i) {
            const ShadowLightPlan& p = frame.lights[i];
            const LightShadowStats& ls = rendered.stats.lights[i];
            EXPECT_EQ(
                ls.mapBytes + ls.filterChainBytes,
                shadowMapBytes(p.technique(), p.mapSize, static_cast<int>(p.layers.size()), p.settings.maxFilterTexels))
                << techniqueName(technique) << ", " << p.name;
            EXPECT_GT(ls.mapBytes, 0);
        }
    }
}

TEST(ShadowSystem, OwnsTheMeshCacheItDrawsFromWhenGivenNone) {
    test::glContext();
    Scene scene = test::threeLightScene();
    updateTransforms(scene.world);
    const CameraView camera = makeCameraView(scene.world, scene.cameras.at(0), 4.0f / 3.0f);
    ShadowSystem shadows;
    shadows.prepare(scene.world, camera, scene.lights);
    FrameStats stats;
    shadows.render(scene.world, stats);
    EXPECT_EQ(shadows.meshes().size(), 3u);  // ground, box, post
    Entity post;
    scene.world.view<Name>().each([&](Entity e, const Name& n) {
        if (n.value == "post") post = e;
    });
    scene.world.destroy(post);
    updateTransforms(scene.world);
    shadows.prepare(scene.world, camera, scene.lights);
    shadows.render(scene.world, stats);
    EXPECT_EQ(shadows.meshes().size(), 2u) << "its owner collects it";
}

// A game that drives the shadow system alone (its own shaders) sees the programs its passes build:
// some on the first frame (the depth pass and a VSM light's filter chain), none once they exist.
TEST(ShadowSystem, CountsTheProgramsItsPassesBuild) {
    test::glContext();
    Scene scene = test::threeLightScene();
    scene.world.get<Shadow>(scene.lights.at(0)).technique = ShadowTechnique::Vsm;
    updateTransforms(scene.world);
    const CameraView camera = makeCameraView(scene.world, scene.cameras.at(0), 4.0f / 3.0f);
    ShadowSystem shadows;
    FrameStats first;
    shadows.prepare(scene.world, camera, scene.lights);
    shadows.render(scene.world, first);
    EXPECT_GE(first.programsCompiled, 2) << "the depth pass and the moments' chain";
    FrameStats second;
    shadows.prepare(scene.world, camera, scene.lights);
    shadows.render(scene.world, second);
    EXPECT_EQ(second.programsCompiled, 0);
}

}  // namespace
}  // namespace shadow::shadow_system_test
