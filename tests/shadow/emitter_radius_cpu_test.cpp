// The automatic filter widths (engine/src/shadow/emitter_radius.h): PCF and VSM's radius, the
// penumbra of the light's emitter from each caster's corner nearest its receiver, the median over
// the casters, and the widest penumbra in texels, against similar triangles worked out by hand.
// No GL.
#include <gtest/gtest.h>
#include <shadow/components.h>

#include <cmath>
#include <vector>

#include "shadow/emitter_radius.h"

namespace shadow::test::emitter_radius_cpu_test {
namespace {

constexpr double kEps = 1e-12;

/// A ground 20 m across at y = 0 (the only receiver) and casters with the given boxes, all in
/// one layer; entities 1, 2, ... in order.
struct Casters {
    SceneGeometry geometry;
    std::vector<ShadowLayerPlan> layers{1};

    explicit Casters(const std::vector<DAabb>& casters, double scale = 1.0) {
        geometry.receivers = DAabb{glm::dvec3(-10.0, 0.0, -10.0) * scale, glm::dvec3(10.0, 0.0, 10.0) * scale};
        for (std::size_t k = 0; k < casters.size(); ++k) {
            const Entity e = Entity(static_cast<std::uint32_t>(k + 1), 0);
            geometry.casters.push_back({e, DAabb{casters[k].min * scale, casters[k].max * scale}});
            layers[0].casters.push_back(e);
        }
    }
    [[nodiscard]] double radius(const LayerInputs& light, double size) {
        std::vector<double> scratch;
        return emitterFilterRadius(light, size, geometry, layers, scratch);
    }
};

LayerInputs sunFrom(const glm::dvec3& direction) {
    LayerInputs l;
    l.type = LightType::Directional;
    l.pose.wsDirection = glm::normalize(direction);
    return l;
}

LayerInputs spotAt(const glm::dvec3& position, LightType type = LightType::Spot) {
    LayerInputs l;
    l.type = type;
    l.pose.wsPosition = position;
    l.pose.wsDirection = {0.0, -1.0, 0.0};
    return l;
}

/// A flat square plate of half-size `half` at height `y`, centred over (x, z).
DAabb plate(double x, double y, double z, double half) {
    return DAabb{{x - half, y, z - half}, {x + half, y, z + half}};
}

TEST(EmitterRadius, AFloatingPlateUnderTheSunGetsItsGapsPenumbra) {
    // Sun 30 degrees off the vertical: the gap along the ray is h / cos(30 deg).
    const double angle = 30.0 * 3.14159265358979 / 180.0;
    Casters s({plate(0.0, 1.5, 0.0, 0.5)});
    const double r = s.radius(sunFrom({std::sin(angle), -std::cos(angle), 0.0}), 0.02);
    EXPECT_NEAR(r, 1.5 / std::cos(angle) * std::tan(0.02), kEps);
}

TEST(EmitterRadius, ASpotsPenumbraFollowsSimilarTrianglesAndItsForeshortenedDisk) {
    // A tiny plate on the axis 1 m over the ground, the spot 4 m up: R * 1 / 3.
    Casters onAxis({plate(0.0, 1.0, 0.0, 1e-4)});
    EXPECT_NEAR(onAxis.radius(spotAt({0.0, 4.0, 0.0}), 0.3), 0.3 * 1.0 / 3.0, 1e-4);
    // Off the axis (a point light has no disk to foreshorten): the ray from (0, 4, 0) through
    // (3, 0, 0)'s plate at height 2 meets the ground at (6, 0, 0).
    Casters off({plate(3.0, 2.0, 0.0, 1e-6)});
    const double toBlocker = std::hypot(3.0, 2.0);
    EXPECT_NEAR(off.radius(spotAt({0.0, 4.0, 0.0}, LightType::Point), 0.2), 0.2 * toBlocker / toBlocker, 1e-5);
    // The spot's disk seen from there is narrower by sqrt(cos) of the angle off its axis.
    EXPECT_NEAR(off.radius(spotAt({0.0, 4.0, 0.0}), 0.2), 0.2 * std::sqrt(2.0 / toBlocker), 1e-5);
}

TEST(EmitterRadius, CastersRestingOnTheirReceiverAndTheGroundItselfAskForNoWidth) {
    const LayerInputs sun = sunFrom({0.3, -1.0, 0.2});
    // A box standing on the ground: its contact casts a penumbra of width 0.
    Casters resting({DAabb{{-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}}});
    EXPECT_EQ(resting.radius(sun, 0.05), 0.0);
    // The ground as a caster casts onto nothing behind it: it is not counted, so the floating
    // plate's width is the median of one.
    Casters withGround({DAabb{{-10.0, 0.0, -10.0}, {10.0, 0.0, 10.0}}, plate(0.0, 2.0, 0.0, 0.3)});
    Casters plateOnly({plate(0.0, 2.0, 0.0, 0.3)});
    EXPECT_GT(plateOnly.radius(sun, 0.05), 0.0);
    EXPECT_EQ(withGround.radius(sun, 0.05), plateOnly.radius(sun, 0.05));
    // No emitter, no caster, no receiver: 0.
    EXPECT_EQ(plateOnly.radius(sun, 0.0), 0.0);
    Casters none({});
    EXPECT_EQ(none.radius(sun, 0.05), 0.0);
    plateOnly.geometry.receivers = DAabb{};
    EXPECT_EQ(plateOnly.radius(sun, 0.05), 0.0);
}

TEST(EmitterRadius, TheMedianOverCastersAndTheSameAtEveryScale) {
    const LayerInputs sun = sunFrom({0.0, -1.0, 0.0});
    const double t = std::tan(0.01);
    Casters three({plate(-3.0, 1.0, 0.0, 0.2), plate(0.0, 2.0, 0.0, 0.2), plate(3.0, 4.0, 0.0, 0.2)});
    EXPECT_NEAR(three.radius(sun, 0.01), 2.0 * t, kEps);
    Casters two({plate(-3.0, 1.0, 0.0, 0.2), plate(3.0, 4.0, 0.0, 0.2)});
    EXPECT_NEAR(two.radius(sun, 0.01), 2.5 * t, kEps);  // the mean of the middle two
    // The scene 100 times larger (a spot's emitter with it): a radius 100 times larger.
    const std::vector<DAabb> boxes{plate(-1.0, 1.0, 0.5, 0.3), plate(1.0, 2.0, -0.5, 0.2)};
    Casters unit(boxes);
    Casters large(boxes, 100.0);
    const double small = unit.radius(spotAt({0.2, 4.0, 0.1}), 0.4);
    EXPECT_GT(small, 0.0);
    EXPECT_NEAR(large.radius(spotAt({20.0, 400.0, 10.0}), 40.0), 100.0 * small, 1e-9 * 100.0 * small);
}

/// `layers[0]` of `c` made an orthographic layer `width` m across (a cascade), or the
/// perspective layer of a light at `apex` looking straight down with P[0][0] = `p00`.
void orthographic(Casters& c, double width) {
    c.layers[0].orthographic = true;
    c.layers[0].clipFromLight = glm::dmat4(1.0);
    c.layers[0].clipFromLight[0][0] = 2.0 / width;
}
void perspectiveDown(Casters& c, const glm::dvec3& apex, double p00) {
    c.layers[0].orthographic = false;
    c.layers[0].clipFromLight = glm::dmat4(1.0);
    c.layers[0].clipFromLight[0][0] = p00;
    // Light space: -z along the light's axis (down), the light at the origin.
    c.layers[0].lightFromWorld = glm::dmat4(glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, 1, 0, 0),
                                            glm::dvec4(-apex.x, -apex.z, -apex.y, 1));
}

TEST(EmitterRadius, TheWidestPenumbraInTexelsOfTheLayerWhereItFalls) {
    // A sun straight down over a plate 2 m up and a box resting on the ground 1 m tall, a cascade
    // of 1000 texels over 10 m (1 cm texels): the plate's penumbra tan(0.01) * 2 m = 2.0 texels
    // is the widest (the box's top casts tan(0.01) * 1 m).
    Casters sun({plate(-3.0, 2.0, 0.0, 0.5), DAabb{{1.0, 0.0, 0.0}, {2.0, 1.0, 1.0}}});
    orthographic(sun, 10.0);
    LayerInputs light = sunFrom({0.0, -1.0, 0.0});
    light.mapSize = 1000;
    EXPECT_NEAR(widestPenumbraTexels(light, 0.01, sun.geometry, sun.layers), 2.0 * std::tan(0.01) / 0.01, 1e-9);
    // A spot 4 m up (P00 = 1: 2 mm of texel per metre of axial distance, 8 mm at the ground) and a
    // tiny plate 1 m up on its axis: R / 3 = 0.1 m = 12.5 texels of the ground's.
    Casters spot({plate(0.0, 1.0, 0.0, 1e-6)});
    perspectiveDown(spot, {0.0, 4.0, 0.0}, 1.0);
    LayerInputs s = spotAt({0.0, 4.0, 0.0});
    s.mapSize = 1000;
    EXPECT_NEAR(widestPenumbraTexels(s, 0.3, spot.geometry, spot.layers), 0.1 / 0.008, 1e-4);
    // Without an emitter or a receiver behind the casters: 0.
    EXPECT_EQ(widestPenumbraTexels(s, 0.0, spot.geometry, spot.layers), 0.0);
    spot.geometry.receivers = DAabb{};
    EXPECT_EQ(widestPenumbraTexels(s, 0.3, spot.geometry, spot.layers), 0.0);
}

}  // namespace
}  // namespace shadow::test::emitter_radius_cpu_test
