// Nothing allocates per frame in steady state (docs/architecture.md, "Leave out what a scene does not
// need"): FrameRunner::runFrame (engine/src/render/frame_runner.cpp) and all it calls, frame
// after frame of an animated scene whose casters move, with one FrameStats reused. The binary's
// operator new counts (tests/allocation_counter.h). On a failure the call stacks of the first
// allocations are on stderr; SHADOW_ALLOC_TRACE=N prints the first N instead of 3.
#include "allocation_counter.h"
#include "render/render_test_support.h"

#include <cstdio>
#include <cstdlib>

namespace shadow {
namespace {

constexpr int kWarmupFrames = 3;    // programs, maps, pyramids and lists grow to their size
constexpr int kCountedFrames = 5;   // the casters move between any two of them
constexpr double kFrameStep = 0.1;  // s

/// How many of the allocations counted get their call stack printed.
int tracedAllocations() {
    const char* n = std::getenv("SHADOW_ALLOC_TRACE");
    return n != nullptr ? std::atoi(n) : 3;
}

/// Allocations during `kCountedFrames` frames of `scene` after `kWarmupFrames`, time advancing.
long allocationsInSteadyState(Scene& scene, const RenderOptions& options, const char* what) {
    test::glContext();
    FrameRunner runner;
    FrameStats stats;
    const Entity camera = scene.cameras.at(0);
    int frame = 0;
    for (; frame < kWarmupFrames; ++frame) runner.runFrame(scene, frame * kFrameStep, camera, options, stats);
    long allocations = 0;
    {
        const test::AllocationCounter counter(tracedAllocations());
        for (; frame < kWarmupFrames + kCountedFrames; ++frame) {
            runner.runFrame(scene, frame * kFrameStep, camera, options, stats);
        }
        allocations = counter.count();
    }
    std::printf("%s: %ld allocations in %d frames after %d of warm-up (last: %d main passes, %d shadow layers drawn)\n",
                what, allocations, kCountedFrames, kWarmupFrames, stats.mainPasses, stats.shadowLayersDrawn);
    // The counted frames did work worth counting: moving casters were redrawn into their layers.
    EXPECT_GT(stats.shadowLayersDrawn, 0);
    return allocations;
}

/// The built-in scene `spec` names (`builtin:NAME`).
Scene loadBuiltin(const std::string& spec) {
    Result<Scene> scene = loadScene(spec);
    if (!scene) throw std::runtime_error(scene.error().message);
    return std::move(scene).value();
}

/// The entity named `name` (null if none).
Entity entityNamed(World& world, const std::string& name) {
    Entity found;
    world.view<Name>().each([&](Entity e, Name& n) {
        if (n.value == name) found = e;
    });
    return found;
}

/// Checks first that this binary's operator new is the counting one. It is under the sanitizer
/// build too (GCC's AddressSanitizer: the executable's definitions win over the runtime's, and
/// the memory is still checked, through malloc), so nothing is skipped there.
class FrameRunnerAllocations : public ::testing::Test {
protected:
    void SetUp() override { ASSERT_TRUE(test::allocationCountingWorks()) << "operator new does not count"; }
};

// builtin:default as shadow_render renders it by default: a PCSS sun with three cascades, a
// PCF spot and a hard point light, with AOVs.
TEST_F(FrameRunnerAllocations, DefaultSceneAllocatesNothingPerFrame) {
    Scene scene = loadBuiltin("builtin:default");
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.aovs = true;
    EXPECT_EQ(allocationsInSteadyState(scene, options, "builtin:default"), 0)
        << "see stderr for where the first ones come from";
}

// Other techniques in use, other passes: every light PCSS (the point light's six faces each with
// a min/max pyramid), a depth pre-pass, no AOVs.
TEST_F(FrameRunnerAllocations, PcssPointLightAndPrepassAllocateNothingPerFrame) {
    Scene scene = loadBuiltin("builtin:default");
    scene.world.view<Shadow>().each([](Entity, Shadow& s) { s.technique = ShadowTechnique::Pcss; });
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.depthPrepass = true;
    EXPECT_EQ(allocationsInSteadyState(scene, options, "builtin:default, every light PCSS"), 0)
        << "see stderr for where the first ones come from";
}

// Many lights, many passes: 64 small lights, each with its own map (a spot's layer, a point
// light's six), packed into 65 main passes, each scissored to its lights' reach (no AOVs); a
// box bobbing under the first light is redrawn into its map every frame.
TEST_F(FrameRunnerAllocations, ManyLightsAllocateNothingPerFrame) {
    Scene scene = loadBuiltin("builtin:many-lights");
    const Entity box = entityNamed(scene.world, "box 0");
    ASSERT_FALSE(box.isNull());
    ProceduralMotion bob;
    bob.kind = ProceduralMotion::Kind::Bob;
    bob.center = scene.world.get<Transform>(box).translation;
    bob.axis = {0.0, 1.0, 0.0};
    bob.amplitude = 0.3;
    bob.speed = 2.0;
    scene.world.emplace<ProceduralMotion>(box, bob);
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    EXPECT_EQ(allocationsInSteadyState(scene, options, "builtin:many-lights"), 0)
        << "see stderr for where the first ones come from";
}

}  // namespace
}  // namespace shadow
