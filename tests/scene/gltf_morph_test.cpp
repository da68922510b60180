// glTF morph targets on the CPU: what the loader reads (targets, mesh and node weights, `weights`
// channels), what it refuses (one error naming the accessor's glTF path), and the morphed
// positions and bounds `updateTransforms` gives.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <algorithm>
#include <iterator>

#include "scene/gltf_test_support.h"

namespace shadow::gltf_test {
namespace {

Scene load(Doc doc) {
    auto scene = loadGltf(doc.write(testDir() / "morph.gltf").string());
    EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
    return scene.ok() ? std::move(*scene) : Scene{};
}

// The loader keeps the target's displacements and the mesh's weights, with no warning; the
// morphed positions and world bounds follow the weight.
TEST(GltfMorph, ReadsTargetsAndWeights) {
    Scene scene = load(morphSheetDoc(0.25f));
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front().message;
    const Entity sheet = findByName(scene, "sheet");
    const Morph& morph = scene.world.get<Morph>(sheet);
    ASSERT_EQ(morph.weights, std::vector<float>{0.25f});
    const MeshData& data = *scene.world.get<Mesh>(sheet).data;
    ASSERT_EQ(data.morphTargets, 1U);
    ASSERT_EQ(data.morphPositions.size(), 4U);
    (void)updateTransforms(scene.world);
    ASSERT_EQ(morph.drawn.size(), 1U);
    expectVec3(glm::dvec3(morphedPosition(data, morph, 1)), {0.75, 0.0, -0.5});
    const DAabb& box = scene.world.get<WorldBounds>(sheet).box;
    expectVec3(box.min, {-0.5, 1.0, -0.5});
    expectVec3(box.max, {0.75, 1.0, 0.5});
}

// The node's weights override the mesh's; all-zero weights draw no target (a rigid draw).
TEST(GltfMorph, NodeWeightsOverrideTheMesh) {
    Doc doc = morphSheetDoc(0.25f);
    doc.j["nodes"][0]["weights"] = {0.0};
    Scene scene = load(doc);
    const Entity sheet = findByName(scene, "sheet");
    EXPECT_EQ(scene.world.get<Morph>(sheet).weights, std::vector<float>{0.0f});
    (void)updateTransforms(scene.world);
    EXPECT_TRUE(scene.world.get<Morph>(sheet).drawn.empty());
    expectVec3(scene.world.get<WorldBounds>(sheet).box.max, {0.5, 1.0, 0.5});
}

// A `weights` channel drives the weight: LINEAR halfway at t = 1, STEP holding the first key,
// CUBICSPLINE with zero tangents a smoothstep (0.5 at the middle, 0.15625 at a quarter).
TEST(GltfMorph, WeightsChannelsPlay) {
    const std::vector<std::tuple<std::string, double, float>> cases{
        {"LINEAR", 1.0, 0.5f}, {"STEP", 1.9, 0.0f}, {"CUBICSPLINE", 1.0, 0.5f}, {"CUBICSPLINE", 0.5, 0.15625f}};
    for (const auto& [interpolation, t, expected] : cases) {
        Scene scene = load(morphSheetDoc(0.0f, true, interpolation));
        animate(scene.world, t);
        EXPECT_NEAR(scene.world.get<Morph>(findByName(scene, "sheet")).weights.at(0), expected, 1e-6)
            << interpolation << " at t = " << t;
    }
}

// A target accessor of the wrong count or type is one error naming its glTF path.
TEST(GltfMorph, BadTargetAccessorNamesItsPath) {
    Doc count = morphSheetDoc(0.0f);
    count.j["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = count.floats({1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");
    EXPECT_MESSAGE(loadError(count.write(testDir() / "count.gltf")),
                   "meshes[0].primitives[0].targets[0].POSITION: has 3 elements, POSITION has 4");
    Doc type = morphSheetDoc(0.0f);
    type.j["meshes"][0]["primitives"][0]["targets"][0]["NORMAL"] = type.floats({0, 0, 0, 0, 0, 0, 0, 0}, "VEC2");
    EXPECT_MESSAGE(loadError(type.write(testDir() / "type.gltf")), "meshes[0].primitives[0].targets[0].NORMAL: ");
    Doc weights = morphSheetDoc(0.0f);
    weights.j["meshes"][0]["weights"] = {0.0, 1.0};
    EXPECT_MESSAGE(loadError(weights.write(testDir() / "weights.gltf")),
                   "meshes[0].weights: has 2 weights for 1 morph targets");
}

// A `weights` channel of a node without morph targets is one error naming the channel.
TEST(GltfMorph, WeightsChannelWithoutTargetsIsAnError) {
    Doc doc = morphSheetDoc(0.0f, true);
    doc.j["meshes"][0]["primitives"][0].erase("targets");
    doc.j["meshes"][0].erase("weights");
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "animations[0].channels[0].target.node: node 0 has no mesh with morph targets");
}

/// The `MorphTargetsDropped` warnings in `warnings`.
std::vector<Warning> droppedTargets(const std::vector<Warning>& warnings) {
    std::vector<Warning> out;
    std::copy_if(warnings.begin(), warnings.end(), std::back_inserter(out),
                 [](const Warning& w) { return w.code == WarningCode::MorphTargetsDropped; });
    return out;
}

// 17 non-zero weights are one more than a draw blends: one warning naming the node and the mesh,
// however many frames follow; 16 fit, and none is given.
TEST(GltfMorph, MoreWeightsThanADrawBlendsWarnOncePerEntity) {
    for (const std::size_t targets : {kMaxMorphInfluences + 1, kMaxMorphInfluences}) {
        Scene scene = load(manyTargetsSheetDoc(targets));
        ASSERT_TRUE(droppedTargets(scene.warnings).empty()) << "a frame reports it, not the load";
        for (int frame = 0; frame < 3; ++frame) {
            (void)updateTransforms(scene.world);
            reportTruncatedMorphs(scene.world, scene.warnings);
        }
        const std::vector<Warning> dropped = droppedTargets(scene.warnings);
        if (targets == kMaxMorphInfluences) {
            EXPECT_TRUE(dropped.empty()) << dropped.front().message;
            continue;
        }
        ASSERT_EQ(dropped.size(), 1U) << "once per entity, not once per frame";
        expectWarning(dropped[0], WarningCode::MorphTargetsDropped, "sheet",
                      "sheet: mesh 'fan' has 17 morph weights non-zero at once, more than the 16 a draw blends; "
                      "the 16 of largest magnitude are drawn and the rest left out");
        EXPECT_EQ(scene.world.get<Morph>(findByName(scene, "sheet")).drawn.size(), kMaxMorphInfluences);
    }
}

}  // namespace
}  // namespace shadow::gltf_test
