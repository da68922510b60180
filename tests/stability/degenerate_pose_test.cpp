// Degenerate light poses: lights pointing straight down or straight up (the usual up vector of
// a view matrix is parallel to the axis), a light standing exactly on a receiver point, a light
// at a blocker's surface (dBlocker -> 0) and receivers on the blocker itself (dReceiver -
// dBlocker -> 0). Every technique must give finite matrices, finite maps, finite images and
// visibility in [0, 1]; where the answer is known it must be right.
#include <gtest/gtest.h>

#include <string>

#include "stability/stability_test_support.h"

namespace shadow::degenerate_pose_test {
namespace {

const glm::dvec3 kBoxCenter{0.0, 1.2, 0.0};
const glm::dvec3 kBoxHalf{0.5, 0.3, 0.4};

/// Ground (3 m from the centre), a box floating over it and a camera above; the light is added
/// by the caller.
Scene groundAndBox() {
    Scene scene;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "box", kBoxCenter, kBoxHalf);
    addCamera(scene, "camera", Camera{}, {0.5, 5.0, 4.5}, {0.0, 0.0, 0.0});
    return scene;
}

Light softLight(LightType type) {
    Light light = test::pointSizedLight(type, 0.7f);
    light.radius = 0.1f;
    light.angularRadius = 0.02f;
    return light;
}

/// Fraction of ground pixels with visibility < 0.5 for light `i`.
double darkGroundFraction(const FrameImages& images, std::size_t i = 0) {
    return test::countGround(images, i).darkFraction();
}

TEST(Stability, LightsAlongTheUpAxisHaveFiniteMatrices) {
    struct Case {
        const char* name;
        LightType type;
        glm::dvec3 position;
        glm::dvec3 direction;
        bool castsOnGround;  // the box's shadow falls on the lit ground
    };
    const Case cases[] = {
        {"sun straight down", LightType::Directional, {0, 8, 0}, {0, -1, 0}, true},
        {"sun straight up", LightType::Directional, {0, -8, 0}, {0, 1, 0}, false},
        {"spot straight down", LightType::Spot, {0, 4, 0}, {0, -1, 0}, true},
        {"spot straight up", LightType::Spot, {0, 0.5, 0}, {0, 1, 0}, false},
        {"point above", LightType::Point, {0, 4, 0}, {0, -1, 0}, true},
        {"point, node looking straight up", LightType::Point, {0, 4, 0}, {0, 1, 0}, true},
    };
    for (const Case& c : cases) {
        Scene scene = groundAndBox();
        addLight(scene, c.name, softLight(c.type), test::shadowWith(ShadowTechnique::Hard, 512), c.position,
                 c.direction);
        test::forEveryTechnique(
            scene, 128, 96, c.name, [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
                const double dark = darkGroundFraction(frame.images);
                test::reportFigure(std::string(c.name) + ", " + techniqueName(technique) + ": dark ground fraction",
                                   dark);
                if (c.castsOnGround) {
                    EXPECT_GT(dark, 0.01) << c.name << ": the box casts no shadow";
                    EXPECT_LT(dark, 0.5) << c.name << ": the ground is dark all over";
                }
            });
    }
}

/// A camera looking straight down: its view matrix has the same up-vector problem.
TEST(Stability, CameraLookingStraightDownRendersFinite) {
    Scene scene;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "box", kBoxCenter, kBoxHalf);
    addCamera(scene, "camera", Camera{}, {0.0, 6.0, 0.0}, {0.0, 0.0, 0.0});
    addLight(scene, "sun", softLight(LightType::Directional), test::shadowWith(ShadowTechnique::Hard, 512), {0, 8, 0},
             {0.3, -1, 0.2});
    test::forEveryTechnique(scene, 96, 96, "camera straight down",
                            [&](ShadowTechnique, const test::RenderedFrame& frame, FrameRunner&) {
                                EXPECT_GT(darkGroundFraction(frame.images), 0.01);
                            });
}

/// A light standing exactly on a vertex of the ground (the plane mesh has one at the origin),
/// where the direction from the receiver to the light is 0/0.
TEST(Stability, LightStandingOnAReceiverPointStaysFinite) {
    struct Case {
        const char* name;
        LightType type;
        glm::dvec3 direction;
    };
    const Case cases[] = {
        {"spot on the ground aiming along it", LightType::Spot, {1, 0, 0}},
        {"spot on the ground aiming into it", LightType::Spot, {1, -0.3, 0.2}},
        {"spot on the ground aiming up", LightType::Spot, {0, 1, 0}},
        {"point on the ground", LightType::Point, {0, -1, 0}},
    };
    for (const Case& c : cases) {
        Scene scene = groundAndBox();
        addLight(scene, c.name, softLight(c.type), test::shadowWith(ShadowTechnique::Hard, 512), {0.0, 0.0, 0.0},
                 c.direction);
        test::forEveryTechnique(scene, 128, 96, c.name,
                                [&](ShadowTechnique, const test::RenderedFrame&, FrameRunner& runner) {
                                    ASSERT_EQ(runner.shadows().frame().lights.size(), 1u);
                                });
    }
}

