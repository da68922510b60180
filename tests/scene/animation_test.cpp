// Tests of the animation system (engine/src/scene/animation.cpp) against closed forms.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <vector>

namespace shadow {
namespace {

using Path = AnimationChannel::Path;
using Interpolation = AnimationChannel::Interpolation;

AnimationChannel channel(Path path, Interpolation interpolation, std::vector<float> times,
                         std::vector<glm::vec4> values) {
    AnimationChannel c;
    c.path = path;
    c.interpolation = interpolation;
    c.times = std::move(times);
    c.values = std::move(values);
    return c;
}

Entity animated(World& world, std::vector<AnimationChannel> channels, double duration) {
    const Entity e = world.create();
    world.emplace<Transform>(e);
    world.emplace<Animation>(e, Animation{std::move(channels), duration});
    return e;
}

/// xyzw of the rotation by `angle` about +Y.
glm::vec4 yRotation(double angle, double length = 1.0) {
    return glm::vec4(0.0f, static_cast<float>(length * std::sin(angle / 2)), 0.0f,
                     static_cast<float>(length * std::cos(angle / 2)));
}

void expectRotationAboutY(const glm::dquat& q, double angle) {
    EXPECT_NEAR(glm::length(q), 1.0, 1e-9);
    EXPECT_NEAR(std::abs(glm::dot(q, glm::angleAxis(angle, glm::dvec3(0, 1, 0)))), 1.0, 1e-6)
        << "angle " << glm::angle(q);
}

double translationX(World& world, Entity e, double t) {
    animate(world, t);
    return world.get<Transform>(e).translation.x;
}

TEST(Animation, InterpolatesTranslationLinearlyAtMidpoint) {
    World world;
    const Entity e = animated(
        world, {channel(Path::Translation, Interpolation::Linear, {0, 2}, {{0, 0, 0, 0}, {2, 4, -6, 0}})}, 2.0);
    animate(world, 1.0);
    const glm::dvec3 p = world.get<Transform>(e).translation;
    EXPECT_NEAR(p.x, 1.0, 1e-12);
    EXPECT_NEAR(p.y, 2.0, 1e-12);
    EXPECT_NEAR(p.z, -3.0, 1e-12);
}

TEST(Animation, SlerpsRotationAlongTheShorterArc) {
    const double quarter = glm::half_pi<double>();
    World world;
    const Entity plain = animated(
        world, {channel(Path::Rotation, Interpolation::Linear, {0, 1}, {yRotation(0), yRotation(quarter)})}, 1.0);
    // 270 degrees is -90 degrees the short way: the midpoint is -45, not +135.
    const Entity longWay = animated(
        world, {channel(Path::Rotation, Interpolation::Linear, {0, 1}, {yRotation(0), yRotation(3 * quarter)})}, 1.0);
    animate(world, 0.5);
    expectRotationAboutY(world.get<Transform>(plain).rotation, quarter / 2);
    expectRotationAboutY(world.get<Transform>(longWay).rotation, -quarter / 2);
    animate(world, 0.25);  // slerp is uniform in angle, unlike a normalised lerp
    expectRotationAboutY(world.get<Transform>(plain).rotation, quarter / 4);
}

TEST(Animation, StepHoldsEachKeyUntilTheNext) {
    World world;
    const Entity e = animated(
        world,
        {channel(Path::Translation, Interpolation::Step, {0, 1, 2}, {{10, 0, 0, 0}, {20, 0, 0, 0}, {30, 0, 0, 0}})},
        3.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, 0.99), 10.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, 1.0), 20.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, 1.5), 20.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, 2.5), 30.0);
}

TEST(Animation, CubicSplineMatchesHermiteWithScaledTangents) {
    // Keys at t = 1 (value 1, out-tangent 2) and t = 3 (in-tangent -1, value 3); dt = 2.
    World world;
    const Entity e =
        animated(world,
                 {channel(Path::Translation, Interpolation::CubicSpline, {1, 3},
                          {{99, 0, 0, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}, {-1, 0, 0, 0}, {3, 0, 0, 0}, {99, 0, 0, 0}})},
                 4.0);
    const auto hermite = [](double u) {
        const double dt = 2.0;
        return (2 * u * u * u - 3 * u * u + 1) * 1.0 + (u * u * u - 2 * u * u + u) * dt * 2.0 +
               (-2 * u * u * u + 3 * u * u) * 3.0 + (u * u * u - u * u) * dt * -1.0;
    };
    EXPECT_NEAR(translationX(world, e, 2.0), 2.75, 1e-6);  // hermite(0.5) by hand
    EXPECT_NEAR(translationX(world, e, 1.5), hermite(0.25), 1e-6);
    EXPECT_NEAR(translationX(world, e, 2.75), hermite(0.875), 1e-6);
    EXPECT_NEAR(translationX(world, e, 0.5), 1.0, 1e-12);  // before the first key: its value
    EXPECT_NEAR(translationX(world, e, 3.5), 3.0, 1e-12);  // after the last key: its value
}

