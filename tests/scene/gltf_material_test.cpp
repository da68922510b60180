// Materials from glTF (engine/src/scene/gltf_material.cpp): every texture of the core
// specification with its TEXCOORD set, KHR_texture_transform (the base colour's baked into the
// mesh's first set), KHR_materials_emissive_strength, doubleSided, a normal map's tangents from
// the file or computed, and the error for a third texture-coordinate set.
#include <gtest/gtest.h>
#include <shadow/image_io.h>
#include <shadow/scene.h>

#include <string>
#include <vector>

#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

/// A 2x2 PNG beside the document, as images[i].
int addImage(Doc& doc, const fs::path& dir, const std::string& name) {
    const std::vector<std::uint8_t> pixels(2 * 2 * 4, 200);
    EXPECT_TRUE(writePng((dir / name).string(), 2, 2, 4, pixels).ok());
    const int image = doc.push("images", {{"uri", name}});
    return doc.push("textures", {{"source", image}});
}

/// A unit quad in the XZ plane facing +Y with two texture-coordinate sets (the second is the
/// first mirrored in u), and optionally TANGENT.
int quadMesh(Doc& doc, int material, const std::vector<float>& tangents = {}) {
    json attributes = {
        {"POSITION", doc.floats({0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1}, "VEC3")},
        {"NORMAL", doc.floats({0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3")},
        {"TEXCOORD_0", doc.accessor(doc.view(std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}), kFloat, 4, "VEC2")},
        {"TEXCOORD_1", doc.accessor(doc.view(std::vector<float>{1, 0, 0, 0, 0, 1, 1, 1}), kFloat, 4, "VEC2")}};
    if (!tangents.empty()) attributes["TANGENT"] = doc.floats(tangents, "VEC4");
    // Counter-clockwise seen from +Y.
    json primitive = {{"attributes", attributes}, {"indices", doc.indices({0, 2, 1, 0, 3, 2})}, {"material", material}};
    return doc.push("meshes", {{"primitives", json::array({primitive})}});
}

Result<Scene> loadQuad(Doc& doc, const fs::path& dir, int material, const std::vector<float>& tangents = {}) {
    doc.node({{"name", "quad"}, {"mesh", quadMesh(doc, material, tangents)}});
    doc.scene({0});
    return loadGltf(doc.write(dir / "quad.gltf").string());
}

TEST(GltfMaterial, ReadsEveryCoreTextureAndTheExtensions) {
    const fs::path dir = testDir();
    Doc doc;
    const int a = addImage(doc, dir, "a.png"), b = addImage(doc, dir, "b.png");
    const json baseTransform = {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}, {"scale", {2.0, 2.0}}}}};
    const json emissiveTransform = {{"KHR_texture_transform", {{"rotation", 0.5}, {"texCoord", 1}}}};
    doc.push("materials", {{"pbrMetallicRoughness",
                            {{"baseColorTexture", {{"index", a}, {"extensions", baseTransform}}},
                             {"metallicRoughnessTexture", {{"index", b}}}}},
                           {"normalTexture", {{"index", b}, {"scale", 0.5}}},
                           {"occlusionTexture", {{"index", b}, {"texCoord", 1}, {"strength", 0.25}}},
                           {"emissiveTexture", {{"index", a}, {"extensions", emissiveTransform}}},
                           {"emissiveFactor", {1.0, 0.5, 0.25}},
                           {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}},
                           {"doubleSided", false}});
    auto scene = loadQuad(doc, dir, 0);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Entity e = findByName(*scene, "quad");
    const Material& m = scene->world.get<Material>(e);
    const MeshData& mesh = *scene->world.get<Mesh>(e).data;
    // Absent factors are 1: the map alone says how metallic and rough.
    EXPECT_EQ(m.metallic, 1.0f);
    EXPECT_EQ(m.roughness, 1.0f);
    ASSERT_NE(m.baseColorTexture, nullptr);
    ASSERT_NE(m.metallicRoughnessMap.texture, nullptr);
    EXPECT_TRUE(m.usesMaps());
    EXPECT_FALSE(m.doubleSided);
    EXPECT_EQ(m.normalScale, 0.5f);
    EXPECT_EQ(m.occlusionStrength, 0.25f);
    expectVec3(m.emissive, {4.0, 2.0, 1.0});
    // The base colour's transform is baked into set 0 (uv' = offset + 2 uv) ...
    ASSERT_EQ(mesh.texcoords.size(), 4u);
    expectVec3(glm::vec3(mesh.texcoords[2], 0.0f), {2.5, 2.0, 0.0});
    // ... and the other maps of TEXCOORD_0 take it back: they read the file's uv.
    EXPECT_EQ(m.metallicRoughnessMap.texcoordSet, 0);
    const glm::vec2 back = m.metallicRoughnessMap.uvTransform * glm::vec3(mesh.texcoords[2], 1.0f);
    expectVec3(glm::vec3(back, 0.0f), {1.0, 1.0, 0.0});
    EXPECT_EQ(m.normalMap.texcoordSet, 0);
    // TEXCOORD_1 (the occlusion's, and the emission's by its transform's texCoord) is set 1.
    EXPECT_EQ(m.occlusionMap.texcoordSet, 1);
    EXPECT_EQ(m.emissiveMap.texcoordSet, 1);
    ASSERT_EQ(mesh.texcoords1.size(), 4u);
    expectVec3(glm::vec3(mesh.texcoords1[0], 0.0f), {1.0, 0.0, 0.0});
    const glm::mat3x2 rotation = textureTransform(glm::vec2(0.0f), 0.5f, glm::vec2(1.0f));
    for (int c = 0; c < 3; ++c) expectVec3(glm::vec3(m.emissiveMap.uvTransform[c], 0.0f), glm::vec3(rotation[c], 0.0f));
    // No TANGENT: computed from the normal map's set, +u along +X, +v along +Z (w = -1: the
    // bitangent w x cross(+Y, +X) = +Z).
    ASSERT_EQ(mesh.tangents.size(), 4u);
    for (const glm::vec4& t : mesh.tangents) {
        expectVec3(glm::vec3(t), {1.0, 0.0, 0.0}, 1e-5);
        EXPECT_EQ(t.w, -1.0f);
    }
}

