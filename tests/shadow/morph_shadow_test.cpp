// Morph targets in the shadow passes: a morphed sheet over the ground under a sun casts the
// shadow of its morphed shape (against the geometric projection of that shape and against the
// ray-traced reference, which morphs on the CPU), its weight animated or set, and its layers are
// redrawn when, and only when, its drawn weights changed. The sheet comes from a glTF file the
// test writes (tests/scene/gltf_test_support.h, `morphSheetDoc`).
#include <gtest/gtest.h>
#include <shadow/reference.h>

#include <algorithm>
#include <string>

#include "render/render_test_support.h"
#include "scene/gltf_test_support.h"

namespace shadow::test {
namespace {

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

/// Ground pixels by the geometric projection of the sheet at `weight` (x in [-0.5, 0.5 + weight],
/// z in [-0.5, 0.5] at y = 1) against light 0's visibility, away from the outline.
struct Footprint {
    int judged = 0;     ///< ground pixels farther than kEdgeMargin from the outline
    int predicted = 0;  ///< of those, inside the projected sheet
    int mismatches = 0;
    int band = 0;  ///< predicted pixels under the moving part (x in [0.6, 0.5 + weight - 0.1] at y = 1)
};

Footprint footprint(const FrameImages& images, double weight) {
    Footprint f;
    const double xMax = 0.5 + weight;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (!isGroundPixel(images, x, y)) continue;
            const glm::dvec3 p = positionAt(images, x, y);
            const glm::dvec3 q = p + kToSun * ((1.0 - p.y) / kToSun.y);  // on the sheet's plane
            const double inside = std::min({q.x + 0.5, xMax - q.x, q.z + 0.5, 0.5 - q.z});
            if (std::abs(inside) < kEdgeMargin) continue;
            ++f.judged;
            const bool shadowed = images.visibility.at(0).at(x, y, 0) < 0.5f;
            f.predicted += inside > 0.0 ? 1 : 0;
            f.band += inside > 0.0 && q.x > 0.6 ? 1 : 0;
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
    const Footprint rest = footprint(renderFrame(runner, scene, kWidth, kHeight).images, 0.0);
    scene.world.get<Morph>(gltf_test::findByName(scene, "sheet")).weights[0] = 1.0f;
    const Footprint stretched = footprint(renderFrame(runner, scene, kWidth, kHeight).images, 1.0);
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
    const Footprint half = footprint(renderFrame(runner, scene, kWidth, kHeight, 1.0).images, 0.5);
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
    reference::ReferenceOptions options;
    options.width = kWidth;
    options.height = kHeight;
    options.samples = 1;
    options.wsPositions = &frame.images.position;
    auto ref = reference::traceVisibility(scene, runner.lastCamera(), options);
    ASSERT_TRUE(ref.ok()) << ref.error().message;
    int shadowed = 0;
    int mismatches = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (!isGroundPixel(frame.images, x, y)) continue;
            const bool truth = ref->visibility.at(0).at(x, y, 0) < 0.5f;
            shadowed += truth ? 1 : 0;
            mismatches += truth != (frame.images.visibility.at(0).at(x, y, 0) < 0.5f) ? 1 : 0;
        }
    }
    std::printf("reference: %d shadowed ground pixels, %d mismatches\n", shadowed, mismatches);
    const Footprint geometry = footprint(frame.images, 1.0);
    ASSERT_GT(shadowed, geometry.predicted * 9 / 10) << "the reference's shadow is the stretched sheet's";
    EXPECT_LE(mismatches, 0.03 * shadowed);
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
}  // namespace shadow::test
