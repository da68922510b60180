// ShadowPlanner, the CPU "decide" phase of the shadow system (engine/src/shadow/planner.cpp):
// which layers are dirty from frame to frame (caching), the clamping of settings with its
// warnings, which lights get a plan at all, the memory budget in bytes, and a world it reads only. The layers' geometry is tested in
// planner_layers_cpu_test.cpp. No GL: these run in shadow_planner_tests.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <shadow/shadow_planner.h>

#include "shadow/map_memory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/light_records.h"
#include "shadow/planner_test_support.h"
#include "test_support.h"

namespace shadow {
namespace {

using test::at;
using test::contains;
using test::hard;
using test::lightOf;
using test::planOf;
using test::TestScene;

// ---- Caching ----

/// A point light beside box A and box B (near plane and range fixed so that moving a box
/// cannot change its matrices), a narrow spot over the middle that sees neither box, and a
/// directional light.
struct CachingScene : TestScene {
    CachingScene() {
        Light point = lightOf(LightType::Point);
        point.range = 20.0f;
        Shadow s = hard();
        s.nearPlane = 0.1f;
        addLight(scene, "bulb", point, s, {0, 3, 0}, {0, -1, 0});
        Light spot = lightOf(LightType::Spot);
        spot.outerConeAngle = 0.3f;
        spot.range = 20.0f;
        addLight(scene, "spot", spot, s, {0, 6, 0}, {0, -1, 0});
        addLight(scene, "sun", lightOf(LightType::Directional), hard(), {0, 10, 0}, {0.2, -1, 0.1});
    }

    void move(Entity e, const glm::dvec3& to) { scene.world.get<Transform>(e).translation = to; }
};

std::vector<bool> dirtyFlags(const ShadowFrame& frame) {
    std::vector<bool> out;
    for (const ShadowLightPlan& p : frame.lights) {
        for (const ShadowLayerPlan& l : p.layers) out.push_back(l.dirty);
    }
    return out;
}

TEST(Planner, EveryLayerIsDirtyOnTheFirstFrame) {
    CachingScene t;
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 3u);
    const std::vector<bool> dirty = dirtyFlags(frame);
    EXPECT_EQ(dirty.size(), 8u);
    EXPECT_TRUE(std::all_of(dirty.begin(), dirty.end(), [](bool d) { return d; }));
}

TEST(Planner, ReusesEveryLayerWhenNothingMoved) {
    CachingScene t;
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 3u);
    for (const ShadowLightPlan& p : frame.lights) {
        for (std::size_t k = 0; k < p.layers.size(); ++k) EXPECT_FALSE(p.layers[k].dirty) << p.name << " layer " << k;
    }
}

/// Moves `box` to `to` after a settled frame and checks that exactly the layers that held it
/// before or after are dirty.
void expectOnlyLayersOfMovedCasterDirty(CachingScene& t, Entity box, const glm::dvec3& to) {
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowFrame before = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    t.move(box, to);
    const ShadowFrame& after = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(before.lights.size(), after.lights.size());
    int expectedDirty = 0;
    int clean = 0;
    for (std::size_t i = 0; i < after.lights.size(); ++i) {
        const ShadowLightPlan& p = after.lights[i];
        ASSERT_EQ(p.layers.size(), before.lights[i].layers.size());
        for (std::size_t k = 0; k < p.layers.size(); ++k) {
            const bool holds = contains(before.lights[i].layers[k].casters, box) || contains(p.layers[k].casters, box);
            EXPECT_EQ(p.layers[k].dirty, holds) << p.name << " layer " << k;
            expectedDirty += holds ? 1 : 0;
            clean += holds ? 0 : 1;
        }
    }
    // Guards against a vacuous pass: something moved, and something must stay cached.
    EXPECT_GT(expectedDirty, 0);
    EXPECT_GT(clean, 0);
}

TEST(Planner, MovingOneCasterDirtiesOnlyTheLayersHoldingIt) {
    CachingScene t;
    // Box A stays in the bulb's +X face: that face and the sun's layer redraw; the bulb's other
    // faces and the spot, which never see box A, stay cached.
    expectOnlyLayersOfMovedCasterDirty(t, t.boxA, {3, 3, 0.3});
}

