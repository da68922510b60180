// Bad light settings never stop the other lights: lights built in code with NaN, infinite or
// negative fields are drawn clamped (with one warning per field) and every other light renders
// exactly as without them; a glTF file whose `extras.shadow` does not parse fails as a whole
// under the default (strict) options, and under lenient ones keeps the other lights' settings
// and gives the bad light the defaults, with the error as a warning.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "scene/gltf_import.h"
#include "stability/stability_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

/// Ground, a box, a good spot and a good sun, and a camera.
Scene goodScene() {
    Scene scene;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "box", {0.0, 1.2, 0.0}, {0.5, 0.3, 0.4});
    addCamera(scene, "camera", Camera{}, {0.5, 5.0, 4.5}, {0.0, 0.0, 0.0});
    Light spot = test::pointSizedLight(LightType::Spot, 0.7f);
    spot.radius = 0.1f;
    addLight(scene, "good spot", spot, test::shadowWith(ShadowTechnique::Hard, 512), {0.3, 4.0, 0.2}, {0, -1, 0});
    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.02f;
    addLight(scene, "good sun", sun, test::shadowWith(ShadowTechnique::Hard, 512), {0, 8, 0}, {0.2, -1, 0.1});
    return scene;
}

TEST(Stability, BadLightSettingsNeverStopTheOtherLights) {
    Scene clean = goodScene();
    Scene scene = goodScene();
    // Shading fields out of range, on an unshadowed and on a shadowed light.
    Light nanSpot = test::pointSizedLight(LightType::Spot, kNaN);
    nanSpot.intensity = kNaN;
    nanSpot.color = glm::vec3(-kInf, kNaN, 1e30f);
    nanSpot.range = -1.0f;
    Shadow none;
    none.technique = ShadowTechnique::None;
    addLight(scene, "nan lamp", nanSpot, none, {-1.0, 3.0, 0.0}, {0, -1, 0});
    Light wild = test::pointSizedLight(LightType::Point);
    wild.intensity = kInf;
    wild.radius = kNaN;
    Shadow bad;
    bad.technique = ShadowTechnique::Pcss;
    bad.mapSize = -7;
    bad.constantBias = kNaN;
    bad.slopeBias = -kInf;
    bad.normalOffset = 1e9f;
    bad.pcfRadius = kInf;
    bad.pcfSamples = 0;
    bad.blockerSamples = 100000;
    bad.maxFilterTexels = kNaN;
    bad.lightBleedReduction = -kInf;
    bad.nearPlane = -3.0f;
    addLight(scene, "wild bulb", wild, bad, {1.0, 3.0, -0.5}, {0, -1, 0});

    test::glContext();
    FrameRunner cleanRunner;
    const test::RenderedFrame reference = test::renderFrame(cleanRunner, clean, 128, 96);
    test::forEveryTechnique(
        scene, 128, 96, "bad lights", [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
            // One warning per bad field: the nan lamp's intensity, colour (3), range and both
            // cone angles (the inner one is half the NaN outer one); the wild bulb's intensity,
            // radius and its ten bad shadow settings. Nothing about the good lights.
            const auto& w = frame.stats.warnings;
            EXPECT_EQ(test::countWarnings(w, WarningCode::SettingClamped, "nan lamp"), 7) << test::describe(w);
            EXPECT_EQ(test::countWarnings(w, WarningCode::SettingClamped, "wild bulb"), 12) << test::describe(w);
            EXPECT_EQ(w.size(), 19u) << test::describe(w);
            if (technique != ShadowTechnique::Hard) return;
            // The good lights' shadows are those of the clean scene.
            for (std::size_t i = 0; i < reference.images.visibility.size(); ++i) {
                EXPECT_EQ(reference.images.visibility[i].pixels, frame.images.visibility[i].pixels) << "light " << i;
            }
        });
}

/// A glTF document (JSON, no buffers) with three lights, a node for each and a camera; light 1
/// carries `badShadow` as its extras.shadow.
std::string threeLights(const std::string& badShadow) {
    return R"({
  "asset": {"version": "2.0"},
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "intensity": 20, "spot": {"outerConeAngle": 0.7},
     "extras": {"shadow": {"technique": "pcf", "mapSize": 512}}},
    {"type": "point", "intensity": 20, "extras": {"shadow": )" +
           badShadow + R"(}},
    {"type": "directional", "intensity": 3, "extras": {"shadow": {"technique": "pcss", "mapSize": 256}}}
  ]}},
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100}}],
  "nodes": [
    {"name": "spot", "translation": [0.3, 4, 0.2], "rotation": [-0.7071068, 0, 0, 0.7071068],
     "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "bulb", "translation": [-0.5, 3.5, 0.4], "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"name": "sun", "rotation": [-0.6, 0.1, 0.1, 0.78], "extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"name": "camera", "translation": [0.5, 5, 4.5], "rotation": [-0.42, 0.04, 0.02, 0.9], "camera": 0}
  ]
})";
}

