// Animation extremes through the whole frame (animate, updateTransforms, shadows, main pass):
// dt = 0, negative dt, dt = 10^4 s, time 10^7 s, a key of zero scale, unnormalised quaternion
// keys. Transforms stay finite; an entity whose transform is not finite (set in code, or
// overflowing through its parents) is skipped by every pass and reported, and does not
// change a single pixel of the others.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

#include "stability/stability_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

/// Ground, two animated boxes (keyframes with a zero-scale key and unnormalised rotation keys;
/// a fast orbit), a spinning spot and a sun.
Scene animatedScene() {
    Scene scene;
    test::addGround(scene, 4.0f);
    const Entity keyed = test::addBox(scene, "keyed", {0.0, 1.0, 0.0}, {0.4, 0.3, 0.4});
    Animation anim;
    AnimationChannel scale;
    scale.path = AnimationChannel::Path::Scale;
    scale.times = {0.0f, 1.0f, 2.0f};
    scale.values = {glm::vec4(1.0f), glm::vec4(0.0f), glm::vec4(1.0f, 2.0f, 1.0f, 0.0f)};
    AnimationChannel rotation;
    rotation.path = AnimationChannel::Path::Rotation;
    rotation.times = {0.0f, 2.0f};
    rotation.values = {glm::vec4(0.0f, 0.0f, 0.0f, 5.0f), glm::vec4(0.0f, 3.0f, 0.0f, 4.0f)};  // |q| = 5
    AnimationChannel translation;
    translation.path = AnimationChannel::Path::Translation;
    translation.interpolation = AnimationChannel::Interpolation::CubicSpline;
    translation.times = {0.0f, 2.0f};
    translation.values = {glm::vec4(0.0f),  glm::vec4(-1.0f, 1.0f, 0.0f, 0.0f), glm::vec4(1e3f),
                          glm::vec4(-1e3f), glm::vec4(1.0f, 1.0f, 0.5f, 0.0f),  glm::vec4(0.0f)};
    anim.channels = {scale, rotation, translation};
    anim.duration = 2.0;
    scene.world.emplace<Animation>(keyed, anim);
    scene.animationDuration = 2.0;

    const Entity orbiting = test::addBox(scene, "orbiting", {1.5, 0.8, 0.0}, {0.3, 0.3, 0.3});
    ProceduralMotion orbit;
    orbit.kind = ProceduralMotion::Kind::Orbit;
    orbit.center = {0.0, 0.8, 0.0};
    orbit.radius = 1.5;
    orbit.speed = 1e6;  // rad/s: sin and cos of arguments up to 1e13
    scene.world.emplace<ProceduralMotion>(orbiting, orbit);

    Light spot = test::pointSizedLight(LightType::Spot, 0.6f);
    spot.radius = 0.1f;
    const Entity lamp =
        addLight(scene, "lamp", spot, test::shadowWith(ShadowTechnique::Pcss, 512), {0.5, 4.0, 0.5}, {0, -1, 0});
    ProceduralMotion spin;
    spin.kind = ProceduralMotion::Kind::Spin;
    spin.axis = {0.0, 0.0, 0.0};  // no axis: the rotation is left as it was
    scene.world.emplace<ProceduralMotion>(lamp, spin);
    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 0.01f;
    addLight(scene, "sun", sun, test::shadowWith(ShadowTechnique::Pcf, 512), {0, 8, 0}, {0.3, -1, 0.2});
    addCamera(scene, "camera", Camera{}, {0.0, 5.0, 6.0}, {0.0, 0.0, 0.0});
    return scene;
}

/// Every entity's world matrix is finite and usable, or it is one of `poisoned` and flagged.
void expectFiniteTransforms(World& world, const std::vector<Entity>& poisoned, const std::string& when) {
    world.view<WorldTransform>().each([&](Entity e, WorldTransform& wt) {
        const bool expectedBad = std::find(poisoned.begin(), poisoned.end(), e) != poisoned.end();
        EXPECT_EQ(wt.finite, !expectedBad) << when << ": " << world.get<Name>(e).value;
        if (!expectedBad) {
            EXPECT_TRUE(isFinite(wt.worldFromLocal)) << when << ": " << world.get<Name>(e).value;
        }
    });
}

