// The `extras.shadow` parsers (engine/src/scene/shadow_extras.cpp) on their own, as the glTF
// fuzzer drives them: values that are not what the key wants fail naming the key.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "scene/shadow_extras.h"

namespace shadow {
namespace {

tinygltf::Value object(tinygltf::Value::Object members) { return tinygltf::Value(std::move(members)); }

TEST(GltfShadowExtras, RejectsNonFiniteNumbers) {
    const auto extras = object({{"shadow", object({{"radius", tinygltf::Value(std::nan(""))}})}});
    const auto result = gltf::parseShadowExtras(extras, "L");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message, "L.extras.shadow.radius: not finite");
}

TEST(GltfShadowExtras, TechniqueAutoAsksThePlannerToChoose) {
    const auto extras = object({{"shadow", object({{"technique", tinygltf::Value(std::string("auto"))}})}});
    const auto result = gltf::parseShadowExtras(extras, "L");
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_TRUE(result->shadow.autoTechnique);
    EXPECT_NE(result->shadow.technique, ShadowTechnique::None);  // a light with a map
    const auto pcf = gltf::parseShadowExtras(
        object({{"shadow", object({{"technique", tinygltf::Value(std::string("pcf"))}})}}), "L");
    ASSERT_TRUE(pcf.ok());
    EXPECT_FALSE(pcf->shadow.autoTechnique);
    const auto typo = gltf::parseShadowExtras(
        object({{"shadow", object({{"technique", tinygltf::Value(std::string("autom"))}})}}), "L");
    ASSERT_FALSE(typo.ok());
    EXPECT_NE(typo.error().message.find("auto)"), std::string::npos) << typo.error().message;
}

TEST(GltfShadowExtras, AcceptsIntegralRealAsInteger) {
    const auto extras = object({{"shadow", object({{"mapSize", tinygltf::Value(512.0)}})}});
    const auto result = gltf::parseShadowExtras(extras, "L");
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_EQ(result->shadow.mapSize, 512);
    EXPECT_FALSE(gltf::parseShadowExtras(object({{"shadow", object({{"mapSize", tinygltf::Value(1e12)}})}}), "L").ok());
}

TEST(GltfShadowExtras, ReadsTheDepthModeByNameAndRejectsAnUnknownOne) {
    for (DepthMode mode : {DepthMode::Nearest, DepthMode::Midpoint, DepthMode::Second}) {
        const auto extras =
            object({{"shadow", object({{"depthMode", tinygltf::Value(std::string(depthModeName(mode)))}})}});
        const auto result = gltf::parseShadowExtras(extras, "L");
        ASSERT_TRUE(result.ok()) << result.error().message;
        EXPECT_EQ(result->shadow.depthMode, mode);
    }
    EXPECT_EQ(gltf::parseShadowExtras(object({{"shadow", object({})}}), "L")->shadow.depthMode, DepthMode::Nearest);
    const auto bad = gltf::parseShadowExtras(
        object({{"shadow", object({{"depthMode", tinygltf::Value(std::string("mid"))}})}}), "L");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().code, ErrorCode::InvalidValue);
    EXPECT_EQ(bad.error().message,
              "L.extras.shadow.depthMode: unknown depth mode \"mid\" (expected nearest, midpoint or second)");
    std::vector<Warning> warnings;
    gltf::warnUnknownShadowKeys(object({{"shadow", object({{"depthmode", tinygltf::Value(std::string("second"))}})}}),
                                "L", true, warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].message.find("did you mean \"depthMode\""), std::string::npos) << warnings[0].message;
}

TEST(GltfShadowExtras, RejectsShadowThatIsNotAnObjectButIgnoresOtherExtras) {
    const auto bad = gltf::parseShadowExtras(object({{"shadow", tinygltf::Value(true)}}), "L");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "L.extras.shadow: must be an object");
    EXPECT_TRUE(gltf::parseShadowExtras(tinygltf::Value(std::string("note")), "L").ok());
    EXPECT_TRUE(gltf::parseShadowExtras(tinygltf::Value(), "L").ok());
}

TEST(GltfShadowExtras, MeshFlagsMustBeBooleans) {
    const auto bad =
        gltf::parseMeshShadowExtras(object({{"shadow", object({{"cast", tinygltf::Value(1)}})}}), "nodes[2]");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "nodes[2].extras.shadow.cast: must be true or false");
}

}  // namespace
}  // namespace shadow
