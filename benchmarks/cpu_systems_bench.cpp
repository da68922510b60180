// CPU cost of the per-frame systems on the default scene: animation, transforms, and the
// shadow system's decide phase (no GL); and the decide phase of a game-sized scene, 1, 64 and
// 256 shadowed lights over 10 000 instances, when nothing moved and when 1 % of the instances
// move each frame, with the heap allocations it makes per frame in steady state. Google
// Benchmark; run build/bin/cpu_systems_bench.
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>
#include <cmath>
#include <new>
#include <string>
#include <vector>

namespace {
std::atomic<long long> gAllocations{0};
}  // namespace

// Every allocation of the process, counted (the decide phase's are read around its call). The
// replacements pair malloc with free, which GCC cannot tell from a mismatch once it sees both.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
    gAllocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace {

using namespace shadow;

Scene defaultScene() {
    Result<Scene> s = makeBuiltinScene("default");
    if (!s) std::abort();
    return std::move(s).value();
}

void BM_AnimateAndTransforms(benchmark::State& state) {
    Scene scene = defaultScene();
    double t = 0.0;
    for (auto _ : state) {
        animate(scene.world, t);
        benchmark::DoNotOptimize(updateTransforms(scene.world));
        t += 1.0 / 60.0;
    }
}
BENCHMARK(BM_AnimateAndTransforms);

void BM_ShadowPrepare(benchmark::State& state) {
    Scene scene = defaultScene();
    ShadowPlanner planner;
    double t = 0.0;
    for (auto _ : state) {
        state.PauseTiming();
        animate(scene.world, t);
        (void)updateTransforms(scene.world);
        const CameraView view = makeCameraView(scene.world, scene.cameras.front(), 16.0f / 9.0f);
        state.ResumeTiming();
        benchmark::DoNotOptimize(planner.prepare(scene.world, view, scene.lights).lights.size());
        t += 1.0 / 60.0;
    }
}
BENCHMARK(BM_ShadowPrepare);

/// `instances` boxes on a square grid 2 m apart over a ground, and `lights` lights 3 m above
/// them (spot, point and, one in eight, a directional light, in turn; hard shadows, 512^2 maps),
/// a camera above one corner looking across: what a game's level streams in.
struct GameSizedScene {
    Scene scene;
    std::vector<Entity> boxes;
};

GameSizedScene gameSizedScene(int lights, int instances) {
    GameSizedScene game;
    Scene& scene = game.scene;
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(instances))));
    addMeshInstance(scene.world, "ground", makePlaneMesh(static_cast<float>(side)), Transform{});
    const auto box = makeBoxMesh(glm::vec3(0.3f));
    for (int i = 0; i < instances; ++i) {
        Transform t;
        t.translation = {2.0 * (i % side) - side, 0.3, 2.0 * (i / side) - side};
        game.boxes.push_back(addMeshInstance(scene.world, "box " + std::to_string(i), box, t));
    }
    for (int i = 0; i < lights; ++i) {
        Light light;
        light.type = i % 8 == 7 ? LightType::Directional : (i % 2 == 0 ? LightType::Spot : LightType::Point);
        light.range = 6.0f;
        light.outerConeAngle = 0.8f;
        light.innerConeAngle = 0.6f;
        Shadow shadow;
        shadow.mapSize = 512;
        const int cell = (i * 7919) % (side * side);  // spread over the grid
        const glm::dvec3 at{2.0 * (cell % side) - side, 3.0, 2.0 * (cell / side) - side};
        addLight(scene, "light " + std::to_string(i), light, shadow, at, glm::normalize(glm::dvec3(0.2, -1.0, 0.1)));
    }
    addCamera(scene, "camera", Camera{}, {-side, 12.0, -side}, {0.0, 0.0, 0.0});
    return game;
}

/// Moves `count` of the game-sized scene's boxes `step` m along x, a different `count` each
/// `frame` spread over the grid, back again when their turn comes round the next time.
void moveSomeBoxes(GameSizedScene& game, std::size_t count, double step, std::size_t frame) {
    if (count == 0) return;
    const std::size_t stride = game.boxes.size() / count;
    const std::size_t turn = frame % stride;
    const double dx = (frame / stride) % 2 == 0 ? step : -step;
    for (std::size_t k = 0; k < count; ++k) {
        game.scene.world.get<Transform>(game.boxes[k * stride + turn]).translation.x += dx;
    }
}

// The decide phase of a game-sized scene, with the allocations it made: range(2) per mille of
// the boxes move range(3) cm each frame (0: the common frame of a game, in which nothing moved
// and the maps are kept; 5 cm, a step that seldom crosses a layer's edge; 250 cm, more than a
// box's spacing, so that boxes enter and leave the lights' layers every frame). The transform
// system runs between frames, outside the timing.
void BM_ShadowPrepareGameSized(benchmark::State& state) {
    GameSizedScene game = gameSizedScene(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
    Scene& scene = game.scene;
    const auto moving = static_cast<std::size_t>(state.range(2)) * game.boxes.size() / 1000;
    const double step = 0.01 * static_cast<double>(state.range(3));
    (void)updateTransforms(scene.world);
    (void)updateTransforms(scene.world);  // settled: nothing moved since the last frame
    const CameraView view = makeCameraView(scene.world, scene.cameras.front(), 16.0f / 9.0f);
    ShadowPlanner planner;
    std::size_t frame = 0;
    const auto nextFrame = [&] {
        moveSomeBoxes(game, moving, step, frame++);
        (void)updateTransforms(scene.world);
    };
    for (int warm = 0; warm < 3; ++warm) {
        nextFrame();
        (void)planner.prepare(scene.world, view, scene.lights);
    }
    long long allocations = 0;
    for (auto _ : state) {
        state.PauseTiming();
        nextFrame();
        state.ResumeTiming();
        const long long before = gAllocations.load(std::memory_order_relaxed);
        benchmark::DoNotOptimize(planner.prepare(scene.world, view, scene.lights).lights.size());
        allocations += gAllocations.load(std::memory_order_relaxed) - before;
    }
    state.counters["allocations/frame"] =
        benchmark::Counter(static_cast<double>(allocations) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_ShadowPrepareGameSized)
    ->ArgNames({"lights", "instances", "moving_permille", "step_cm"})
    ->Args({1, 10000, 0, 0})
    ->Args({64, 10000, 0, 0})
    ->Args({256, 10000, 0, 0})
    ->Args({1, 10000, 10, 5})
    ->Args({64, 10000, 10, 5})
    ->Args({256, 10000, 10, 5})
    ->Args({64, 10000, 10, 250})
    ->Args({256, 10000, 10, 250})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
