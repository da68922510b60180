// Bad glTF files fail the load with one message naming the file and the element at fault:
// missing and truncated files, broken accessors and buffers, bad nodes, unsupported cameras.
// (Bad lights and animations: gltf_lights_test.cpp, gltf_animation_test.cpp.)
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

TEST(GltfImport, RejectsMissingFile) {
    EXPECT_NE(loadError(testDir() / "absent.gltf").find("absent.gltf"), std::string::npos);
}

TEST(GltfImport, RejectsTruncatedGltf) {
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path path = doc.write(testDir() / "cut.gltf");
    const std::string text = readBytes(path);
    writeText(path, text.substr(0, text.size() / 2));
    EXPECT_NE(loadError(path).find("cut.gltf: "), std::string::npos);
}

TEST(GltfImport, RejectsTruncatedGlb) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path glb = convertToGlb(doc.write(dir / "s.gltf"), dir / "cut.glb");
    const std::string bytes = readBytes(glb);
    writeText(glb, bytes.substr(0, bytes.size() / 2));
    EXPECT_NE(loadError(glb).find("cut.glb: "), std::string::npos);
}

TEST(GltfImport, RejectsGlbWithWrongMagic) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path glb = convertToGlb(doc.write(dir / "s.gltf"), dir / "magic.glb");
    std::string bytes = readBytes(glb);
    bytes[0] = 'x';
    writeText(glb, bytes);
    const std::string message = loadError(glb);
    EXPECT_NE(message.find("magic.glb: "), std::string::npos) << message;
    EXPECT_NE(message.find("magic is not \"glTF\""), std::string::npos) << message;
}

/// A document with one triangle mesh on node 0, then `edit` applied to its JSON.
template <typename Edit>
std::string errorAfterEdit(Edit edit) {
    Doc doc;
    doc.node({{"name", "n"}, {"mesh", doc.triangleMesh()}});
    edit(doc);
    return loadError(doc.write(testDir() / "bad.gltf"));
}

TEST(GltfImport, RejectsAccessorOutOfBounds) {
    const std::string m = errorAfterEdit([](Doc& d) { d.j["accessors"][0]["count"] = 4; });
    EXPECT_MESSAGE(m,
                   "bad.gltf: meshes[0].primitives[0].attributes.POSITION: accessors[0]: "
                   "exceeds bufferViews[0]");
}

TEST(GltfImport, RejectsBufferViewOutsideBuffer) {
    const std::string m = errorAfterEdit([](Doc& d) { d.j["bufferViews"][0]["byteOffset"] = 60; });
    EXPECT_MESSAGE(m, "bufferViews[0]: exceeds buffers[0]");
}

TEST(GltfImport, RejectsIndexOutOfRange) {
    const std::string m = errorAfterEdit([](Doc& d) {
        d.j["meshes"][0]["primitives"][0]["indices"] = d.indices({0, 1, 3});
    });
    EXPECT_MESSAGE(m, "meshes[0].primitives[0].indices: accessors[3]: index 3");
}

TEST(GltfImport, RejectsPositionsThatAreNotFloatVec3) {
    const std::string m = errorAfterEdit([](Doc& d) { d.j["accessors"][0]["type"] = "VEC4"; });
    EXPECT_MESSAGE(m, "accessors[0]: must be FLOAT VEC3");
}

TEST(GltfImport, RejectsNanInPositions) {
    const std::string m = errorAfterEdit([](Doc& d) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        d.j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = d.floats({0, 0, 0, nan, 0, 0, 0, 1, 0}, "VEC3");
    });
    EXPECT_MESSAGE(m, "attributes.POSITION: accessors[3]: element 1 not finite");
}

TEST(GltfImport, RejectsNanInNodeRotation) {
    // JSON has no NaN: tinygltf's writer turns it into null, which is what such files hold.
    tinygltf::Model model;
    tinygltf::Node node;
    node.rotation = {0.0, std::nan(""), 0.0, 1.0};
    model.nodes.push_back(node);
    const fs::path path = testDir() / "nan.gltf";
    tinygltf::TinyGLTF io;
    ASSERT_TRUE(io.WriteGltfSceneToFile(&model, path.string(), true, true, false, false));
    EXPECT_MESSAGE(loadError(path), "nan.gltf: nodes[0].rotation");
}

TEST(GltfImport, RejectsCycleInNodeGraph) {
    Doc doc;
    doc.node({{"children", {1}}});
    doc.node({{"children", {0}}});
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")), "is part of a cycle in the node graph");
}

TEST(GltfImport, RejectsNodeWithTwoParents) {
    Doc doc;
    doc.node({{"children", {2}}});
    doc.node({{"children", {2}}});
    doc.node(json::object());
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")), "nodes[2]: has two parents, nodes[0] and nodes[1]");
}

TEST(GltfImport, RejectsReferencesOutOfRange) {
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) { d.j["nodes"][0]["children"] = {7}; }),
                   "nodes[0].children: node 7 does not exist");
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) { d.j["nodes"][0]["mesh"] = 3; }), "nodes[0].mesh: mesh 3 does not exist");
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) { d.j["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0; }),
                   "nodes[0].extensions.KHR_lights_punctual.light: light 0 does not exist");
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) { d.scene({0, 5}); }), "scenes[0].nodes: node 5 does not exist");
}

TEST(GltfImport, RejectsOrthographicCamera) {
    Doc doc;
    doc.push("cameras",
             {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}});
    doc.node({{"camera", 0}});
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")), "cameras[0]: orthographic cameras are not supported");
}

TEST(GltfImport, RejectsMissingExternalBuffer) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path path = doc.write(dir / "ext.gltf", "gone.bin");
    fs::remove(dir / "gone.bin");
    const std::string message = loadError(path);
    EXPECT_MESSAGE(message, "ext.gltf: ");
    EXPECT_MESSAGE(message, "gone.bin");
}

}  // namespace
}  // namespace shadow
