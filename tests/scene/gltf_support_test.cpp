// What a file uses that the module leaves out (engine/src/scene/gltf_support.cpp): one
// UnsupportedFeature warning per kind naming its first use, files that require such content load,
// and a required extension the module does not know fails the load naming it.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <algorithm>
#include <string>
#include <vector>

#include "scene/gltf_support.h"
#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

/// The warnings of `scene` with `code`.
std::vector<Warning> warningsOf(const Scene& scene, WarningCode code) {
    std::vector<Warning> out;
    for (const Warning& w : scene.warnings) {
        if (w.code == code) out.push_back(w);
    }
    return out;
}

/// Two triangles, each with its own material, both on one node.
Doc twoMaterialDoc(const json& first, const json& second) {
    Doc doc;
    const int m0 = doc.push("materials", first);
    const int m1 = doc.push("materials", second);
    doc.node({{"name", "a"}, {"mesh", doc.triangleMesh(m0)}});
    doc.node({{"name", "b"}, {"mesh", doc.triangleMesh(m1)}});
    return doc;
}

TEST(GltfSupport, RequiredUnlitLoadsWithOneWarningCountingItsUses) {
    const json material = {{"extensions", {{"KHR_materials_unlit", json::object()}}}};
    Doc doc = twoMaterialDoc(material, material);
    doc.j["extensionsUsed"] = {"KHR_materials_unlit"};
    doc.j["extensionsRequired"] = {"KHR_materials_unlit"};
    const auto path = doc.write(testDir() / "s.gltf");
    auto scene = loadGltf(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const std::vector<Warning> w = warningsOf(*scene, WarningCode::UnsupportedFeature);
    ASSERT_EQ(w.size(), 1u);
    const std::string first = "materials[0].extensions.KHR_materials_unlit";
    expectWarning(w[0], WarningCode::UnsupportedFeature, first,
                  path.string() + ": KHR_materials_unlit (used 2 times, first at " + first +
                      "): unlit materials are shaded by the lights like the others");
}

TEST(GltfSupport, WhatTheMaterialsReadAndExtensionsOnlyListedAreNotWarnedAbout) {
    // A texture transform, an emission and its strength are read (Materials.* draw them); an
    // extension listed in extensionsUsed that no object uses is nothing to warn about.
    const json transform = {{"KHR_texture_transform", {{"offset", {0.5, 0}}, {"scale", {2, 2}}}}};
    const json emissive = {{"emissiveFactor", {1, 0.5, 0}},
                           {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3}}}}}};
    Doc doc = twoMaterialDoc({{"pbrMetallicRoughness", {{"extensions", transform}}}}, emissive);
    doc.j["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_materials_unlit"};
    doc.j["extensionsRequired"] = {"KHR_texture_transform"};
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0].message;
}

TEST(GltfSupport, EachKindLeftOutIsOneWarningNamingItsFirstUse) {
    Doc doc = twoMaterialDoc({{"emissiveFactor", {0, 0, 0}}, {"extensions", {{"KHR_materials_unlit", json::object()}}}},
                             {{"emissiveFactor", {1, 0.5, 0}}, {"alphaMode", "BLEND"}});
    doc.j["extensionsUsed"] = {"KHR_materials_unlit", "EXT_made_up"};
    // Vertex colours on the second mesh.
    doc.j["meshes"][1]["primitives"][0]["attributes"]["COLOR_0"] = 0;
    doc.j["meshes"][0]["extensions"] = {{"EXT_made_up", json::object()}};
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const std::vector<Warning> w = warningsOf(*scene, WarningCode::UnsupportedFeature);
    std::vector<std::string> elements;
    for (const Warning& warning : w) elements.push_back(warning.element);
    // In the table's order, then the unknown extension; the emission is read, not warned about.
    // A blended material, drawn as a cut-out, is said too.
    const std::vector<std::string> expected = {"materials[0].extensions.KHR_materials_unlit",
                                               "meshes[1].primitives[0].attributes.COLOR_0", "materials[1].alphaMode",
                                               "meshes[0].extensions.EXT_made_up"};
    EXPECT_EQ(elements, expected);
    ASSERT_EQ(w.size(), 4u);
    EXPECT_NE(w[0].message.find("KHR_materials_unlit (used once, first at"), std::string::npos) << w[0].message;
    EXPECT_NE(w[2].message.find("cut-outs at alpha 0.5"), std::string::npos) << w[2].message;
    EXPECT_NE(w[3].message.find("an extension the module does not know"), std::string::npos) << w[3].message;
}