TEST(Stability, BogusShadowExtrasFailStrictlyOrFallBackToDefaultsLeniently) {
    const std::vector<std::string> bogus = {
        R"({"technique": "raytraced"})",
        R"({"mapSize": "big"})",
        R"({"mapSize": -512})",
        R"({"radius": -1})",
        R"({"lightBleedReduction": -0.5})",
        R"({"pcfSamples": 2.5})",
        R"({"kernel": 7})",
        R"("hard")",
        R"([1, 2])",
        R"({"cascades": 0})",
        R"({"cast": "yes", "technique": "hard", "slopeBias": "steep"})",
    };
    GltfLoadOptions lenient;
    lenient.strictShadowSettings = false;
    for (const std::string& b : bogus) {
        const std::string json = threeLights(b);
        // Strict (the CLIs): one message naming the element.
        const Result<Scene> strict = gltf::loadGltfFromMemory(json, "bogus.gltf");
        ASSERT_FALSE(strict.ok()) << b;
        EXPECT_NE(strict.error().message.find("bogus.gltf: KHR_lights_punctual.lights[1].extras.shadow"),
                  std::string::npos)
            << strict.error().message;
        // Lenient: every light is there, the bad one with the defaults, the others as written.
        Result<Scene> loaded = gltf::loadGltfFromMemory(json, "bogus.gltf", lenient);
        ASSERT_TRUE(loaded.ok()) << b << ": " << loaded.error().message;
        Scene& scene = *loaded;
        ASSERT_EQ(scene.lights.size(), 3u);
        // One warning for the settings set aside; besides it only a key no light reads (`cast`
        // is a mesh's) is named, as unknown.
        const auto ignored = std::find_if(scene.warnings.begin(), scene.warnings.end(), [](const Warning& w) {
            return w.code == WarningCode::ShadowSettingsIgnored;
        });
        ASSERT_NE(ignored, scene.warnings.end()) << b;
        const bool hasUnknownKey = b.find("\"cast\"") != std::string::npos;
        ASSERT_EQ(scene.warnings.size(), hasUnknownKey ? 2u : 1u) << b;
        for (const Warning& w : scene.warnings) {
            if (&w != &*ignored) {
                EXPECT_EQ(w.code, WarningCode::UnknownSetting) << b << ": " << w.message;
            }
        }
        EXPECT_EQ(ignored->element, "KHR_lights_punctual.lights[1].extras.shadow") << b;
        // The line a person reads names the file first.
        EXPECT_EQ(ignored->message.rfind("bogus.gltf: ", 0), 0u) << ignored->message;
        const World& w = scene.world;
        EXPECT_EQ(w.get<Shadow>(scene.lights[0]).technique, ShadowTechnique::Pcf);
        EXPECT_EQ(w.get<Shadow>(scene.lights[0]).mapSize, 512);
        EXPECT_EQ(w.get<Shadow>(scene.lights[1]).technique, Shadow{}.technique);
        EXPECT_EQ(w.get<Shadow>(scene.lights[1]).mapSize, Shadow{}.mapSize);
        EXPECT_EQ(w.get<Shadow>(scene.lights[2]).technique, ShadowTechnique::Pcss);
    }
}

/// A mesh node's bogus `extras.shadow` (the fuzz corpus's triangle, its flags made a number).
TEST(Stability, BogusMeshShadowFlagsFailStrictlyOrFallBackToDefaultsLeniently) {
    std::ifstream in(SHADOW_FUZZ_DIR "/corpus/triangle.gltf");
    nlohmann::json doc = nlohmann::json::parse(in);
    doc["nodes"][0]["extras"]["shadow"]["cast"] = 1;
    const std::string json = doc.dump();
    const Result<Scene> strict = gltf::loadGltfFromMemory(json, "mesh.gltf");
    ASSERT_FALSE(strict.ok());
    EXPECT_EQ(strict.error().message, "mesh.gltf: nodes[0].extras.shadow.cast: must be true or false");
    GltfLoadOptions lenient;
    lenient.strictShadowSettings = false;
    Result<Scene> loaded = gltf::loadGltfFromMemory(json, "mesh.gltf", lenient);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    ASSERT_EQ(loaded->warnings.size(), 1u);
    EXPECT_EQ(loaded->warnings[0].code, WarningCode::ShadowSettingsIgnored);
    EXPECT_EQ(loaded->warnings[0].element, "nodes[0].extras.shadow");
    // The strict load's message, and what was done about it.
    EXPECT_EQ(loaded->warnings[0].message,
              "mesh.gltf: nodes[0].extras.shadow.cast: must be true or false (ignored: the "
              "defaults are used)");
    int meshes = 0;
    loaded->world.view<Mesh>().each([&](Entity, Mesh& m) {
        ++meshes;
        EXPECT_TRUE(m.castShadows && m.receiveShadows) << "the defaults: cast and receive";
    });
    EXPECT_EQ(meshes, 2);
}

/// The lenient scene renders every light, the one with bogus settings included.
TEST(Stability, LenientlyLoadedSceneRendersEveryLight) {
    GltfLoadOptions lenient;
    lenient.strictShadowSettings = false;
    Result<Scene> loaded =
        gltf::loadGltfFromMemory(threeLights(R"({"technique": "raytraced", "mapSize": "big"})"), "bogus.gltf", lenient);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    Scene& scene = *loaded;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "box", {0.0, 1.2, 0.0}, {0.5, 0.3, 0.4});
    scene.world.get<Shadow>(scene.lights[1]).mapSize = 512;  // keep the test fast
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, 128, 96);
    test::expectSaneFrame(frame.images, runner.shadows(), "lenient scene");
    ASSERT_EQ(runner.shadows().frame().lights.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_GT(test::countGround(frame.images, i).dark, 100) << "light " << i << " casts no shadow";
    }
}

}  // namespace
}  // namespace shadow
