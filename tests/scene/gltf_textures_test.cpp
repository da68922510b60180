// Textures from glTF (engine/src/scene/gltf_textures.cpp, the texture coordinates in
// gltf_mesh.cpp): the decoded size limit (8192 x 8192 pixels, 16384 on a side) and a texture
// whose TEXCOORD set the primitive lacks.
#include <gtest/gtest.h>
#include <shadow/image_io.h>
#include <shadow/scene.h>

#include <cstdint>
#include <string>
#include <vector>

#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

void putBigEndian(std::string& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> static_cast<unsigned>(shift)) & 0xFFU);
}

/// A PNG whose header says `width` x `height` RGBA and whose pixel data is too short to decode:
/// the size check reads only the header, so a large size costs nothing to test.
std::string pngHeaderOnly(std::uint32_t width, std::uint32_t height) {
    std::string png = "\x89PNG\r\n\x1a\n";
    putBigEndian(png, 13);
    png += "IHDR";
    putBigEndian(png, width);
    putBigEndian(png, height);
    png += std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, no filter, no interlace
    putBigEndian(png, 0);                           // CRC (not checked by the decoder)
    putBigEndian(png, 2);
    png += "IDAT";
    png += std::string("\x78\x9c", 2);
    putBigEndian(png, 0);
    putBigEndian(png, 0);
    png += "IEND";
    putBigEndian(png, 0);
    return png;
}

/// One textured triangle whose texture is the image file `image` (beside the .gltf), read
/// through TEXCOORD_`texCoord`; the mesh has TEXCOORD_0 only.
fs::path texturedDoc(const fs::path& dir, const std::string& image, int texCoord) {
    Doc doc;
    doc.push("images", {{"uri", image}});
    doc.push("textures", {{"source", 0}});
    doc.push("materials", {{"name", "bark"},
                           {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", texCoord}}}}}});
    const int mesh = doc.triangleMesh(0);
    doc.j["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        doc.accessor(doc.view(std::vector<float>{0, 0, 1, 0, 0, 1}), kFloat, 3, "VEC2");
    doc.node({{"name", "tri"}, {"mesh", mesh}});
    return doc.write(dir / "s.gltf");
}

TEST(GltfTextures, DecodesUpTo8192SquaredAndRefusesMoreNamingTheLimit) {
    const fs::path dir = testDir();
    writeText(dir / "big.png", pngHeaderOnly(8192, 8192));
    writeText(dir / "wide.png", pngHeaderOnly(16384, 4096));
    writeText(dir / "over.png", pngHeaderOnly(8193, 8192));
    writeText(dir / "edge.png", pngHeaderOnly(16385, 16));
    // Within the limit the decoder is reached (and finds no pixels): the size was accepted.
    for (const char* image : {"big.png", "wide.png"}) {
        EXPECT_MESSAGE(loadError(texturedDoc(dir, image, 0)), "images[0]: could not be decoded");
    }
    for (const char* image : {"over.png", "edge.png"}) {
        EXPECT_MESSAGE(loadError(texturedDoc(dir, image, 0)),
                       "pixels; the loader decodes at most 16384 on a side and 67108864 in all (8192 x 8192)");
    }
}

TEST(GltfTextures, TextureReadingATexcoordSetThePrimitiveLacksWarnsAndIsLeftOut) {
    const fs::path dir = testDir();
    const std::vector<std::uint8_t> pixels(2 * 2 * 4, 200);
    ASSERT_TRUE(writePng((dir / "bark.png").string(), 2, 2, 4, pixels).ok());
    {
        auto scene = loadGltf(texturedDoc(dir, "bark.png", 0).string());
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        EXPECT_NE(scene->world.get<Material>(findByName(*scene, "tri")).baseColorTexture, nullptr);
        EXPECT_TRUE(scene->warnings.empty());
    }
    const fs::path path = texturedDoc(dir, "bark.png", 1);
    auto scene = loadGltf(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->world.get<Material>(findByName(*scene, "tri")).baseColorTexture, nullptr);
    ASSERT_EQ(scene->warnings.size(), 1u);
    expectWarning(scene->warnings[0], WarningCode::MissingTexcoord, "meshes[0].primitives[0]",
                  path.string() +
                      ": meshes[0].primitives[0] has no TEXCOORD_1, which materials[0] (\"bark\")"
                      ".pbrMetallicRoughness.baseColorTexture reads: the primitive is drawn without that texture");
}

/// Exporters write KTX2 (and WebP, DDS) files as core images, outside glTF 2.0's PNG and JPEG:
/// the file loads, drawn without that texture, with one warning naming the image; a file that
/// claims to be a PNG and does not decode stays an error.
TEST(GltfTextures, ImageInAFormatTheLoaderDoesNotDecodeIsLeftOutWithAWarning) {
    const fs::path dir = testDir();
    writeText(dir / "bark.ktx2", std::string("\xABKTX 20\xBB\r\n\x1A\n", 12) + std::string(64, '\0'));
    const fs::path path = texturedDoc(dir, "bark.ktx2", 0);
    auto scene = loadGltf(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->world.get<Material>(findByName(*scene, "tri")).baseColorTexture, nullptr);
    ASSERT_EQ(scene->warnings.size(), 1u);
    expectWarning(scene->warnings[0], WarningCode::UnsupportedFeature, "images[0]",
                  path.string() +
                      ": images[0] (bark.ktx2): not a PNG or JPEG image, the formats the loader decodes; the "
                      "materials using it are drawn without this texture");

    writeText(dir / "broken.png", std::string("\x89PNG\r\n\x1a\n", 8) + std::string(64, 'x'));
    EXPECT_MESSAGE(loadError(texturedDoc(dir, "broken.png", 0)),
                   "images[0]: is not an image the loader decodes (PNG or JPEG)");
}

}  // namespace
}  // namespace shadow
