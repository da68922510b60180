// FrameRunner: the frame in its documented order (docs/architecture.md, "The frame, as data flows").
#include <shadow/context.h>
#include <shadow/frame_runner.h>

#include <chrono>

namespace shadow {
namespace {
double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

struct FrameRunner::Impl {
    ShadowSystem shadows;
    Renderer renderer;
    CameraView camera;
    std::string rendererName = queryGlInfo().renderer;
};

FrameRunner::FrameRunner() : impl_(std::make_unique<Impl>()) {
    // The runner serves the samples, tests and benchmarks, which report pass timings.
    impl_->shadows.setTiming(true);
    impl_->renderer.setTiming(true);
}
FrameRunner::~FrameRunner() = default;

ShadowSystem& FrameRunner::shadows() { return impl_->shadows; }
Renderer& FrameRunner::renderer() { return impl_->renderer; }
const CameraView& FrameRunner::lastCamera() const { return impl_->camera; }

FrameStats FrameRunner::runFrame(Scene& scene, double t, Entity camera, const RenderOptions& options) {
    FrameStats stats;
    runFrame(scene, t, camera, options, stats);
    return stats;
}

void FrameRunner::runFrame(Scene& scene, double t, Entity camera, const RenderOptions& options, FrameStats& stats) {
    stats.reset();
    stats.renderer = impl_->rendererName;
    auto t0 = std::chrono::steady_clock::now();
    animate(scene.world, t);
    stats.cpuAnimateMs = msSince(t0);

    t0 = std::chrono::steady_clock::now();
    const TransformStats ts = updateTransforms(scene.world);
    stats.cpuTransformsMs = msSince(t0);
    stats.entitiesSkippedNonFinite = ts.nonFinite;
    reportSkippedTransforms(scene.world, ts, stats.warnings);
    // Once per entity, so into the scene's standing list rather than this frame's.
    reportTruncatedMorphs(scene.world, scene.warnings);

    const float aspect = static_cast<float>(options.width) / static_cast<float>(std::max(options.height, 1));
    impl_->camera = makeCameraView(scene.world, camera, aspect);
    impl_->camera.pixelWidth = options.width;
    impl_->camera.pixelHeight = options.height;

    t0 = std::chrono::steady_clock::now();
    impl_->shadows.planner().setSceneTime(t);
    impl_->shadows.prepare(scene.world, impl_->camera, scene.lights);
    stats.cpuShadowPrepareMs = msSince(t0);

    t0 = std::chrono::steady_clock::now();
    impl_->shadows.render(scene.world, impl_->renderer.meshes(), stats);
    impl_->renderer.render(scene.world, impl_->camera, impl_->shadows, options, stats);
    stats.cpuRenderSubmitMs = msSince(t0);
    impl_->shadows.planner().observe(stats);  // technique auto's cost model, from this frame's passes
}

}  // namespace shadow
