// Rendering a scene with several techniques and comparing light 0's visibility with the
// ray-traced truth over the pixels that light shades (the terminator and distance-field fallback
// tests).
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <gtest/gtest.h>
#include <shadow/metrics.h>
#include <shadow/reference.h>

#include <optional>
#include <vector>

#include "render/render_test_support.h"

namespace shadow::test {

/// Light 0's errors against the truth, and the frame's warnings.
struct AgainstTruth {
    VisibilityErrors errors;
    std::vector<Warning> warnings;
    float maxFilterTexels = 0.0f;  ///< light 0's widest filter as planned (LightShadowStats)
};

/// The ray-traced truth at the pixels of `images` (their world positions, seen by `camera`),
/// `samples` rays per pixel. A failure to trace fails the test and gives nothing.
inline std::optional<reference::ReferenceResult> truthAt(Scene& scene, const CameraView& camera,
                                                         const FrameImages& images, int samples) {
    reference::ReferenceOptions options;
    options.width = images.position.width;
    options.height = images.position.height;
    options.samples = samples;
    options.wsPositions = &images.position;
    Result<reference::ReferenceResult> truth = reference::traceVisibility(scene, camera, options);
    EXPECT_TRUE(static_cast<bool>(truth)) << (truth ? "" : truth.error().message);
    if (!truth) return std::nullopt;
    return std::move(*truth);
}

/// Light `light`'s errors in `images` against `truth`, over the truth's lit mask of that light. A
/// failure to compare fails the test and leaves the errors at their defaults.
inline VisibilityErrors lightErrors(const FrameImages& images, const reference::ReferenceResult& truth,
                                    std::size_t light) {
    const Result<VisibilityErrors> e =
        compareVisibility(images.visibility.at(light), truth.visibility.at(light), &truth.lit.at(light));
    EXPECT_TRUE(static_cast<bool>(e)) << (e ? "" : e.error().message);
    return e ? *e : VisibilityErrors{};
}

/// `lightErrors` of light 0.
inline VisibilityErrors light0Errors(const FrameImages& images, const reference::ReferenceResult& truth) {
    return lightErrors(images, truth, 0);
}

/// Light 0's shadow on the ground (`isGroundPixel`) of `images` against the traced truth (one
/// ray a pixel, at `images`' positions, a point-sized emitter's exact answer): shadowed pixels
/// (visibility < 0.5) of each, and the pixels where they disagree.
struct GroundAgreement {
    int shadowed = 0;           ///< by the engine
    int referenceShadowed = 0;  ///< by the truth
    int mismatches = 0;
};

inline GroundAgreement groundAgreement(Scene& scene, const CameraView& camera, const FrameImages& images) {
    GroundAgreement out;
    const std::optional<reference::ReferenceResult> truth = truthAt(scene, camera, images, 1);
    if (!truth) return out;
    for (int y = 0; y < images.position.height; ++y) {
        for (int x = 0; x < images.position.width; ++x) {
            if (!isGroundPixel(images, x, y)) continue;
            const bool engine = images.visibility.at(0).at(x, y, 0) < 0.5f;
            const bool traced = truth->visibility.at(0).at(x, y, 0) < 0.5f;
            out.shadowed += engine ? 1 : 0;
            out.referenceShadowed += traced ? 1 : 0;
            out.mismatches += engine != traced ? 1 : 0;
        }
    }
    return out;
}

/// Renders one frame of `scene` at `width` x `height` for each technique of `techniques` (every
/// shadowed light set to it) and traces the truth once, with `samples` rays per pixel, at the
/// first frame's pixel positions: a technique moves no surface, so one truth serves every frame.
/// Light 0's errors over the reference's lit mask, one per technique in order. A failure to
/// trace or compare fails the test and leaves the errors at their defaults.
inline std::vector<AgainstTruth> renderAgainstTruth(Scene& scene, int width, int height, int samples,
                                                    const std::vector<ShadowTechnique>& techniques) {
    glContext();
    std::vector<AgainstTruth> out;
    std::optional<reference::ReferenceResult> truth;
    for (const ShadowTechnique technique : techniques) {
        scene.world.view<Shadow>().each([&](Entity, Shadow& s) { s.technique = technique; });
        FrameRunner runner;
        const RenderedFrame frame = renderFrame(runner, scene, width, height);
        if (out.empty()) truth = truthAt(scene, runner.lastCamera(), frame.images, samples);
        AgainstTruth& a = out.emplace_back();
        a.warnings = frame.stats.warnings;
        if (!frame.stats.lights.empty()) a.maxFilterTexels = frame.stats.lights.front().maxFilterTexels;
        if (truth) a.errors = light0Errors(frame.images, *truth);
    }
    return out;
}

}  // namespace shadow::test