/// Blocker at the light: the light sits on a corner of the box, and on the centre of its top
/// face shining down into it (every tap's blocker is at distance ~0, the PCSS penumbra
/// estimate (dR - dB) / dB diverges and must be clamped). Receiver on the blocker: a small
/// step standing on a table top, lit from above; the table top next to the step has its blocker
/// at its own depth.
TEST(Stability, BlockerAtTheLightAndReceiverOnTheBlocker) {
    const glm::dvec3 corner = kBoxCenter + kBoxHalf;
    const glm::dvec3 topCentre = kBoxCenter + glm::dvec3(0.0, kBoxHalf.y, 0.0);
    struct Case {
        const char* name;
        LightType type;
        glm::dvec3 position;
        glm::dvec3 direction;
    };
    const Case cases[] = {
        {"spot on the box corner", LightType::Spot, corner, {0.2, -1, 0.1}},
        {"point on the box corner", LightType::Point, corner, {0, -1, 0}},
        {"spot on the box top shining into it", LightType::Spot, topCentre, {0, -1, 0}},
    };
    for (const Case& c : cases) {
        Scene scene = groundAndBox();
        addLight(scene, c.name, softLight(c.type), test::shadowWith(ShadowTechnique::Hard, 512), c.position,
                 c.direction);
        test::forEveryTechnique(
            scene, 128, 96, c.name, [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
                test::reportFigure(std::string(c.name) + ", " + techniqueName(technique) + ": dark ground fraction",
                                   darkGroundFraction(frame.images));
            });
    }
    // The box fills the whole cone of a spot shining into it: the ground in the cone is dark.
    {
        Scene scene = groundAndBox();
        const glm::dvec3 dir(0, -1, 0);
        addLight(scene, "into the box", softLight(LightType::Spot), test::shadowWith(ShadowTechnique::Hard, 512),
                 topCentre, dir);
        test::forEveryTechnique(scene, 128, 96, "into the box",
                                [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
                                    const test::GroundCounts g = test::countGround(
                                        frame.images, 0,
                                        [&](const glm::dvec3& p) { return test::insideCone(p, topCentre, dir, 0.3); });
                                    ASSERT_GT(g.ground, 100);
                                    EXPECT_GT(g.darkFraction(), 0.999) << techniqueName(technique);
                                });
    }

    // Receiver on the blocker: the table top around a step, lit by a soft sun from above.
    Scene table;
    addMeshInstance(table.world, "table", makeBoxMesh({1.0f, 0.4f, 1.0f}), test::placed({0.0, 0.4, 0.0}));
    test::addBox(table, "step", {0.0, 0.9, 0.0}, {0.2, 0.1, 0.2});
    addCamera(table, "camera", Camera{}, {0.0, 3.0, 2.5}, {0.0, 0.8, 0.0});
    addLight(table, "sun", softLight(LightType::Directional), test::shadowWith(ShadowTechnique::Hard, 1024), {0, 8, 0},
             {0.15, -1, 0.1});
    test::forEveryTechnique(
        table, 160, 120, "step on a table",
        [&](ShadowTechnique technique, const test::RenderedFrame& frame, FrameRunner&) {
            // Table-top pixels (y = 0.8) farther than 0.15 m from the step's footprint: lit.
            int top = 0;
            int dark = 0;
            const FrameImages& im = frame.images;
            for (int y = 0; y < im.position.height; ++y) {
                for (int x = 0; x < im.position.width; ++x) {
                    if (im.position.at(x, y, 3) < 0.5f) continue;
                    const glm::dvec3 p = test::positionAt(im, x, y);
                    if (std::abs(p.y - 0.8) > 1e-3) continue;
                    if (std::abs(p.x) < 0.35 + 0.3 && std::abs(p.z) < 0.35 + 0.3) continue;  // the step's shadow side
                    ++top;
                    if (im.visibility[0].at(x, y, 0) < 0.5f) ++dark;
                }
            }
            ASSERT_GT(top, 1000);
            test::reportFigure(std::string("table top around the step, ") + techniqueName(technique) + ": false shadow",
                               static_cast<double>(dark) / top);
            EXPECT_LT(dark, top / 1000 + 1) << techniqueName(technique);
        });
}

}  // namespace
}  // namespace shadow::degenerate_pose_test
