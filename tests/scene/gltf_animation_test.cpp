// glTF animations (engine/src/scene/gltf_animation.cpp): channels imported so that they animate
// as sampled, and the malformed samplers that fail the load.
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

/// Animation 0 (2 s): LINEAR translation (0..2 s) and STEP scale of node 0. Animation 1 (4 s):
/// CUBICSPLINE translation of node 1 (0..2 s) and LINEAR rotation of node 0 (0..4 s).
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
    doc.push("animations", {{"samplers",
                             {sampler(t02, doc.floats({0, 0, 0, 2, 4, 6}, "VEC3"), "LINEAR"),
                              sampler(t01, doc.floats({1, 1, 1, 3, 3, 3}, "VEC3"), "STEP")}},
                            {"channels", {channel(0, 0, "translation"), channel(1, 0, "scale")}}});
    const float s = static_cast<float>(std::sin(0.25 * M_PI));
    const int cubic = doc.floats({0, 0, 0, 0, 0, 0, 1, 0, 0,  /* key 0: in, value, out */
                                  0, 0, 0, 1, 0, 0, 0, 0, 0}, /* key 1 */
                                 "VEC3");
    doc.push(
        "animations",
        {{"samplers",
          {sampler(t02, cubic, "CUBICSPLINE"), sampler(t04, doc.floats({0, 0, 0, 1, 0, s, 0, s}, "VEC4"), "LINEAR")}},
         {"channels", {channel(0, 1, "translation"), channel(1, 0, "rotation")}}});
    return doc;
}

TEST(GltfImport, ImportsAnimationChannelsThatAnimateAsSampled) {
    Doc doc = animatedDoc();
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
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
