// KHR_lights_punctual lights and their `extras.shadow` settings (engine/src/scene/gltf_lights.cpp):
// every light type, light order, the errors of strict loading and the warnings of lenient loading,
// and where a light on a node of scale 0 points.
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

TEST(GltfImport, ImportsAllLightTypesWithShadowExtras) {
    Doc doc = lightsDoc();
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.size(), 4u);
    World& w = scene->world;
    const Light& sun = w.get<Light>(scene->lights[0]);
    EXPECT_EQ(sun.type, LightType::Directional);
    expectVec3(sun.color, {1.0, 0.5, 0.25});
    EXPECT_FLOAT_EQ(sun.intensity, 3.0f);
    EXPECT_FLOAT_EQ(sun.angularRadius, 0.01f);
    const Shadow& sunShadow = w.get<Shadow>(scene->lights[0]);
    EXPECT_EQ(sunShadow.technique, ShadowTechnique::Pcss);
    EXPECT_EQ(sunShadow.mapSize, 2048);
    EXPECT_EQ(sunShadow.cascades, 3);
    EXPECT_FLOAT_EQ(sunShadow.cascadeSplitLambda, 0.5f);
    EXPECT_FLOAT_EQ(sunShadow.shadowDistance, 80.0f);

    const Light& spot = w.get<Light>(scene->lights[1]);
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_FLOAT_EQ(spot.range, 20.0f);
    EXPECT_FLOAT_EQ(spot.innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(spot.outerConeAngle, 0.6f);
    EXPECT_FLOAT_EQ(spot.radius, 0.25f);
    const Shadow& spotShadow = w.get<Shadow>(scene->lights[1]);
    EXPECT_EQ(spotShadow.technique, ShadowTechnique::Pcf);
    EXPECT_EQ(spotShadow.pcfSamples, 32);
    EXPECT_EQ(spotShadow.blockerSamples, 8);
    EXPECT_FLOAT_EQ(spotShadow.pcfRadius, 0.1f);
    EXPECT_FLOAT_EQ(spotShadow.maxFilterTexels, 16.0f);
    EXPECT_FLOAT_EQ(spotShadow.constantBias, 0.01f);
    EXPECT_FLOAT_EQ(spotShadow.slopeBias, 2.0f);
    EXPECT_FLOAT_EQ(spotShadow.normalOffset, 0.5f);
    EXPECT_FLOAT_EQ(spotShadow.nearPlane, 0.3f);

    EXPECT_EQ(w.get<Light>(scene->lights[2]).type, LightType::Point);
    EXPECT_FLOAT_EQ(w.get<Light>(scene->lights[2]).radius, 0.1f);
    EXPECT_FALSE(w.has<Shadow>(scene->lights[2]));  // technique none: no shadow map at all
    const Shadow& defaults = w.get<Shadow>(scene->lights[3]);
    EXPECT_EQ(defaults.technique, ShadowTechnique::Hard);
    EXPECT_EQ(defaults.mapSize, Shadow{}.mapSize);
}

TEST(GltfImport, OrdersLightsDepthFirstFromSceneRoots) {
    Doc doc;
    for (int i = 0; i < 5; ++i) doc.light({{"type", "point"}});
    const auto lit = [](const char* name, int light) {
        return json{{"name", name}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}};
    };
    json a = lit("a", 0), c = lit("c", 2);
    a["children"] = {1, 2};
    c["children"] = {3};
    doc.node(a);
    doc.node(lit("b", 1));
    doc.node(c);
    doc.node(lit("d", 3));
    doc.node(lit("e", 4));
    doc.scene({4, 0});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    std::vector<std::string> order;
    for (Entity e : scene->lights) order.push_back(scene->world.get<Name>(e).value);
    EXPECT_EQ(order, (std::vector<std::string>{"e", "a", "b", "c", "d"}));
}

/// A file with one point light whose `extras.shadow` is `shadow`.
std::string lightShadowError(const json& shadow) {
    Doc doc;
    doc.light({{"type", "point"}});
    doc.light({{"type", "point"}, {"extras", {{"shadow", shadow}}}});
    doc.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    return loadError(doc.write(testDir() / "light.gltf"));
}

