// Acceptance test of hard shadows: the visibility AOV of a box floating over a ground plane
// must match the shadow computed by ray casting against the box, for every light type.
//
// The box floats (its bottom 1 m above the ground) so its footprint is the clean projection of
// its silhouette and the depth bias cannot shift the edge: the blocker is far above the
// receiver. For every ground pixel the analytic answer is a slab test of the segment from the
// ground point to the light (point/spot) or along -direction (directional). A shadow map can
// only place the edge to within its texels, so pixels whose analytic answer changes within two
// texel footprints are an edge band where either answer is accepted. Outside the band at most
// 0.1 % of the ground pixels may disagree (measured on llvmpipe: 0 where the engine is right;
// all mismatches then lie in the band and cover 0.01-0.14 % of the ground).
#include <gtest/gtest.h>
#include <shadow/shadow_system.h>

#include <array>
#include <cstdio>
#include <vector>

#include "render/render_test_support.h"

namespace shadow::hard_shadow_test {
namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 192;
constexpr int kMapSize = 1024;
/// Edge band half-width in shadow texels (see the file comment).
constexpr double kBandTexels = 2.0;
/// Largest fraction of ground pixels allowed to disagree with the geometry outside the band.
constexpr double kMaxMismatchOutsideBand = 0.001;
/// Smallest fraction of ground pixels that must be truly shadowed: the test cannot pass
/// vacuously with a shadow that fell out of view.
constexpr double kMinShadowedFraction = 0.02;

const glm::dvec3 kBoxCenter{0.0, 1.4, 0.0};
const glm::dvec3 kBoxHalf{0.8, 0.4, 0.6};  // not a cube: a swapped axis shows
constexpr float kGroundHalfSize = 6.0f;

struct HardCase {
    const char* name;
    LightType type;
    glm::dvec3 position;
    glm::dvec3 direction;  // need not be unit
    glm::dvec3 cameraTarget;
    float outerConeAngle = 0.6f;  // spot only (rad)
    glm::dvec3 boxCenter = kBoxCenter;
    /// Added to every position of the scene (ground, box, light, camera).
    glm::dvec3 origin{0.0};
};

struct Measured : test::GeometryAgreement {
    int backgroundPixels = 0;
    FrameImages images;
};

Measured measure(const HardCase& c) {
    Scene scene;
    const glm::dvec3 boxCenter = c.boxCenter + c.origin;
    const glm::dvec3 position = c.position + c.origin;
    const glm::dvec3 target = c.cameraTarget + c.origin;
    addMeshInstance(scene.world, "ground", makePlaneMesh(kGroundHalfSize, 4), test::placed(c.origin));
    test::addBox(scene, "box", boxCenter, kBoxHalf);
    const glm::dvec3 direction = glm::normalize(c.direction);
    addLight(scene, c.name, test::pointSizedLight(c.type, c.outerConeAngle), test::hardShadow(kMapSize), position,
             direction);
    addCamera(scene, "camera", Camera{}, target + glm::dvec3(0.0, 4.0, 4.5), target);

    test::glContext();
    FrameRunner runner;
    Measured m;
    m.images = test::renderFrame(runner, scene, kWidth, kHeight).images;
    const ShadowFrame& frame = runner.shadows().frame();
    if (frame.lights.size() != 1 || m.images.visibility.size() != 1) {
        ADD_FAILURE() << c.name << ": expected one shadowed light and one visibility AOV, got " << frame.lights.size()
                      << " and " << m.images.visibility.size();
        return m;
    }
    const test::AnalyticLight light{c.type, position, direction};
    const std::array<DAabb, 1> boxes{test::boxBounds(boxCenter, kBoxHalf)};
    static_cast<test::GeometryAgreement&>(m) = test::compareWithGeometry(
        m.images, m.images.visibility[0], frame.lights[0], light, boxes, kBandTexels, c.outerConeAngle);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (m.images.position.at(x, y, 3) < 0.5f) ++m.backgroundPixels;
        }
    }
    std::printf(
        "[ measured ] %s: ground %d px, shadowed %.2f %%, mismatches %.3f %% (outside band %.4f "
        "%%)\n",
        c.name, m.groundPixels, 100.0 * m.shadowedPixels / std::max(m.groundPixels, 1),
        100.0 * m.mismatches / std::max(m.groundPixels, 1), 100.0 * m.outsideBand / std::max(m.groundPixels, 1));
    return m;
}

