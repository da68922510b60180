// loadGltf on valid files (engine/src/scene/gltf_import.cpp): the node hierarchy of the chosen
// scene, node matrices decomposed into translation, rotation and scale, cameras, and the file
// forms (.glb, external buffers). Meshes, lights, animation and bad files have their own files.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

TEST(GltfImport, BuildsNodeHierarchyFromChosenSceneOnly) {
    Doc doc;
    doc.node({{"name", "root"}, {"translation", {1, 2, 3}}, {"children", {1}}});
    doc.node({{"rotation", {0, std::sin(0.25 * M_PI), 0, std::cos(0.25 * M_PI)}}});
    doc.node({{"name", "elsewhere"}});
    doc.scene({0});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->world.size(), 2u);
    const Entity root = findByName(*scene, "root");
    const Entity child = findByName(*scene, "node1");  // unnamed nodes are named by index
    ASSERT_TRUE(scene->world.alive(child));
    EXPECT_TRUE(scene->world.get<Transform>(root).parent.isNull());
    EXPECT_EQ(scene->world.get<Transform>(child).parent, root);
    expectVec3(scene->world.get<Transform>(root).translation, {1, 2, 3});
    expectSameRotation(scene->world.get<Transform>(child).rotation, glm::angleAxis(0.5 * M_PI, glm::dvec3(0, 1, 0)));
    EXPECT_FALSE(scene->world.alive(findByName(*scene, "elsewhere")));
}

