// Meshes and materials from glTF (engine/src/scene/gltf_mesh.cpp): triangles, normals made when
// missing, materials mapped to Blinn-Phong, shadow flags from `extras.shadow`, shared mesh data,
// and primitives split into child entities.
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

TEST(GltfImport, LoadsTriangleMeshWithMaterial) {
    Doc doc;
    doc.push("materials",
             {{"pbrMetallicRoughness",
               {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"metallicFactor", 0.5}, {"roughnessFactor", 0.5}}}});
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh(0)}});
    doc.scene({0});
    auto scene = loadGltf(doc.write(testDir() / "tri_scene.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->name, "tri_scene");
    const Entity e = findByName(*scene, "tri");
    ASSERT_TRUE(scene->world.has<Mesh>(e));
    const MeshData& mesh = *scene->world.get<Mesh>(e).data;
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    expectVec3(mesh.normals[1], {0, 0, 1});
    expectVec3(mesh.bounds.min, {0, 0, 0});
    expectVec3(mesh.bounds.max, {1, 1, 0});
    const Material& m = scene->world.get<Material>(e);
    // Metals have no diffuse: albedo = base colour x (1 - metallic).
    expectVec3(m.albedo, {0.25, 0.125, 0.5});
    EXPECT_FLOAT_EQ(m.metallic, 0.5f);
    expectVec3(m.specular, {0.27, 0.145, 0.52});  // mix(0.04, base, 0.5)
    EXPECT_NEAR(m.shininess, 30.0f, 1e-3f);       // 2 / 0.5^4 - 2
}

TEST(GltfImport, GeneratesFlatNormalsAndSequentialIndicesWhenMissing) {
    Doc doc;
    const int pos = doc.floats({0, 0, 0, 1, 0, 0, 0, 0, -1}, "VEC3");  // faces +Y
    doc.push("meshes", {{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}}})}});
    doc.node({{"name", "floor"}, {"mesh", 0}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const MeshData& mesh = *scene->world.get<Mesh>(findByName(*scene, "floor")).data;
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    ASSERT_EQ(mesh.normals.size(), 3u);
    expectVec3(mesh.normals[0], {0, 1, 0});
    const Material& m = scene->world.get<Material>(findByName(*scene, "floor"));
    EXPECT_EQ(m.shininess, Material{}.shininess);  // no material: the default
}

TEST(GltfImport, ReadsMeshShadowFlagsAndSharesMeshData) {
    Doc doc;
    const int mesh = doc.triangleMesh();
    doc.node({{"name", "noCast"}, {"mesh", mesh}, {"extras", {{"shadow", {{"cast", false}}}}}});
    doc.node({{"name", "noReceive"}, {"mesh", mesh}, {"extras", {{"shadow", {{"receive", false}}}}}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& a = scene->world.get<Mesh>(findByName(*scene, "noCast"));
    const Mesh& b = scene->world.get<Mesh>(findByName(*scene, "noReceive"));
    EXPECT_FALSE(a.castShadows);
    EXPECT_TRUE(a.receiveShadows);
    EXPECT_TRUE(b.castShadows);
    EXPECT_FALSE(b.receiveShadows);
    EXPECT_EQ(a.data.get(), b.data.get());
}

TEST(GltfImport, SplitsPrimitivesIntoChildEntitiesAndSkipsNonTriangles) {
    Doc doc;
    const int pos = doc.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const json tri = {{"attributes", {{"POSITION", pos}}}};
    const json points = {{"attributes", {{"POSITION", pos}}}, {"mode", 0}};
    doc.push("meshes", {{"primitives", json::array({tri, points, tri})}});
    doc.node({{"name", "multi"}, {"mesh", 0}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Entity multi = findByName(*scene, "multi");
    EXPECT_FALSE(scene->world.has<Mesh>(multi));
    for (const char* name : {"multi/primitive0", "multi/primitive1"}) {
        const Entity part = findByName(*scene, name);
        ASSERT_TRUE(scene->world.has<Mesh>(part)) << name;
        EXPECT_EQ(scene->world.get<Transform>(part).parent, multi);
    }
    EXPECT_FALSE(scene->world.alive(findByName(*scene, "multi/primitive2")));
}

}  // namespace
}  // namespace shadow
