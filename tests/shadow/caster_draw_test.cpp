// Casters from the game's own geometry (ShadowCasterDraw): its vertex array and index range, or a
// draw callback, give the same shadow map as the same geometry mirrored as a Mesh; a caster
// whose geometry changes without moving redraws its layers when the game says so; the GPU
// copies of meshes gone are freed; a light's texture name stays with the light.
#include <gtest/gtest.h>
#include <shadow/mesh_cache.h>
#include <shadow/shadow_system.h>

#include "gl/gl_api.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/game_mesh_test_support.h"

namespace shadow::caster_draw_test {
namespace {

const glm::dvec3 kBoxAt{0.2, 0.6, -0.1};
const glm::dvec3 kSecondBoxAt{-0.9, 0.4, 0.5};

std::shared_ptr<const MeshData> boxMesh() { return makeBoxMesh(glm::vec3(0.4f, 0.3f, 0.4f)); }

/// A ground and a spot light; the casters are added by each test.
Scene baseScene() {
    Scene scene;
    test::addGround(scene, 3.0f);
    addLight(scene, "spot", test::pointSizedLight(LightType::Spot, 0.8f), test::hardShadow(256), {0.3, 4.0, 0.2},
             {0, -1, 0});
    addCamera(scene, "camera", Camera{}, {0.0, 3.0, 5.0}, {0.0, 0.0, 0.0});
    return scene;
}

struct Shadows {
    ShadowSystem system;

