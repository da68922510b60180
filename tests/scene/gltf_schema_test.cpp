// Core members of the wrong JSON type (engine/src/scene/gltf_schema.cpp): tinygltf takes them
// for absent and keeps its defaults; the importer fails naming the member.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <string>
#include <vector>

#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

/// A MASK material on one triangle, with `edit` applied to the document.
template <typename Edit>
std::string errorOf(Edit edit) {
    Doc doc;
    const int m = doc.push("materials", {{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}});
    doc.node({{"name", "a"}, {"mesh", doc.triangleMesh(m)}, {"translation", {1, 2, 3}}});
    edit(doc.j);
    const auto path = doc.write(testDir() / "s.gltf");
    const Result<Scene> result = loadGltf(path.string());
    if (result.ok()) {
        ADD_FAILURE() << "loaded: " << doc.j.dump();
        return {};
    }
    EXPECT_EQ(result.error().message.rfind(path.string() + ": ", 0), 0u) << result.error().message;
    return result.error().message.substr(path.string().size() + 2);
}

TEST(GltfSchema, AlphaCutoffStringIsAnErrorNamingIt) {
    EXPECT_EQ(errorOf([](json& j) { j["materials"][0]["alphaCutoff"] = "half"; }),
              "materials[0].alphaCutoff: must be a number, not a string");
}

TEST(GltfSchema, CoreMembersOfTheWrongTypeAreErrorsNamingThem) {
    EXPECT_EQ(errorOf([](json& j) { j["nodes"][0]["translation"][1] = "2"; }),
              "nodes[0].translation[1]: must be a number, not a string");
    EXPECT_EQ(errorOf([](json& j) { j["nodes"][0]["mesh"] = 0.5; }),
              "nodes[0].mesh: must be an integer, not a fractional number");
    EXPECT_EQ(errorOf([](json& j) { j["materials"][0]["doubleSided"] = 1; }),
              "materials[0].doubleSided: must be a boolean, not a number");
    EXPECT_EQ(errorOf([](json& j) {
                  j["materials"][0]["pbrMetallicRoughness"] = {{"metallicFactor", {0}}};
              }),
              "materials[0].pbrMetallicRoughness.metallicFactor: must be a number, not an array");
    EXPECT_EQ(errorOf([](json& j) { j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = "1"; }),
              "meshes[0].primitives[0].attributes.NORMAL: must be an integer, not a string");
    EXPECT_EQ(errorOf([](json& j) { j["nodes"][0]["mesh"] = 4294967296LL; }),
              "nodes[0].mesh: must be an integer, not a number");
    EXPECT_EQ(errorOf([](json& j) {
                  j["extensionsUsed"] = {"KHR_lights_punctual", 3};
              }),
              "extensionsUsed[1]: must be a string, not a number");
}

TEST(GltfSchema, MembersOfTheRightTypeLoadAsWritten) {
    Doc doc;
    const int m = doc.push("materials", {{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}, {"doubleSided", true}});
    doc.node({{"name", "a"}, {"mesh", doc.triangleMesh(m)}, {"extras", {{"anything", {1, "two", nullptr}}}}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_FLOAT_EQ(scene->world.get<Material>(findByName(*scene, "a")).alphaCutoff, 0.25f);
}

}  // namespace
}  // namespace shadow