TEST(GltfImport, SceneListingAChildNodeLoadsWithAWarningNamingIt) {
    // What some exporters write: every node in the scene's list, children too; and a child
    // whose parent is in no listed subtree.
    Doc doc;
    doc.node({{"name", "root"}, {"translation", {1, 0, 0}}, {"children", {1}}});
    doc.node({{"name", "child"}, {"translation", {0, 2, 0}}});
    doc.node({{"name", "unlisted"}, {"translation", {5, 0, 0}}, {"children", {3}}});
    doc.node({{"name", "orphan"}, {"translation", {0, 0, 3}}});
    doc.scene({0, 1, 3, 0});
    const auto path = doc.write(testDir() / "s.gltf");
    auto scene = loadGltf(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    World& w = scene->world;
    EXPECT_EQ(w.size(), 3u) << "root, child once, orphan; not the unlisted parent";
    const Entity root = findByName(*scene, "root");
    EXPECT_EQ(w.get<Transform>(findByName(*scene, "child")).parent, root);
    const Entity orphan = findByName(*scene, "orphan");
    ASSERT_TRUE(w.alive(orphan));
    EXPECT_TRUE(w.get<Transform>(orphan).parent.isNull());
    expectVec3(w.get<Transform>(orphan).translation, {0, 0, 3});
    ASSERT_EQ(scene->warnings.size(), 3u);
    const std::string file = path.string() + ": ";
    expectWarning(scene->warnings[0], WarningCode::SceneNodeNotRoot, "nodes[0]",
                  file + "scenes[0].nodes lists nodes[0] (\"root\") twice; it is taken once");
    expectWarning(scene->warnings[1], WarningCode::SceneNodeNotRoot, "nodes[1]",
                  file +
                      "scenes[0].nodes lists nodes[1] (\"child\"), which is not a root node (its parent is "
                      "nodes[0]); it is taken once, below nodes[0], which the scene holds too");
    expectWarning(scene->warnings[2], WarningCode::SceneNodeNotRoot, "nodes[3]",
                  file +
                      "scenes[0].nodes lists nodes[3] (\"orphan\"), which is not a root node (its parent is "
                      "nodes[2]); it is taken as a root of its own subtree, with its own transform (its ancestors "
                      "are in no subtree the scene lists)");
}

TEST(GltfImport, DecomposesNodeMatrixIntoTrs) {
    Doc doc;  // T(1,2,3) * R_y(90 deg) * S(2), column-major
    doc.node({{"name", "m"}, {"matrix", {0, 0, -2, 0, 0, 2, 0, 0, 2, 0, 0, 0, 1, 2, 3, 1}}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Transform& t = scene->world.get<Transform>(findByName(*scene, "m"));
    expectVec3(t.translation, {1, 2, 3});
    expectVec3(t.scale, {2, 2, 2});
    expectSameRotation(t.rotation, glm::angleAxis(0.5 * M_PI, glm::dvec3(0, 1, 0)));
}

TEST(GltfImport, DecomposesMirroredMatrixAndOneWithAZeroColumn) {
    Doc doc;
    doc.node({{"name", "mirror"}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Transform& t = scene->world.get<Transform>(findByName(*scene, "mirror"));
    glm::dmat3 m = glm::mat3_cast(t.rotation);  // recompose R * S
    for (int c = 0; c < 3; ++c) m[c] *= t.scale[c];
    EXPECT_NEAR(m[0][0], -1.0, 1e-9);
    EXPECT_NEAR(m[1][1], 1.0, 1e-9);
    EXPECT_NEAR(m[2][2], 1.0, 1e-9);

    // A zero column (scale 0 along x) keeps the rotation of the other two and the matrix itself.
    doc.j["nodes"][0]["matrix"] = {0, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1};
    auto singular = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(singular.ok()) << singular.error().message;
    EXPECT_TRUE(singular->warnings.empty());
    const Transform& z = singular->world.get<Transform>(findByName(*singular, "mirror"));
    expectVec3(z.scale, {0, 1, 1});
    expectSameRotation(z.rotation, glm::angleAxis(0.5 * M_PI, glm::dvec3(1, 0, 0)));
}

TEST(GltfImport, ImportsPerspectiveCamerasInNodeOrder) {
    Doc doc;
    doc.push("cameras", {{"type", "perspective"},
                         {"perspective", {{"yfov", 0.9}, {"znear", 0.1}, {"zfar", 50.0}, {"aspectRatio", 1.5}}}});
    doc.push("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.2}}}});
    doc.node({{"name", "first"}, {"camera", 1}});
    doc.node({{"name", "second"}, {"camera", 0}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->cameras.size(), 2u);
    EXPECT_EQ(scene->cameras[0], findByName(*scene, "first"));
    const Camera& infinite = scene->world.get<Camera>(scene->cameras[0]);
    EXPECT_FLOAT_EQ(infinite.yfov, 0.5f);
    EXPECT_FLOAT_EQ(infinite.zfar, 1e4f);  // no zfar: "infinite"
    EXPECT_FLOAT_EQ(infinite.aspectRatio, 0.0f);
    const Camera& full = scene->world.get<Camera>(scene->cameras[1]);
    EXPECT_FLOAT_EQ(full.znear, 0.1f);
    EXPECT_FLOAT_EQ(full.zfar, 50.0f);
    EXPECT_FLOAT_EQ(full.aspectRatio, 1.5f);
}

TEST(GltfImport, GlbRoundTripMatchesGltf) {
    const fs::path dir = testDir();
    Doc doc = lightsDoc();
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh()}});
    const fs::path gltf = doc.write(dir / "scene.gltf");
    const fs::path glb = convertToGlb(gltf, dir / "scene.glb");
    ASSERT_EQ(readBytes(glb).substr(0, 4), "glTF");
    auto fromText = loadGltf(gltf.string());
    auto fromBinary = loadGltf(glb.string());
    ASSERT_TRUE(fromText.ok()) << fromText.error().message;
    ASSERT_TRUE(fromBinary.ok()) << fromBinary.error().message;
    EXPECT_EQ(fromBinary->name, "scene");
    EXPECT_EQ(fromBinary->world.size(), fromText->world.size());
    ASSERT_EQ(fromBinary->lights.size(), 4u);
    EXPECT_EQ(fromBinary->world.get<Shadow>(fromBinary->lights[0]).mapSize, 2048);
    const MeshData& mesh = *fromBinary->world.get<Mesh>(findByName(*fromBinary, "tri")).data;
    EXPECT_EQ(mesh.positions, fromText->world.get<Mesh>(findByName(*fromText, "tri")).data->positions);
}

TEST(GltfImport, LoadsExternalBuffer) {
    Doc doc;
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh()}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf", "s.bin").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->world.get<Mesh>(findByName(*scene, "tri")).data->indices.size(), 3u);
}

}  // namespace
}  // namespace shadow
