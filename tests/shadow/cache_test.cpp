// Layer caching of the shadow system (engine/src/shadow/planner.cpp, shadow_system.cpp): a
// reused layer must give exactly the image a redrawn one gives, and a layer is redrawn only
// when something in its frustum changed.
#include <gtest/gtest.h>
#include <shadow/shadow_system.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadow/soft_test_support.h"

namespace shadow {
namespace {

constexpr int kFrames = 5;
constexpr double kDt = 0.1;

/// Number of values that differ bit for bit (-0 and +0 differ, NaN equals itself).
int bitDifferences(const ImageF& a, const ImageF& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels) return -1;
    int n = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0) ++n;
    }
    return n;
}

/// Three lights over three separate areas of a ground plane, each with a static box under it;
/// a bobbing box lies under the first spot light only.
struct ThreeAreas {
    Scene scene;
    Entity mover;
};

ThreeAreas makeThreeAreas() {
    ThreeAreas s;
    Scene& scene = s.scene;
    test::addGround(scene, 8.0f);
    Light spot = test::pointSizedLight(LightType::Spot, 0.5f);
    spot.range = 10.0f;
    Light bulb = test::pointSizedLight(LightType::Point);
    bulb.range = 3.0f;  // the bobbing box, 7 m away, is outside every face's frustum
    addLight(scene, "spot with mover", spot, test::shadowWith(ShadowTechnique::Pcf, 512), {-4, 4, 0}, {0, -1, 0});
    addLight(scene, "static spot", spot, test::shadowWith(ShadowTechnique::Pcss, 512), {4, 4, 0}, {0, -1, 0});
    addLight(scene, "static bulb", bulb, test::shadowWith(ShadowTechnique::Hard, 256), {0, 2, -5}, {0, -1, 0});
    test::addBox(scene, "box A", {-4, 0.5, -1}, glm::dvec3(0.4));
    test::addBox(scene, "box B", {4, 0.5, 0}, glm::dvec3(0.4));
    test::addBox(scene, "box C", {0, 0.5, -4}, glm::dvec3(0.4));
    s.mover = test::addBox(scene, "mover", {-4, 1.5, 1}, glm::dvec3(0.3));
    ProceduralMotion bob;
    bob.kind = ProceduralMotion::Kind::Bob;
    bob.center = {-4, 1.5, 1};
    bob.axis = {0, 1, 0};
    bob.amplitude = 0.5;
    bob.speed = 2.0;
    scene.world.emplace<ProceduralMotion>(s.mover, bob);
    addCamera(scene, "camera", Camera{}, {0, 12, 12}, {0, 0, 0});
    return s;
}

/// Renders `kFrames` frames (dt kDt) of two copies of a scene, one through a runner with
/// caching and one without, and expects the colour and every visibility AOV to be identical
/// bit for bit frame by frame. Returns the layers the cached run reused on frames 2+.
template <typename MakeScene>
int expectCachedEqualsUncached(const char* what, MakeScene makeScene) {
    Scene cachedScene = makeScene();
    Scene uncachedScene = makeScene();
    test::glContext();
    FrameRunner cached;
    FrameRunner uncached;
    uncached.shadows().planner().setCaching(false);
    int reused = 0;
    for (int f = 0; f < kFrames; ++f) {
        const double t = f * kDt;
        const test::RenderedFrame a = test::renderFrame(cached, cachedScene, 192, 108, t);
        const test::RenderedFrame b = test::renderFrame(uncached, uncachedScene, 192, 108, t);
        test::expectSaneAovs(a.images);
        if (f > 0) reused += a.stats.shadowLayersReused;
        EXPECT_EQ(b.stats.shadowLayersReused, 0) << what << " frame " << f << ": caching off still reused layers";
        EXPECT_EQ(bitDifferences(a.images.color, b.images.color), 0) << what << " frame " << f << ": colour differs";
        EXPECT_EQ(a.images.visibility.size(), cachedScene.lights.size());
        EXPECT_EQ(a.images.visibility.size(), b.images.visibility.size());
        for (std::size_t i = 0; i < std::min(a.images.visibility.size(), b.images.visibility.size()); ++i) {
            EXPECT_EQ(bitDifferences(a.images.visibility[i], b.images.visibility[i]), 0)
                << what << " frame " << f << ": visibility of light " << i << " differs";
        }
        std::printf(
            "[ measured ] %s frame %d: cached drew %d reused %d cleared %d; uncached drew %d "
            "cleared %d\n",
            what, f, a.stats.shadowLayersDrawn, a.stats.shadowLayersReused, a.stats.shadowLayersCleared,
            b.stats.shadowLayersDrawn, b.stats.shadowLayersCleared);
    }
    return reused;
}

