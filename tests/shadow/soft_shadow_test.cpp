// Acceptance tests of the soft-shadow techniques (PCF, PCSS) against geometry and closed
// forms, and of the hard technique where soft and hard must agree: no acne on a lit plane, no
// gap between a caster and its shadow, and a scene whose lights each keep their own technique.
//
// Visibility is read from the per-light AOVs and mapped to world points with the position AOV,
// so every expectation is stated in metres on the receiver, not in pixels.
#include <gtest/gtest.h>
#include <shadow/shadow_system.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "shadow/soft_test_support.h"

namespace shadow {
namespace {

using test::countGround;
using test::GroundCounts;
using test::Profile;

// ---------------------------------------------------------------------------------------------
// Contact hardening: the PCSS penumbra of a straight edge against the disk-light closed form.
// ---------------------------------------------------------------------------------------------

/// A spot light straight down from kLightHeight with a disk emitter of kLightRadius; two
/// 1 mm plates whose edge lies on the plane x = 0 (through the light's axis, so the geometric
/// shadow edge is x = 0 on the ground whatever the plate's height), one near the ground and one
/// half way up, over separate strips of z so neither plate's blocker search reaches the other.
constexpr double kLightHeight = 6.0;
constexpr float kLightRadius = 0.3f;
constexpr double kNearPlateHeight = 0.5;
constexpr double kFarPlateHeight = 3.0;
const glm::dvec3 kPlateHalf{0.75, 0.0005, 0.5};
constexpr double kNearPlateZ = -0.8;  // plate covers z in [-1.3, -0.3]
constexpr double kFarPlateZ = 0.6;    // plate covers z in [0.1, 1.1]
/// Allowed relative error of the measured 5-95 % band against the closed form. Measured on
/// llvmpipe: near 0.0444 m against 0.0439 m, far 0.4857 m against 0.4832 m (within 1.2 %).
constexpr double kBandTolerance = 0.25;

struct EdgeMeasurement {
    double measured = 0.0;   ///< width (m) of the 5-95 % band of the mean profile
    double expected = 0.0;   ///< the same width of the exact disk-light profile
    double fullWidth = 0.0;  ///< geometric full penumbra width (m)
    double midpoint = 0.0;   ///< x (m) where the mean profile crosses 50 %; the edge is at 0
    int minPixelsPerBin = 0;
};

/// Full penumbra width (m) on a ground plane parallel to the emitter disk, blocker edge at
/// height `blockerHeight`: the disk's image through the edge, 2 R (dR - dB) / dB.
double geometricPenumbra(double blockerHeight) {
    const double dReceiver = kLightHeight;
    const double dBlocker = kLightHeight - blockerHeight;
    return (dReceiver - dBlocker) * 2.0 * kLightRadius / dBlocker;
}

/// Mean visibility profile across x = 0 of the ground pixels with z in [zLo, zHi] seen through
/// `camera`, over x in [-halfRange, halfRange].
EdgeMeasurement measureEdge(FrameRunner& runner, Scene& scene, Entity camera, double blockerHeight,
                            double zLo, double zHi, double halfRange) {
    EdgeMeasurement m;
    m.fullWidth = geometricPenumbra(blockerHeight);
    m.expected = test::diskEdgeBandWidth(m.fullWidth, 0.05, 0.95);
    const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 256, 0.0, camera);
    test::expectSaneAovs(frame.images);
    const int bins = 60;
    Profile profile(-halfRange, halfRange, bins);
    const FrameImages& im = frame.images;
    for (int y = 0; y < im.position.height; ++y) {
        for (int x = 0; x < im.position.width; ++x) {
            if (!test::isGroundPixel(im, x, y)) continue;
            const glm::dvec3 p = test::positionAt(im, x, y);
            if (p.z < zLo || p.z > zHi) continue;
            profile.add(p.x, im.visibility[0].at(x, y, 0));
        }
    }
    m.minPixelsPerBin = profile.minCount();
    const auto lo = profile.firstCrossingUp(0.05);
    const auto hi = profile.firstCrossingUp(0.95);
    if (!lo || !hi) {
        ADD_FAILURE() << "the profile does not rise from below 5 % to above 95 %";
        return m;
    }
    m.measured = *hi - *lo;
    m.midpoint = profile.firstCrossingUp(0.5).value_or(1e9);
    return m;
}

TEST(SoftShadow, PcssContactHardeningMatchesGeometry) {
    Scene scene;
    test::addGround(scene, 4.0f);
    test::addBox(scene, "near plate", {-kPlateHalf.x, kNearPlateHeight, kNearPlateZ}, kPlateHalf);
    test::addBox(scene, "far plate", {-kPlateHalf.x, kFarPlateHeight, kFarPlateZ}, kPlateHalf);

    Light spot = test::pointSizedLight(LightType::Spot, 0.55f);
    spot.radius = kLightRadius;
    Shadow pcss = test::shadowWith(ShadowTechnique::Pcss, 2048);
    pcss.blockerSamples = 32;
    pcss.pcfSamples = 32;
    pcss.maxFilterTexels = 256.0f;  // the far plate's half penumbra is ~95 texels
    addLight(scene, "spot", spot, pcss, {0.0, kLightHeight, 0.0}, {0.0, -1.0, 0.0});

    // Each camera looks down at one edge from the lit (+x) side, so no plate hides the part of
    // the penumbra that lies under it, and zooms so that the band spans ~50-80 pixels.
    Camera farLens;
    farLens.yfov = 0.35f;
    const Entity farCamera =
        addCamera(scene, "far edge", farLens, {1.6, 4.0, 1.2}, {0.0, 0.0, 1.2});
    Camera nearLens;
    nearLens.yfov = 0.12f;
    const Entity nearCamera =
        addCamera(scene, "near edge", nearLens, {0.5, 1.2, -0.85}, {0.0, 0.0, -0.85});

    test::glContext();
    FrameRunner runner;
    // Rows of z at least one far-penumbra half-width (0.3 m) inside each shadow's z extent, so
    // the plates' other edges do not enter the profile.
    const EdgeMeasurement nearEdge =
        measureEdge(runner, scene, nearCamera, kNearPlateHeight, -1.1, -0.6, 0.08);
    const EdgeMeasurement farEdge =
        measureEdge(runner, scene, farCamera, kFarPlateHeight, 0.8, 1.6, 0.6);

    std::printf(
        "[ measured ] PCSS near plate (h=%.1f m): 5-95%% band %.4f m, closed form %.4f m (full "
        "%.4f m), 50%% at x=%.4f m\n",
        kNearPlateHeight, nearEdge.measured, nearEdge.expected, nearEdge.fullWidth,
        nearEdge.midpoint);
    std::printf(
        "[ measured ] PCSS far plate  (h=%.1f m): 5-95%% band %.4f m, closed form %.4f m (full "
        "%.4f m), 50%% at x=%.4f m\n",
        kFarPlateHeight, farEdge.measured, farEdge.expected, farEdge.fullWidth, farEdge.midpoint);
    EXPECT_GE(nearEdge.minPixelsPerBin, 20) << "too few pixels per profile bin near the near edge";
    EXPECT_GE(farEdge.minPixelsPerBin, 20) << "too few pixels per profile bin near the far edge";
    EXPECT_NEAR(nearEdge.measured, nearEdge.expected, kBandTolerance * nearEdge.expected);
    EXPECT_NEAR(farEdge.measured, farEdge.expected, kBandTolerance * farEdge.expected);
    EXPECT_LT(nearEdge.measured, farEdge.measured) << "no contact hardening";
    // The 50 % point of a symmetric profile is the geometric edge, x = 0: within a tenth of
    // the full width plus two texels (3.2 mm each at the ground) for rasterisation.
    EXPECT_NEAR(nearEdge.midpoint, 0.0, 0.1 * nearEdge.fullWidth + 0.0065);
    EXPECT_NEAR(farEdge.midpoint, 0.0, 0.1 * farEdge.fullWidth + 0.0065);
}

// ---------------------------------------------------------------------------------------------
// No acne: an open plane lit at any elevation must not shadow itself.
// ---------------------------------------------------------------------------------------------

/// Largest fraction of lit-plane pixels allowed to read visibility < 0.5. Measured on llvmpipe:
/// 0 for every technique, light and elevation (the taps lie on the receiver's tangent plane).
constexpr double kMaxAcneFraction = 0.001;
constexpr std::array<ShadowTechnique, 3> kTechniques{ShadowTechnique::Hard, ShadowTechnique::Pcf,
                                                     ShadowTechnique::Pcss};


/// Unit direction of light travelling downwards at `elevation` (rad) above the horizon, turned
/// by `azimuth` (rad) about +Y so that no grid axis lines up with it.
glm::dvec3 downAt(double elevation, double azimuth) {
    return glm::normalize(glm::dvec3(std::cos(elevation) * std::cos(azimuth), -std::sin(elevation),
                                     std::cos(elevation) * std::sin(azimuth)));
}

/// Sets the pose and technique of the scene's light (moved lights redraw their layers).
void poseLight(Scene& scene, Entity light, const glm::dvec3& position, const glm::dvec3& direction,
               ShadowTechnique technique) {
    Transform& t = scene.world.get<Transform>(light);
    t.translation = position;
    t.rotation = rotationLookingAlong(direction);
    scene.world.get<Shadow>(light).technique = technique;
}

TEST(SoftShadow, NoAcneOnLitPlaneAtAnyElevation) {
    constexpr double kAzimuth = 0.4;
    constexpr float kSpotHalfAngle = 0.5f;
    const std::array<double, 6> sunElevationsDeg{90, 60, 30, 15, 10, 5};
    const std::array<double, 4> spotElevationsDeg{75, 45, 30, 20};

    test::glContext();
    std::array<double, 3> worst{-1.0, -1.0, -1.0};
    std::array<std::string, 3> worstCase;
    for (LightType type : {LightType::Directional, LightType::Spot}) {
        Scene scene;
        test::addGround(scene, 10.0f);
        Light light = test::pointSizedLight(type, kSpotHalfAngle);
        light.angularRadius = 0.02f;  // PCSS needs an emitter; hard and PCF ignore it
        light.radius = 0.1f;
        const Entity e = addLight(scene, "light", light, test::shadowWith(ShadowTechnique::Hard),
                                  {0, 8, 0}, {0, -1, 0});
        addCamera(scene, "camera", Camera{}, {0.0, 9.0, 13.0}, {0.0, 0.0, 0.0});
        FrameRunner runner;
        const auto& elevations =
            type == LightType::Directional
                ? std::vector<double>(sunElevationsDeg.begin(), sunElevationsDeg.end())
                : std::vector<double>(spotElevationsDeg.begin(), spotElevationsDeg.end());
        for (double deg : elevations) {
            const glm::dvec3 dir =
                deg == 90.0 ? glm::dvec3(0, -1, 0) : downAt(deg * test::kPi / 180.0, kAzimuth);
            // Spot: 8 m from the plane's centre, aimed at it.
            const glm::dvec3 position = type == LightType::Spot ? -8.0 * dir : glm::dvec3(0, 8, 0);
            for (std::size_t k = 0; k < kTechniques.size(); ++k) {
                poseLight(scene, e, position, dir, kTechniques[k]);
                const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 192);
                test::expectSaneAovs(frame.images);
                // A spot lights only its cone (a hair inside, where its map ends).
                const GroundCounts c = countGround(frame.images, 0, [&](const glm::dvec3& p) {
                    return type != LightType::Spot ||
                           test::insideCone(p, position, dir, kSpotHalfAngle - 0.02);
                });
                const std::string name = std::string(type == LightType::Spot ? "spot" : "sun") +
                                         " at " + std::to_string(static_cast<int>(deg)) + " deg";
                ASSERT_GT(c.ground, 2000) << name << ": too few lit plane pixels to judge";
                EXPECT_LT(c.darkFraction(), kMaxAcneFraction)
                    << techniqueName(kTechniques[k]) << ", " << name << ": " << c.dark << " of "
                    << c.ground << " lit plane pixels read visibility < 0.5";
                if (c.darkFraction() > worst[k]) {
                    worst[k] = c.darkFraction();
                    worstCase[k] = name;
                }
            }
        }
    }
    for (std::size_t k = 0; k < kTechniques.size(); ++k) {
        std::printf("[ measured ] acne, %s: worst dark fraction %.5f (%s)\n",
                    techniqueName(kTechniques[k]), worst[k], worstCase[k].c_str());
    }
}

