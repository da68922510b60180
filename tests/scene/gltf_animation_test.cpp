// glTF animations (engine/src/scene/gltf_animation.cpp, animation_clips.cpp): channels imported
// so that they animate as sampled, one clip playing unless all are asked for, and the malformed
// samplers that fail the load.
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

/// Animation 0, "walk" (2 s): LINEAR translation (0..2 s) and STEP scale of node 0. Animation 1,
/// "wave" (4 s): CUBICSPLINE translation of node 1 (0..2 s) and LINEAR rotation of node 0 (0..4 s).
Doc animatedDoc() {
    Doc doc;
    doc.node({{"name", "a"}});
    doc.node({{"name", "b"}});
    const int t02 = doc.floats({0, 2}, "SCALAR");
    const int t01 = doc.floats({0, 1}, "SCALAR");
    const int t04 = doc.floats({0, 4}, "SCALAR");
    const auto sampler = [](int in, int out, const char* interpolation) {
        return json{{"input", in}, {"output", out}, {"interpolation", interpolation}};
    };
    const auto channel = [](int s, int node, const char* path) {
        return json{{"sampler", s}, {"target", {{"node", node}, {"path", path}}}};
    };
    doc.push("animations", {{"name", "walk"},
                            {"samplers",
                             {sampler(t02, doc.floats({0, 0, 0, 2, 4, 6}, "VEC3"), "LINEAR"),
                              sampler(t01, doc.floats({1, 1, 1, 3, 3, 3}, "VEC3"), "STEP")}},
                            {"channels", {channel(0, 0, "translation"), channel(1, 0, "scale")}}});
    const float s = static_cast<float>(std::sin(0.25 * M_PI));
    const int cubic = doc.floats({0, 0, 0, 0, 0, 0, 1, 0, 0,  /* key 0: in, value, out */
                                  0, 0, 0, 1, 0, 0, 0, 0, 0}, /* key 1 */
                                 "VEC3");
    doc.push(
        "animations",
        {{"name", "wave"},
         {"samplers",
          {sampler(t02, cubic, "CUBICSPLINE"), sampler(t04, doc.floats({0, 0, 0, 1, 0, s, 0, s}, "VEC4"), "LINEAR")}},
         {"channels", {channel(0, 1, "translation"), channel(1, 0, "rotation")}}});
    return doc;
}

TEST(GltfImport, ImportsAnimationChannelsThatAnimateAsSampled) {
    Doc doc = animatedDoc();
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string(), {.animation = "all"});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    World& w = scene->world;
    const Entity a = findByName(*scene, "a");
    const Entity b = findByName(*scene, "b");
    EXPECT_DOUBLE_EQ(scene->animationDuration, 4.0);
    EXPECT_DOUBLE_EQ(w.get<Animation>(a).duration, 4.0);  // longest animation targeting it
    EXPECT_DOUBLE_EQ(w.get<Animation>(b).duration, 4.0);  // its animation's last key is at 4 s
    EXPECT_EQ(w.get<Animation>(a).channels.size(), 3u);

    animate(w, 0.5);
    expectVec3(w.get<Transform>(a).translation, {0.5, 1.0, 1.5});
    expectVec3(w.get<Transform>(a).scale, {1, 1, 1});  // STEP holds key 0 until t = 1
    animate(w, 1.0);
    expectVec3(w.get<Transform>(a).scale, {3, 3, 3});
    // Hermite with dt = 2, out-tangent 1 at key 0: x(u=0.5) = 2 * 0.125 + 0.5.
    expectVec3(w.get<Transform>(b).translation, {0.75, 0, 0});
    animate(w, 2.0);  // 45 deg of the 90 deg turn over 4 s
    expectSameRotation(w.get<Transform>(a).rotation, glm::angleAxis(0.25 * M_PI, glm::dvec3(0, 1, 0)));
    animate(w, 3.0);  // after the last translation key: held
    expectVec3(w.get<Transform>(a).translation, {2, 4, 6});
    animate(w, 4.5);  // wraps: 4.5 mod 4 = 0.5
    expectVec3(w.get<Transform>(a).translation, {0.5, 1.0, 1.5});
    animate(w, 5.0);  // b loops with animation 1: 5 mod 4 = 1
    expectVec3(w.get<Transform>(b).translation, {0.75, 0, 0});
    animate(w, 3.0);  // b holds its last key from 2 s to the end of its 4 s animation
    expectVec3(w.get<Transform>(b).translation, {1, 0, 0});
}

