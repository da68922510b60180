// Morph targets in the shadow passes: a morphed sheet over the ground under a sun casts the
// shadow of its morphed shape (against the geometric projection of that shape and against the
// ray-traced reference, which morphs on the CPU), its weight animated or set, and its layers are
// redrawn when, and only when, its drawn weights changed; skinned too, it is morphed first and
// then skinned (glTF's order) in the shadow pass and the reference alike. The sheet comes from a
// glTF file the test writes (tests/scene/gltf_test_support.h, `morphSheetDoc`).
#include <gtest/gtest.h>
#include <shadow/reference.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/truth_test_support.h"
#include "scene/gltf_test_support.h"

namespace shadow::test::morph_shadow_test {
namespace {

using gltf_test::json;

constexpr int kWidth = 240;
constexpr int kHeight = 180;
/// Towards the sun, tilted so the shadow falls beside the sheet where the camera sees it.
const glm::dvec3 kToSun = glm::normalize(glm::dvec3(-0.5, 1.0, 0.2));
/// Ground pixels this close (m) to the projected outline are not judged: a 2048 map's texel on
/// this view is below 1 cm, and a pixel spans about 2 cm.
constexpr double kEdgeMargin = 0.04;

/// The sheet scene: the file's sheet (1 m above the ground) and a ground, sun and camera.
Scene sheetScene(gltf_test::Doc doc) {
    auto loaded = loadGltf(doc.write(gltf_test::testDir() / "sheet.gltf").string());
    EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : loaded.error().message);
    Scene scene = loaded.ok() ? std::move(*loaded) : Scene{};
    addGround(scene, 4.0f);
    addLight(scene, "sun", pointSizedLight(LightType::Directional), hardShadow(2048), {0, 10, 0}, -kToSun);
    addCamera(scene, "camera", Camera{}, {1.0, 5.0, 3.5}, {1.0, 0.0, 0.0});
    return scene;
}

/// The sheet's shape at y = 1 m: a rectangle x in [x0, x1], z in [z0, z1] (m, world space).
struct Rect {
    double x0 = -0.5, x1 = 0.5, z0 = -0.5, z1 = 0.5;
};

/// The sheet at `weight`: its +x edge moved by `weight` m.
Rect stretchedSheet(double weight) { return {-0.5, 0.5 + weight, -0.5, 0.5}; }

/// Ground pixels by the geometric projection of the sheet `shape` against light 0's visibility,
/// away from the outline.
struct Footprint {
    int judged = 0;     ///< ground pixels farther than kEdgeMargin from the outline
    int predicted = 0;  ///< of those, inside the projected sheet
    int mismatches = 0;
    /// Predicted pixels under the part a morph moved: outside the rest square grown by 0.1 m.
    int band = 0;
};

Footprint footprint(const FrameImages& images, const Rect& shape) {
    Footprint f;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (!isGroundPixel(images, x, y)) continue;
            const glm::dvec3 p = positionAt(images, x, y);
            const glm::dvec3 q = p + kToSun * ((1.0 - p.y) / kToSun.y);  // on the sheet's plane
            const double inside = std::min({q.x - shape.x0, shape.x1 - q.x, q.z - shape.z0, shape.z1 - q.z});
            if (std::abs(inside) < kEdgeMargin) continue;
            ++f.judged;
            const bool shadowed = images.visibility.at(0).at(x, y, 0) < 0.5f;
            f.predicted += inside > 0.0 ? 1 : 0;
            f.band += inside > 0.0 && std::max(std::abs(q.x), std::abs(q.z)) > 0.6 ? 1 : 0;
            f.mismatches += (inside > 0.0) != shadowed ? 1 : 0;
        }
    }
    return f;
}