// ---------------------------------------------------------------------------------------------
// No peter-panning: a caster resting on the plane casts a shadow that starts at its base.
// ---------------------------------------------------------------------------------------------

/// Largest lit gap (in shadow texels) allowed between a box's base and its shadow.
constexpr double kMaxGapTexels = 2.0;
/// x of the shadowed face of the casters below: the light travels towards +x.
constexpr double kBaseX = 0.5;

struct BaseGap {
    /// Largest x - kBaseX (m) of a lit (visibility >= 0.5) ground pixel in the probed strip:
    /// the strictest reading, where any single noisy pixel counts.
    double pixelGap = 0.0;
    /// x - kBaseX (m) where the mean visibility over the strip's rows (2 mm bins of x) first
    /// falls below 0.5: the edge of a filtered shadow, free of the sample patterns' noise.
    double meanGap = 0.0;
    double texel = 0.0;  ///< lateral texel footprint (m) of the sun's layer: extent / mapSize
    double bias = 0.0;   ///< the sun's depth bias (m) at the ground, as the shader computes it
    int considered = 0;
    int dark = 0;
};

/// Renders a caster whose shadowed (+x) face stands on the ground at x = kBaseX, lit by a sun
/// at `elevationDeg` with `technique`, and measures the lit gap at the foot of that face over
/// the ground strip |z| < 0.3, kBaseX < x < kBaseX + 0.5 (inside the shadow, which is at least
/// 1 / tan(elevation) >= 1 m long, and 0.2 m from its sides).
BaseGap measureBaseGap(const glm::dvec3& casterCentre, const glm::dvec3& casterHalf,
                       double elevationDeg, ShadowTechnique technique) {
    Scene scene;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "caster", casterCentre, casterHalf);
    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.02f;
    const double elevation = elevationDeg * test::kPi / 180.0;
    const Shadow settings = test::shadowWith(technique, 1024);
    addLight(scene, "sun", sun, settings, {0, 8, 0}, downAt(elevation, 0.0));
    // From the shadowed side, high enough to see the ground at the foot of the +x face; a
    // pixel is under a texel there.
    Camera lens;
    lens.yfov = 0.25f;
    addCamera(scene, "camera", lens, {2.5, 2.0, 0.3}, {0.8, 0.0, 0.0});

    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 256);
    test::expectSaneAovs(frame.images);
    const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
    BaseGap g;
    g.texel = test::orthoTexel(plan.layers.at(0), plan.mapSize);
    // shadow_sampling.glsl: constantBias + slopeBias * texel * tan(angle to the normal).
    g.bias = settings.constantBias + settings.slopeBias * g.texel / std::tan(elevation);
    Profile darkness(kBaseX, kBaseX + 0.1, 50);
    const FrameImages& im = frame.images;
    for (int y = 0; y < im.position.height; ++y) {
        for (int x = 0; x < im.position.width; ++x) {
            if (!test::isGroundPixel(im, x, y)) continue;
            const glm::dvec3 p = test::positionAt(im, x, y);
            if (std::abs(p.z) > 0.3 || p.x < kBaseX || p.x > kBaseX + 0.5) continue;
            ++g.considered;
            const float v = im.visibility[0].at(x, y, 0);
            darkness.add(p.x, 1.0 - v);
            if (v < 0.5f) {
                ++g.dark;
            } else {
                g.pixelGap = std::max(g.pixelGap, p.x - kBaseX);
            }
        }
    }
    g.meanGap = darkness.firstCrossingUp(0.5).value_or(1e9) - kBaseX;
    return g;
}

