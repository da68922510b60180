// FrameRunner: one frame of a scene in the documented order (docs/architecture.md, "The frame, as data
// flows"): animate, transforms, shadow prepare, shadow render, main pass.
#pragma once

#include <shadow/renderer.h>
#include <shadow/shadow_system.h>

#include <memory>

namespace shadow {

/// Everything a frame needs, in the documented order: animate, transforms, shadow prepare,
/// shadow render, main pass. A convenience for samples and games with no loop of their own.
/// Turns pass timing on (`ShadowSystem::setTiming`, `Renderer::setTiming`).
/// Requires a current OpenGL 4.5 context with `loadGl` done, from construction on.
class FrameRunner {
public:
    FrameRunner();
    ~FrameRunner();
    FrameRunner(const FrameRunner&) = delete;
    FrameRunner& operator=(const FrameRunner&) = delete;

    /// Runs one frame of `scene` at time `t` (s) through camera entity `camera`, measured into
    /// `stats`. `stats` is reset first and its storage reused: given the same `stats` every
    /// frame, a frame in steady state allocates nothing (one that reports warnings allocates
    /// their text). Bad input (settings out of range, non-finite transforms) never throws: it is
    /// clamped or skipped and reported in `FrameStats::warnings`; what the content does once per
    /// entity (`MorphTargetsDropped`) goes to `Scene::warnings`, the first frame it happens.
    /// Throws `GlError` only when the GL side fails (a shader that does not compile, an
    /// incomplete framebuffer: a broken build or driver).
    void runFrame(Scene& scene, double t, Entity camera, const RenderOptions& options, FrameStats& stats);
    /// `runFrame` into a new `FrameStats`: a convenience that allocates its lists every frame.
    FrameStats runFrame(Scene& scene, double t, Entity camera, const RenderOptions& options);

    [[nodiscard]] ShadowSystem& shadows();
    [[nodiscard]] Renderer& renderer();
    /// The camera view of the last frame.
    [[nodiscard]] const CameraView& lastCamera() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
