// The default rig (engine/src/scene/default_rig.cpp): where its sun, ground and camera go, from
// the model's bounds and the camera, checked against the placement rule of shadow/default_rig.h.
#include <gtest/gtest.h>
#include <shadow/default_rig.h>

#include "scene/gltf_test_support.h"
#include "test_support.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace shadow {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// A 1 x 2 x 1 m box standing on y = 0 at (3, 0, -2).
Scene boxScene() {
    Scene scene;
    scene.name = "box.gltf";
    Transform at;
    at.translation = {3.0, 1.0, -2.0};
    addMeshInstance(scene.world, "box", makeBoxMesh({0.5f, 1.0f, 0.5f}), at);
    return scene;
}

/// The forward (-Z) of a posed entity.
glm::dvec3 forwardOf(const World& world, Entity e) { return -worldOrientation(world.get<WorldTransform>(e))[2]; }

TEST(DefaultRig, SunShinesFromTheElevationAndAzimuthAskedRelativeToTheCamera) {
    for (const double azimuth : {60.0, -30.0, 150.0}) {
        Scene scene = boxScene();
        // A camera looking along +X, down at the box.
        const Entity camera = addCamera(scene, "camera", Camera{}, {-6.0, 5.0, -2.0}, {3.0, 0.0, -2.0});
        DefaultRigOptions options;
        options.sunElevation = 40.0 * kDegree;
        options.sunAzimuth = azimuth * kDegree;
        const DefaultRig rig = addDefaultRig(scene, camera, options);
        ASSERT_EQ(scene.lights.size(), 1u);
        EXPECT_EQ(scene.lights[0], rig.sun);
        EXPECT_FALSE(rig.cameraAdded);
        EXPECT_EQ(rig.camera, camera);
        const glm::dvec3 d = rig.sunDirection;
        EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
        EXPECT_NEAR(std::asin(-d.y), 40.0 * kDegree, 1e-9) << "elevation";
        // The camera's horizontal forward is +X and its right +Z (forward x up): the light's
        // horizontal travel is cos(a) forward + sin(a) right.
        EXPECT_NEAR(std::atan2(d.z, d.x), azimuth * kDegree, 1e-9) << "azimuth " << azimuth;
        // The light entity points where the rig says.
        EXPECT_NEAR(glm::length(forwardOf(scene.world, rig.sun) - d), 0.0, 1e-9);
        const Light& light = scene.world.get<Light>(rig.sun);
        EXPECT_EQ(light.type, LightType::Directional);
        EXPECT_FLOAT_EQ(light.angularRadius, 0.02f);
        EXPECT_EQ(scene.world.get<Shadow>(rig.sun).technique, ShadowTechnique::Pcss);
    }
}

TEST(DefaultRig, GroundLiesUnderTheModelAndHoldsItsShadow) {
    Scene scene = boxScene();
    const DefaultRig rig = addDefaultRig(scene, std::nullopt);
    ASSERT_FALSE(rig.ground.isNull());
    const Mesh& mesh = scene.world.get<Mesh>(rig.ground);
    EXPECT_FALSE(mesh.castShadows) << "a shadow catcher casts nothing";
    EXPECT_TRUE(mesh.receiveShadows);
    // At the bounds' lowest point (y = 0), 1e-3 of the model's size (2 m) below.
    EXPECT_NEAR(rig.groundHeight, -2e-3, 1e-12);
    const DAabb& ground = scene.world.get<WorldBounds>(rig.ground).box;
    EXPECT_NEAR(ground.min.y, rig.groundHeight, 1e-9);
    EXPECT_NEAR(ground.max.y, rig.groundHeight, 1e-9);
    // Every corner of the box's shadow (its top corners along the sun to the ground) is on it.
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p = DAabb{{2.5, 0.0, -2.5}, {3.5, 2.0, -1.5}}.corner(c);
        const glm::dvec3 q = p + rig.sunDirection * ((p.y - rig.groundHeight) / -rig.sunDirection.y);
        EXPECT_GE(q.x, ground.min.x);
        EXPECT_LE(q.x, ground.max.x);
        EXPECT_GE(q.z, ground.min.z);
        EXPECT_LE(q.z, ground.max.z);
    }
    // At least 4x the model's largest edge across, centred under it.
    EXPECT_GE(ground.max.x - ground.min.x, 8.0 - 1e-9);
    EXPECT_NEAR(0.5 * (ground.min.x + ground.max.x), 3.0, 1e-9);
    EXPECT_NEAR(0.5 * (ground.min.z + ground.max.z), -2.0, 1e-9);

    Scene bare = boxScene();
    DefaultRigOptions noGround;
    noGround.ground = false;
    const DefaultRig without = addDefaultRig(bare, std::nullopt, noGround);
    EXPECT_TRUE(without.ground.isNull());
    EXPECT_EQ(without.groundHalfSize, 0.0);
    int meshes = 0;
    bare.world.view<Mesh>().each([&](Entity, Mesh&) { ++meshes; });
    EXPECT_EQ(meshes, 1) << "the model only";
}