/// A solid box hides the depth bias (the ray from the ground at its foot crosses the whole box),
/// so what this catches is a map misregistered against the receivers or a normal offset that
/// lifts receivers out of the shadow. Measured: no lit pixel at all beyond the base (gap 0).
TEST(SoftShadow, BoxShadowTouchesBox) {
    const glm::dvec3 boxHalf{0.5, 0.5, 0.5};
    for (double elevationDeg : {45.0, 25.0}) {
        for (ShadowTechnique technique : kTechniques) {
            const BaseGap g = measureBaseGap({kBaseX - boxHalf.x, boxHalf.y, 0.0}, boxHalf,
                                             elevationDeg, technique);
            std::printf(
                "[ measured ] box, %s, sun at %.0f deg: lit gap at the base %.4f m = %.2f texels "
                "(mean-profile gap %.4f m; texel %.4f m)\n",
                techniqueName(technique), elevationDeg, g.pixelGap, g.pixelGap / g.texel, g.meanGap,
                g.texel);
            ASSERT_GT(g.considered, 5000) << "the camera does not see the foot of the box";
            EXPECT_GT(g.dark, g.considered / 2)
                << techniqueName(technique) << ": the box casts no shadow";
            EXPECT_LE(g.pixelGap / g.texel, kMaxGapTexels)
                << techniqueName(technique) << ", sun at " << elevationDeg
                << " deg: shadow detached by " << g.pixelGap << " m";
        }
    }
}

