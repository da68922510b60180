// PCSS under a spot light whose emitter is a disk facing along the spot's axis: seen from a
// receiver off the axis the disk is an ellipse, narrower towards the axis by the cosine of the
// angle off it, and so is the penumbra it casts. A search and filter over a round disk there
// widen the penumbra towards the axis and lighten its umbra. Checked against the ray-traced
// truth, which samples the disk itself.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cstdio>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/soft_test_support.h"
#include "shadow/truth_test_support.h"

namespace shadow::test {
namespace {

/// A disk light 0.4 m in radius 4 m above the ground, pointing down; a 1 cm plate 60 x 40 cm at
/// 2.6 m, 1.2 m off the axis: its shadow lies about 40 degrees off the axis (cos 0.77), with a
/// penumbra about 0.75 m wide on each side of its edges, wider than its umbra.
Scene offAxisPlate() {
    Scene scene;
    addGround(scene, 8.0f);
    addBox(scene, "plate", {1.2, 2.6, 0.0}, {0.3, 0.005, 0.2});
    Light spot = pointSizedLight(LightType::Spot, 0.95f);
    spot.radius = 0.4f;
    Shadow shadow = shadowWith(ShadowTechnique::Pcss, 2048);
    shadow.blockerSamples = 32;
    shadow.pcfSamples = 32;
    shadow.maxFilterTexels = 256.0f;  // the penumbra spans ~140 texels of the ground
    addLight(scene, "disk light", spot, shadow, {0.0, 4.0, 0.0}, {0.0, -1.0, 0.0});
    Camera camera;
    camera.yfov = 0.8f;
    addCamera(scene, "camera", camera, {3.4, 3.5, 3.5}, {3.4, 0.0, 0.0});
    return scene;
}

/// Measured with the ellipse: penumbra RMSE 0.0233 (RMSE 0.0127); with a round disk (the
/// emitter's shape left out of the search and filter) 0.0466 (RMSE 0.0278). The allowance lies
/// between the two.
TEST(EmitterShape, PcssPenumbraOfASpotsDiskMatchesTheTruthOffTheAxis) {
    Scene scene = offAxisPlate();
    const std::vector<AgainstTruth> errors = renderAgainstTruth(scene, 240, 180, 256, {ShadowTechnique::Pcss});
    const VisibilityErrors& e = errors.at(0).errors;
    std::printf(
        "[ measured ] off-axis plate under a disk spot, pcss: penumbra RMSE %.4f, RMSE %.4f (%lld penumbra px)\n",
        e.penumbraRmse, e.rmse, static_cast<long long>(e.penumbraPixels));
    ASSERT_GT(e.penumbraPixels, 5000) << "the camera does not see the penumbra";
    EXPECT_LE(e.penumbraRmse, 0.033);
}

}  // namespace
}  // namespace shadow::test
