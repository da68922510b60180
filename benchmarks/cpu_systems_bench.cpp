// CPU cost of the per-frame systems on the default scene: animation, transforms, and the
// shadow system's decide phase (no GL). Google Benchmark; run build/bin/cpu_systems_bench.
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <benchmark/benchmark.h>

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

}  // namespace

BENCHMARK_MAIN();