TEST(DefaultRig, AddedCameraFramesTheModelAndItsShadow) {
    Scene scene = boxScene();
    const DefaultRig rig = addDefaultRig(scene, std::nullopt);
    ASSERT_TRUE(rig.cameraAdded);
    ASSERT_EQ(scene.cameras.size(), 1u);
    EXPECT_EQ(scene.cameras[0], rig.camera);
    const double aspect = DefaultRigOptions{}.imageAspect;  // 16:9
    const CameraView view = makeCameraView(scene.world, rig.camera, static_cast<float>(aspect));
    const double tanHalf = std::tan(0.5 * view.yfov);
    // The box's corners (its pose, without the margin) and their shadows: inside the field of
    // view of a 16:9 image, between the near and far planes; the framing is tight (some point
    // within 10 % of an edge).
    double widest = 0.0;
    const DAabb box{{2.5, 0.0, -2.5}, {3.5, 2.0, -1.5}};
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p = box.corner(c);
        const glm::dvec3 shadow = p + rig.sunDirection * ((p.y - rig.groundHeight) / -rig.sunDirection.y);
        for (const glm::dvec3& q : {p, shadow}) {
            const glm::dvec3 v(view.viewFromWorld * glm::dvec4(q, 1.0));
            const double depth = -v.z;
            EXPECT_GT(depth, view.znear);
            EXPECT_LT(depth, view.zfar);
            const double across = std::max(std::abs(v.x) / aspect, std::abs(v.y)) / (depth * tanHalf);
            EXPECT_LE(across, 1.0) << "corner " << c;
            widest = std::max(widest, across);
        }
    }
    EXPECT_GT(widest, 0.9) << "framed with room to spare";
    // Looking down from the front-right, as addDefaultCamera does: 25 degrees below the horizon.
    const glm::dvec3 forward = forwardOf(scene.world, rig.camera);
    EXPECT_NEAR(std::asin(-forward.y), 24.94 * kDegree, 0.01 * kDegree);
}

