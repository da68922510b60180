// Scenes and checks shared by the CPU tests of the shadow planner (planner_cpu_test.cpp,
// planner_layers_cpu_test.cpp) and of light_projection.cpp: they build a world, run the systems
// before `ShadowPlanner::prepare`, and read the plans. No GL.
#pragma once

#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <shadow/shadow_planner.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace shadow::test {

/// Relative slack of clip-space comparisons (double rounding of composed matrices).
inline constexpr double kClipEps = 1e-9;

/// A transform placing an entity at `position`, unrotated and unscaled.
inline Transform at(const glm::dvec3& position) {
    Transform t;
    t.translation = position;
    return t;
}

/// A ground plane, two boxes and a camera that sees them all.
struct TestScene {
    Scene scene;
    Entity camera;
    Entity boxA;  // at (3, 3, 0): beside a light at (0, 3, 0), in its +X cube face only
    Entity boxB;  // at (-3, 3, 0): in the -X cube face only

    TestScene() {
        addMeshInstance(scene.world, "ground", makePlaneMesh(5.0f, 2), at({0, 0, 0}));
        boxA = addMeshInstance(scene.world, "box A", makeBoxMesh(glm::vec3(0.4f)), at({3, 3, 0}));
        boxB = addMeshInstance(scene.world, "box B", makeBoxMesh(glm::vec3(0.4f)), at({-3, 3, 0}));
        camera = addCamera(scene, "camera", Camera{}, {0, 8, 12}, {0, 1, 0});
    }

    /// Runs the systems before `prepare` and returns this frame's camera view.
    CameraView update() {
        animate(scene.world, 0.0);
        (void)updateTransforms(scene.world);
        return makeCameraView(scene.world, camera, 16.0f / 9.0f);
    }

    /// World bounds of every shadow caster.
    std::vector<DAabb> casterBounds() {
        std::vector<DAabb> out;
        scene.world.view<Mesh, WorldBounds>().each([&](Entity, Mesh& m, WorldBounds& b) {
            if (m.castShadows) out.push_back(b.box);
        });
        return out;
    }
};

/// Hard shadows in a 512^2 map, everything else the defaults.
inline Shadow hard() {
    Shadow s;
    s.technique = ShadowTechnique::Hard;
    s.mapSize = 512;
    return s;
}

/// A light of `type` with the defaults, a spot's cone 0.6 rad.
inline Light lightOf(LightType type) {
    Light l;
    l.type = type;
    l.outerConeAngle = 0.6f;
    return l;
}

/// The upper 3x3 of `m` is a rotation: orthonormal rows, determinant +1, and all finite.
inline void expectRigid(const glm::dmat4& m, const std::string& what) {
    ASSERT_TRUE(isFinite(m)) << what;
    const glm::dmat3 r(m);
    const glm::dmat3 rrt = r * glm::transpose(r);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(rrt[i][j], i == j ? 1.0 : 0.0, 1e-12) << what;
    }
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-12) << what;
}

/// World point `p` in the clip space of `layer`.
inline glm::dvec4 clipOf(const ShadowLayerPlan& layer, const glm::dvec3& p) {
    return layer.clipFromLight * layer.lightFromWorld * glm::dvec4(p, 1.0);
}

/// Whether a clip-space point lies in front of the light and inside the layer's x and y bounds.
inline bool laterallyInside(const glm::dvec4& clip) {
    return clip.w > 0.0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
}

/// Cube face (+X,-X,+Y,-Y,+Z,-Z) of a direction, as the shader's cubeFace() chooses it.
inline int cubeFace(const glm::dvec3& d) {
    const glm::dvec3 a = glm::abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

/// The plan of the light called `name`, or null.
inline const ShadowLightPlan* planOf(const ShadowFrame& frame, const std::string& name) {
    for (const ShadowLightPlan& p : frame.lights) {
        if (p.name == name) return &p;
    }
    return nullptr;
}

/// Whether `e` is in `v`.
/// A game's own caster (`ShadowCasterDraw`: a 0.6 m cube's bounds, a made-up vertex array of 36
/// indices) at `position`; the planner never draws, so no GL object is needed.
inline Entity addGameCaster(Scene& scene, const glm::dvec3& position, bool changedThisFrame = false) {
    ShadowCasterDraw own;
    own.localBounds.extend(glm::vec3(-0.3f));
    own.localBounds.extend(glm::vec3(0.3f));
    own.vertexArray = GlVertexArray{7};
    own.indexCount = 36;
    own.changedThisFrame = changedThisFrame;
    const Entity e = scene.world.create();
    scene.world.emplace<Transform>(e, at(position));
    scene.world.emplace<ShadowCasterDraw>(e, own);
    return e;
}

inline bool contains(const std::vector<Entity>& v, Entity e) { return std::find(v.begin(), v.end(), e) != v.end(); }

}  // namespace shadow::test