/// The assertions every case shares.
void expectMatchesGeometry(const HardCase& c, const Measured& m) {
    test::expectSaneAovs(m.images);
    ASSERT_GT(m.groundPixels, kWidth * kHeight / 4) << c.name << ": the camera must see the lit ground";
    EXPECT_GT(m.backgroundPixels, 0) << c.name << ": the background check needs background pixels";
    EXPECT_GT(m.shadowedPixels, kMinShadowedFraction * m.groundPixels) << c.name << ": shadow out of view";
    EXPECT_LT(m.outsideBand, kMaxMismatchOutsideBand * m.groundPixels)
        << c.name << ": " << m.outsideBand << " of " << m.groundPixels
        << " ground pixels disagree with the geometry away from the shadow edge (" << m.mismatches
        << " mismatches in all)";
}

void expectMatchesGeometry(const HardCase& c) { expectMatchesGeometry(c, measure(c)); }

TEST(HardShadow, DirectionalStraightDownFootprintMatchesGeometry) {
    expectMatchesGeometry({"directional-down", LightType::Directional, {0, 10, 0}, {0, -1, 0}, {0, 0, 0}});
}

TEST(HardShadow, DirectionalTiltedFootprintMatchesGeometry) {
    expectMatchesGeometry({"directional-tilted", LightType::Directional, {0, 10, 0}, {0.6, -1.0, 0.35}, {0.8, 0, 0.5}});
}

TEST(HardShadow, SpotLightStraightDownFootprintMatchesGeometry) {
    expectMatchesGeometry({"spot-down", LightType::Spot, {0, 4, 0}, {0, -1, 0}, {0, 0, 0}});
}

TEST(HardShadow, SpotLightTiltedFootprintMatchesGeometry) {
    const glm::dvec3 position(-2.5, 4.0, 1.0);
    expectMatchesGeometry({"spot-tilted", LightType::Spot, position, kBoxCenter - position, {1.3, 0, -0.5}});
}

// Far from the origin (docs/architecture.md: 10^5 m keeps millimetre precision) the shadows must stay as
// exact. The position AOV is float32 there (ulp 8 mm), well inside the edge band.
TEST(HardShadow, FootprintsFarFromTheOriginMatchGeometry) {
    const glm::dvec3 far(1.0e5, 0.0, -1.0e5);
    HardCase sun{"directional-far", LightType::Directional, {0, 10, 0}, {0.6, -1.0, 0.35}, {0.8, 0, 0.5}};
    sun.origin = far;
    expectMatchesGeometry(sun);
    HardCase spot{
        "spot-far", LightType::Spot, {-2.5, 4.0, 1.0}, kBoxCenter - glm::dvec3(-2.5, 4.0, 1.0), {1.3, 0, -0.5}};
    spot.origin = far;
    expectMatchesGeometry(spot);
    HardCase bulb{"point-far", LightType::Point, {0.7, 3.5, -0.4}, {0, -1, 0}, {-0.4, 0, 0.3}};
    bulb.origin = far;
    expectMatchesGeometry(bulb);
}

// A wide spot whose nearest caster sits 40 degrees off its axis, close to the light: the
// caster must not be clipped by the projection's near plane, which bounds the axial depth, not
// the distance from the light (see Planner.SpotNearPlaneHoldsOffAxisCasterNearTheLight).
TEST(HardShadow, SpotLightOffAxisCasterFootprintMatchesGeometry) {
    HardCase c{"spot-off-axis", LightType::Spot, {0, 3, 0}, {0, -1, 0}, {1.6, 0, 0}};
    c.outerConeAngle = 1.0f;
    c.boxCenter = {1.8, 1.4, 0.0};
    expectMatchesGeometry(c);
}

TEST(HardShadow, PointLightFootprintMatchesGeometry) {
    expectMatchesGeometry({"point-above", LightType::Point, {0.7, 3.5, -0.4}, {0, -1, 0}, {-0.4, 0, 0.3}});
}

// The light sits so that the direction to the box is 45 degrees down towards +X: the shadow
// falls partly in the +X face and partly in the -Y face of the cube map, and the box lies off
// the axis of both faces (see Planner.PointNearPlaneHoldsCasterOffTheFaceAxes).
TEST(HardShadow, PointLightFootprintAcrossCubeFacesMatchesGeometry) {
    const HardCase c{"point-face-split", LightType::Point, {-2.0, 3.4, 0.0}, {0, -1, 0}, {1.8, 0, 0}};
    const Measured m = measure(c);
    // The case only tests the seam if the shadow really straddles it.
    EXPECT_GT(m.shadowedPerLayer[0], 0.005 * m.groundPixels) << "too little shadow in the +X face";
    EXPECT_GT(m.shadowedPerLayer[3], 0.005 * m.groundPixels) << "too little shadow in the -Y face";
    expectMatchesGeometry(c, m);
}

}  // namespace
}  // namespace shadow::hard_shadow_test