TEST(Cache, CachedFramesAreBitIdenticalToUncached) {
    expectCachedEqualsUncached("default", [] {
        Result<Scene> scene = makeBuiltinScene("default");
        if (!scene) throw std::runtime_error(scene.error().message);
        return std::move(scene.value());
    });
    // The default scene's movers reach into nearly every layer, so few layers are reused
    // there; this scene reuses most of its layers, so the comparison is not vacuous.
    const int reused = expectCachedEqualsUncached("three areas", [] { return makeThreeAreas().scene; });
    EXPECT_GT(reused, 0) << "the cached run never reused a layer";
    // The same with every light on VSM, VSSM, then MSM-soft: their moments are rebuilt with the
    // layers they come from.
    for (ShadowTechnique t : {ShadowTechnique::Vsm, ShadowTechnique::Vssm, ShadowTechnique::MsmSoft}) {
        const std::string name = std::string("three areas, ") + techniqueName(t);
        const int reusedMoments = expectCachedEqualsUncached(name.c_str(), [t] {
            Scene scene = makeThreeAreas().scene;
            for (Entity light : scene.lights) scene.world.get<Shadow>(light).technique = t;
            return scene;
        });
        EXPECT_GT(reusedMoments, 0) << name << ": the cached run never reused a layer";
    }
}

TEST(Cache, OnlyTheLightSeeingTheMovingCasterRedraws) {
    ThreeAreas s = makeThreeAreas();
    test::glContext();
    FrameRunner runner;
    for (int f = 0; f < kFrames; ++f) {
        const test::RenderedFrame frame = test::renderFrame(runner, s.scene, 128, 96, f * kDt);
        ASSERT_EQ(frame.stats.lights.size(), 3u);
        const std::vector<LightShadowStats>& lights = frame.stats.lights;  // indexed by scene light
        std::printf("[ measured ] frame %d drawn/reused:", f);
        for (const LightShadowStats& l : lights)
            std::printf("  %s %d/%d", l.name.c_str(), l.layersDrawn, l.layersReused);
        std::printf("\n");
        if (f == 0) continue;
        EXPECT_EQ(lights[0].layersDrawn, 1) << "frame " << f << ": the spot seeing the mover did not redraw";
        for (std::size_t i = 1; i < 3; ++i) {
            const LightShadowStats& l = lights[i];
            EXPECT_EQ(l.layersDrawn, 0) << "frame " << f << ": static light " << l.name << " redrew";
            EXPECT_EQ(l.layersReused, l.layers) << "frame " << f << ": static light " << l.name;
        }
    }
}