TEST(Planner, CasterCrossingCubeFacesDirtiesBothFaces) {
    CachingScene t;
    ShadowPlanner planner;
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    t.move(t.boxA, {0, 3, 3});  // from the +X face to the +Z face of the bulb
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowLightPlan* bulb = planOf(frame, "bulb");
    ASSERT_NE(bulb, nullptr);
    ASSERT_EQ(bulb->layers.size(), 6u);
    EXPECT_TRUE(bulb->layers[0].dirty) << "+X face lost box A";
    EXPECT_TRUE(bulb->layers[4].dirty) << "+Z face gained box A";
    EXPECT_FALSE(bulb->layers[1].dirty) << "-X face holds only box B and the ground";
    EXPECT_FALSE(bulb->layers[2].dirty) << "+Y face holds nothing";
    EXPECT_FALSE(bulb->layers[3].dirty) << "-Y face holds only the ground";
    EXPECT_FALSE(bulb->layers[5].dirty) << "-Z face never held box A";
    const ShadowLightPlan* spot = planOf(frame, "spot");
    ASSERT_NE(spot, nullptr);
    EXPECT_FALSE(spot->layers[0].dirty) << "the spot sees neither position of box A";
}

TEST(Planner, CachingOffMakesEveryLayerDirty) {
    CachingScene t;
    ShadowPlanner planner;
    planner.setCaching(false);
    (void)planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const std::vector<bool> dirty = dirtyFlags(frame);
    ASSERT_EQ(dirty.size(), 8u);
    EXPECT_TRUE(std::all_of(dirty.begin(), dirty.end(), [](bool d) { return d; }));
}

TEST(Planner, LayerWithoutCastersHasEmptyCasterList) {
    CachingScene t;
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    const ShadowLightPlan* bulb = planOf(frame, "bulb");
    ASSERT_NE(bulb, nullptr);
    ASSERT_EQ(bulb->layers.size(), 6u);
    EXPECT_TRUE(bulb->layers[2].casters.empty()) << "nothing lies above the bulb";
    EXPECT_TRUE(contains(bulb->layers[0].casters, t.boxA));
    EXPECT_FALSE(contains(bulb->layers[0].casters, t.boxB));
    EXPECT_TRUE(contains(bulb->layers[1].casters, t.boxB));
    EXPECT_FALSE(contains(bulb->layers[1].casters, t.boxA));
}

// ---- Settings and which lights get a plan ----

TEST(Planner, ClampShadowSettingsClampsAndNamesTheLightAndField) {
    const ShadowLimits limits{4096, 2048};
    {
        Shadow s;
        s.mapSize = 0;
        Light l;
        std::vector<Warning> warnings;
        clampShadowSettings(s, l, limits, "lamp", warnings);
        EXPECT_EQ(s.mapSize, 1);
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_EQ(warnings[0].code, WarningCode::SettingClamped);
        EXPECT_EQ(warnings[0].element, "lamp");
        // The line the CLI prints and stats.json lists: light, field, value and the clamp.
        EXPECT_EQ(warnings[0].message, "lamp: mapSize 0 clamped to 1");
    }
    {
        Shadow s;
        s.mapSize = 100000;
        s.constantBias = -2.0f;  // negative, and not kAutomatic
        s.pcfRadius = std::nanf("");
        s.sdfMinStep = kAutomatic;  // stays automatic, without a warning
        Light l;
        l.radius = -2.0f;
        std::vector<Warning> warnings;
        clampShadowSettings(s, l, limits, "lamp", warnings);
        // One warning per field, each about the lamp; the values show which fields.
        EXPECT_EQ(s.mapSize, 4096);
        EXPECT_EQ(s.constantBias, 0.0f);
        EXPECT_EQ(s.pcfRadius, 0.0f) << "NaN goes to the low end";
        EXPECT_EQ(l.radius, 0.0f);
        EXPECT_TRUE(isAutomatic(s.sdfMinStep));
        EXPECT_EQ(test::countWarnings(warnings, WarningCode::SettingClamped, "lamp"), 4) << test::describe(warnings);
        EXPECT_EQ(warnings.size(), 4u);
    }
    {
        Shadow s;  // the defaults are in range: nothing to say
        Light l;
        std::vector<Warning> warnings;
        clampShadowSettings(s, l, limits, "lamp", warnings);
        EXPECT_TRUE(warnings.empty());
    }
}

