// Degenerate geometry: zero-area triangles, a mesh whose vertices all coincide, meshes with no
// triangles (no indices, or nothing at all), zero normals, a scene with no casters, and a scene
// with no lights or no meshes. Every technique renders such scenes finite, and the degenerate
// meshes neither cast nor corrupt the shadows of the real ones.
#include <gtest/gtest.h>

#include <string>

#include "stability/stability_test_support.h"

namespace shadow::degenerate_geometry_test {
namespace {

const glm::dvec3 kBoxCenter{0.0, 1.2, 0.0};
const glm::dvec3 kBoxHalf{0.5, 0.3, 0.4};

std::shared_ptr<MeshData> meshOf(std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices,
                                 std::vector<glm::vec3> normals = {}) {
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "degenerate";
    mesh->positions = std::move(positions);
    mesh->indices = std::move(indices);
    mesh->normals =
        normals.empty() ? std::vector<glm::vec3>(mesh->positions.size(), glm::vec3(0, 1, 0)) : std::move(normals);
    computeBounds(*mesh);
    return mesh;
}

/// Ground, a real box, the three lights types over them, and a camera.
Scene baseScene() {
    Scene scene;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "box", kBoxCenter, kBoxHalf);
    addCamera(scene, "camera", Camera{}, {0.5, 5.0, 4.5}, {0.0, 0.0, 0.0});
    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.02f;
    addLight(scene, "sun", sun, test::shadowWith(ShadowTechnique::Hard, 512), {0, 8, 0}, {0.2, -1, 0.1});
    Light spot = test::pointSizedLight(LightType::Spot, 0.7f);
    spot.radius = 0.1f;
    addLight(scene, "spot", spot, test::shadowWith(ShadowTechnique::Hard, 512), {0.3, 4.0, 0.2}, {0, -1, 0});
    Light bulb = test::pointSizedLight(LightType::Point);
    bulb.radius = 0.05f;
    addLight(scene, "bulb", bulb, test::shadowWith(ShadowTechnique::Hard, 512), {-0.5, 3.5, 0.4}, {0, -1, 0});
    return scene;
}

TEST(Stability, DegenerateMeshesNeitherCastNorCorruptTheFrame) {
    Scene plain = baseScene();
    Scene scene = baseScene();
    World& w = scene.world;
    // Between the lights and the ground, where any mistaken shadow would show, and inside the
    // bounds of the real meshes, so the layers' fits stay as they are.
    const Transform above = test::placed({0.1, 1.0, 0.1});
    addMeshInstance(w, "zero-area triangles",
                    meshOf({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {0, 1, 2, 3, 4, 5}),
                    above);
    addMeshInstance(w, "coincident vertices",
                    meshOf(std::vector<glm::vec3>(9, glm::vec3(0.3f)), {0, 1, 2, 3, 4, 5, 6, 7, 8}), above);
    addMeshInstance(w, "no indices", meshOf({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {}), above);
    addMeshInstance(w, "nothing at all", meshOf({}, {}), above);
    addMeshInstance(w, "null mesh data", nullptr, above);
    // Flat normals of a degenerate triangle are made +Y, not NaN.
    auto flat = meshOf({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {0, 1, 2});
    makeFlatNormals(*flat);
    addMeshInstance(w, "flat normals of nothing", flat, above);
    // A visible square whose normals are zero (a file may carry them): shaded with its own
    // face normal, not NaN.
    addMeshInstance(w, "zero normals",
                    meshOf({{-0.3f, 0, -0.3f}, {0.3f, 0, -0.3f}, {0.3f, 0, 0.3f}, {-0.3f, 0, 0.3f}}, {0, 1, 2, 0, 2, 3},
                           std::vector<glm::vec3>(4, glm::vec3(0.0f))),
                    test::placed({2.0, 0.01, 2.0}));

    test::glContext();
    FrameRunner plainRunner;
    const test::RenderedFrame reference = test::renderFrame(plainRunner, plain, 128, 96);
    test::forEveryTechnique(scene, 128, 96, "degenerate meshes",
                            [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
                                if (technique != ShadowTechnique::Hard) return;
                                // The shadows are those of the scene without the degenerate meshes; the zero-normal
                                // square covers some ground pixels, which are left out.
                                for (std::size_t i = 0; i < reference.images.visibility.size(); ++i) {
                                    int differing = 0;
                                    for (int y = 0; y < 96; ++y) {
                                        for (int x = 0; x < 128; ++x) {
                                            const glm::dvec3 p = test::positionAt(frame.images, x, y);
                                            if (std::abs(p.x - 2.0) < 0.35 && std::abs(p.z - 2.0) < 0.35) continue;
                                            differing += reference.images.visibility[i].at(x, y, 0) !=
                                                         frame.images.visibility[i].at(x, y, 0);
                                        }
                                    }
                                    EXPECT_EQ(differing, 0) << "light " << i;
                                }
                            });
}

TEST(Stability, SceneWithoutCastersClearsEveryLayer) {
    Scene scene = baseScene();
    scene.world.view<Mesh>().each([](Entity, Mesh& m) { m.castShadows = false; });
    test::forEveryTechnique(
        scene, 96, 72, "no casters", [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
            EXPECT_EQ(frame.stats.shadowDrawCalls, 0);
            // Nor is a filter chain built: cleared (one value) or, a summed-area table, left out.
            for (const auto& pass : frame.stats.passes) {
                EXPECT_EQ(pass.name.find("moments"), std::string::npos)
                    << techniqueName(technique) << ": " << pass.name;
                EXPECT_EQ(pass.name.find("minmax"), std::string::npos) << techniqueName(technique) << ": " << pass.name;
            }
            for (const ImageF& v : frame.images.visibility) {
                EXPECT_TRUE(std::all_of(v.pixels.begin(), v.pixels.end(), [](float x) { return x == 1.0f; }))
                    << techniqueName(technique);
            }
        });
}

TEST(Stability, SceneWithoutMeshesOrWithoutLightsRendersFinite) {
    {
        Scene scene = baseScene();
        std::vector<Entity> meshes;
        scene.world.view<Mesh>().each([&](Entity e, Mesh&) { meshes.push_back(e); });
        for (Entity e : meshes) scene.world.destroy(e);
        test::forEveryTechnique(scene, 96, 72, "no meshes",
                                [&](ShadowTechnique, const test::RenderedFrame& frame, FrameRunner&) {
                                    EXPECT_EQ(frame.stats.mainDrawCalls, 0);
                                    EXPECT_EQ(test::countNonFinite(frame.images.color), 0);
                                });
    }
    {
        Scene scene;
        test::addGround(scene, 3.0f);
        addCamera(scene, "camera", Camera{}, {0.5, 5.0, 4.5}, {0.0, 0.0, 0.0});
        test::glContext();
        FrameRunner runner;
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 96, 72);
        test::expectSaneFrame(frame.images, runner.shadows(), "no lights");
        EXPECT_TRUE(frame.images.visibility.empty());
    }
}

}  // namespace
}  // namespace shadow::degenerate_geometry_test