/// The design rule "a layer that did not change is reused", over the animated default scene
/// with its camera and lights still: from frame 2 on, a layer whose caster set is the same as
/// last frame's and none of whose casters moved this frame must not be drawn (nor cleared).
TEST(Cache, LayerWhoseCastersDidNotMoveIsReused) {
    Result<Scene> made = makeBuiltinScene("default");
    ASSERT_TRUE(made);
    Scene& scene = made.value();
    test::glContext();
    FrameRunner runner;
    std::vector<std::vector<std::vector<Entity>>> lastCasters;  // [frame light][layer]
    for (int f = 0; f < kFrames; ++f) {
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 128, 72, f * kDt);
        const ShadowFrame& plan = runner.shadows().frame();
        std::vector<std::vector<std::vector<Entity>>> casters;
        int unchanged = 0;
        int unchangedRedrawn = 0;
        for (std::size_t i = 0; i < plan.lights.size(); ++i) {
            const ShadowLightPlan& light = plan.lights[i];
            casters.emplace_back();
            for (std::size_t k = 0; k < light.layers.size(); ++k) {
                const ShadowLayerPlan& layer = light.layers[k];
                casters.back().push_back(layer.casters);
                if (f == 0) continue;
                const bool sameSet =
                    i < lastCasters.size() && k < lastCasters[i].size() && lastCasters[i][k] == layer.casters;
                const bool anyMoved = std::any_of(layer.casters.begin(), layer.casters.end(), [&](Entity e) {
                    const WorldTransform* wt = scene.world.tryGet<WorldTransform>(e);
                    return wt == nullptr || wt->movedThisFrame;
                });
                if (!sameSet || anyMoved) continue;
                ++unchanged;
                if (layer.dirty) {
                    ++unchangedRedrawn;
                    ADD_FAILURE() << "frame " << f << ": " << light.name << " layer " << k << " ("
                                  << layer.casters.size() << " casters, none moved) was redrawn; near plane "
                                  << layer.depthNear << " m";
                }
            }
        }
        if (f > 0) {
            std::printf(
                "[ measured ] default frame %d: %d layers unchanged, %d of them redrawn (layers "
                "drawn %d, "
                "cleared %d, reused %d)\n",
                f, unchanged, unchangedRedrawn, frame.stats.shadowLayersDrawn, frame.stats.shadowLayersCleared,
                frame.stats.shadowLayersReused);
        }
        lastCasters = std::move(casters);
    }
}

/// Renders frames of a point light at (0, 2.5, 0) with `range` over a 10 m ground, a static
/// box in its +X face and a small box bobbing along `moverAxis` about `moverCentre`, inside face
/// `moverFace` only (shadow_receiver.glsl's sg_cubeFace order +X, -X, +Y, -Y, +Z, -Z), and expects
/// from frame 2 on that face alone to be redrawn.
void expectOnlyTheMoversFaceRedrawn(float range, const glm::dvec3& moverCentre, const glm::dvec3& moverAxis,
                                    std::size_t moverFace) {
    Scene scene;
    test::addGround(scene, 5.0f);
    Light bulb = test::pointSizedLight(LightType::Point);
    bulb.range = range;
    addLight(scene, "bulb", bulb, test::shadowWith(ShadowTechnique::Hard, 256), {0, 2.5, 0}, {0, -1, 0});
    test::addBox(scene, "static box", {2.5, 0.5, 0.3}, glm::dvec3(0.4));
    const Entity mover = test::addBox(scene, "mover", moverCentre, glm::dvec3(0.15));
    ProceduralMotion bob;
    bob.kind = ProceduralMotion::Kind::Bob;
    bob.center = moverCentre;
    bob.axis = moverAxis;
    bob.amplitude = 0.2;
    bob.speed = 2.0;
    scene.world.emplace<ProceduralMotion>(mover, bob);
    addCamera(scene, "camera", Camera{}, {0, 7, 9}, {0, 0, 0});

    test::glContext();
    FrameRunner runner;
    for (int f = 0; f < kFrames; ++f) {
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 128, 96, f * kDt);
        ASSERT_EQ(frame.stats.lights.size(), 1u);
        const LightShadowStats& l = frame.stats.lights[0];
        const ShadowLightPlan& plan = runner.shadows().frame().lights.at(0);
        const ShadowLayerPlan& staticFace = plan.layers.at(0);
        std::printf(
            "[ measured ] bulb (range %.0f) frame %d: drawn %d cleared %d reused %d; +X face near "
            "%.4f m, depth scale %.4f m\n",
            range, f, l.layersDrawn, l.layersCleared, l.layersReused, staticFace.depthNear, staticFace.depthScale);
        if (f == 0) continue;
        std::vector<std::size_t> redrawnWithoutMover;
        for (std::size_t k = 0; k < plan.layers.size(); ++k) {
            const auto& casters = plan.layers[k].casters;
            const bool holdsMover = std::find(casters.begin(), casters.end(), mover) != casters.end();
            EXPECT_EQ(holdsMover, k == moverFace) << "face " << k;
            if (plan.layers[k].dirty && !holdsMover) redrawnWithoutMover.push_back(k);
        }
        EXPECT_TRUE(redrawnWithoutMover.empty())
            << "frame " << f
            << ": faces without the mover were redrawn: " << testing::PrintToString(redrawnWithoutMover)
            << " (+X face near plane " << staticFace.depthNear << " m, depth scale " << staticFace.depthScale << " m)";
        EXPECT_EQ(l.layersDrawn, 1) << "frame " << f;
        EXPECT_EQ(l.layersReused, 5) << "frame " << f;
    }
}