/// A skinned 1 m box following one joint that a keyframed clip (2 s) moves from x = 0 (t = 0)
/// to x = 10 (t = 1) and back (t = 2); the mesh instance itself stands far away (glTF does not
/// apply it to a skinned mesh). `Scene::animationDuration` is left 0 (nothing said to play).
Scene skinnedSlideScene(Entity& joint) {
    Scene scene;
    joint = scene.world.create();
    scene.world.emplace<Transform>(joint, Transform{});
    AnimationChannel slide;
    slide.times = {0.0f, 1.0f, 2.0f};
    slide.values = {glm::vec4(0.0f), glm::vec4(10.0f, 0.0f, 0.0f, 0.0f), glm::vec4(0.0f)};
    scene.world.emplace<Animation>(joint, Animation{{slide}, 2.0});
    auto box = makeBoxMesh({0.5f, 0.5f, 0.5f});
    auto mesh = std::make_shared<MeshData>(*box);
    mesh->joints.assign(mesh->positions.size(), glm::u16vec4(0));
    mesh->weights.assign(mesh->positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
    computeJointBounds(*mesh);
    Transform far;
    far.translation = {100.0, 100.0, 100.0};
    const Entity skinned = addMeshInstance(scene.world, "skinned", mesh, far);
    Skin skin;
    skin.joints = {joint};
    skin.inverseBind = {glm::dmat4(1.0)};
    scene.world.emplace<Skin>(skinned, skin);
    return scene;
}

TEST(DefaultRig, BoundsAreTheSkinnedPoseAtTimeZeroWithAMargin) {
    Entity joint;
    Scene scene = skinnedSlideScene(joint);
    const DAabb atZero = modelBounds(scene.world, 0.0);
    EXPECT_NEAR(atZero.min.x, -0.5, 1e-6);
    EXPECT_NEAR(atZero.max.x, 0.5, 1e-6);
    const DAabb atOne = modelBounds(scene.world, 1.0);
    EXPECT_NEAR(atOne.min.x, 9.5, 1e-6) << "the pose follows the clip";

    scene.world.get<Transform>(joint).translation = {7.0, 0.0, 0.0};  // posed elsewhere before the rig
    const DefaultRig rig = addDefaultRig(scene, std::nullopt);
    EXPECT_EQ(rig.posesSampled, 1) << "nothing plays";
    const double margin = 0.1 * std::sqrt(3.0);  // a tenth of the 1 m cube's diagonal
    EXPECT_NEAR(rig.modelBounds.min.x, -0.5 - margin, 1e-6);
    EXPECT_NEAR(rig.modelBounds.max.x, 0.5 + margin, 1e-6);
    EXPECT_NEAR(rig.modelBounds.min.y, -0.5 - margin, 1e-6);
    EXPECT_NEAR(rig.groundHeight, -0.5 - 1e-3, 1e-9) << "the ground under the pose, not the margin";
}

// With the clip playing (2 s), the skinned box's bounds are the union of its 16 poses at 2k/15 s:
// the farthest at 14/15 and 16/15 s, the joint at x = 28/3, so x spans [-0.5, 28/3 + 0.5]; the
// world is posed at t = 0 again.
TEST(DefaultRig, SkinnedBoundsCoverTheClipThatPlays) {
    Entity joint;
    Scene scene = skinnedSlideScene(joint);
    scene.animationDuration = 2.0;
    const DefaultRig rig = addDefaultRig(scene, std::nullopt);
    EXPECT_EQ(rig.posesSampled, 16);
    const double farthest = 28.0 / 3.0;
    const double margin = 0.1 * std::sqrt((farthest + 1.0) * (farthest + 1.0) + 2.0);  // a tenth of the diagonal
    EXPECT_NEAR(rig.modelBounds.min.x, -0.5 - margin, 1e-5);
    EXPECT_NEAR(rig.modelBounds.max.x, farthest + 0.5 + margin, 1e-5);
    EXPECT_NEAR(scene.world.get<WorldTransform>(joint).worldFromLocal[3].x, 0.0, 1e-12) << "posed at t = 0 again";
}

/// A glTF file whose only node, "box" (a 1 m cube centred on it), moves over a 3 s LINEAR clip
/// from (0, 0, 0) at t = 0 down to (4, -3, 0) at t = 1 and up to (10, 2, 0) at t = 3: the rig's
/// 16 poses (every 0.2 s, the last just before 3 s) include t = 1, its lowest point.
gltf_test::Doc walkingBoxDoc() {
    gltf_test::Doc doc;
    std::vector<float> corners;
    for (int c = 0; c < 8; ++c) {
        for (int axis = 0; axis < 3; ++axis) corners.push_back(((c >> axis) & 1) != 0 ? 0.5f : -0.5f);
    }
    // Two triangles per face, each face the corners with one axis' bit fixed.
    const std::vector<std::uint16_t> indices{0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                             2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    const gltf_test::json primitive = {{"attributes", {{"POSITION", doc.floats(corners, "VEC3")}}},
                                       {"indices", doc.indices(indices)}};
    doc.push("meshes", {{"primitives", gltf_test::json::array({primitive})}});
    doc.node({{"name", "box"}, {"mesh", 0}});
    doc.scene({0});
    const int times = doc.floats({0, 1, 3}, "SCALAR");
    const int values = doc.floats({0, 0, 0, 4, -3, 0, 10, 2, 0}, "VEC3");
    doc.push(
        "animations",
        {{"samplers", gltf_test::json::array({{{"input", times}, {"output", values}, {"interpolation", "LINEAR"}}})},
         {"channels", gltf_test::json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}});
    return doc;
}

/// The box's position on its clip at `t` (s), t in [0, 3].
glm::dvec3 walkingBoxAt(double t) {
    return t <= 1.0 ? glm::dvec3(4.0 * t, -3.0 * t, 0.0)
                    : glm::dvec3(4.0 + 3.0 * (t - 1.0), -3.0 + 2.5 * (t - 1.0), 0.0);
}

// A clip that walks the model away and down and up: the ground lies at the lowest point over the
// clip (y = -3.5, not the pose at t = 0's -0.5), holds the box wherever it goes, the added camera
// frames the box at every time of the clip, and the scene is left posed at t = 0.
TEST(DefaultRig, GroundAndCameraCoverTheWholeClip) {
    auto loaded = loadGltf(walkingBoxDoc().write(gltf_test::testDir() / "walk.gltf").string());
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    Scene& scene = *loaded;
    ASSERT_DOUBLE_EQ(scene.animationDuration, 3.0);
    const DefaultRig rig = addDefaultRig(scene, std::nullopt);
    const double size = 11.0;  // the path's bounds: x in [-0.5, 10.5], y in [-3.5, 2.5]
    EXPECT_NEAR(rig.groundHeight, -3.5 - 1e-3 * size, 1e-6) << "the lowest point over the clip";
    const DAabb& ground = scene.world.get<WorldBounds>(rig.ground).box;
    const double aspect = DefaultRigOptions{}.imageAspect;
    const CameraView view = makeCameraView(scene.world, rig.camera, static_cast<float>(aspect));
    const double tanHalf = std::tan(0.5 * view.yfov);
    double widest = 0.0;
    for (int i = 0; i <= 60; ++i) {
        const glm::dvec3 at = walkingBoxAt(0.05 * i);
        EXPECT_GE(at.x - 0.5, ground.min.x);
        EXPECT_LE(at.x + 0.5, ground.max.x);
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 p = at + DAabb{glm::dvec3(-0.5), glm::dvec3(0.5)}.corner(c);
            const glm::dvec3 v(view.viewFromWorld * glm::dvec4(p, 1.0));
            const double depth = -v.z;
            EXPECT_GT(depth, view.znear);
            EXPECT_LT(depth, view.zfar);
            const double across = std::max(std::abs(v.x) / aspect, std::abs(v.y)) / (depth * tanHalf);
            EXPECT_LE(across, 1.0) << "corner " << c << " at t = " << 0.05 * i;
            widest = std::max(widest, across);
        }
    }
    std::printf("ground y %.4f, widest corner at %.3f of the half field of view\n", rig.groundHeight, widest);
    const Entity box = gltf_test::findByName(scene, "box");
    EXPECT_NEAR(glm::length(glm::dvec3(scene.world.get<WorldTransform>(box).worldFromLocal[3])), 0.0, 1e-12)
        << "posed at t = 0 again";
    EXPECT_NE(scene.warnings.back().message.find("over 16 poses of its 3 s animation"), std::string::npos)
        << scene.warnings.back().message;
}

TEST(DefaultRig, SaysWhatItAddedAsAWarning) {
    Scene scene = boxScene();
    (void)addDefaultRig(scene, std::nullopt);
    ASSERT_EQ(test::countWarnings(scene.warnings, WarningCode::DefaultRigAdded, "box.gltf"), 1)
        << test::describe(scene.warnings);
    const std::string& message = scene.warnings.back().message;
    EXPECT_NE(message.find("box.gltf: no lights; added the default rig: a pcss sun 50 degrees up"), std::string::npos)
        << message;
    EXPECT_NE(message.find("a ground"), std::string::npos) << message;
    EXPECT_NE(message.find("a camera"), std::string::npos) << message;
    EXPECT_STREQ(warningCodeName(WarningCode::DefaultRigAdded), "DefaultRigAdded");
}

TEST(DefaultRig, OptionsOutOfRangeAreClampedAndAnEmptySceneIsLit) {
    Scene scene;  // no mesh at all: lit around a 2 m box at the origin
    DefaultRigOptions wild;
    wild.sunElevation = -1.0;
    wild.sunAzimuth = std::nan("");
    wild.angularRadius = 5.0f;
    const DefaultRig rig = addDefaultRig(scene, std::nullopt, wild);
    EXPECT_NEAR(std::asin(-rig.sunDirection.y), 10.0 * kDegree, 1e-9) << "the lowest elevation offered";
    EXPECT_FLOAT_EQ(scene.world.get<Light>(rig.sun).angularRadius, 0.2f);
    EXPECT_NEAR(rig.groundHeight, -1.0 - 2e-3, 1e-9);
    for (const double v : {rig.sunDirection.x, rig.sunDirection.y, rig.sunDirection.z}) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace shadow
