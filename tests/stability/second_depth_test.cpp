// Second-depth maps (DepthMode::Midpoint) against biased nearest-depth maps, on closed casters:
// acne at grazing light on a curved and a flat receiver, and peter-panning at contact. Every
// figure is printed for the README table (tests/stability/README.md); the midpoint mode is held
// to the grazing-light suite's acne bound with zero constant and slope bias.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "stability/stability_test_support.h"
#include "test_support.h"

namespace shadow::second_depth_test {
namespace {

constexpr std::array<ShadowTechnique, 3> kTechniques{ShadowTechnique::Hard, ShadowTechnique::Pcf,
                                                     ShadowTechnique::Pcss};

/// A depth mode with the biases it is used with: the defaults for the nearest depth, none for
/// the midpoint.
struct Setting {
    const char* name;
    DepthMode mode;
    bool zeroBias;
};
constexpr std::array<Setting, 3> kSettings{{{"nearest, default bias", DepthMode::Nearest, false},
                                            {"nearest, zero bias", DepthMode::Nearest, true},
                                            {"midpoint, zero bias", DepthMode::Midpoint, true}}};

void apply(Scene& scene, ShadowTechnique technique, const Setting& setting) {
    scene.world.view<Shadow>().each([&](Entity, Shadow& s) {
        s.technique = technique;
        s.depthMode = setting.mode;
        const Shadow defaults;
        s.constantBias = setting.zeroBias ? 0.0f : defaults.constantBias;
        s.slopeBias = setting.zeroBias ? 0.0f : defaults.slopeBias;
    });
}

constexpr double kSphereRadius = 0.5;
const glm::dvec3 kSphereCentre{0.0, 0.6, 0.0};

/// The receivers, each alone in its scene so that every pixel facing the light must read lit:
/// a closed slab whose top is y = 0 (flat), and a sphere (curved).
enum class Receiver { Slab, Sphere };

/// Renders `receiver` lit by `type` from elevation after elevation with each of `settings` and
/// every technique; counts the pixels that face the light by more than 6 degrees (n.l > 0.1; a
/// spot also: inside its cone) and read shadowed. Returns the largest false-shadow fraction of the
/// nearest depth without bias (the test's proof that there is acne to remove; 0 without it).
double measureGrazing(LightType type, Receiver receiver, std::span<const Setting> settings) {
    constexpr float kSpotHalfAngle = 0.5f;
    Scene scene;
    if (receiver == Receiver::Slab) {
        test::addBox(scene, "slab", {0.0, -0.1, 0.0}, {6.0, 0.1, 6.0});
    } else {
        addMeshInstance(scene.world, "sphere", makeSphereMesh(static_cast<float>(kSphereRadius), 48, 24),
                        test::placed(kSphereCentre));
    }
    Light light = test::pointSizedLight(type, kSpotHalfAngle);
    light.angularRadius = 0.02f;
    light.radius = 0.1f;
    const Entity e = addLight(scene, "light", light, test::shadowWith(ShadowTechnique::Hard), {0, 8, 0}, {0, -1, 0});
    // The slab from above; the sphere from the side the light comes from, close enough to fill
    // the view.
    const glm::dvec3 towardsLight(-std::cos(test::kGrazingAzimuth), 0.3, -std::sin(test::kGrazingAzimuth));
    if (receiver == Receiver::Slab) {
        addCamera(scene, "camera", Camera{}, {0.0, 3.0, 5.0}, {0.0, 0.3, 0.0});
    } else {
        addCamera(scene, "camera", Camera{}, kSphereCentre + 1.6 * towardsLight, kSphereCentre);
    }
    const char* what = receiver == Receiver::Slab ? "slab" : "sphere";
    test::glContext();
    double worstUnbiasedNearest = 0.0;
    for (double deg : test::kGrazingElevationsDeg) {
        const glm::dvec3 dir = test::grazingDirection(deg);
        // A spot 8 m from the receiver's centre, aimed at it; the sun's position does not matter.
        const glm::dvec3 target = receiver == Receiver::Slab ? glm::dvec3(0.0) : kSphereCentre;
        const glm::dvec3 position = type == LightType::Spot ? target - 8.0 * dir : glm::dvec3(0, 8, 0);
        Transform& t = scene.world.get<Transform>(e);
        t.translation = position;
        t.rotation = rotationLookingAlong(dir);
        for (const Setting& setting : settings) {
            FrameRunner runner;
            for (ShadowTechnique technique : kTechniques) {
                apply(scene, technique, setting);
                const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 192);
                test::AcneCount a;
                const FrameImages& im = frame.images;
                for (int y = 0; y < im.position.height; ++y) {
                    for (int x = 0; x < im.position.width; ++x) {
                        if (im.position.at(x, y, 3) < 0.5f) continue;
                        const glm::dvec3 p = test::positionAt(im, x, y);
                        if (type == LightType::Spot && !test::insideCone(p, position, dir, kSpotHalfAngle - 0.02))
                            continue;
                        const glm::dvec3 n =
                            receiver == Receiver::Slab ? glm::dvec3(0, 1, 0) : glm::normalize(p - kSphereCentre);
                        if (receiver == Receiver::Slab && std::abs(p.y) > 1e-3) continue;  // its top only
                        const glm::dvec3 toLight = type == LightType::Spot ? glm::normalize(position - p) : -dir;
                        if (glm::dot(n, toLight) < 0.1 * (receiver == Receiver::Sphere ? 1.0 : 0.0)) continue;
                        const float v = im.visibility[0].at(x, y, 0);
                        ++a.lit;
                        a.dark += v < 0.5f ? 1 : 0;
                        a.darkened += v < 0.99f ? 1 : 0;
                    }
                }
                std::printf("[ measured ] grazing %s at %.1f deg on the %s, %s, %s: false shadow %.5f, darkened %.5f\n",
                            type == LightType::Spot ? "spot" : "sun", deg, what, techniqueName(technique), setting.name,
                            a.darkFraction(), a.darkenedFraction());
                EXPECT_GT(a.lit, 500) << what << ": too few lit pixels to judge";
                EXPECT_TRUE(frame.stats.warnings.empty()) << test::describe(frame.stats.warnings);
                if (setting.mode == DepthMode::Nearest && setting.zeroBias) {
                    worstUnbiasedNearest = std::max(worstUnbiasedNearest, a.darkFraction());
                }
                if (setting.mode != DepthMode::Midpoint) continue;
                const std::string name =
                    std::string(what) + ", " + techniqueName(technique) + " at " + std::to_string(deg) + " deg";
                EXPECT_LT(a.darkFraction(), test::kMaxAcneFraction) << name;
                EXPECT_LT(a.darkenedFraction(), test::kMaxAcneFraction) << name;
            }
        }
    }
    return worstUnbiasedNearest;
}

/// The settings the grazing tests hold to their bound or against it: the nearest depth and the
/// midpoint, both without bias.
constexpr std::array<Setting, 2> kZeroBias{kSettings[1], kSettings[2]};

TEST(Stability, MidpointDepthHasNoAcneAtGrazingSunWithoutBias) {
    EXPECT_GT(measureGrazing(LightType::Directional, Receiver::Slab, kZeroBias), 0.1)
        << "no acne without bias to remove";
    measureGrazing(LightType::Directional, Receiver::Sphere, kZeroBias);
}

TEST(Stability, MidpointDepthHasNoAcneAtGrazingSpotWithoutBias) {
    EXPECT_GT(measureGrazing(LightType::Spot, Receiver::Slab, kZeroBias), 0.1) << "no acne without bias to remove";
    measureGrazing(LightType::Spot, Receiver::Sphere, kZeroBias);
}

// The same frames with the nearest depth and the default bias: figures only (README.md's
// second-depth table compares the midpoint with them), a third of the two tests above. Slow tier:
// the fast tier holds the default bias at grazing light to the acne bound in
// grazing_light_test.cpp (Stability.GrazingSunCausesNoAcne, Stability.GrazingSpotCausesNoAcne).
TEST(Stability, SlowNearestDepthWithTheDefaultBiasAtGrazingLightForTheMidpointTable) {
    const std::array<Setting, 1> defaultBias{kSettings[0]};
    for (LightType type : {LightType::Directional, LightType::Spot}) {
        for (Receiver receiver : {Receiver::Slab, Receiver::Sphere}) measureGrazing(type, receiver, defaultBias);
    }
}

/// A 40 cm box resting on the closed slab, lit obliquely: the ground pixels the box shadows (ray
/// cast) within 10 cm of its footprint, and the fraction of them that read lit (visibility >
/// 0.5): the shadow detached from its caster (peter-panning), per setting.
double detachedFraction(LightType type, const glm::dvec3& direction, ShadowTechnique technique, const Setting& setting,
                        const std::string& name) {
    constexpr double kHalf = 0.2;
    Scene scene;
    test::addBox(scene, "slab", {0.0, -0.1, 0.0}, {3.0, 0.1, 3.0});
    test::addBox(scene, "box", {0.0, kHalf, 0.0}, glm::dvec3(kHalf));
    Light light = test::pointSizedLight(type, 0.6f);
    const glm::dvec3 dir = glm::normalize(direction);
    addLight(scene, "light", light, test::shadowWith(technique, 1024), -4.0 * dir, dir);
    addCamera(scene, "camera", Camera{}, glm::dvec3(0.0, 1.6, 0.0) + 1.2 * glm::dvec3(dir.x, 0.0, dir.z),
              {0.0, 0.0, 0.0});
    apply(scene, technique, setting);
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 256);
    const std::array<DAabb, 1> boxes{test::boxBounds({0.0, kHalf, 0.0}, glm::dvec3(kHalf))};
    const glm::dvec3 lightPosition = -4.0 * dir;
    int shadowed = 0;
    int lit = 0;
    const FrameImages& im = frame.images;
    for (int y = 0; y < im.position.height; ++y) {
        for (int x = 0; x < im.position.width; ++x) {
            if (!test::isGroundPixel(im, x, y)) continue;
            const glm::dvec3 p = test::positionAt(im, x, y);
            const double outside = std::max(std::abs(p.x), std::abs(p.z)) - kHalf;
            if (outside < 0.0 || outside > 0.1) continue;
            const glm::dvec3 toLight = type == LightType::Directional ? -dir : lightPosition - p;
            if (!test::segmentHitsBox(p, toLight, 1e-6, type == LightType::Directional ? 100.0 : 1.0, boxes[0]))
                continue;
            ++shadowed;
            lit += im.visibility[0].at(x, y, 0) > 0.5f ? 1 : 0;
        }
    }
    EXPECT_GT(shadowed, 300) << name;
    const double fraction = shadowed > 0 ? static_cast<double>(lit) / shadowed : 0.0;
    std::printf("[ measured ] contact, %s, %s, %s: shadowed ground within 10 cm read lit %.5f (%d px)\n", name.c_str(),
                techniqueName(technique), setting.name, fraction, shadowed);
    return fraction;
}