TEST(GltfSupport, BasisuTextureWithoutFallbackDrawsTheMaterialWithoutIt) {
    Doc doc;
    doc.push("images", {{"uri", "never_read.ktx2"}, {"mimeType", "image/ktx2"}});
    doc.push("textures", {{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}});
    const int m = doc.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
    doc.node({{"name", "a"}, {"mesh", doc.triangleMesh(m)}});
    doc.j["extensionsUsed"] = {"KHR_texture_basisu"};
    doc.j["extensionsRequired"] = {"KHR_texture_basisu"};
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->world.get<Material>(findByName(*scene, "a")).baseColorTexture, nullptr);
    const std::vector<Warning> w = warningsOf(*scene, WarningCode::UnsupportedFeature);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].element, "textures[0].extensions.KHR_texture_basisu");
}

TEST(GltfSupport, RequiredExtensionTheModuleDoesNotKnowFailsNamingIt) {
    Doc doc = twoMaterialDoc(json::object(), json::object());
    doc.j["extensionsUsed"] = {"KHR_lights_punctual", "EXT_made_up"};
    doc.j["extensionsRequired"] = {"KHR_lights_punctual", "EXT_made_up"};
    const auto path = doc.write(testDir() / "s.gltf");
    const Result<Scene> result = loadGltf(path.string());
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(result.error().message, path.string() +
                                          ": extensionsRequired[1]: the file requires EXT_made_up, which the module "
                                          "does not know: it cannot be drawn");
    // Refused rows: compressed geometry the module cannot decode.
    doc.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    EXPECT_MESSAGE(
        loadError(doc.write(testDir() / "draco.gltf")),
        "extensionsRequired[0]: the file requires KHR_draco_mesh_compression, which the module does not read");
}

TEST(GltfSupport, TableNamesEachFeatureOnce) {
    std::vector<std::string> names;
    for (const gltf::FeatureSupport& row : gltf::featureTable()) {
        EXPECT_EQ(std::count(names.begin(), names.end(), row.name), 0) << row.name;
        names.emplace_back(row.name);
        EXPECT_EQ(std::string(row.instead).empty(), row.support == gltf::Support::Read) << row.name;
    }
}

// README.md's table of what the module leaves out is this table, row for row.
TEST(GltfSupport, ReadmeTableIsTheFeatureTable) {
    const std::string readme = readBytes(fs::path(SHADOW_SOURCE_DIR) / "README.md");
    const std::size_t begin = readme.find("<!-- gltf-support:begin -->");
    const std::size_t end = readme.find("<!-- gltf-support:end -->");
    ASSERT_NE(begin, std::string::npos);
    ASSERT_NE(end, std::string::npos);
    std::string expected = "| extension or feature | the module | what is drawn instead |\n|---|---|---|\n";
    for (const gltf::FeatureSupport& row : gltf::featureTable()) {
        const char* what = row.support == gltf::Support::Read      ? "read"
                           : row.support == gltf::Support::Dropped ? "left out, one warning"
                                                                   : "left out, one warning; required: the load fails";
        expected += std::string("| `") + row.name + "` | " + what + " | " + (*row.instead ? row.instead : "—") + " |\n";
    }
    const std::size_t tableStart = readme.find('\n', begin) + 1;
    EXPECT_EQ(readme.substr(tableStart, end - tableStart), expected);
}

}  // namespace
}  // namespace shadow
