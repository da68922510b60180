// What a viewer pays to show a finished frame, at 1280x720 on builtin:default: the CPU path
// (read the linear colour back, meter it with autoExposure, tone-map it with toneMapToSrgb8, what
// shadow_viewer did before) against the GPU one (Renderer::meterExposure, presentToTexture; what
// it does now), the same tone map (shadow/tone_map.h) either way. Google Benchmark, wall clock
// (FrameRunner turns pass timing on, whose wall-clock timer ends each GPU pass with glFinish);
// run build/bin/present_bench --benchmark_repetitions=5.
#include <shadow/context_osmesa.h>
#include <shadow/frame_runner.h>
#include <shadow/image_io.h>
#include <shadow/scene.h>

#include <benchmark/benchmark.h>

#include <memory>
#include <stdexcept>

namespace {

using namespace shadow;

/// One rendered frame of builtin:default at 1280x720, kept for every benchmark.
struct Frame {
    std::unique_ptr<GlContext> context;
    Scene scene;
    std::unique_ptr<FrameRunner> runner;
    FrameStats stats;

    Frame() {
        Result<std::unique_ptr<GlContext>> made = createOsMesaContext();
        if (!made) throw std::runtime_error(made.error().message);
        context = std::move(made.value());
        scene = std::move(makeBuiltinScene("default").value());
        runner = std::make_unique<FrameRunner>();
        RenderOptions options;
        options.width = 1280;
        options.height = 720;
        stats = runner->runFrame(scene, 1.0, scene.cameras.at(0), options);
    }
};

Frame& frame() {
    static Frame f;
    return f;
}

void cpuPresent(benchmark::State& state) {
    Frame& f = frame();
    for (auto _ : state) {
        const FrameImages images = f.runner->renderer().readback(f.runner->lastCamera(), f.stats);
        const float exposure = autoExposure(images.color);
        benchmark::DoNotOptimize(toneMapToSrgb8(images.color, exposure));
    }
}
BENCHMARK(cpuPresent)->Unit(benchmark::kMillisecond)->UseRealTime();

void gpuPresent(benchmark::State& state) {
    Frame& f = frame();
    Renderer& renderer = f.runner->renderer();
    for (auto _ : state) {
        const float exposure = exposureFromHistogram(renderer.meterExposure(f.stats));
        benchmark::DoNotOptimize(renderer.presentToTexture(exposure, f.stats));  // ends with glFinish
    }
}
BENCHMARK(gpuPresent)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
