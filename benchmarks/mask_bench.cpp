// What the game-facing screen-space mask (ShadowSystem::renderMask) costs at each resolution
// (ShadowMaskRequest::resolution: Full, Half, Quarter), one light at a time, on
// builtin:bunny-spot-wide at 1280x720: its spot light with PCSS, PCF and sdf. The game's depth is
// the renderer's own frame's, written as window depth into an R32F texture. Google Benchmark,
// wall clock, each iteration one renderMask and a glFinish; run
// build/bin/mask_bench --benchmark_repetitions=3 (benchmarks/run_mask.sh writes the table). Each
// reduced-resolution case also reports `vsFull`: the mean difference of its mask from the
// full-resolution one over the covered pixels.
#include <shadow/context_osmesa.h>
#include <shadow/frame_runner.h>
#include <shadow/scene.h>
#include <shadow/shadow_mask.h>

#include "core/camera.h"
#include "gl/gl_api.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

using namespace shadow;

constexpr int kWidth = 1280;
constexpr int kHeight = 720;

/// A rendered frame of builtin:bunny-spot-wide, its depth as a game would hand it over, and a
/// target for the mask.
struct Frame {
    std::unique_ptr<GlContext> context;
    Scene scene;
    std::unique_ptr<FrameRunner> runner;
    RenderOptions options;
    ShadowTechnique technique = ShadowTechnique::Pcss;  ///< the light's, in the maps rendered last
    GLuint depth = 0, target = 0;
    std::vector<float> covered;  ///< 1 where the frame has geometry

    Frame() {
        Result<std::unique_ptr<GlContext>> made = createOsMesaContext();
        if (!made) throw std::runtime_error(made.error().message);
        context = std::move(made.value());
        scene = std::move(makeBuiltinScene("bunny-spot-wide").value());
        runner = std::make_unique<FrameRunner>();
        options.width = kWidth;
        options.height = kHeight;
        options.aovs = true;
        use(technique);
        FrameStats stats;
        const FrameImages images = runner->renderer().readback(runner->lastCamera(), stats);
        // Window depth of each pixel from its world position (rows bottom first, as GL's).
        const CameraView& camera = runner->lastCamera();
        const glm::dmat4 clipFromWorld = cameraClipFromView(camera) * camera.viewFromWorld;
        std::vector<float> window(static_cast<std::size_t>(kWidth) * kHeight, 1.0f);
        covered.assign(window.size(), 0.0f);
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                if (images.position.at(x, y, 3) < 0.5f) continue;
                const glm::dvec4 clip =
                    clipFromWorld * glm::dvec4(images.position.at(x, y, 0), images.position.at(x, y, 1),
                                               images.position.at(x, y, 2), 1.0);
                const std::size_t i = static_cast<std::size_t>(kHeight - 1 - y) * kWidth + static_cast<std::size_t>(x);
                window[i] = static_cast<float>(0.5 * clip.z / clip.w + 0.5);
                covered[i] = 1.0f;
            }
        }
        gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
        gl.TextureStorage2D(depth, 1, GL_R32F, kWidth, kHeight);
        gl.TextureSubImage2D(depth, 0, 0, 0, kWidth, kHeight, GL_RED, GL_FLOAT, window.data());
        gl.CreateTextures(GL_TEXTURE_2D, 1, &target);
        gl.TextureStorage2D(target, 1, GL_RGBA16F, kWidth, kHeight);
    }

    /// Renders a frame with the light's technique `t` (its maps).
    void use(ShadowTechnique t) {
        scene.world.view<Shadow>().each([t](Entity, Shadow& s) { s.technique = t; });
        (void)runner->runFrame(scene, 0.0, scene.cameras.at(0), options);
        technique = t;
    }

    ShadowMaskRequest request(MaskResolution resolution) const {
        ShadowMaskRequest r;
        r.depthTexture = GlTexture{depth};
        r.target = GlTexture{target};
        r.width = kWidth;
        r.height = kHeight;
        r.camera = runner->lastCamera();
        r.resolution = resolution;
        return r;
    }

    /// The mask's first channel, rows bottom first.
    std::vector<float> read() const {
        std::vector<glm::vec4> pixels(static_cast<std::size_t>(kWidth) * kHeight);
        gl.GetTextureSubImage(target, 0, 0, 0, 0, kWidth, kHeight, 1, GL_RGBA, GL_FLOAT,
                              static_cast<GLsizei>(pixels.size() * sizeof(glm::vec4)), pixels.data());
        std::vector<float> first(pixels.size());
        for (std::size_t i = 0; i < pixels.size(); ++i) first[i] = pixels[i].x;
        return first;
    }
};

Frame& frame(ShadowTechnique technique) {
    static Frame f;
    if (f.technique != technique) f.use(technique);
    return f;
}

void mask(benchmark::State& state) {
    const auto technique = static_cast<ShadowTechnique>(state.range(0));
    const auto resolution = static_cast<MaskResolution>(state.range(1));
    Frame& f = frame(technique);
    const std::array<int, 1> lights{0};
    FrameStats stats;
    // The full-resolution mask, for the difference; then one untimed run (programs built).
    f.runner->shadows().renderMask(lights, f.request(MaskResolution::Full), stats);
    const std::vector<float> full = f.read();
    f.runner->shadows().renderMask(lights, f.request(resolution), stats);
    gl.Finish();
    for (auto _ : state) {
        f.runner->shadows().renderMask(lights, f.request(resolution), stats);
        gl.Finish();
    }
    const std::vector<float> reduced = f.read();
    double sum = 0.0, pixels = 0.0;
    for (std::size_t i = 0; i < full.size(); ++i) {
        sum += f.covered[i] * std::abs(static_cast<double>(reduced[i]) - full[i]);
        pixels += f.covered[i];
    }
    state.counters["vsFull"] = sum / std::max(pixels, 1.0);
    state.SetLabel(std::string(techniqueName(technique)));
}
BENCHMARK(mask)
    ->ArgNames({"technique", "resolution"})
    ->ArgsProduct({{static_cast<int>(ShadowTechnique::Pcf), static_cast<int>(ShadowTechnique::Pcss),
                    static_cast<int>(ShadowTechnique::Sdf)},
                   {static_cast<int>(MaskResolution::Full), static_cast<int>(MaskResolution::Half),
                    static_cast<int>(MaskResolution::Quarter)}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