// Weight 0 casts the square's shadow, weight 1 the sheet stretched to twice its width: each
// matches the projection of its shape (mismatches at most a tenth of the pixels under the moved
// part, which the base shape would get wrong; measured 0).
TEST(MorphShadow, FollowsTheWeightsAndMatchesTheGeometry) {
    glContext();
    Scene scene = sheetScene(gltf_test::morphSheetDoc(0.0f));
    FrameRunner runner;
    const Footprint rest = footprint(renderFrame(runner, scene, kWidth, kHeight).images, stretchedSheet(0.0));
    scene.world.get<Morph>(gltf_test::findByName(scene, "sheet")).weights[0] = 1.0f;
    const Footprint stretched = footprint(renderFrame(runner, scene, kWidth, kHeight).images, stretchedSheet(1.0));
    std::printf(
        "weight 0: %d of %d judged pixels predicted, %d mismatches; weight 1: %d (%d under the moved part), "
        "%d mismatches\n",
        rest.predicted, rest.judged, rest.mismatches, stretched.predicted, stretched.band, stretched.mismatches);
    ASSERT_GT(rest.predicted, 300);
    ASSERT_GT(stretched.band, 300);
    EXPECT_LE(rest.mismatches, 0.1 * stretched.band);
    EXPECT_LE(stretched.mismatches, 0.1 * stretched.band);
}

// Animated by a `weights` channel (0 at t = 0 to 1 at t = 2 s, LINEAR), the shadow at t = 1 s is
// the half-stretched sheet's.
TEST(MorphShadow, AnimatedWeightsDeformTheShadow) {
    glContext();
    Scene scene = sheetScene(gltf_test::morphSheetDoc(0.0f, true));
    FrameRunner runner;
    const Footprint half = footprint(renderFrame(runner, scene, kWidth, kHeight, 1.0).images, stretchedSheet(0.5));
    EXPECT_FLOAT_EQ(scene.world.get<Morph>(gltf_test::findByName(scene, "sheet")).weights[0], 0.5f);
    std::printf("t = 1: %d predicted (%d under the moved part), %d mismatches of %d judged\n", half.predicted,
                half.band, half.mismatches, half.judged);
    ASSERT_GT(half.band, 100);
    EXPECT_LE(half.mismatches, 0.1 * half.band);
}

// The ray-traced reference morphs the sheet as the vertex shader does: the shadowed ground pixels
// agree (at most 3 % of the shadow differs, the outline's pixels; measured below 1 %).
TEST(MorphShadow, ReferenceSeesTheSameDeformation) {
    glContext();
    Scene scene = sheetScene(gltf_test::morphSheetDoc(1.0f));
    FrameRunner runner;
    const RenderedFrame frame = renderFrame(runner, scene, kWidth, kHeight);
    const GroundAgreement ref = groundAgreement(scene, runner.lastCamera(), frame.images);
    std::printf("reference: %d shadowed ground pixels, %d mismatches\n", ref.referenceShadowed, ref.mismatches);
    const Footprint geometry = footprint(frame.images, stretchedSheet(1.0));
    ASSERT_GT(ref.referenceShadowed, geometry.predicted * 9 / 10) << "the reference's shadow is the stretched sheet's";
    EXPECT_LE(ref.mismatches, 0.03 * ref.referenceShadowed);
}

/// `morphSheetDoc`'s sheet at weight 1, skinned (glTF `skins`) to one joint, node 1 "joint" at
/// (0, 1, 0) turned -90 degrees about +Y; the sheet's node stands at the origin, which glTF does
/// not apply to a skinned mesh. Morphed first (x in [-0.5, 1.5] in the mesh's space), then skinned
/// (mesh x to world +z): the sheet spans x in [-0.5, 0.5], z in [-0.5, 1.5] at y = 1.
gltf_test::Doc skinnedMorphSheetDoc() {
    gltf_test::Doc doc = gltf_test::morphSheetDoc(1.0f);
    json& primitive = doc.j["meshes"][0]["primitives"][0];
    primitive["attributes"]["JOINTS_0"] =
        doc.accessor(doc.view(std::vector<std::uint16_t>(16, 0)), gltf_test::kUnsignedShort, 4, "VEC4");
    primitive["attributes"]["WEIGHTS_0"] = doc.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    doc.j["nodes"][0]["translation"] = {0, 0, 0};
    doc.j["nodes"][0]["skin"] = 0;
    const double s = std::sqrt(0.5);
    doc.node({{"name", "joint"}, {"translation", {0, 1, 0}}, {"rotation", {0, -s, 0, s}}});
    doc.push("skins", {{"joints", {1}}});
    doc.scene({0, 1});
    return doc;
}