TEST(Planner, PrepareClampsMapSizeToTheLimitsAndWarns) {
    TestScene t;
    Shadow s = hard();
    s.mapSize = 8192;
    addLight(t.scene, "big lamp", lightOf(LightType::Spot), s, {0, 5, 0}, {0, -1, 0});
    ShadowPlanner planner;
    planner.setLimits({2048, 2048});
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    EXPECT_EQ(frame.lights[0].mapSize, 2048);
    EXPECT_EQ(frame.lights[0].settings.mapSize, 2048);
    EXPECT_EQ(test::countWarnings(frame.warnings, WarningCode::SettingClamped, "big lamp"), 1)
        << test::describe(frame.warnings);
}

TEST(Planner, LightsWithoutShadowOrWithTechniqueNoneGetNoPlan) {
    TestScene t;
    Shadow none = hard();
    none.technique = ShadowTechnique::None;
    addLight(t.scene, "unshadowed", lightOf(LightType::Point), none, {0, 4, 0}, {0, -1, 0});  // no Shadow component
    const Entity shadowed = addLight(t.scene, "shadowed", lightOf(LightType::Spot), hard(), {0, 5, 0}, {0, -1, 0});
    const Entity switchedOff =
        addLight(t.scene, "switched off", lightOf(LightType::Point), hard(), {1, 4, 0}, {0, -1, 0});
    t.scene.world.get<Shadow>(switchedOff).technique = ShadowTechnique::None;
    ASSERT_FALSE(t.scene.world.has<Shadow>(t.scene.lights[0]));

    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 3u) << "one entry per scene light";
    EXPECT_FALSE(frame.lights[0].hasMap());
    EXPECT_FALSE(frame.lights[2].hasMap());
    EXPECT_TRUE(frame.lights[1].hasMap());
    EXPECT_EQ(frame.lights[1].entity, shadowed);
    EXPECT_EQ(frame.lights[1].sceneIndex, 1);
    EXPECT_EQ(frame.lights[1].name, "shadowed");
    EXPECT_EQ(frame.techniquesInUse, (1u << static_cast<unsigned>(ShadowTechnique::None)) |
                                         (1u << static_cast<unsigned>(ShadowTechnique::Hard)));
}

TEST(Planner, SecondDepthModesWarnOnceAboutCastersNotKnownToBeClosed) {
    // The scene's ground plane is open, its boxes closed; a game's caster is closed only on its
    // word. A point light sees all of them.
    TestScene t;
    const Entity game = test::addGameCaster(t.scene, {0.0, 1.5, 2.0});
    Shadow s = hard();
    s.depthMode = DepthMode::Midpoint;
    const Entity bulb = addLight(t.scene, "bulb", lightOf(LightType::Point), s, {0, 3, 0}, {0, -1, 0});
    auto warningsOf = [&](DepthMode mode, bool groundCasts, bool gameClosed) {
        t.scene.world.get<Shadow>(bulb).depthMode = mode;
        t.scene.world.view<Mesh, Name>().each([&](Entity, Mesh& m, Name& n) {
            if (n.value == "ground") m.castShadows = groundCasts;
        });
        t.scene.world.get<ShadowCasterDraw>(game).closed = gameClosed;
        ShadowPlanner planner;
        return planner.prepare(t.scene.world, t.update(), t.scene.lights).warnings;
    };
    const std::vector<Warning> both = warningsOf(DepthMode::Midpoint, true, false);
    ASSERT_EQ(test::countWarnings(both, WarningCode::OpenCaster, "bulb"), 1) << test::describe(both);
    EXPECT_NE(both[0].message.find("2 are not"), std::string::npos) << both[0].message;
    EXPECT_NE(both[0].message.find("depth mode midpoint"), std::string::npos) << both[0].message;
    const std::vector<Warning> ground = warningsOf(DepthMode::Second, true, true);
    ASSERT_EQ(test::countWarnings(ground, WarningCode::OpenCaster, "bulb"), 1) << test::describe(ground);
    EXPECT_NE(ground[0].message.find("1 is not (\"ground\" first)"), std::string::npos) << ground[0].message;
    EXPECT_TRUE(warningsOf(DepthMode::Midpoint, false, true).empty());
    EXPECT_TRUE(warningsOf(DepthMode::Nearest, true, false).empty());
}

TEST(Planner, ADepthModeOutsideTheEnumIsReplacedByNearestAndReported) {
    TestScene t;
    Shadow s = hard();
    s.depthMode = static_cast<DepthMode>(7);
    addLight(t.scene, "lamp", lightOf(LightType::Spot), s, {0, 5, 0}, {0, -1, 0});
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    EXPECT_EQ(frame.lights.at(0).settings.depthMode, DepthMode::Nearest);
    EXPECT_EQ(test::countWarnings(frame.warnings, WarningCode::SettingClamped, "lamp"), 1)
        << test::describe(frame.warnings);
}