/// The mover bobs straight below the light, nearer to it than anything else: the near plane
/// must not follow it in the other faces.
TEST(Cache, MovingCasterRedrawsOnlyTheCubeFaceHoldingIt) {
    expectOnlyTheMoversFaceRedrawn(6.0f, {0, 1.2, 0}, {0, 1, 0}, 3);
}

/// A light without a range reaches the whole scene, and the mover, beyond the ground's edge in
/// the +Z face and moving away from the light and back, sets the scene's farthest point: the
/// far plane must not follow it in the other faces either.
TEST(Cache, CasterMovingAtTheSceneEdgeRedrawsOnlyItsFace) {
    expectOnlyTheMoversFaceRedrawn(0.0f, {0, 2.5, 8.5}, {0, 0, 1}, 4);
}

// A game with a fixed-step simulation updates its transforms more often than it renders: a
// caster moved, then `updateTransforms` run once, twice or three times before the frame (whose
// own update then sees nothing move) must still redraw the layers holding it. Each layer's
// validity is the transform versions it was drawn from, not a per-update moved flag. Against a
// runner without caching, bit for bit; with no update between frames, the layers are reused.
TEST(Cache, ACasterMovedThenUpdatedSeveralTimesBeforeTheFrameIsRedrawn) {
    for (int updates : {0, 1, 2, 3}) {
        ThreeAreas cachedAreas = makeThreeAreas();
        ThreeAreas uncachedAreas = makeThreeAreas();
        for (ThreeAreas* s : {&cachedAreas, &uncachedAreas}) s->scene.world.remove<ProceduralMotion>(s->mover);
        test::glContext();
        FrameRunner cached;
        FrameRunner uncached;
        uncached.shadows().planner().setCaching(false);
        (void)test::renderFrame(cached, cachedAreas.scene, 128, 96);
        (void)test::renderFrame(uncached, uncachedAreas.scene, 128, 96);
        for (ThreeAreas* s : {&cachedAreas, &uncachedAreas}) {
            s->scene.world.get<Transform>(s->mover).translation = {-4.0, 1.0, -0.4};  // over box A
            for (int u = 0; u < updates; ++u) (void)updateTransforms(s->scene.world);
        }
        const test::RenderedFrame a = test::renderFrame(cached, cachedAreas.scene, 128, 96);
        const test::RenderedFrame b = test::renderFrame(uncached, uncachedAreas.scene, 128, 96);
        EXPECT_EQ(a.stats.lights.at(0).layersDrawn, 1) << updates << " updates: the moved caster's layer was reused";
        EXPECT_EQ(bitDifferences(a.images.visibility.at(0), b.images.visibility.at(0)), 0)
            << updates << " updates before the frame: a stale shadow";
        const test::RenderedFrame still = test::renderFrame(cached, cachedAreas.scene, 128, 96);
        EXPECT_EQ(still.stats.lights.at(0).layersDrawn, 0) << updates << " updates: nothing moved, yet it redrew";
    }
}

}  // namespace
}  // namespace shadow
