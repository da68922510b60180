// Emitter shapes and their samples (emitters.cpp), and what they make of the visibility at a
// straight blocker edge for each light type, traced through the reference tracer.
#include "reference/emitters.h"

#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

#include "reference/closed_forms.h"
#include <shadow/reference.h>

namespace shadow::reference {
namespace {

// ---- Samples and shapes ----

TEST(Emitters, MultiJitteredSamplesAreStratified) {
    // Square count: one sample per cell of the 8 x 8 grid and per row of height 1/64.
    std::set<int> cells;
    std::set<int> rows;
    for (std::uint32_t k = 0; k < 64; ++k) {
        const glm::dvec2 s = multiJitteredSample(k, 64, 77);
        ASSERT_TRUE(s.x >= 0.0 && s.x < 1.0 && s.y >= 0.0 && s.y < 1.0);
        cells.insert(static_cast<int>(s.x * 8) * 8 + static_cast<int>(s.y * 8));
        rows.insert(static_cast<int>(s.y * 64));
    }
    EXPECT_EQ(cells.size(), 64u);
    EXPECT_EQ(rows.size(), 64u);
    // Any count: one sample per row of height 1/N.
    rows.clear();
    for (std::uint32_t k = 0; k < 50; ++k) rows.insert(static_cast<int>(multiJitteredSample(k, 50, 5).y * 50));
    EXPECT_EQ(rows.size(), 50u);
}

TEST(Emitters, ConcentricMapPreservesArea) {
    EXPECT_EQ(concentricDisk({0.5, 0.5}), glm::dvec2(0.0));
    EXPECT_NEAR(glm::length(concentricDisk({1.0, 0.3})), 1.0, 1e-12);
    constexpr int kGrid = 400;
    int inner = 0;
    for (int i = 0; i < kGrid; ++i) {
        for (int j = 0; j < kGrid; ++j) {
            const glm::dvec2 d = concentricDisk({(i + 0.5) / kGrid, (j + 0.5) / kGrid});
            ASSERT_LE(glm::length(d), 1.0 + 1e-12);
            inner += glm::length(d) <= 0.5 ? 1 : 0;
        }
    }
    EXPECT_NEAR(static_cast<double>(inner) / (kGrid * kGrid), 0.25, 2e-3);  // area of r <= 1/2
}

TEST(Emitters, PointLightSilhouetteRaysAreTangentToTheSphere) {
    Emitter e;
    e.type = LightType::Point;
    e.wsPosition = {0.3, 2.0, -0.4};
    e.radius = 0.5;
    const glm::dvec3 p(0.1, 0.0, 0.6);
    for (int k = 0; k < 16; ++k) {
        const double phi = 2.0 * std::numbers::pi * k / 16;
        const ShadowRayAim aim = aimAtEmitter(e, p, {std::cos(phi), std::sin(phi)});
        const glm::dvec3 target = p + aim.direction * aim.distance;
        EXPECT_NEAR(glm::length(target - e.wsPosition), e.radius, 1e-12);  // on the sphere
        EXPECT_NEAR(glm::length(glm::cross(e.wsPosition - p, aim.direction)), e.radius,
                    1e-12);  // tangent
    }
    EXPECT_EQ(aimAtEmitter(e, e.wsPosition + glm::dvec3(0.1, 0, 0), {0.3, 0.2}).distance,
              0.0);  // inside
}

TEST(Emitters, DirectionalConeRimHasTheHalfAngle) {
    Emitter e;
    e.type = LightType::Directional;
    e.wsTowardLight = glm::normalize(glm::dvec3(0.2, 1.0, -0.3));
    e.angularRadius = 0.1;
    for (int k = 0; k < 12; ++k) {
        const double phi = 2.0 * std::numbers::pi * k / 12;
        const ShadowRayAim aim = aimAtEmitter(e, {}, {std::cos(phi), std::sin(phi)});
        EXPECT_NEAR(std::acos(std::clamp(glm::dot(aim.direction, e.wsTowardLight), -1.0, 1.0)), 0.1, 1e-7);
        EXPECT_TRUE(std::isinf(aim.distance));
    }
    EXPECT_NEAR(glm::length(aimAtEmitter(e, {}, {0, 0}).direction - e.wsTowardLight), 0.0, 1e-15);
}

TEST(Emitters, SpotDiskIsCentredOnTheLightAndPerpendicularToItsAxis) {
    Emitter e;
    e.type = LightType::Spot;
    e.wsPosition = {1.0, 3.0, 0.5};
    e.wsTowardLight = glm::normalize(glm::dvec3(0.3, 1.0, 0.1));
    e.radius = 0.25;
    const glm::dvec3 p(0.0, 0.0, 0.0);
    const glm::dvec2 disk(0.6, -0.3);
    const ShadowRayAim aim = aimAtEmitter(e, p, disk);
    const glm::dvec3 offset = p + aim.direction * aim.distance - e.wsPosition;
    EXPECT_NEAR(glm::dot(offset, e.wsTowardLight), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(offset), e.radius * glm::length(disk), 1e-12);
}

TEST(Emitters, EmitterOfReadsThePoseAndClampsTheSize) {
    Scene scene;
    Light light;
    light.type = LightType::Spot;
    light.radius = 5000.0f;
    const Entity e = addLight(scene, "spot", light, Shadow{}, {1, 2, 3}, {0, -1, 0});
    (void)updateTransforms(scene.world);
    const std::optional<Emitter> emitter = emitterOf(scene.world, e);
    ASSERT_TRUE(emitter.has_value());
    EXPECT_NEAR(glm::length(emitter->wsPosition - glm::dvec3(1, 2, 3)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(emitter->wsTowardLight - glm::dvec3(0, 1, 0)), 0.0, 1e-12);
    EXPECT_EQ(emitter->radius, 1e3);
    EXPECT_TRUE(emitter->clamped);
}

TEST(Emitters, AZeroScaleSpotShinesAlongItsRotationAsInTheRenderer) {
    // The renderer's rule (worldOrientation, read by the planner's lightPose): a node of scale 0
    // points along its rotation, not down -Z.
    Scene scene;
    Light light;
    light.type = LightType::Spot;
    const Entity e = addLight(scene, "spot", light, Shadow{}, {0, 4, 0}, {0, 0, -1});
    const glm::dquat rotation = glm::angleAxis(0.9, glm::normalize(glm::dvec3(1.0, 0.0, 0.5)));
    scene.world.get<Transform>(e).rotation = rotation;
    scene.world.get<Transform>(e).scale = glm::dvec3(0.0);
    (void)updateTransforms(scene.world);
    const std::optional<Emitter> emitter = emitterOf(scene.world, e);
    ASSERT_TRUE(emitter.has_value());
    const glm::dvec3 towardLight = rotation * glm::dvec3(0.0, 0.0, 1.0);
    EXPECT_NEAR(glm::length(emitter->wsTowardLight - towardLight), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(emitter->wsTowardLight - worldOrientation(scene.world.get<WorldTransform>(e))[2]), 0.0,
                1e-15);
}

// ---- Each light type at a straight blocker edge, through the tracer ----

constexpr double kBlockerHeight = 1.0;

/// A receiver at y = 0 and a blocker plate at `kBlockerHeight` covering x in [-8, 0],
/// z in [-4, 4] (its edge on x = 0 along z), one light, and a camera high above.
Scene edgeScene(const Light& light, const glm::dvec3& position, const glm::dvec3& direction) {
    Scene scene;
    scene.name = "edge";
    addMeshInstance(scene.world, "receiver", makePlaneMesh(10.0f), Transform{});
    Transform blocker;
    blocker.translation = {-4.0, kBlockerHeight, 0.0};
    addMeshInstance(scene.world, "blocker", makePlaneMesh(4.0f), blocker);
    addLight(scene, "light", light, Shadow{}, position, direction);
    addCamera(scene, "camera", Camera{}, {0.0, 12.0, 0.5}, {0.0, 0.0, 0.0});
    animate(scene.world, 0.0);
    (void)updateTransforms(scene.world);
    return scene;
}

/// Traces the visibility of light 0 at receiver points `points` (positions mode).
ReferenceResult traceAt(Scene& scene, const std::vector<glm::dvec3>& points, int samples) {
    ImageF positions = makeImage(static_cast<int>(points.size()), 1, 4);
    for (std::size_t k = 0; k < points.size(); ++k) {
        for (int c = 0; c < 3; ++c) positions.at(static_cast<int>(k), 0, c) = static_cast<float>(points[k][c]);
        positions.at(static_cast<int>(k), 0, 3) = 1.0f;
    }
    ReferenceOptions options;
    options.width = positions.width;
    options.height = 1;
    options.samples = samples;
    options.wsPositions = &positions;
    const CameraView view = makeCameraView(scene.world, scene.cameras.at(0), 1.0f);
    Result<ReferenceResult> r = traceVisibility(scene, view, options);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    EXPECT_EQ(r->positionsWithoutSurface, 0);
    return std::move(r.value());
}

std::vector<glm::dvec3> pointsAlongX(double from, double to, int count) {
    std::vector<glm::dvec3> points;
    for (int k = 0; k < count; ++k) points.emplace_back(from + (to - from) * k / (count - 1), 0.0, 0.0);
    return points;
}

TEST(Reference, ZeroSizeEmittersCastExactlyHardShadows) {
    struct Case {
        LightType type;
        glm::dvec3 position, direction;
    };
    for (const Case& c :
         {Case{LightType::Spot, {0.5, 3.0, 0.2}, {0, -1, 0}}, Case{LightType::Point, {-0.7, 2.5, 0.4}, {0, -1, 0}},
          Case{LightType::Directional, {0, 20, 0}, glm::normalize(glm::dvec3(0.4, -1.0, 0.3))}}) {
        Light light;
        light.type = c.type;
        Scene scene = edgeScene(light, c.position, c.direction);
        std::vector<glm::dvec3> points;
        for (int i = 0; i < 40; ++i) {
            for (int j = 0; j < 40; ++j) points.emplace_back(-3.0 + 6.0 * i / 39, 0.0, -3.0 + 6.0 * j / 39);
        }
        const ReferenceResult r = traceAt(scene, points, 64);
        EXPECT_EQ(r.lights.at(0).raysPerPixel, 1);
        int lit = 0;
        int checked = 0;
        for (std::size_t k = 0; k < points.size(); ++k) {
            const float v = r.visibility[0].pixels[k];
            ASSERT_TRUE(v == 0.0f || v == 1.0f) << "light type " << int(c.type) << ", point " << k;
            ASSERT_EQ(r.standardError[0].pixels[k], 0.0f);
            // The hard-shadow truth: where the ray to the light's centre crosses the plate plane.
            const glm::dvec3 p = points[k];
            const glm::dvec3 toLight = c.type == LightType::Directional ? -c.direction : glm::normalize(c.position - p);
            const glm::dvec3 crossing = p + toLight * ((kBlockerHeight - p.y) / toLight.y);
            const bool onAnEdge = std::abs(crossing.x) < 1e-6 || std::abs(crossing.x + 8.0) < 1e-6 ||
                                  std::abs(4.0 - std::abs(crossing.z)) < 1e-6;
            if (onAnEdge) continue;
            const bool blocked = crossing.x < 0.0 && crossing.x > -8.0 && std::abs(crossing.z) < 4.0;
            EXPECT_EQ(v, blocked ? 0.0f : 1.0f) << "light type " << int(c.type) << " at (" << p.x << ", " << p.z << ")";
            lit += v == 1.0f ? 1 : 0;
            ++checked;
        }
        EXPECT_GT(lit, checked / 5);
        EXPECT_LT(lit, checked * 4 / 5);
    }
}

TEST(Reference, OnlyCastersOcclude) {
    Light light;
    light.type = LightType::Point;
    Scene scene = edgeScene(light, {0.0, 3.0, 0.0}, {0, -1, 0});
    scene.world.view<Mesh>().each([](Entity, Mesh& mesh) { mesh.castShadows = false; });
    const ReferenceResult r = traceAt(scene, pointsAlongX(-2.0, 2.0, 41), 16);
    for (const float v : r.visibility[0].pixels) EXPECT_EQ(v, 1.0f);
}

TEST(Reference, DirectionalConePenumbraWidthIsTwoHeightsTimesTanAlpha) {
    constexpr double kAlpha = 0.05;
    constexpr int kSamples = 4096;
    Light sun;
    sun.type = LightType::Directional;
    sun.angularRadius = static_cast<float>(kAlpha);
    Scene scene = edgeScene(sun, {0, 20, 0}, {0, -1, 0});
    const double alpha = static_cast<double>(sun.angularRadius);
    const double halfWidth = kBlockerHeight * std::tan(alpha);  // d·tan α either side of the edge
    const std::vector<glm::dvec3> points = pointsAlongX(-1.6 * halfWidth, 1.6 * halfWidth, 321);
    const ReferenceResult r = traceAt(scene, points, kSamples);

    double firstLit = HUGE_VAL;       // lowest x with V > 0
    double lastShadowed = -HUGE_VAL;  // highest x with V < 1
    double worst = 0.0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double x = points[k].x;
        const double v = r.visibility[0].pixels[k];
        const double se = r.standardError[0].pixels[k];
        if (v > 0.0) firstLit = std::min(firstLit, x);
        if (v < 1.0) lastShadowed = std::max(lastShadowed, x);
        // Geometry, exactly: beyond d·tan α every direction of the cone passes or none does.
        if (x > halfWidth * (1.0 + 1e-3)) {
            EXPECT_EQ(v, 1.0) << "x = " << x;
        }
        if (x < -halfWidth * (1.0 + 1e-3)) {
            EXPECT_EQ(v, 0.0) << "x = " << x;
        }
        // The profile: the fraction of the (small) cone on the lit side of the edge's plane is
        // the circular segment beyond u = -x/(d tan α), to O(α²).
        const double expected = 1.0 - circularSegmentFraction(x / halfWidth);
        const double sigma = std::max(se, binomialStandardError(expected, kSamples));
        if (sigma > 0.0) worst = std::max(worst, std::abs(v - expected) / sigma);
        // 0.005: the O(α²) of the small-cone closed form.
        EXPECT_LE(std::abs(v - expected), 3.0 * sigma + 0.005) << "x = " << x;
    }
    const double measured = lastShadowed - firstLit;
    std::printf(
        "[ measured ] directional α=%.3f at d=%.1f m: penumbra %.5f m, 2·d·tan α = %.5f m, "
        "worst |V − closed form| = %.2f SE\n",
        alpha, kBlockerHeight, measured, 2.0 * halfWidth, worst);
    EXPECT_NEAR(measured, 2.0 * halfWidth, 0.03 * 2.0 * halfWidth);
}

TEST(Reference, PointLightPenumbraEndsAtTheSpheresTangentPlanes) {
    constexpr int kSamples = 4096;
    Light bulb;
    bulb.type = LightType::Point;
    bulb.radius = 0.5f;  // r/d up to 0.3: the silhouette is 5 % narrower than a disk of radius r
    const glm::dvec3 c(0.2, 1.8, 0.0);
    Scene scene = edgeScene(bulb, c, {0, -1, 0});
    const double radius = static_cast<double>(bulb.radius);
    const std::vector<glm::dvec3> points = pointsAlongX(-1.5, 0.6, 211);
    const ReferenceResult r = traceAt(scene, points, kSamples);

    int penumbra = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const glm::dvec3 p = points[k];
        const double v = r.visibility[0].pixels[k];
        const double se = r.standardError[0].pixels[k];
        // The plane through p and the edge line {(0, d, z)}, normal towards the lit side.
        const glm::dvec3 n = glm::normalize(glm::dvec3(kBlockerHeight, p.x, 0.0));
        const double sCenter = glm::dot(n, c - p);  // signed distance of the sphere's centre
        if (sCenter > radius * (1.0 + 1e-4)) {
            EXPECT_EQ(v, 1.0) << "x = " << p.x;
        }
        if (sCenter < -radius * (1.0 + 1e-4)) {
            EXPECT_EQ(v, 0.0) << "x = " << p.x;
        }
        // In between: the silhouette disk (radius ρ at distance d − r²/d) cut by that plane.
        const double d = glm::length(c - p);
        const glm::dvec3 w = (c - p) / d;
        const double rho = radius * std::sqrt(1.0 - (radius / d) * (radius / d));
        const glm::dvec3 m = p + w * (d - radius * radius / d);
        const double inPlane = std::sqrt(1.0 - glm::dot(n, w) * glm::dot(n, w));
        const double expected = circularSegmentFraction(-glm::dot(n, m - p) / (rho * inPlane));
        const double sigma = std::max(se, binomialStandardError(expected, kSamples));
        EXPECT_LE(std::abs(v - expected), 3.0 * sigma + 1e-9) << "x = " << p.x;
        penumbra += v > 0.0 && v < 1.0 ? 1 : 0;
    }
    EXPECT_GT(penumbra, 50);
}

}  // namespace
}  // namespace shadow::reference
