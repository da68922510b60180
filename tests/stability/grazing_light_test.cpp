// Grazing light: a lit plane must not shadow itself (acne) however low the light stands.
//
// At elevation e the plane's depth changes by cot(e) metres per metre across the light's view
// (114 at 0.5 degrees), so every texel-sized error of the lookup becomes a large depth error.
// The sampling code places every tap on the receiver's tangent plane (shadow_receiver.glsl,
// sg_makeReceiver); the test holds that to its promise down to 0.5 degrees for every technique.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

#include "stability/stability_test_support.h"

namespace shadow {
namespace {

/// The seeds' textbook PCSS filters in the receiver's map UV with one reference depth, so a
/// steep receiver shadows itself by design; it is held to the bound down to this elevation.
constexpr double kTextbookLowestDeg = 2.0;

/// Renders the plane lit by `type` at every elevation with every technique, checks the bound,
/// and prints every figure.
void expectNoAcne(LightType type) {
    constexpr float kSpotHalfAngle = 0.5f;
    Scene scene;
    test::addGround(scene, 10.0f);
    Light light = test::pointSizedLight(type, kSpotHalfAngle);
    light.angularRadius = 0.02f;  // PCSS needs an emitter; hard and PCF ignore it
    light.radius = 0.1f;
    const Entity e = addLight(scene, "light", light, test::shadowWith(ShadowTechnique::Hard), {0, 8, 0}, {0, -1, 0});
    addCamera(scene, "camera", Camera{}, {0.0, 9.0, 13.0}, {0.0, 0.0, 0.0});
    for (double deg : test::kGrazingElevationsDeg) {
        const glm::dvec3 dir = test::grazingDirection(deg);
        // A spot 8 m from the plane's centre, aimed at it; the sun's position does not matter.
        const glm::dvec3 position = type == LightType::Spot ? -8.0 * dir : glm::dvec3(0, 8, 0);
        Transform& t = scene.world.get<Transform>(e);
        t.translation = position;
        t.rotation = rotationLookingAlong(dir);
        char name[64];
        std::snprintf(name, sizeof(name), "%s at %.1f deg", type == LightType::Spot ? "spot" : "sun", deg);
        test::forEveryTechnique(
            scene, 256, 192, name, [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
                test::AcneCount a;  // lit: the lit plane pixels considered
                const ImageF& v = frame.images.visibility[0];
                for (int y = 0; y < v.height; ++y) {
                    for (int x = 0; x < v.width; ++x) {
                        if (!test::isGroundPixel(frame.images, x, y)) continue;
                        // A spot lights only its cone (a hair inside, where its map ends).
                        const glm::dvec3 p = test::positionAt(frame.images, x, y);
                        if (type == LightType::Spot && !test::insideCone(p, position, dir, kSpotHalfAngle - 0.02))
                            continue;
                        const float value = v.at(x, y, 0);
                        ++a.lit;
                        a.dark += value < 0.5f ? 1 : 0;
                        a.darkened += value < 0.99f ? 1 : 0;
                        a.lowest = std::min(a.lowest, value);
                    }
                }
                std::printf(
                    "[ measured ] acne, %s, %s: false shadow %.5f, darkened %.5f, lowest "
                    "visibility %.3f\n",
                    techniqueName(technique), name, a.darkFraction(), a.darkenedFraction(), a.lowest);
                ASSERT_GT(a.lit, 500) << name << ": too few lit plane pixels to judge";
                if (technique == ShadowTechnique::PcssTextbook) {
                    if (deg >= kTextbookLowestDeg) {
                        EXPECT_LT(a.darkFraction(), test::kMaxAcneFraction) << name;
                    }
                    return;
                }
                EXPECT_LT(a.darkFraction(), test::kMaxAcneFraction) << techniqueName(technique) << ", " << name;
                EXPECT_LT(a.darkenedFraction(), test::kMaxAcneFraction) << techniqueName(technique) << ", " << name;
            });
    }
}

TEST(Stability, GrazingSunCausesNoAcne) { expectNoAcne(LightType::Directional); }

TEST(Stability, GrazingSpotCausesNoAcne) { expectNoAcne(LightType::Spot); }

}  // namespace
}  // namespace shadow