TEST(GltfImport, PlaysOnlyTheFirstClipUnlessAskedOtherwise) {
    Doc doc = animatedDoc();
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    World& w = scene->world;
    const Entity a = findByName(*scene, "a");
    const Entity b = findByName(*scene, "b");
    ASSERT_EQ(scene->clips.size(), 2u);
    EXPECT_EQ(scene->clips[0].name, "walk");
    EXPECT_EQ(scene->clips[1].name, "wave");
    EXPECT_EQ(scene->playing, std::vector<std::size_t>{0});
    EXPECT_DOUBLE_EQ(scene->animationDuration, 2.0);
    EXPECT_EQ(w.get<Animation>(a).channels.size(), 2u);  // walk's translation and scale
    EXPECT_DOUBLE_EQ(w.get<Animation>(a).duration, 2.0);
    EXPECT_FALSE(w.has<Animation>(b)) << "wave moves b; it does not play";
    animate(w, 2.0);
    expectVec3(w.get<Transform>(a).translation, {0, 0, 0});                    // walk loops: 2 mod 2 = 0
    expectSameRotation(w.get<Transform>(a).rotation, glm::dquat(1, 0, 0, 0));  // wave's turn is not applied
    animate(w, 0.5);
    expectVec3(w.get<Transform>(a).translation, {0.5, 1.0, 1.5});
}

TEST(GltfImport, PlaysOnlyTheChosenClipByNameOrIndex) {
    Doc doc = animatedDoc();
    const auto path = doc.write(testDir() / "s.gltf").string();
    for (const char* choice : {"wave", "1"}) {
        auto scene = loadGltf(path, {.animation = choice});
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        World& w = scene->world;
        const Entity a = findByName(*scene, "a");
        EXPECT_EQ(scene->playing, std::vector<std::size_t>{1}) << choice;
        EXPECT_DOUBLE_EQ(scene->animationDuration, 4.0) << choice;
        animate(w, 2.0);  // 45 deg of wave's 90 deg turn; walk's translation is not applied
        expectSameRotation(w.get<Transform>(a).rotation, glm::angleAxis(0.25 * M_PI, glm::dvec3(0, 1, 0)));
        expectVec3(w.get<Transform>(a).translation, {0, 0, 0});
        expectVec3(w.get<Transform>(findByName(*scene, "b")).translation, {1, 0, 0});
    }
}

TEST(GltfImport, SwitchingClipsPutsWhatTheOldOneMovedBackAsLoaded) {
    Doc doc = animatedDoc();
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    World& w = scene->world;
    const Entity a = findByName(*scene, "a");
    animate(w, 1.0);
    expectVec3(w.get<Transform>(a).scale, {3, 3, 3});  // walk's STEP scale
    ASSERT_TRUE(playAnimation(*scene, "wave").ok());
    expectVec3(w.get<Transform>(a).scale, {1, 1, 1});
    expectVec3(w.get<Transform>(a).translation, {0, 0, 0});
    EXPECT_EQ(w.get<Animation>(a).channels.size(), 1u);
    ASSERT_TRUE(playAnimation(*scene, "").ok());  // back to the first
    EXPECT_EQ(scene->playing, std::vector<std::size_t>{0});
    EXPECT_FALSE(w.has<Animation>(findByName(*scene, "b")));
}

TEST(GltfImport, ClipTheFileLacksIsOneErrorNamingIt) {
    Doc doc = animatedDoc();
    const auto path = doc.write(testDir() / "s.gltf").string();
    const Result<Scene> byName = loadGltf(path, {.animation = "run"});
    ASSERT_FALSE(byName.ok());
    EXPECT_EQ(byName.error().message,
              path + ": animation \"run\": no clip of that name (the scene's: 0 \"walk\", 1 \"wave\", or all)");
    const Result<Scene> byIndex = loadGltf(path, {.animation = "2"});
    ASSERT_FALSE(byIndex.ok());
    EXPECT_MESSAGE(byIndex.error().message, "animation \"2\": no clip of that index");
    // A scene without clips: a name is an error, the default and `all` play nothing.
    auto still = makeBuiltinScene("plates");
    ASSERT_TRUE(still.ok());
    EXPECT_FALSE(playAnimation(*still, "walk").ok());
    EXPECT_TRUE(playAnimation(*still, "all").ok());
    EXPECT_FALSE(loadScene("builtin:plates", {.animation = "0"}).ok());
}

TEST(GltfImport, RejectsNonIncreasingKeyTimes) {
    Doc doc = animatedDoc();
    doc.j["animations"][0]["samplers"][0]["input"] = doc.floats({1, 1}, "SCALAR");
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "animations[0].samplers[0].input: key times not strictly increasing at key 1");
}

TEST(GltfImport, RejectsCubicSplineWithOneValuePerKey) {
    Doc doc = animatedDoc();
    doc.j["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE";
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "animations[0].samplers[0].output: has 2 values for 2 keys (expected 6)");
}

TEST(GltfImport, RejectsNanInAnimationKeys) {
    Doc doc = animatedDoc();
    doc.j["animations"][0]["samplers"][0]["output"] =
        doc.floats({0, 0, 0, 2, std::numeric_limits<float>::infinity(), 6}, "VEC3");
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")), "animations[0].samplers[0].output: accessors[");
}

}  // namespace
}  // namespace shadow