TEST(GltfMaterial, KeepsTheFilesTangents) {
    const fs::path dir = testDir();
    Doc doc;
    const int a = addImage(doc, dir, "n.png");
    doc.push("materials", {{"normalTexture", {{"index", a}}}});
    // Tangents along +Z, right-handed (w = 1), scaled by 2: read unit, handedness kept.
    auto scene = loadQuad(doc, dir, 0, {0, 0, 2, 1, 0, 0, 2, 1, 0, 0, 2, 1, 0, 0, 2, 1});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const MeshData& mesh = *scene->world.get<Mesh>(findByName(*scene, "quad")).data;
    ASSERT_EQ(mesh.tangents.size(), 4u);
    expectVec3(glm::vec3(mesh.tangents[1]), {0.0, 0.0, 1.0});
    EXPECT_EQ(mesh.tangents[1].w, 1.0f);
    EXPECT_TRUE(scene->world.get<Material>(findByName(*scene, "quad")).doubleSided == false);
}

TEST(GltfMaterial, AThirdTexcoordSetIsAnErrorNamingTheTexture) {
    const fs::path dir = testDir();
    Doc doc;
    const int a = addImage(doc, dir, "a.png");
    doc.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", a}}}}},
                           {"normalTexture", {{"index", a}, {"texCoord", 1}}},
                           {"occlusionTexture", {{"index", a}, {"texCoord", 2}}}});
    auto scene = loadQuad(doc, dir, 0);
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().code, ErrorCode::Unsupported);
    EXPECT_NE(scene.error().message.find("materials[0].occlusionTexture"), std::string::npos) << scene.error().message;
}

TEST(GltfMaterial, ATransformMemberOfTheWrongTypeIsAnError) {
    const fs::path dir = testDir();
    Doc doc;
    const int a = addImage(doc, dir, "a.png");
    const json bad = {{"KHR_texture_transform", {{"scale", "large"}}}};
    doc.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", a}, {"extensions", bad}}}}}});
    auto scene = loadQuad(doc, dir, 0);
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("baseColorTexture.extensions.KHR_texture_transform.scale"), std::string::npos)
        << scene.error().message;
}

}  // namespace
}  // namespace shadow
