// Depth range: spot and point lights whose near/far ratio runs from 1:10 to 1:10^6, and a sun
// over a 10 km ground with 1 m casters. A layer stores linear depth / depthScale in a 32-bit
// float, so its precision is relative to the depth itself (24 bits), not to the range: the
// tests measure the stored depth of the open ground against the exact plane, and every
// technique's shadow against ray casting.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "stability/stability_test_support.h"

namespace shadow::depth_range_test {
namespace {

/// Edge band half-width in shadow texels and the largest mismatch allowed beyond it, as a
/// fraction of the analytically shadowed area (the bound: 1 %).
constexpr double kBandTexels = 2.0;
constexpr double kMaxMismatchOfShadow = 0.01;

const glm::dvec3 kBoxCenter{0.0, 1.4, 0.0};
const glm::dvec3 kBoxHalf{0.8, 0.4, 0.6};
constexpr float kGroundHalf = 6.0f;

struct RangeCase {
    LightType type;
    double nearPlane;
    double range;
};

TEST(Stability, NearFarRatiosUpToAMillionKeepEveryTechniquesShadow) {
    const glm::dvec3 position{0.7, 3.5, -0.4};
    std::vector<RangeCase> cases;
    for (LightType type : {LightType::Spot, LightType::Point}) {
        for (double ratio : {1e1, 1e2, 1e4, 1e6}) cases.push_back({type, 1.0, ratio});
        cases.push_back({type, 1e-3, 1e3});  // 1:10^6 with the near plane at 1 mm
    }
    for (const RangeCase& c : cases) {
        Scene scene;
        test::addGround(scene, kGroundHalf);
        test::addBox(scene, "box", kBoxCenter, kBoxHalf);
        addCamera(scene, "camera", Camera{}, {-0.4, 4.0, 4.8}, {-0.4, 0.0, 0.3});
        Light light = test::pointSizedLight(c.type, 1.0f);
        light.range = static_cast<float>(c.range);
        light.radius = 0.05f;
        Shadow shadow = test::shadowWith(ShadowTechnique::Hard, 512);
        shadow.nearPlane = static_cast<float>(c.nearPlane);
        addLight(scene, "light", light, shadow, position, {0, -1, 0});
        const std::string name = std::string(c.type == LightType::Spot ? "spot" : "point") + " near " +
                                 std::to_string(c.nearPlane).substr(0, 5) + " m, range " +
                                 std::to_string(static_cast<long long>(c.range)) + " m";
        const std::array<DAabb, 1> boxes{test::boxBounds(kBoxCenter, kBoxHalf)};
        test::forEveryTechnique(
            scene, 192, 144, name,
            [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner& runner) {
                const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
                EXPECT_NEAR(plan.layers.at(0).depthNear, c.nearPlane, 1e-6 * c.nearPlane) << name;
                const test::AnalyticLight analytic{c.type, position, {0, -1, 0}};
                const test::GeometryAgreement m = test::compareWithGeometry(frame.images, frame.images.visibility[0],
                                                                            plan, analytic, boxes, kBandTexels, 1.0);
                const double ofShadow = static_cast<double>(m.outsideBand) / std::max(m.shadowedPixels, 1);
                // Every technique: the soft ones' penumbrae (5 cm emitter) cross 0.5 at the
                // analytic edge; beyond the band a mismatch is acne or a leak. The moment
                // techniques are the ones to watch: their moments of depths near 0 (a scene
                // 10^-6 of the range deep) cancel in float (MSM) or vanish in a fixed point (VSSM).
                test::reportFigure(
                    name + ", " + techniqueName(technique) + ": mismatch beyond the edge band / shadowed area",
                    ofShadow);
                EXPECT_LT(ofShadow, kMaxMismatchOfShadow) << name << ", " << techniqueName(technique);
                if (technique != ShadowTechnique::Hard) return;
                const test::StoredDepthError depth =
                    test::storedGroundDepthError(runner.shadows(), 0, glm::dvec3(0.0), kGroundHalf, boxes);
                test::reportFigure(name + ": stored ground depth, largest error", depth.maxAbs, " m");
                test::reportFigure(name + ": stored ground depth, largest relative error", depth.maxRelative);
                EXPECT_GT(m.shadowedPixels, m.groundPixels / 50) << name << ": shadow out of view";
                EXPECT_LT(ofShadow, kMaxMismatchOfShadow) << name;
                EXPECT_GT(depth.texels, 100000) << name;
                // 32-bit float: 2^-24 relative per rounding; interpolation adds a few more.
                EXPECT_LT(depth.maxRelative, 1e-5) << name;
            });
    }
}

/// A sun over a 10 km square of ground with 1 m boxes near the camera: the layer's depth range
/// spans kilometres while the casters are a metre tall.
TEST(Stability, SunOverTenKilometresKeepsMetreCastersExact) {
    constexpr double kHalf = 5000.0;
    const std::vector<glm::dvec3> centres{{0.0, 0.5, 0.0}, {3.0, 0.5, -2.0}, {-2.5, 0.5, -5.0}, {1.5, 0.5, 3.0}};
    const glm::dvec3 half{0.5, 0.5, 0.5};
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(static_cast<float>(kHalf), 4), test::placed(glm::dvec3(0.0)));
    std::vector<DAabb> boxes;
    for (std::size_t i = 0; i < centres.size(); ++i) {
        test::addBox(scene, "box" + std::to_string(i), centres[i], half);
        boxes.push_back(test::boxBounds(centres[i], half));
    }
    Camera lens;
    lens.zfar = 20000.0f;
    // Looking 22 degrees down (the view's top edge 1 degree above the horizon): the ground is in view from the boxes at the bottom of the screen to
    // its far edge 5 km away, below the horizon (cascades span what receivers are visible).
    addCamera(scene, "camera", lens, {0.0, 4.0, 7.0}, {0.0, 4.0 - 100.0 * std::tan(0.384), 7.0 - 100.0});
    const glm::dvec3 sunDirection = glm::normalize(glm::dvec3(0.5, -1.0, 0.3));
    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.005f;
    Shadow shadow = test::shadowWith(ShadowTechnique::Hard, 2048);
    shadow.cascades = 4;
    shadow.cascadeSplitLambda = 1.0f;  // logarithmic: the first cascade holds the boxes
    addLight(scene, "sun", sun, shadow, {0, 10, 0}, sunDirection);

