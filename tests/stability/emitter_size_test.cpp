// Emitter size extremes for the soft techniques: radius 0 (PCSS must degenerate to the hard
// shadow exactly), 1e-6 m (a hard shadow, give or take the edge texels), and emitters larger
// than the blocker's distance to the light (the similar-triangles penumbra (dR - dB) w / dB
// exceeds any map: the filter radius must be clamped to maxFilterTexels texels).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "stability/stability_test_support.h"
#include "test_support.h"

namespace shadow::emitter_size_test {
namespace {

const glm::dvec3 kBoxCenter{0.0, 1.2, 0.0};
const glm::dvec3 kBoxHalf{0.5, 0.3, 0.4};
const glm::dvec3 kSpotPosition{0.3, 4.0, 0.2};
constexpr int kMapSize = 512;

Scene spotOverBox(float radius, ShadowTechnique technique) {
    Scene scene;
    test::addGround(scene, 3.0f);
    test::addBox(scene, "box", kBoxCenter, kBoxHalf);
    addCamera(scene, "camera", Camera{}, {0.5, 5.0, 4.5}, {0.0, 0.0, 0.0});
    Light spot = test::pointSizedLight(LightType::Spot, 0.7f);
    spot.radius = radius;
    addLight(scene, "spot", spot, test::shadowWith(technique, kMapSize), kSpotPosition, {0, -1, 0});
    return scene;
}

/// Renders `scene` through `runner` with AOVs and, when `debug` is set, the debug view in the
/// colour image.
test::RenderedFrame render(FrameRunner& runner, Scene& scene, DebugView debug = DebugView::None) {
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.aovs = true;
    options.debugView = debug;
    test::RenderedFrame frame;
    frame.stats = runner.runFrame(scene, 0.0, scene.cameras.at(0), options);
    frame.images = runner.renderer().readback(runner.lastCamera(), frame.stats);
    test::expectSaneFrame(frame.images, runner.shadows(), "emitter");
    return frame;
}

test::RenderedFrame render(Scene& scene) {
    test::glContext();
    FrameRunner runner;
    return render(runner, scene);
}

/// Pixels whose hard/soft answers (visibility > 0.5) differ.
int binaryMismatches(const ImageF& a, const ImageF& b) {
    int n = 0;
    for (std::size_t p = 0; p < a.pixels.size(); ++p) n += (a.pixels[p] > 0.5f) != (b.pixels[p] > 0.5f) ? 1 : 0;
    return n;
}

/// The hard shadow with the textbook PCSS's classic bias (shadow_receiver.glsl): a one-texel
/// normal offset and the whole slope bias, where the other techniques keep a fifth of it.
Scene hardWithClassicBias() {
    Scene scene = spotOverBox(0.0f, ShadowTechnique::Hard);
    scene.world.view<Shadow>().each([](Entity, Shadow& s) {
        s.normalOffset = 1.0f;
        s.slopeBias *= 5.0f;
    });
    return scene;
}

TEST(Stability, PcssWithAZeroEmitterIsTheHardShadow) {
    Scene hard = spotOverBox(0.0f, ShadowTechnique::Hard);
    const test::RenderedFrame ownHard = render(hard);
    Scene classic = hardWithClassicBias();
    const test::RenderedFrame classicHard = render(classic);
    for (ShadowTechnique technique : test::offered({ShadowTechnique::Pcss, ShadowTechnique::PcssTextbook})) {
        const test::RenderedFrame& reference = technique == ShadowTechnique::Pcss ? ownHard : classicHard;
        Scene zero = spotOverBox(0.0f, technique);
        const test::RenderedFrame frame = render(zero);
        const ImageF& a = reference.images.visibility[0];
        const ImageF& b = frame.images.visibility[0];
        float worst = 0.0f;
        for (std::size_t p = 0; p < a.pixels.size(); ++p) worst = std::max(worst, std::abs(a.pixels[p] - b.pixels[p]));
        test::reportFigure(std::string(techniqueName(technique)) + ", radius 0: largest |V - V_hard|", worst);
        if (technique == ShadowTechnique::Pcss) {
            EXPECT_EQ(worst, 0.0f) << "PCSS with no emitter is not the hard shadow";
        }

        // 1e-6 m: a penumbra of ~1e-6 m, far below a texel: the hard shadow but for edge pixels.
        Scene tiny = spotOverBox(1e-6f, technique);
        const test::RenderedFrame small = render(tiny);
        const int mismatches = binaryMismatches(a, small.images.visibility[0]);
        const test::GroundCounts shadowed = test::countGround(reference.images, 0);
        test::reportFigure(std::string(techniqueName(technique)) + ", radius 1e-6 m: pixels differing from hard",
                           mismatches);
        EXPECT_GT(shadowed.dark, 500);
        // The textbook filters around its receiver's UV with one reference depth (the classic
        // bias), where the hard reference compares each texel with its receiver plane: their
        // edges part by up to a texel (measured 50 of 562 dark pixels; 0 for our PCSS).
        const int allowed = technique == ShadowTechnique::Pcss ? shadowed.dark / 20 : shadowed.dark / 8;
        EXPECT_LT(mismatches, allowed) << techniqueName(technique) << ": a 1 um emitter is not hard";
    }
}

TEST(Stability, HugeEmitterKeepsTheFilterRadiusClamped) {
    // 100 m and the clamp's limit 1000 m: far larger than the blocker's 2.5 m from the light.
    for (float radius : {100.0f, 1000.0f}) {
        for (ShadowTechnique technique : test::offered({ShadowTechnique::Pcss, ShadowTechnique::PcssTextbook})) {
            Scene scene = spotOverBox(radius, technique);
            test::glContext();
            FrameRunner runner;
            const test::RenderedFrame vis = render(runner, scene);
            const test::RenderedFrame penumbra = render(runner, scene, DebugView::Penumbra);
            // The clamp: the light's maxFilterTexels (automatic: the widest it can cast, here 256) texels
            // of the receiver's footprint, 2 / (P[0][0] mapSize)
            // per metre of axial distance.
            const ShadowLayerPlan& layer = runner.shadows().frame().lights.at(0).layers.at(0);
            const double perMetre = 2.0 / (layer.clipFromLight[0][0] * kMapSize);
            double worstRatio = 0.0;
            int receivers = 0;
            const FrameImages& im = penumbra.images;
            for (int y = 0; y < im.position.height; ++y) {
                for (int x = 0; x < im.position.width; ++x) {
                    if (im.position.at(x, y, 3) < 0.5f) continue;
                    const glm::dvec3 p = test::positionAt(im, x, y);
                    const double axial = -(layer.lightFromWorld * glm::dvec4(p, 1.0)).z;
                    if (axial <= 0.0) continue;
                    const double clamp = runner.shadows().frame().lights.at(0).maxFilterTexels * perMetre * axial;
                    worstRatio = std::max(worstRatio, im.color.at(x, y, 0) / clamp);
                    ++receivers;
                }
            }
            const std::string name =
                std::string(techniqueName(technique)) + ", radius " + std::to_string(static_cast<int>(radius)) + " m";
            test::reportFigure(name + ": largest penumbra / clamp", worstRatio);
            test::reportFigure(name + ": dark ground fraction", test::countGround(vis.images, 0).darkFraction());
            EXPECT_GT(receivers, 1000);
            // The normal offset moves the receiver a texel or so, changing its axial distance
            // by far less than 1 %.
            EXPECT_LE(worstRatio, 1.01) << name << ": the filter radius is not clamped";
            EXPECT_GT(worstRatio, 0.5) << name << ": the penumbra never reaches the clamp";
        }
    }
}

TEST(Stability, EmitterSizesBeyondTheirRangeAreClampedWithAWarning) {
    Scene scene = spotOverBox(1e9f, ShadowTechnique::Pcss);
    Light sun = test::pointSizedLight(LightType::Directional);
    sun.angularRadius = 10.0f;
    addLight(scene, "sun", sun, test::shadowWith(ShadowTechnique::Pcss, 256), {0, 8, 0}, {0.2, -1, 0.1});
    const test::RenderedFrame frame = render(scene);
    const std::vector<Warning>& w = frame.stats.warnings;
    // One field out of range each: the spot's radius, the sun's angular radius.
    EXPECT_EQ(test::countWarnings(w, WarningCode::SettingClamped, "spot"), 1) << test::describe(w);
    EXPECT_EQ(test::countWarnings(w, WarningCode::SettingClamped, "sun"), 1) << test::describe(w);
    EXPECT_EQ(w.size(), 2u) << test::describe(w);
}

}  // namespace
}  // namespace shadow::emitter_size_test