TEST(Stability, ExtremeTimeStepsKeepEveryTransformFinite) {
    struct Run {
        const char* name;
        double start;
        double dt;
    };
    const Run runs[] = {
        {"dt = 0", 0.5, 0.0},
        {"negative dt", 1.0, -0.7},
        {"dt = 1e4 s", 0.0, 1e4},
        {"time 1e7 s", 1e7, 1.0 / 30.0},
        {"time 1e7 s, negative dt", 1e7, -1e4},
    };
    test::glContext();
    for (const Run& run : runs) {
        Scene scene = animatedScene();
        FrameRunner runner;
        for (int f = 0; f < 3; ++f) {
            const double t = run.start + run.dt * f;
            const test::RenderedFrame frame = test::renderFrame(runner, scene, 96, 72, t);
            const std::string when = std::string(run.name) + ", frame " + std::to_string(f);
            test::expectSaneFrame(frame.images, runner.shadows(), when);
            expectFiniteTransforms(scene.world, {}, when);
            EXPECT_EQ(frame.stats.entitiesSkippedNonFinite, 0) << when;
            if (run.dt == 0.0 && f > 0) {
                // Nothing moved: every layer is reused.
                EXPECT_EQ(frame.stats.shadowLayersDrawn, 0) << when;
            }
        }
    }
}

/// The scene plus entities whose transforms are not finite: a NaN translation with a mesh child
/// (the child inherits it), a light at infinity, two scales of 1e200 whose product overflows (the
/// parent, finite, reaches 1e199 m with its vertices: beyond the world, skipped too), and a mesh
/// whose own vertices lie at 1e38 m. `poisoned` lists every entity that must be skipped.
void addPoison(Scene& scene, std::vector<Entity>& poisoned) {
    World& w = scene.world;
    const Entity nanParent = test::addBox(scene, "nan box", {0.0, 1.0, 0.0}, {0.5, 0.5, 0.5});
    w.get<Transform>(nanParent).translation.x = std::numeric_limits<double>::quiet_NaN();
    Transform childTransform = test::placed({0.0, 1.0, 0.0});
    childTransform.parent = nanParent;
    const Entity nanChild = addMeshInstance(w, "child of the nan box", makeBoxMesh(glm::vec3(0.3f)), childTransform);
    const Entity farLight = addLight(scene, "lamp at infinity", test::pointSizedLight(LightType::Point),
                                     test::shadowWith(ShadowTechnique::Hard, 256),
                                     {std::numeric_limits<double>::infinity(), 3.0, 0.0}, {0, -1, 0});
    const Entity huge = test::addBox(scene, "huge", {0.0, 0.0, 0.0}, {0.1, 0.1, 0.1});
    w.get<Transform>(huge).scale = glm::dvec3(1e200);
    Transform overflowTransform = test::placed({0.0, 0.0, 0.0}, glm::dvec3(1e200));
    overflowTransform.parent = huge;
    const Entity overflow = addMeshInstance(w, "overflowing child", makeBoxMesh(glm::vec3(0.1f)), overflowTransform);
    const Entity farVertices =
        addMeshInstance(w, "vertices at 1e38 m", makeBoxMesh(glm::vec3(1e38f)), test::placed({}));
    poisoned = {nanParent, nanChild, farLight, huge, overflow, farVertices};
}

TEST(Stability, NonFiniteTransformIsSkippedReportedAndPoisonsNothingElse) {
    test::glContext();
    Scene clean = animatedScene();
    Scene dirty = animatedScene();
    std::vector<Entity> poisoned;
    addPoison(dirty, poisoned);

    FrameRunner cleanRunner;
    FrameRunner dirtyRunner;
    for (double t : {0.0, 0.7, 1e7}) {
        const test::RenderedFrame a = test::renderFrame(cleanRunner, clean, 96, 72, t);
        const test::RenderedFrame b = test::renderFrame(dirtyRunner, dirty, 96, 72, t);
        const std::string when = "t = " + std::to_string(t);
        test::expectSaneFrame(b.images, dirtyRunner.shadows(), when);
        expectFiniteTransforms(dirty.world, poisoned, when);
        EXPECT_EQ(b.stats.entitiesSkippedNonFinite, 6) << when;
        for (const char* name : {"nan box", "child of the nan box", "lamp at infinity", "huge", "overflowing child",
                                 "vertices at 1e38 m"}) {
            EXPECT_EQ(test::countWarnings(b.stats.warnings, WarningCode::NonFiniteTransform, name), 1)
                << when << ": " << name << " is not reported once\n"
                << test::describe(b.stats.warnings);
        }
        // The rest of the frame is exactly the clean scene's: colour, and each clean light's
        // visibility (the dirty scene's extra light comes last and stays at 1).
        EXPECT_EQ(a.images.color.pixels, b.images.color.pixels) << when;
        ASSERT_EQ(b.images.visibility.size(), a.images.visibility.size() + 1);
        for (std::size_t i = 0; i < a.images.visibility.size(); ++i) {
            EXPECT_EQ(a.images.visibility[i].pixels, b.images.visibility[i].pixels) << when << ", light " << i;
        }
        const ImageF& skippedLight = b.images.visibility.back();
        EXPECT_TRUE(
            std::all_of(skippedLight.pixels.begin(), skippedLight.pixels.end(), [](float v) { return v == 1.0f; }));
    }
}

}  // namespace
}  // namespace shadow
