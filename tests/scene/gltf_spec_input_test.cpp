// Files the glTF 2.0 specification calls valid that the importer once refused: accessors without
// a bufferView (zero-filled), sparse accessors (gltf_accessors.cpp), a .gltf buffer without `uri`
// that nothing reads (gltf_parse.cpp), and a KHR_lights_punctual light of a type the engine does
// not know (gltf_lights.cpp); and the clear errors where such input cannot be read.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cstdint>
#include <string>
#include <vector>

#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

/// A one-triangle mesh node "tri" whose POSITION accessor is `positions` (an index into
/// `accessors`, which the test fills in), with normals and indices from the buffer.
json trianglePrimitive(Doc& doc, int positions) {
    return {{"attributes", {{"POSITION", positions}, {"NORMAL", doc.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")}}},
            {"indices", doc.indices({0, 1, 2})}};
}

/// Adds node "tri", a triangle whose POSITION is accessor `positions`, and the scene holding it.
void addTriangleNode(Doc& doc, int positions) {
    doc.node({{"name", "tri"},
              {"mesh", doc.push("meshes", {{"primitives", json::array({trianglePrimitive(doc, positions)})}})}});
    doc.scene({0});
}

/// Loads `doc` with a triangle whose POSITION is accessor `positions` and returns its positions.
std::vector<glm::vec3> loadedPositions(Doc& doc, int positions, const std::string& file) {
    addTriangleNode(doc, positions);
    auto scene = loadGltf(doc.write(testDir() / file).string());
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    if (!scene.ok()) return {};
    return scene->world.get<Mesh>(findByName(*scene, "tri")).data->positions;
}

/// A sparse block of `values` (VEC3 floats) at `indices` (UNSIGNED_SHORT).
json sparseOf(Doc& doc, const std::vector<std::uint16_t>& indices, const std::vector<float>& values) {
    return {{"count", indices.size()},
            {"indices", {{"bufferView", doc.view(indices)}, {"componentType", kUnsignedShort}}},
            {"values", {{"bufferView", doc.view(values)}}}};
}

TEST(GltfSpecInput, AccessorWithoutBufferViewIsZeroFilledAndSparseValuesReplaceElements) {
    Doc doc;
    json positions = {{"componentType", kFloat}, {"count", 3},
                      {"type", "VEC3"},          {"min", {0, 0, 0}},
                      {"max", {1, 1, 0}},        {"sparse", sparseOf(doc, {1, 2}, {1, 0, 0, 0, 1, 0})}};
    const int accessor = doc.push("accessors", positions);
    const std::vector<glm::vec3> p = loadedPositions(doc, accessor, "zero_filled.gltf");
    ASSERT_EQ(p.size(), 3u);
    expectVec3(p[0], {0, 0, 0});
    expectVec3(p[1], {1, 0, 0});
    expectVec3(p[2], {0, 1, 0});
}

TEST(GltfSpecInput, SparseValuesReplaceElementsOfTheBufferView) {
    Doc doc;
    const int base = doc.floats({0, 0, 0, 5, 5, 5, 0, 1, 0}, "VEC3");
    doc.j["accessors"][static_cast<std::size_t>(base)]["sparse"] = sparseOf(doc, {1}, {1, 0, 0});
    const std::vector<glm::vec3> p = loadedPositions(doc, base, "sparse_on_view.gltf");
    ASSERT_EQ(p.size(), 3u);
    expectVec3(p[0], {0, 0, 0});
    expectVec3(p[1], {1, 0, 0});
    expectVec3(p[2], {0, 1, 0});
}

/// The load error of a triangle of zero-filled positions with two sparse values at `indices`.
std::string sparseTriangleError(const std::vector<std::uint16_t>& indices, const std::string& file) {
    Doc doc;
    json positions = {{"componentType", kFloat}, {"count", 3}, {"type", "VEC3"}};
    positions["sparse"] = sparseOf(doc, indices, {1, 0, 0, 0, 1, 0});
    addTriangleNode(doc, doc.push("accessors", positions));
    return loadError(doc.write(testDir() / file));
}

TEST(GltfSpecInput, BadSparseIndicesAndHugeZeroFilledAccessorsAreRefusedNamingTheAccessor) {
    EXPECT_MESSAGE(sparseTriangleError({1, 3}, "out_of_range.gltf"),
                   "accessors[0].sparse.indices: index 3 at position 1 out of range (count 3)");
    EXPECT_MESSAGE(sparseTriangleError({2, 1}, "decreasing.gltf"),
                   "accessors[0].sparse.indices: not strictly increasing at position 1");
    Doc doc;
    addTriangleNode(
        doc, doc.push("accessors", {{"componentType", kFloat}, {"count", std::uint64_t{1} << 40U}, {"type", "VEC3"}}));
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "huge.gltf")),
                   "accessors[0]: has no bufferView and its 1099511627776 elements exceed the 256 MiB");
}

TEST(GltfSpecInput, AGltfBufferWithoutUriLoadsWhenNothingReadsItAndOtherwiseIsNamed) {
    Doc doc;
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh()}});
    doc.scene({0});
    const fs::path dir = testDir();
    doc.write(dir / "unused.gltf");
    // A second buffer without uri, as only a .glb's BIN chunk may be: nothing reads it.
    json j = json::parse(readBytes(dir / "unused.gltf"));
    j["buffers"].push_back({{"byteLength", 16}});
    writeText(dir / "unused.gltf", j.dump());
    auto scene = loadGltf((dir / "unused.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->world.has<Mesh>(findByName(*scene, "tri")));
    // Now the normals' bufferView reads it.
    const int normals = j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].get<int>();
    const int view = j["accessors"][static_cast<std::size_t>(normals)]["bufferView"].get<int>();
    j["bufferViews"][static_cast<std::size_t>(view)]["buffer"] = 1;
    j["bufferViews"][static_cast<std::size_t>(view)]["byteOffset"] = 0;
    writeText(dir / "read.gltf", j.dump());
    const std::string message = loadError(dir / "read.gltf");
    EXPECT_MESSAGE(message, "bufferViews[" + std::to_string(view) + "]: reads buffers[1], which has no uri");
}

TEST(GltfSpecInput, ALightOfAnUnknownTypeIsSkippedWithAWarning) {
    Doc doc;
    const int area = doc.light({{"type", "area"}, {"name", "panel"}});
    const int spot = doc.light({{"type", "spot"}, {"spot", {{"outerConeAngle", 0.6}}}});
    doc.node({{"name", "panel node"}, {"extensions", {{"KHR_lights_punctual", {{"light", area}}}}}});
    doc.node({{"name", "spot node"}, {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
    doc.scene({0, 1});
    auto scene = loadGltf(doc.write(testDir() / "area.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.size(), 1u);
    EXPECT_EQ(scene->lights[0], findByName(*scene, "spot node"));
    EXPECT_FALSE(scene->world.has<Light>(findByName(*scene, "panel node")));
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_EQ(scene->warnings[0].code, WarningCode::UnsupportedLight);
    EXPECT_EQ(scene->warnings[0].element, "KHR_lights_punctual.lights[0]");
    EXPECT_MESSAGE(scene->warnings[0].message, "unknown light type \"area\"");
}

}  // namespace
}  // namespace shadow