TEST(Animation, CubicSplineRotationIsNormalized) {
    World world;
    const glm::vec4 zero(0.0f);
    const Entity e = animated(world,
                              {channel(Path::Rotation, Interpolation::CubicSpline, {0, 1},
                                       {zero, yRotation(0), zero, zero, yRotation(glm::half_pi<double>()), zero})},
                              1.0);
    animate(world, 0.5);  // zero tangents: the midpoint is the normalised average
    expectRotationAboutY(world.get<Transform>(e).rotation, glm::half_pi<double>() / 2);
}

TEST(Animation, ClampsBeforeFirstAndAfterLastKey) {
    World world;
    const Entity e =
        animated(world, {channel(Path::Translation, Interpolation::Linear, {1, 2}, {{5, 0, 0, 0}, {7, 0, 0, 0}})}, 3.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, 0.5), 5.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, 2.5), 7.0);
}

TEST(Animation, WrapsAroundTheDuration) {
    World world;
    const Entity e =
        animated(world, {channel(Path::Translation, Interpolation::Linear, {0, 2}, {{0, 0, 0, 0}, {2, 0, 0, 0}})}, 2.0);
    EXPECT_NEAR(translationX(world, e, 2.5), 0.5, 1e-12);
    EXPECT_NEAR(translationX(world, e, 7.25), 1.25, 1e-12);
}

TEST(Animation, KeepsPrecisionAtTenMillionSeconds) {
    World world;
    const Entity e =
        animated(world, {channel(Path::Translation, Interpolation::Linear, {0, 3}, {{0, 0, 0, 0}, {3, 0, 0, 0}})}, 3.0);
    EXPECT_NEAR(translationX(world, e, 1e7), 1.0, 1e-6);  // 1e7 = 3 * 3333333 + 1
    EXPECT_NEAR(translationX(world, e, 1e7 + 0.25), 1.25, 1e-6);
}

TEST(Animation, TreatsNegativeAndNonFiniteTimeAsZero) {
    World world;
    const Entity e =
        animated(world, {channel(Path::Translation, Interpolation::Linear, {0, 4}, {{0, 0, 0, 0}, {4, 0, 0, 0}})}, 4.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, -1.0), 0.0);  // not 3, as a positive modulo gives
    EXPECT_DOUBLE_EQ(translationX(world, e, std::numeric_limits<double>::quiet_NaN()), 0.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, std::numeric_limits<double>::infinity()), 0.0);
}

TEST(Animation, ZeroDurationSamplesTimeZero) {
    World world;
    const Entity e =
        animated(world, {channel(Path::Translation, Interpolation::Linear, {0, 1}, {{1, 0, 0, 0}, {2, 0, 0, 0}})}, 0.0);
    EXPECT_DOUBLE_EQ(translationX(world, e, 0.7), 1.0);
}

TEST(Animation, ZeroScaleKeyStaysFinite) {
    World world;
    const Entity e =
        animated(world, {channel(Path::Scale, Interpolation::Linear, {0, 1}, {{1, 1, 1, 0}, {0, 0, 0, 0}})}, 2.0);
    animate(world, 1.0);
    EXPECT_EQ(world.get<Transform>(e).scale, glm::dvec3(0.0));
    animate(world, 0.5);
    EXPECT_EQ(world.get<Transform>(e).scale, glm::dvec3(0.5));
}