/// The morphed-then-skinned sheet (glTF's order), and what the two other orders of business
/// would draw: skinned then morphed (the morph's +x stretch stays along world x), and either one
/// alone.
const Rect kMorphedThenSkinned{-0.5, 0.5, -0.5, 1.5};
const Rect kSkinnedThenMorphed{-0.5, 1.5, -0.5, 0.5};
const Rect kSkinnedOnly{-0.5, 0.5, -0.5, 0.5};

// A sheet both morphed and skinned casts the shadow of the morphed-then-skinned shape, which the
// reference traces too; the shapes of the other order, and of the skin alone, miss it by far
// (a morph alone, with the node at the origin, draws the sheet on the ground: no shadow at all).
TEST(MorphShadow, MorphedThenSkinnedCastsItsShape) {
    glContext();
    Scene scene = sheetScene(skinnedMorphSheetDoc());
    FrameRunner runner;
    const RenderedFrame frame = renderFrame(runner, scene, kWidth, kHeight);
    const Footprint right = footprint(frame.images, kMorphedThenSkinned);
    const Footprint swapped = footprint(frame.images, kSkinnedThenMorphed);
    const Footprint skinOnly = footprint(frame.images, kSkinnedOnly);
    const GroundAgreement ref = groundAgreement(scene, runner.lastCamera(), frame.images);
    std::printf(
        "morphed then skinned: %d predicted (%d under the moved part), %d mismatches of %d judged; skinned then "
        "morphed: %d mismatches; skin alone: %d; reference: %d shadowed, %d mismatches\n",
        right.predicted, right.band, right.mismatches, right.judged, swapped.mismatches, skinOnly.mismatches,
        ref.referenceShadowed, ref.mismatches);
    ASSERT_GT(right.band, 300);
    EXPECT_LE(right.mismatches, 0.1 * right.band);
    EXPECT_GT(swapped.mismatches, right.band / 2) << "the order matters on this pose";
    EXPECT_GT(skinOnly.mismatches, right.band / 2) << "the morph matters on this pose";
    ASSERT_GT(ref.referenceShadowed, right.predicted * 9 / 10) << "the reference's shadow is the same shape";
    EXPECT_LE(ref.mismatches, 0.03 * ref.referenceShadowed);
}

// Unchanged weights reuse every layer; a changed weight redraws them.
TEST(MorphShadow, LayersRedrawnOnlyWhenTheWeightsChanged) {
    glContext();
    Scene scene = sheetScene(gltf_test::morphSheetDoc(0.5f));
    FrameRunner runner;
    (void)renderFrame(runner, scene, kWidth, kHeight);
    const RenderedFrame still = renderFrame(runner, scene, kWidth, kHeight);
    EXPECT_EQ(still.stats.shadowLayersDrawn, 0) << "nothing changed";
    scene.world.get<Morph>(gltf_test::findByName(scene, "sheet")).weights[0] = 0.75f;
    const RenderedFrame changed = renderFrame(runner, scene, kWidth, kHeight);
    EXPECT_GT(changed.stats.shadowLayersDrawn, 0) << "the weight changed";
}

// More non-zero weights than a draw blends: the frames add one `MorphTargetsDropped` warning to
// the scene's list, the first frame, and none after.
TEST(MorphShadow, DroppedTargetsReportedOnceByTheFrames) {
    glContext();
    Scene scene = sheetScene(gltf_test::manyTargetsSheetDoc(kMaxMorphInfluences + 1));
    FrameRunner runner;
    const auto dropped = [&] {
        return std::count_if(scene.warnings.begin(), scene.warnings.end(),
                             [](const Warning& w) { return w.code == WarningCode::MorphTargetsDropped; });
    };
    ASSERT_EQ(dropped(), 0);
    (void)renderFrame(runner, scene, kWidth / 4, kHeight / 4);
    EXPECT_EQ(dropped(), 1);
    (void)renderFrame(runner, scene, kWidth / 4, kHeight / 4, 0.5);
    EXPECT_EQ(dropped(), 1) << "once per entity, not once per frame";
}

}  // namespace
}  // namespace shadow::test::morph_shadow_test