/// A 1 mm wall is the hard case of peter-panning: no thickness hides the depth bias, so the
/// shadow may detach by what the bias allows and no more. A ground point at distance d from
/// the wall's foot lies d / cos(elevation) behind the wall along the ray, so the documented
/// bias b leaves a lit gap of b cos(elevation) on the ground; allowed: that plus 1 texel, on
/// the mean profile (PCF noise spreads single pixels either side of the 50 % line: measured,
/// the largest lit pixel of a 16-tap PCF lies 5.5 texels out at 25 deg where the mean edge is
/// at 3).
TEST(SoftShadow, ThinWallShadowGapStaysWithinTheDepthBias) {
    const glm::dvec3 wallHalf{0.0005, 0.5, 0.5};
    for (double elevationDeg : {45.0, 25.0}) {
        for (ShadowTechnique technique : kTechniques) {
            const BaseGap g = measureBaseGap({kBaseX - wallHalf.x, wallHalf.y, 0.0}, wallHalf,
                                             elevationDeg, technique);
            const double allowed = g.bias * std::cos(elevationDeg * test::kPi / 180.0) + g.texel;
            std::printf(
                "[ measured ] thin wall, %s, sun at %.0f deg: mean-profile gap %.4f m = %.2f "
                "texels "
                "(largest lit pixel %.4f m); bias allows %.4f m\n",
                techniqueName(technique), elevationDeg, g.meanGap, g.meanGap / g.texel, g.pixelGap,
                allowed);
            ASSERT_GT(g.considered, 5000) << "the camera does not see the foot of the wall";
            EXPECT_GT(g.dark, g.considered / 2)
                << techniqueName(technique) << ": the wall casts no shadow";
            EXPECT_LE(g.meanGap, allowed)
                << techniqueName(technique) << ", sun at " << elevationDeg << " deg";
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Mixed techniques: each light is sampled with its own technique in one frame.
// ---------------------------------------------------------------------------------------------

/// Fraction of ground pixels in (0.05, 0.95) allowed for a hard light (edge pixels only).
constexpr double kMaxHardPenumbraFraction = 0.015;
/// Fraction a soft light must exceed: measured 0.033 (PCSS sun) and 0.050 (PCF spot) against
/// 0.0004-0.0017 for the same lights forced to hard.
constexpr double kMinSoftPenumbraFraction = 0.02;

TEST(Mixed, EachLightUsesItsOwnTechnique) {
    Scene scene;
    test::addGround(scene, 6.0f);
    // Floating boxes (1.3 m above the ground) so every technique has room for a penumbra.
    const glm::dvec3 half{0.6, 0.2, 0.6};
    test::addBox(scene, "sun box", {-2.5, 1.5, -1.0}, half);
    test::addBox(scene, "spot box", {2.5, 1.5, -1.5}, half);
    test::addBox(scene, "bulb box", {0.0, 1.5, 2.0}, half);

    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.1f;
    addLight(scene, "sun", sun, test::shadowWith(ShadowTechnique::Pcss, 1024), {0, 10, 0},
             glm::normalize(glm::dvec3(0.4, -1.0, 0.3)));

    Light spot = test::pointSizedLight(LightType::Spot, 0.6f);
    Shadow pcf = test::shadowWith(ShadowTechnique::Pcf, 1024);
    pcf.pcfRadius = 0.15f;
    const glm::dvec3 spotPosition{2.8, 5.0, -1.2};
    const glm::dvec3 spotDirection = glm::normalize(glm::dvec3(2.3, 0.0, -2.0) - spotPosition);
    addLight(scene, "spot", spot, pcf, spotPosition, spotDirection);

    Light bulb = test::pointSizedLight(LightType::Point);
    bulb.radius = 0.05f;
    addLight(scene, "bulb", bulb, test::shadowWith(ShadowTechnique::Hard, 1024), {0.0, 3.5, 2.4},
             {0, -1, 0});
    addCamera(scene, "camera", Camera{}, {0.0, 10.0, 10.0}, {0.0, 0.0, 0.0});

    test::glContext();
    FrameRunner runner;
    auto penumbraFractions = [&] {
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 192);
        test::expectSaneAovs(frame.images);
        std::array<double, 3> f{};
        for (std::size_t i = 0; i < 3; ++i) {
            const GroundCounts c = countGround(frame.images, i, [&](const glm::dvec3& p) {
                return i != 1 || test::insideCone(p, spotPosition, spotDirection, 0.58);
            });
            EXPECT_GT(c.dark, c.ground / 100)
                << "light " << i << " casts (almost) no shadow in view";
            f[i] = c.penumbraFraction();
        }
        return f;
    };
    const std::array<double, 3> own = penumbraFractions();
    for (Entity light : scene.lights)
        scene.world.get<Shadow>(light).technique = ShadowTechnique::Hard;
    const std::array<double, 3> allHard = penumbraFractions();
    std::printf(
        "[ measured ] penumbra fraction own technique: sun/pcss %.4f, spot/pcf %.4f, bulb/hard "
        "%.4f\n",
        own[0], own[1], own[2]);
    std::printf("[ measured ] penumbra fraction all hard:      sun %.4f, spot %.4f, bulb %.4f\n",
                allHard[0], allHard[1], allHard[2]);

    EXPECT_LT(own[2], kMaxHardPenumbraFraction) << "the hard light is not binary";
    for (std::size_t i = 0; i < 2; ++i) {
        // A soft technique: a penumbra band several times wider than a hard edge's.
        EXPECT_GT(own[i], kMinSoftPenumbraFraction) << "light " << i << " shows no soft penumbra";
        EXPECT_LT(allHard[i], kMaxHardPenumbraFraction)
            << "light " << i << " forced to hard is not binary";
        EXPECT_LT(allHard[i], 0.5 * own[i]) << "light " << i << ": forcing hard did not sharpen it";
    }
    // The hard light did not change.
    EXPECT_NEAR(allHard[2], own[2], 1e-9);
}

}  // namespace
}  // namespace shadow
