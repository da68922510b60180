// Rendering a scene once and comparing light 0's visibility with the ray-traced truth over the
// pixels that light shades (the terminator and distance-field fallback tests).
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <gtest/gtest.h>
#include <shadow/metrics.h>
#include <shadow/reference.h>

#include <vector>

#include "render/render_test_support.h"

namespace shadow::test {

/// Light 0's errors against the truth, and the frame's warnings.
struct AgainstTruth {
    VisibilityErrors errors;
    std::vector<Warning> warnings;
};

/// Renders one frame of `scene` at `width` x `height` and traces the truth at the same pixels'
/// positions with `samples` rays per pixel; light 0's errors over the reference's lit mask.
/// A failure to trace or compare fails the test and leaves the errors at their defaults.
inline AgainstTruth renderAgainstTruth(Scene& scene, int width, int height, int samples) {
    glContext();
    FrameRunner runner;
    const RenderedFrame frame = renderFrame(runner, scene, width, height);
    reference::ReferenceOptions options;
    options.width = width;
    options.height = height;
    options.samples = samples;
    options.wsPositions = &frame.images.position;
    const Result<reference::ReferenceResult> truth = reference::traceVisibility(scene, runner.lastCamera(), options);
    EXPECT_TRUE(static_cast<bool>(truth)) << (truth ? "" : truth.error().message);
    AgainstTruth out;
    out.warnings = frame.stats.warnings;
    if (!truth) return out;
    const Result<VisibilityErrors> e =
        compareVisibility(frame.images.visibility.at(0), truth->visibility.at(0), &truth->lit.at(0));
    EXPECT_TRUE(static_cast<bool>(e)) << (e ? "" : e.error().message);
    if (e) out.errors = *e;
    return out;
}

}  // namespace shadow::test