TEST(Planner, ReadsAConstWorldAndLeavesItAsItWas) {
    // The decide phase takes the world as const: what it remembers between frames (which layers
    // are dirty) is its own. A caster the game marked changed stays marked (the game resets it).
    CachingScene t;
    const Entity skinned = test::addGameCaster(t.scene, {2.0, 3.0, 0.0}, true);
    (void)t.update();
    const CameraView view = t.update();  // a settled frame: nothing moved since the last
    const World& world = t.scene.world;
    const std::vector<bool> moved = [&] {
        std::vector<bool> out;
        world.view<WorldTransform>().each([&](Entity, const WorldTransform& wt) { out.push_back(wt.movedThisFrame); });
        return out;
    }();
    ShadowPlanner planner;
    (void)planner.prepare(world, view, t.scene.lights);
    const ShadowFrame& second = planner.prepare(world, view, t.scene.lights);
    EXPECT_TRUE(world.get<ShadowCasterDraw>(skinned).changedThisFrame);
    std::vector<bool> after;
    world.view<WorldTransform>().each([&](Entity, const WorldTransform& wt) { after.push_back(wt.movedThisFrame); });
    EXPECT_EQ(after, moved);
    // Its layers are redrawn every frame while it says it changed; the others are reused.
    const ShadowLightPlan& bulb = second.lights[0];
    int holding = 0;
    for (const ShadowLayerPlan& layer : bulb.layers) {
        const bool holds = contains(layer.casters, skinned);
        holding += holds ? 1 : 0;
        EXPECT_EQ(layer.dirty, holds);
    }
    EXPECT_GT(holding, 0);
}

TEST(Planner, MemoryBudgetCountsEachTechniquesFilterChain) {
    // One spot asking for 16384^2 (the GL limit) under the default 1 GiB: a hard map (1 GiB of
    // depth) fits as asked; every technique that adds a filter chain is halved until depth and
    // chain fit, so that it renders instead of running out of memory.
    for (const ShadowTechnique technique : test::offered(
             {ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss, ShadowTechnique::PcssTextbook,
              ShadowTechnique::Vsm, ShadowTechnique::Vssm, ShadowTechnique::Msm, ShadowTechnique::MsmSoft})) {
        TestScene t;
        Shadow s = hard();
        s.technique = technique;
        s.mapSize = 16384;
        addLight(t.scene, "lamp", lightOf(LightType::Spot), s, {0, 5, 0}, {0, -1, 0});
        ShadowPlanner planner;
        const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
        const ShadowLightPlan& plan = frame.lights.at(0);
        const std::string name = techniqueName(technique);
        ASSERT_TRUE(plan.hasMap()) << name;
        const std::int64_t bytes = shadowMapBytes(technique, plan.mapSize, 1, plan.settings.maxFilterTexels);
        EXPECT_LE(bytes, ShadowLimits{}.maxShadowBytes) << name;
        // Halving once more would waste room: the budget keeps the largest map that fits.
        EXPECT_GT(shadowMapBytes(technique, plan.mapSize * 2, 1, plan.settings.maxFilterTexels),
                  ShadowLimits{}.maxShadowBytes)
            << name;
        const bool chain = filterChainOf(technique).has_value();
        EXPECT_EQ(plan.mapSize < 16384, chain) << name << ": " << plan.mapSize;
        EXPECT_EQ(test::countWarnings(frame.warnings, WarningCode::MapSizeReduced, "lamp"), chain ? 1 : 0)
            << name << ":\n"
            << test::describe(frame.warnings);
        std::printf("%s at 16384^2 under 1 GiB: %d^2, %.0f MiB\n", name.c_str(), plan.mapSize,
                    static_cast<double>(bytes) / (1 << 20));
    }
}