TEST(GltfImport, RejectsUnknownShadowTechnique) {
    EXPECT_MESSAGE(lightShadowError({{"technique", "raytraced"}}),
                   "light.gltf: KHR_lights_punctual.lights[1].extras.shadow.technique: "
                   "unknown technique \"raytraced\"");
}

TEST(GltfImport, RejectsNegativeMapSize) {
    EXPECT_MESSAGE(lightShadowError({{"mapSize", -512}}),
                   "KHR_lights_punctual.lights[1].extras.shadow.mapSize: must be a positive integer");
}

TEST(GltfImport, RejectsStringWhereNumberDue) {
    EXPECT_MESSAGE(lightShadowError({{"pcfRadius", "wide"}}),
                   "KHR_lights_punctual.lights[1].extras.shadow.pcfRadius: must be a number");
    Doc doc;
    doc.light({{"type", "spot"}, {"intensity", "bright"}, {"spot", json::object()}});
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "KHR_lights_punctual.lights[0].intensity: must be a number");
}

// The lengths whose default follows the scene take "auto" (the default itself) or metres.
TEST(GltfImport, LengthSettingsTakeAutoOrMetres) {
    Doc doc;
    doc.light(
        {{"type", "spot"},
         {"spot", json::object()},
         {"extras",
          {{"shadow",
            {{"pcfRadius", "auto"}, {"constantBias", 0.002}, {"sdfStartOffset", "auto"}, {"sdfMinStep", 0.01}}}}}});
    doc.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const Result<Scene> scene = loadGltf(doc.write(testDir() / "auto.gltf").string());
    ASSERT_TRUE(scene) << scene.error().message;
    const Shadow& s = scene->world.get<Shadow>(scene->lights.at(0));
    EXPECT_TRUE(isAutomatic(s.pcfRadius));
    EXPECT_TRUE(isAutomatic(s.sdfStartOffset));
    EXPECT_FLOAT_EQ(s.constantBias, 0.002f);
    EXPECT_FLOAT_EQ(s.sdfMinStep, 0.01f);
    EXPECT_MESSAGE(lightShadowError({{"constantBias", "automatic"}}),
                   "KHR_lights_punctual.lights[1].extras.shadow.constantBias: must be a number >= 0 or \"auto\"");
}