TEST(Stability, MidpointDepthDetachesLessAtContactThanTheDefaultBias) {
    struct Case {
        const char* name;
        LightType type;
        glm::dvec3 direction;
    };
    const Case cases[] = {{"sun at 45 deg", LightType::Directional, {1.0, -1.0, 0.3}},
                          {"sun at 20 deg", LightType::Directional, {2.7, -1.0, 0.4}},
                          {"spot at 40 deg", LightType::Spot, {0.8, -1.0, -0.2}}};
    for (const Case& c : cases) {
        for (ShadowTechnique technique : kTechniques) {
            const double biased = detachedFraction(c.type, c.direction, technique, kSettings[0], c.name);
            const double midpoint = detachedFraction(c.type, c.direction, technique, kSettings[2], c.name);
            // No more detached than under the default bias (both count the same texel-sized
            // stair steps along the shadow's sides; what differs is at the contact line).
            EXPECT_LE(midpoint, biased) << c.name << ", " << techniqueName(technique);
        }
    }
}

/// The contact suite's thin plate (contact_test.cpp): 1 mm thick, 1 mm above the ground, in
/// midpoint mode without bias. The plate is closed, so its texels store the middle of its 1 mm;
/// the ground under it lies 1.5 mm behind that and is dark. (The ground is an open plane: the
/// light warns about it, and where nothing lies behind it its texels store the far depth.)
TEST(Stability, MidpointDepthKeepsTheShadowOfAThinPlateJustAboveTheGround) {
    constexpr double kThickness = 0.001;
    constexpr double kHalf = 0.3;
    struct Case {
        const char* name;
        LightType type;
        glm::dvec3 direction;
    };
    const Case cases[] = {{"sun straight down", LightType::Directional, {0, -1, 0}},
                          {"sun at 62 deg", LightType::Directional, {0.5, -1, 0.2}},
                          {"spot tilted", LightType::Spot, {0.4, -1, -0.3}},
                          {"point", LightType::Point, {0.3, -1, 0.2}}};
    for (const Case& c : cases) {
        Scene scene;
        test::addGround(scene, 1.0f);
        test::addBox(scene, "plate", {0.0, 0.001 + 0.5 * kThickness, 0.0}, {kHalf, 0.5 * kThickness, kHalf});
        Light light = test::pointSizedLight(c.type, 0.5f);
        const glm::dvec3 dir = glm::normalize(c.direction);
        addLight(scene, "light", light, test::shadowWith(ShadowTechnique::Hard, 2048), -3.0 * dir, dir);
        addCamera(scene, "camera", Camera{}, {0.0, -2.0, 0.3}, {0.0, 0.0, 0.0});  // from below
        test::glContext();
        FrameRunner runner;
        for (ShadowTechnique technique : kTechniques) {
            apply(scene, technique, kSettings[2]);
            const test::RenderedFrame frame = test::renderFrame(runner, scene, 192, 192);
            // The ground under the plate's inner part, along the light (5 cm inside its edges).
            const test::GroundCounts under = test::countGround(frame.images, 0, [&](const glm::dvec3& p) {
                const glm::dvec3 q = p - dir * ((0.001 + 0.5 * kThickness) / -dir.y);
                return std::abs(q.x) <= kHalf - 0.05 && std::abs(q.z) <= kHalf - 0.05;
            });
            const double fraction = under.darkFraction();
            test::reportFigure(std::string("thin plate 1 mm above the ground, ") + c.name + ", " +
                                   techniqueName(technique) + ", midpoint, zero bias: dark fraction under the plate",
                               fraction);
            ASSERT_GT(under.ground, 1000) << c.name;
            EXPECT_GE(fraction, 0.99) << c.name << ", " << techniqueName(technique);
            EXPECT_EQ(test::countWarnings(frame.stats.warnings, WarningCode::OpenCaster, "light"), 1);
        }
    }
}

}  // namespace
}  // namespace shadow::second_depth_test