TEST(Planner, AZeroScaleSpotShinesAlongItsRotationInThePlanAndTheLightRecord) {
    // glTF scale 0 with a rotation (regression zero_scale_light_nodes.gltf): the world matrix is
    // singular, and the light used to point down -Z whatever its rotation.
    TestScene t;
    const glm::dquat rotation = glm::angleAxis(0.9, glm::normalize(glm::dvec3(1.0, 0.0, 0.5)));
    const Entity spot = addLight(t.scene, "spot", lightOf(LightType::Spot), hard(), {0, 4, 0}, {0, 0, -1});
    Transform& transform = t.scene.world.get<Transform>(spot);
    transform.rotation = rotation;
    transform.scale = glm::dvec3(0.0);
    ShadowPlanner planner;
    const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
    ASSERT_EQ(frame.lights.size(), 1u);
    const glm::dvec3 expected = rotation * glm::dvec3(0.0, 0.0, -1.0);
    EXPECT_NEAR(glm::length(frame.lights[0].wsDirection - expected), 0.0, 1e-12);
    std::vector<gpu::GpuShadowLayer> layers(SG_MAX_LAYERS_PER_LIGHT);
    const gpu::GpuLight record = packSlot(frame.lights[0], glm::dvec3(0.0), 0, layers.data());
    EXPECT_NEAR(glm::length(glm::dvec3(record.wsDirection) - expected), 0.0, 1e-6);
}

}  // namespace
}  // namespace shadow

namespace shadow {
namespace {

// ---- Whether a light reads its min/max pyramid ----

/// A sun and a spot over the test scene's boxes, PCF or PCSS, 1024^2 maps.
struct PyramidScene : TestScene {
    explicit PyramidScene(ShadowTechnique technique) {
        Shadow s = hard();
        s.technique = technique;
        s.mapSize = 1024;
        Light spot = lightOf(LightType::Spot);
        spot.range = 20.0f;
        addLight(scene, "spot", spot, s, {0, 6, 0}, {0, -1, 0});
        addLight(scene, "sun", lightOf(LightType::Directional), s, {0, 10, 0}, {0.2, -1, 0.1});
    }
    /// This frame's view with an image of `width` x `height` pixels (0: unknown).
    CameraView view(int width, int height) {
        CameraView v = update();
        v.pixelWidth = width;
        v.pixelHeight = height;
        return v;
    }
};

/// Whether the light named `name` reads its pyramid in `frame`; throws when there is no such light.
bool regionTestOf(const ShadowFrame& frame, const char* name) {
    const ShadowLightPlan* plan = planOf(frame, name);
    if (plan == nullptr) throw std::runtime_error(std::string("no light ") + name);
    return plan->regionTest;
}

/// A PCF or PCSS light reads its pyramid when its redrawn layers hold at most
/// `ShadowLimits::pyramidTexelsPerPixel` texels per pixel it reaches on screen, when the image's
/// size is unknown, and when no layer is redrawn; the other techniques never.
TEST(ShadowPlanner, APcfLightReadsItsPyramidWhereItPaysForItself) {
    PyramidScene pcf(ShadowTechnique::Pcf);
    ShadowPlanner planner;
    // 320x240: 76 800 pixels at most against 1024^2 texels a layer (13.7 texels a pixel or more).
    const ShadowFrame& small = planner.prepare(pcf.scene.world, pcf.view(320, 240), pcf.scene.lights);
    EXPECT_FALSE(regionTestOf(small, "spot"));
    EXPECT_FALSE(regionTestOf(small, "sun"));
    // Nothing moved: no layer redrawn, the pyramid (built now) costs nothing more.
    const ShadowFrame& still = planner.prepare(pcf.scene.world, pcf.view(320, 240), pcf.scene.lights);
    EXPECT_TRUE(std::none_of(still.lights.begin(), still.lights.end(),
                             [](const ShadowLightPlan& p) { return p.layers.empty() || p.layers[0].dirty; }));
    EXPECT_TRUE(regionTestOf(still, "spot"));
    // Redrawn every frame (caching off): at 4K the sun's 3 layers are under 6 texels a pixel.
    planner.setCaching(false);
    const ShadowFrame& large = planner.prepare(pcf.scene.world, pcf.view(3840, 2160), pcf.scene.lights);
    EXPECT_TRUE(regionTestOf(large, "sun"));
    const ShadowFrame& unknown = planner.prepare(pcf.scene.world, pcf.view(0, 0), pcf.scene.lights);
    EXPECT_TRUE(regionTestOf(unknown, "spot"));
    EXPECT_TRUE(regionTestOf(unknown, "sun"));
    ShadowLimits limits = planner.limits();
    limits.pyramidTexelsPerPixel = std::nanf("");
    planner.setLimits(limits);
    const ShadowFrame& never = planner.prepare(pcf.scene.world, pcf.view(3840, 2160), pcf.scene.lights);
    EXPECT_FALSE(regionTestOf(never, "sun")) << "NaN reads as 0: never for a redrawn layer";

    // PCSS by the same limit.
    PyramidScene pcss(ShadowTechnique::Pcss);
    ShadowPlanner pcssPlanner;
    const ShadowFrame& soft = pcssPlanner.prepare(pcss.scene.world, pcss.view(320, 240), pcss.scene.lights);
    EXPECT_FALSE(regionTestOf(soft, "spot"));
    EXPECT_FALSE(regionTestOf(soft, "sun"));
    const ShadowFrame& softStill = pcssPlanner.prepare(pcss.scene.world, pcss.view(320, 240), pcss.scene.lights);
    EXPECT_TRUE(regionTestOf(softStill, "sun")) << "no layer redrawn";
    pcssPlanner.setCaching(false);
    const ShadowFrame& softLarge = pcssPlanner.prepare(pcss.scene.world, pcss.view(3840, 2160), pcss.scene.lights);
    EXPECT_TRUE(regionTestOf(softLarge, "sun"));

    PyramidScene hardScene(ShadowTechnique::Hard);
    ShadowPlanner hardPlanner;
    const ShadowFrame& plain = hardPlanner.prepare(hardScene.scene.world, hardScene.view(0, 0), hardScene.scene.lights);
    EXPECT_FALSE(regionTestOf(plain, "spot")) << "hard shadows read no pyramid";
}

}  // namespace
}  // namespace shadow