// A misspelt key of extras.shadow does nothing: it is warned about, naming the key, with the
// known key it is closest to.
TEST(GltfImport, UnknownShadowKeysAreWarnedWithTheClosestKnownKey) {
    Doc doc;
    doc.light({{"type", "point"}, {"extras", {{"shadow", {{"techniqe", "pcss"}, {"futureKnob", 1}}}}}});
    doc.node({{"name", "lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh()}, {"extras", {{"shadow", {{"recieve", false}}}}}});
    const std::string path = doc.write(testDir() / "typo.gltf").string();
    auto scene = loadGltf(path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->warnings.size(), 3u);
    // tinygltf keeps an object's keys sorted: futureKnob, then techniqe.
    EXPECT_EQ(scene->warnings[0].element, "KHR_lights_punctual.lights[0].extras.shadow.futureKnob");
    EXPECT_EQ(scene->warnings[0].message.find("did you mean"), std::string::npos) << scene->warnings[0].message;
    expectWarning(scene->warnings[1], WarningCode::UnknownSetting,
                  "KHR_lights_punctual.lights[0].extras.shadow.techniqe",
                  path +
                      ": KHR_lights_punctual.lights[0].extras.shadow: unknown key \"techniqe\" ignored "
                      "(did you mean \"technique\"?)");
    EXPECT_EQ(scene->warnings[2].code, WarningCode::UnknownSetting);
    EXPECT_EQ(scene->warnings[2].element, "nodes[1].extras.shadow.recieve");
    EXPECT_MESSAGE(scene->warnings[2].message, "(did you mean \"receive\"?)");
}

// Lenient loading (a game that must show what it can): each `extras.shadow` that does not parse
// is replaced by the defaults and reported once, naming the object; the rest loads as written.
TEST(GltfImport, LenientLoadReplacesBadShadowExtrasByDefaultsWithOneWarningEach) {
    Doc doc;
    doc.light({{"type", "point"}, {"extras", {{"shadow", {{"technique", "pcss"}, {"mapSize", -512}}}}}});
    doc.light({{"type", "point"}, {"extras", {{"shadow", {{"technique", "pcf"}, {"mapSize", 256}}}}}});
    doc.node({{"name", "bad lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    doc.node({{"name", "good lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh()}, {"extras", {{"shadow", {{"receive", "no"}}}}}});
    const std::string path = doc.write(testDir() / "lenient.gltf").string();
    EXPECT_MESSAGE(loadError(path), "KHR_lights_punctual.lights[0].extras.shadow.mapSize");

    GltfLoadOptions lenient;
    lenient.strictShadowSettings = false;
    auto scene = loadGltf(path, lenient);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->warnings.size(), 2u);
    expectWarning(scene->warnings[0], WarningCode::ShadowSettingsIgnored, "KHR_lights_punctual.lights[0].extras.shadow",
                  path +
                      ": KHR_lights_punctual.lights[0].extras.shadow.mapSize: must be a positive integer "
                      "(ignored: the defaults are used)");
    expectWarning(scene->warnings[1], WarningCode::ShadowSettingsIgnored, "nodes[2].extras.shadow",
                  path + ": nodes[2].extras.shadow.receive: must be true or false (ignored: the defaults are used)");

    const World& w = scene->world;
    // The whole object is ignored, its valid technique too.
    EXPECT_EQ(w.get<Shadow>(findByName(*scene, "bad lamp")).technique, Shadow{}.technique);
    EXPECT_EQ(w.get<Shadow>(findByName(*scene, "bad lamp")).mapSize, Shadow{}.mapSize);
    EXPECT_EQ(w.get<Shadow>(findByName(*scene, "good lamp")).technique, ShadowTechnique::Pcf);
    EXPECT_EQ(w.get<Shadow>(findByName(*scene, "good lamp")).mapSize, 256);
    EXPECT_TRUE(w.get<Mesh>(findByName(*scene, "tri")).receiveShadows) << "the default";
}

TEST(GltfImport, ZeroScaleLightsPointAlongTheirRotationAndAMatrixWithoutOneWarns) {
    Doc doc;
    const int spot = doc.light({{"type", "spot"}, {"spot", {{"outerConeAngle", 0.6}}}});
    const int sun = doc.light({{"type", "directional"}});
    // Scale 0 with a rotation of -90 degrees about X: the spot shines down -Y.
    const double h = std::sqrt(0.5);
    doc.node({{"name", "spot"},
              {"scale", {0, 0, 0}},
              {"rotation", {-h, 0, 0, h}},
              {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
    // One zero column of three: the other two still hold the rotation (+Y forward, +Z up).
    doc.node({{"name", "tilted"},
              {"matrix", {0, 0, 0, 0, 0, 0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 1}},
              {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
    // Only zero columns: no rotation at all; the sun and a camera below it warn.
    const int camera = doc.push("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
    const int below = doc.node({{"name", "eye"}, {"camera", camera}});
    doc.node({{"name", "sun"},
              {"matrix", {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 3, 1}},
              {"children", {below}},
              {"extensions", {{"KHR_lights_punctual", {{"light", sun}}}}}});
    doc.scene({0, 1, 3});
    auto scene = loadGltf(doc.write(testDir() / "zero_scale.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    (void)updateTransforms(scene->world);
    const auto forward = [&](const std::string& name) {
        return -worldOrientation(scene->world.get<WorldTransform>(findByName(*scene, name)))[2];
    };
    expectVec3(forward("spot"), {0, -1, 0}, 1e-12);
    expectVec3(forward("tilted"), {0, 1, 0}, 1e-12);
    expectVec3(forward("sun"), {0, 0, -1}, 1e-12);
    expectVec3(forward("eye"), {0, 0, -1}, 1e-12);
    ASSERT_EQ(scene->warnings.size(), 2u);
    EXPECT_EQ(scene->warnings[0].code, WarningCode::DegenerateTransform);
    EXPECT_EQ(scene->warnings[0].element, "nodes[3]");
    EXPECT_MESSAGE(scene->warnings[0].message, "nodes[3] (sun): its matrix has fewer than two non-zero columns");
    EXPECT_EQ(scene->warnings[1].code, WarningCode::DegenerateTransform);
    EXPECT_EQ(scene->warnings[1].element, "nodes[2]");
    EXPECT_MESSAGE(scene->warnings[1].message, "the matrix of its ancestor nodes[3]");
}

}  // namespace
}  // namespace shadow