    /// Prepares and draws the maps of `scene` (the meshes from the system's own cache, which it
    /// collects); the stats of the frame.
    FrameStats frame(Scene& scene) {
        updateTransforms(scene.world);
        const CameraView camera = makeCameraView(scene.world, scene.cameras.at(0), 4.0f / 3.0f);
        system.prepare(scene.world, camera, scene.lights);
        FrameStats stats;
        system.render(scene.world, stats);
        return stats;
    }
};

Entity addOwnCaster(Scene& scene, const glm::dvec3& at, ShadowCasterDraw draw) {
    const Entity e = scene.world.create();
    scene.world.emplace<Transform>(e, test::placed(at));
    scene.world.emplace<ShadowCasterDraw>(e, std::move(draw));
    return e;
}

TEST(CasterDraw, TheGamesVertexArrayCastsTheSameShadowAsTheMirroredMesh) {
    test::glContext();
    const std::shared_ptr<const MeshData> box = boxMesh();
    Scene mirrored = baseScene();
    addMeshInstance(mirrored.world, "box", box, test::placed(kBoxAt));
    Shadows reference;
    reference.frame(mirrored);

    test::GameMesh game(*box);
    Scene own = baseScene();
    ShadowCasterDraw draw;
    draw.localBounds = game.bounds;
    draw.vertexArray = GlVertexArray{game.vertexArray};
    draw.indexCount = game.indexCount;
    addOwnCaster(own, kBoxAt, draw);
    Shadows shadows;
    const FrameStats stats = shadows.frame(own);
    EXPECT_EQ(stats.shadowDrawCalls, 2);  // the ground and the game's box
    const std::vector<float> expected = reference.system.maps().readLayerDepth(0, 0);
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(shadows.system.maps().readLayerDepth(0, 0), expected);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(CasterDraw, ASolidGameCasterIsDrawnFrontFacesOnlyWithTheSameDepths) {
    // Two game boxes, one mirrored by its transform (its winding flips), marked solid or not,
    // and a callback marked solid (called with culling off: what it draws is its own business).
    test::glContext();
    test::GameMesh game(*boxMesh());
    const auto render = [&game](bool solid, FrameStats& stats) {
        Scene scene = baseScene();
        ShadowCasterDraw draw;
        draw.localBounds = game.bounds;
        draw.vertexArray = GlVertexArray{game.vertexArray};
        draw.indexCount = game.indexCount;
        draw.solid = solid;
        addOwnCaster(scene, kBoxAt, draw);
        const Entity mirrored = addOwnCaster(scene, kSecondBoxAt, draw);
        scene.world.get<Transform>(mirrored).scale = glm::dvec3(1.0, 1.0, -1.0);
        scene.world.get<Transform>(mirrored).rotation = glm::angleAxis(0.6, glm::dvec3(0.0, 1.0, 0.0));
        ShadowCasterDraw callback = draw;
        callback.draw = [&game](const CasterDrawContext& context) {
            context.setWorldFromLocal(glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 0.3, 1.0)));
            gl.BindVertexArray(game.vertexArray);
            gl.DrawElements(GL_TRIANGLES, game.indexCount, GL_UNSIGNED_INT, nullptr);
        };
        addOwnCaster(scene, glm::dvec3(0.0), callback);
        Shadows shadows;
        stats = shadows.frame(scene);
        return shadows.system.maps().readLayerDepth(0, 0);
    };
    FrameStats solidStats, plainStats;
    const std::vector<float> solid = render(true, solidStats);
    const std::vector<float> plain = render(false, plainStats);
    ASSERT_EQ(solid.size(), plain.size());
    ASSERT_FALSE(solid.empty());
    // As for meshes (solid_culling_test.cpp): the same depths but where the rasteriser's snapping
    // made a silhouette's back face nearer, under 1 mm.
    std::size_t differing = 0;
    double largest = 0.0;
    for (std::size_t i = 0; i < solid.size(); ++i) {
        if (solid[i] == plain[i]) continue;
        ++differing;
        largest = std::max(largest, std::abs(static_cast<double>(solid[i]) - plain[i]));
    }
    EXPECT_LE(differing, solid.size() / 10000);
    EXPECT_LT(largest, 1e-3);
    EXPECT_EQ(solidStats.lights.at(0).castersDrawn, 4);  // the ground, two boxes, the callback
    EXPECT_EQ(solidStats.lights.at(0).castersCulled, 2);
    EXPECT_EQ(plainStats.lights.at(0).castersCulled, 0);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(CasterDraw, ADrawCallbackDrawsItsOwnInstances) {
    test::glContext();
    const std::shared_ptr<const MeshData> box = boxMesh();
    Scene mirrored = baseScene();
    addMeshInstance(mirrored.world, "box", box, test::placed(kBoxAt));
    addMeshInstance(mirrored.world, "box2", box, test::placed(kSecondBoxAt));
    Shadows reference;
    reference.frame(mirrored);

    // One caster entity at the origin whose callback draws two instances of the game's mesh.
    test::GameMesh game(*box);
    Scene own = baseScene();
    ShadowCasterDraw draw;
    draw.localBounds.extend(glm::vec3(kBoxAt) + game.bounds.min);
    draw.localBounds.extend(glm::vec3(kBoxAt) + game.bounds.max);
    draw.localBounds.extend(glm::vec3(kSecondBoxAt) + game.bounds.min);
    draw.localBounds.extend(glm::vec3(kSecondBoxAt) + game.bounds.max);
    int calls = 0;
    draw.draw = [&game, &calls](const CasterDrawContext& context) {
        ++calls;
        gl.BindVertexArray(game.vertexArray);
        for (const glm::dvec3& at : {kBoxAt, kSecondBoxAt}) {
            context.setWorldFromLocal(glm::translate(glm::dmat4(1.0), at));
            gl.DrawElements(GL_TRIANGLES, game.indexCount, GL_UNSIGNED_INT, nullptr);
        }
    };
    const Entity caster = addOwnCaster(own, glm::dvec3(0.0), draw);
    Shadows shadows;
    shadows.frame(own);
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(shadows.system.maps().readLayerDepth(0, 0), reference.system.maps().readLayerDepth(0, 0));

    // Unchanged: the layer is reused and the callback not called; changed in place: redrawn.
    FrameStats still = shadows.frame(own);
    EXPECT_EQ(still.shadowLayersDrawn, 0);
    EXPECT_EQ(calls, 1);
    own.world.get<ShadowCasterDraw>(caster).changedThisFrame = true;
    FrameStats changed = shadows.frame(own);
    EXPECT_EQ(changed.shadowLayersDrawn, 1);
    EXPECT_EQ(calls, 2);
}

/// A moment chain's first level holds the means of the powers of the depth the map stores (z,
/// z^2 over 2x2 texels, VSM's level 1, the first its texture holds) where a callback drew with
/// colour writes off, as a game program that writes depth alone would: the chain is read back
/// from the map, never left to the depth pass.
TEST(CasterDraw, AMomentChainHoldsTheDepthsACallbackDrew) {
    test::glContext();
    const std::shared_ptr<const MeshData> box = boxMesh();
    test::GameMesh game(*box);
    Scene own = baseScene();
    own.world.get<Shadow>(own.lights[0]).technique = ShadowTechnique::Vsm;
    ShadowCasterDraw draw;
    draw.localBounds.extend(glm::vec3(kBoxAt) + game.bounds.min);
    draw.localBounds.extend(glm::vec3(kBoxAt) + game.bounds.max);
    draw.draw = [&game](const CasterDrawContext& context) {
        std::array<GLboolean, 4> mask{};
        gl.GetBooleanv(GL_COLOR_WRITEMASK, mask.data());
        gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        gl.BindVertexArray(game.vertexArray);
        context.setWorldFromLocal(glm::translate(glm::dmat4(1.0), kBoxAt));
        gl.DrawElements(GL_TRIANGLES, game.indexCount, GL_UNSIGNED_INT, nullptr);
        gl.ColorMask(mask[0], mask[1], mask[2], mask[3]);
    };
    (void)addOwnCaster(own, glm::dvec3(0.0), draw);
    Shadows shadows;
    (void)shadows.frame(own);

    const int size = 256, half = size / 2;
    const std::vector<float> depth = shadows.system.maps().readLayerDepth(0, 0);  // metres
    const float scale = shadows.system.frame().lights[0].layers[0].depthScale;
    ASSERT_EQ(shadows.system.frame().lights[0].layers[0].chainFirstLevel, 1);
    std::vector<float> moments(static_cast<std::size_t>(half) * half * 2);  // the texture's level 0
    gl.GetTextureSubImage(shadows.system.maps().filterChainOf(0).name, 0, 0, 0, 0, half, half, 1, GL_RG, GL_FLOAT,
                          static_cast<GLsizei>(moments.size() * sizeof(float)), moments.data());
    int drawnTexels = 0, wrong = 0;
    for (int y = 0; y < half; ++y) {
        for (int x = 0; x < half; ++x) {
            double mean = 0.0, meanSquare = 0.0;
            for (int k = 0; k < 4; ++k) {
                const auto i = static_cast<std::size_t>((2 * y + (k >> 1)) * size + 2 * x + (k & 1));
                const double z = static_cast<float>(depth[i] / scale);  // back to stored units
                if (z < 0.999) ++drawnTexels;
                mean += 0.25 * z;
                meanSquare += 0.25 * static_cast<float>(z * z);
            }
            const auto t = static_cast<std::size_t>(y * half + x);
            if (std::abs(moments[2 * t] - mean) > 1e-6 || std::abs(moments[2 * t + 1] - meanSquare) > 1e-6) ++wrong;
        }
    }
    EXPECT_GT(drawnTexels, 1000) << "the box and the ground are in the map";
    EXPECT_EQ(wrong, 0) << "texels of level 1 that do not hold the means of (z, z^2) of the map";
}

TEST(CasterDraw, ACasterThatDrawsNothingIsLeftOut) {
    test::glContext();
    Scene scene = baseScene();
    ShadowCasterDraw nothing;  // no vertex array, no callback
    nothing.localBounds.extend(glm::vec3(-1.0f));
    nothing.localBounds.extend(glm::vec3(1.0f));
    addOwnCaster(scene, kBoxAt, nothing);
    Shadows shadows;
    const FrameStats stats = shadows.frame(scene);
    EXPECT_EQ(stats.shadowDrawCalls, 1);  // the ground only
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(MeshCache, TheCopiesOfMeshesGoneAreFreedByTheCachesOwner) {
    test::glContext();
    Scene scene = baseScene();
    const Entity box = addMeshInstance(scene.world, "box", boxMesh(), test::placed(kBoxAt));
    Shadows shadows;
    shadows.frame(scene);
    EXPECT_EQ(shadows.system.meshes().size(), 2u);  // ground and box
    // A cache of the game's, handed to the system: drawn from, not collected.
    MeshCache games;
    FrameStats stats;
    shadows.system.render(scene.world, games, stats);
    EXPECT_EQ(games.size(), 2u);
    scene.world.destroy(box);  // the box's MeshData dies with its only instance
    shadows.frame(scene);
    EXPECT_EQ(shadows.system.meshes().size(), 1u) << "the system collects the cache it owns";
    shadows.system.render(scene.world, games, stats);
    EXPECT_EQ(games.size(), 2u) << "the cache's owner collects it, not the system";
    EXPECT_EQ(games.collect(), 1u);
}

TEST(ShadowSystem, ALightsTextureStaysWithTheLightWhateverTheOrder) {
    test::glContext();
    Scene scene = baseScene();
    addMeshInstance(scene.world, "box", boxMesh(), test::placed(kBoxAt));
    const Entity second = addLight(scene, "bulb", test::pointSizedLight(LightType::Point), test::hardShadow(128),
                                   {1.0, 2.0, 0.0}, {0, -1, 0});
    Shadows shadows;
    FrameStats first = shadows.frame(scene);
    ASSERT_EQ(first.lights.size(), 2u);
    EXPECT_TRUE(first.lights[0].mapAllocated);
    EXPECT_TRUE(first.lights[1].mapAllocated);
    const GlTexture bulbTexture = shadows.system.textureOfLight(second);
    ASSERT_TRUE(bulbTexture);
    std::swap(scene.lights[0], scene.lights[1]);  // the bulb is now scene light 0
    FrameStats swapped = shadows.frame(scene);
    EXPECT_EQ(shadows.system.textureOfLight(second), bulbTexture);
    EXPECT_EQ(shadows.system.maps().textureOf(0), bulbTexture);
    EXPECT_FALSE(swapped.lights[0].mapAllocated);
    EXPECT_FALSE(swapped.lights[1].mapAllocated);
    scene.world.get<Shadow>(second).mapSize = 256;  // a new size: a new map, reported
    FrameStats resized = shadows.frame(scene);
    EXPECT_TRUE(resized.lights[0].mapAllocated);
    EXPECT_FALSE(resized.lights[1].mapAllocated);
}

}  // namespace
}  // namespace shadow::caster_draw_test