namespace shadow {
namespace {

TEST(Planner, AVsmCascadeStartsItsChainAtTheLevelOfItsFilterRadius) {
    // A cascade's texel is one size throughout, so each of a VSM sun's cascades reads its chain
    // from the floor of log2(pcfRadius in its texels) (5 % of margin on the texel), at least 1
    // (its lookups take level 0 from the depth map) and at most the chain's top level; the same
    // light on MSM-soft starts at 1, on PCF at 0.
    for (const ShadowTechnique technique : {ShadowTechnique::Vsm, ShadowTechnique::MsmSoft, ShadowTechnique::Pcf}) {
        TestScene t;
        Shadow s = test::hard();
        s.technique = technique;
        s.mapSize = 1024;
        s.cascades = 3;
        s.pcfRadius = 0.2f;
        addLight(t.scene, "sun", test::lightOf(LightType::Directional), s, {0, 10, 0}, {0.2, -1, 0.1});
        ShadowPlanner planner;
        const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
        const ShadowLightPlan& plan = frame.lights.at(0);
        ASSERT_EQ(plan.layers.size(), 3u);
        const int levels = chainLevels(technique, plan.mapSize, plan.settings.maxFilterTexels);
        int widest = 0;
        for (const ShadowLayerPlan& layer : plan.layers) {
            const double texel = 2.0 / (layer.clipFromLight[0][0] * plan.mapSize);
            const double texels = std::min(0.2 / (1.05 * texel), static_cast<double>(plan.maxFilterTexels));
            int expected = technique == ShadowTechnique::MsmSoft ? 1 : 0;
            if (technique == ShadowTechnique::Vsm)
                expected = std::clamp(static_cast<int>(std::floor(std::log2(texels))), 1, levels - 1);
            std::printf("[ measured ] %s cascade: texel %.4f m, radius %.1f texels, first level %d\n",
                        techniqueName(technique), texel, 0.2 / texel, layer.chainFirstLevel);
            EXPECT_EQ(layer.chainFirstLevel, expected) << techniqueName(technique);
            // ... and ends at the level above: the trilinear fetch's two levels, the whole chain.
            // Other techniques keep the chain's top.
            const int last =
                technique == ShadowTechnique::Vsm
                    ? std::clamp(static_cast<int>(std::floor(std::log2(0.2 * 1.05 / texel))) + 1, expected, levels - 1)
                    : levels - 1;
            EXPECT_EQ(layer.chainLastLevel, last) << techniqueName(technique);
            widest = std::max(widest, layer.chainFirstLevel);
        }
        if (technique == ShadowTechnique::Vsm) {
            EXPECT_GE(widest, 2) << "no cascade skips a level: the test is vacuous";
        }
    }
}

TEST(Planner, AVsmSpotBoundsItsTexelByEverythingTheSceneHoldsNotOnlyItsReceivers) {
    // A spot's texel grows with the distance from the light: its chain's first level comes from
    // the farthest corner of the scene's known bounds. Receivers the engine does not know (a
    // game's own surfaces, its ShadowCasterDraw objects) may lie there, so meshes that do not
    // receive count too, and a scene of no known receiver keeps the same first level.
    const auto firstLevel = [](bool receivers) {
        TestScene t;
        t.scene.world.view<Mesh>().each([&](Entity, Mesh& m) { m.receiveShadows = receivers; });
        Shadow s = test::hard();
        s.technique = ShadowTechnique::Vsm;
        s.mapSize = 1024;
        s.pcfRadius = 0.5f;
        Light spot = test::lightOf(LightType::Spot);
        spot.range = 40.0f;
        addLight(t.scene, "spot", spot, s, {0, 6, 0}, {0, -1, 0});
        ShadowPlanner planner;
        const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
        const ShadowLayerPlan& layer = frame.lights.at(0).layers.at(0);
        // The ground's corner (5, 0, 5) is the farthest: sqrt(25 + 36 + 25) m from the light.
        const double texel = 2.0 / (layer.clipFromLight[0][0] * 1024.0) * std::sqrt(86.0);
        const int expected = static_cast<int>(std::floor(std::log2(0.5 / (1.05 * texel))));
        EXPECT_EQ(layer.chainFirstLevel, expected) << (receivers ? "receivers" : "no receivers");
        return layer.chainFirstLevel;
    };
    const int known = firstLevel(true);
    EXPECT_GE(known, 2) << "the test is vacuous: the chain starts at level 0 anyway";
    EXPECT_EQ(firstLevel(false), known);
}

TEST(Planner, AVsmSpotEndsItsChainAtTheLevelOfItsNearestPossibleReceiver) {
    // The highest level a spot's lookups read is the one above log2 of the radius in the
    // smallest texel a receiver can have: the axial distance of the nearest point of the scene's
    // bounds, at least its distance times the cosine of the frustum's corner. A light far above
    // the scene reads few levels; a light inside the scene's bounds (a receiver may stand at it)
    // every level up to the chain's top.
    const auto levelsOf = [](double height) {
        TestScene t;
        Shadow s = test::hard();
        s.technique = ShadowTechnique::Vsm;
        s.mapSize = 1024;
        s.pcfRadius = 0.05f;
        s.maxFilterTexels = 64.0f;
        Light spot = test::lightOf(LightType::Spot);
        spot.range = 100.0f;
        addLight(t.scene, "spot", spot, s, {0, height, 0}, {0, -1, 0});
        ShadowPlanner planner;
        const ShadowFrame& frame = planner.prepare(t.scene.world, t.update(), t.scene.lights);
        const ShadowLightPlan& plan = frame.lights.at(0);
        const ShadowLayerPlan& layer = plan.layers.at(0);
        const int levels = chainLevels(ShadowTechnique::Vsm, plan.mapSize, plan.settings.maxFilterTexels);
        // The scene's bounds reach up to their top; the light stands straight above it.
        double top = 0.0;
        for (const DAabb& box : t.casterBounds()) top = std::max(top, box.max.y);
        const double px = layer.clipFromLight[0][0], py = layer.clipFromLight[1][1];
        const double cornerCos = 1.0 / std::sqrt(1.0 + 1.0 / (px * px) + 1.0 / (py * py));
        const double texel = 2.0 / (px * 1024.0) * std::max(height - top, 0.0) * cornerCos / 1.05;
        const int expected = texel > 0.0
                                 ? std::clamp(static_cast<int>(std::floor(std::log2(std::max(0.05 / texel, 1.0)))) + 1,
                                              layer.chainFirstLevel, levels - 1)
                                 : levels - 1;
        std::printf("[ measured ] vsm spot %.0f m up: levels %d to %d of %d\n", height, layer.chainFirstLevel,
                    layer.chainLastLevel, levels);
        EXPECT_EQ(layer.chainLastLevel, expected) << height << " m up";
        return std::pair{layer.chainLastLevel, levels};
    };
    const auto [high, levels] = levelsOf(30.0);
    EXPECT_LT(high, levels - 1) << "a light far above the scene builds fewer levels: the test is vacuous";
    EXPECT_EQ(levelsOf(0.5).first, levels - 1) << "a light inside the scene's bounds";
}

}  // namespace
}  // namespace shadow