    test::forEveryTechnique(
        scene, 256, 192, "10 km ground",
        [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner& runner) {
            if (technique != ShadowTechnique::Hard) return;
            const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
            const ShadowLayerPlan& first = plan.layers.at(0);
            const CameraView& view = runner.lastCamera();
            const glm::dvec3 forward = -glm::dvec3(glm::transpose(view.viewFromWorld)[2]);
            // Only receivers that use the first cascade alone (before its blend band): the edge
            // band is measured in its texels.
            const double firstOnly = first.splitFar * (1.0 - shadow.cascadeBlend);
            const test::AnalyticLight analytic{LightType::Directional, glm::dvec3(0.0), sunDirection};
            const test::GeometryAgreement m = test::compareWithGeometry(
                frame.images, frame.images.visibility[0], plan, analytic, boxes, kBandTexels, 0.0,
                [&](const glm::dvec3& p) { return glm::dot(p - view.wsPosition, forward) < firstOnly; });
            const double ofShadow = static_cast<double>(m.outsideBand) / std::max(m.shadowedPixels, 1);
            const test::StoredDepthError depth =
                test::storedGroundDepthError(runner.shadows(), 0, glm::dvec3(0.0), kHalf, boxes);
            test::reportFigure("10 km sun: depth scale of the first cascade", first.depthScale, " m");
            test::reportFigure("10 km sun: the first cascade ends at view depth", first.splitFar, " m");
            test::reportFigure("10 km sun: shadowed pixels in it", m.shadowedPixels);
            test::reportFigure("10 km sun: texel of the first cascade",
                               2.0 / (first.clipFromLight[0][0] * plan.mapSize), " m");
            test::reportFigure("10 km sun: hard mismatch beyond the edge band / shadowed area", ofShadow);
            test::reportFigure("10 km sun: stored ground depth, largest error", depth.maxAbs, " m");
            test::reportFigure("10 km sun: stored ground depth, largest relative error", depth.maxRelative);
            // Enough pixels to judge by (measured 645: the view keeps the horizon, so the boxes'
            // shadows are foreshortened).
            EXPECT_GT(m.shadowedPixels, 400) << "the boxes' shadows are not in the first cascade's view";
            EXPECT_LT(ofShadow, kMaxMismatchOfShadow);
            EXPECT_GT(depth.texels, 100000);
            EXPECT_LT(depth.maxRelative, 1e-5);
        });
}

}  // namespace
}  // namespace shadow::depth_range_test