TEST(Animation, NormalizesQuaternionKeys) {
    const double quarter = glm::half_pi<double>();
    World world;
    const Entity step = animated(world,
                                 {channel(Path::Rotation, Interpolation::Step, {0, 1, 2},
                                          {yRotation(0, 2.0), yRotation(quarter, 3.0), glm::vec4(0.0f)})},
                                 3.0);
    const Entity linear = animated(
        world, {channel(Path::Rotation, Interpolation::Linear, {0, 1}, {yRotation(0, 0.5), yRotation(quarter, 4.0)})},
        1.0);
    animate(world, 0.5);
    expectRotationAboutY(world.get<Transform>(step).rotation, 0.0);
    expectRotationAboutY(world.get<Transform>(linear).rotation, quarter / 2);
    animate(world, 1.5);
    expectRotationAboutY(world.get<Transform>(step).rotation, quarter);
    animate(world, 2.5);  // a zero-length key is the identity
    expectRotationAboutY(world.get<Transform>(step).rotation, 0.0);
}

TEST(Animation, IgnoresChannelsWithTooFewValues) {
    World world;
    const Entity e = animated(
        world, {channel(Path::Translation, Interpolation::CubicSpline, {0, 1}, {{1, 0, 0, 0}, {2, 0, 0, 0}})}, 1.0);
    world.get<Transform>(e).translation = glm::dvec3(9.0);
    animate(world, 0.5);
    EXPECT_EQ(world.get<Transform>(e).translation, glm::dvec3(9.0));
}

// ---- procedural motion -------------------------------------------------------------------

Entity moving(World& world, ProceduralMotion motion) {
    const Entity e = world.create();
    world.emplace<Transform>(e);
    world.emplace<ProceduralMotion>(e, motion);
    return e;
}

TEST(AnimationProcedural, OrbitsAroundCenterInXzPlane) {
    World world;
    ProceduralMotion m;
    m.kind = ProceduralMotion::Kind::Orbit;
    m.center = {1, 0.5, 0};
    m.radius = 2.0;
    m.speed = 0.5;
    m.phase = 0.1;
    const Entity e = moving(world, m);
    animate(world, 3.0);
    const glm::dvec3 p = world.get<Transform>(e).translation;
    EXPECT_NEAR(p.x, 1 + 2 * std::cos(1.6), 1e-12);
    EXPECT_NEAR(p.y, 0.5, 1e-12);
    EXPECT_NEAR(p.z, 2 * std::sin(1.6), 1e-12);
}

TEST(AnimationProcedural, BobsAlongAxis) {
    World world;
    ProceduralMotion m;
    m.kind = ProceduralMotion::Kind::Bob;
    m.center = {0, 1, 0};
    m.amplitude = 0.5;
    m.speed = 2.0;
    const Entity e = moving(world, m);
    animate(world, 1.0);
    EXPECT_NEAR(world.get<Transform>(e).translation.y, 1 + 0.5 * std::sin(2.0), 1e-12);
}

TEST(AnimationProcedural, SpinsAboutNormalizedAxisAndKeepsTranslation) {
    World world;
    ProceduralMotion m;
    m.kind = ProceduralMotion::Kind::Spin;
    m.axis = {0, 2, 0};
    const Entity e = moving(world, m);
    world.get<Transform>(e).translation = {3, 4, 5};
    animate(world, 0.5);
    expectRotationAboutY(world.get<Transform>(e).rotation, 0.5);
    EXPECT_EQ(world.get<Transform>(e).translation, glm::dvec3(3, 4, 5));
}

TEST(AnimationProcedural, ZeroSpinAxisLeavesRotationFinite) {
    World world;
    ProceduralMotion m;
    m.kind = ProceduralMotion::Kind::Spin;
    m.axis = glm::dvec3(0.0);
    const Entity e = moving(world, m);
    animate(world, 1.0);
    expectRotationAboutY(world.get<Transform>(e).rotation, 0.0);
}

TEST(AnimationProcedural, OverridesKeyframesOfTheSameComponent) {
    World world;
    const Entity e =
        animated(world, {channel(Path::Translation, Interpolation::Linear, {0, 1}, {{5, 0, 0, 0}, {5, 0, 0, 0}})}, 1.0);
    ProceduralMotion m;
    m.kind = ProceduralMotion::Kind::Bob;
    m.axis = {1, 0, 0};
    m.speed = 0.0;
    m.phase = glm::half_pi<double>();
    world.emplace<ProceduralMotion>(e, m);
    EXPECT_NEAR(translationX(world, e, 0.5), 1.0, 1e-12);
}

}  // namespace
}  // namespace shadow
