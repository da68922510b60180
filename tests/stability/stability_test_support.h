// Helpers of the stability tests (tests/stability/): every technique in turn, the invariants
// every frame must keep in its AOVs *and* in its shadow maps, and the small scenes the extreme
// cases are built from.
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <shadow/frame_runner.h>
#include <shadow/shadow_system.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "shadow/soft_test_support.h"
#include "test_support.h"

namespace shadow::test {

/// Every technique that draws a shadow, the seeds' textbook PCSS included.
inline constexpr std::array<ShadowTechnique, 8> kShadowTechniques{
    ShadowTechnique::Hard, ShadowTechnique::Pcf,  ShadowTechnique::Pcss, ShadowTechnique::PcssTextbook,
    ShadowTechnique::Vsm,  ShadowTechnique::Vssm, ShadowTechnique::Msm,  ShadowTechnique::MsmSoft};

/// The techniques of kShadowTechniques this build offers (`offered`).
inline std::vector<ShadowTechnique> offeredShadowTechniques() { return offered(kShadowTechniques); }

/// Whether `t` reads a depth moments chain (VSM, VSSM, MSM, MSM-soft): a bound over a filter
/// region, which some extreme cases hold to their own measured bounds.
inline constexpr bool readsMoments(ShadowTechnique t) {
    return t == ShadowTechnique::Vsm || t == ShadowTechnique::Vssm || t == ShadowTechnique::Msm ||
           t == ShadowTechnique::MsmSoft;
}

/// Non-finite texels over every layer of every light of the last frame, and texels outside
/// [0, depthScale] (a stored depth is a distance inside the layer's range).
struct ShadowMapCheck {
    long long texels = 0;
    long long nonFinite = 0;
    long long outOfRange = 0;
};

inline ShadowMapCheck checkShadowMaps(const ShadowSystem& shadows) {
    ShadowMapCheck c;
    const ShadowFrame& frame = shadows.frame();
    for (std::size_t i = 0; i < frame.lights.size(); ++i) {
        const ShadowLightPlan& plan = frame.lights[i];
        for (std::size_t k = 0; k < plan.layers.size(); ++k) {
            const float high = plan.layers[k].depthScale * (1.0f + 1e-6f);
            const std::vector<float> depth = shadows.maps().readLayerDepth(i, static_cast<int>(k));
            c.texels += static_cast<long long>(depth.size());
            // Texels outside [0, high], NaN included, counted without a branch (most layers have
            // none: millions of texels a frame); only then told apart.
            long long outside = 0;
            for (float d : depth) outside += (d >= 0.0f && d <= high) ? 0 : 1;
            if (outside == 0) continue;
            for (float d : depth) {
                if (!std::isfinite(d)) {
                    ++c.nonFinite;
                } else if (d < 0.0f || d > high) {
                    ++c.outOfRange;
                }
            }
        }
    }
    return c;
}

/// The frame invariants of docs/output_contract.md over the AOVs (`expectSaneAovs`) and the shadow maps:
/// nothing NaN/Inf, visibility in [0, 1], stored depths inside their layer's range, and every
/// plan's numbers finite.
inline void expectSaneFrame(const FrameImages& images, const ShadowSystem& shadows, const std::string& what) {
    SCOPED_TRACE(what);
    expectSaneAovs(images);
    const ShadowMapCheck maps = checkShadowMaps(shadows);
    EXPECT_EQ(maps.nonFinite, 0) << maps.nonFinite << " of " << maps.texels << " shadow-map texels are NaN/Inf";
    EXPECT_EQ(maps.outOfRange, 0) << maps.outOfRange << " of " << maps.texels
                                  << " shadow-map texels lie outside [0, depthScale]";
    for (const ShadowLightPlan& plan : shadows.frame().lights) {
        for (const ShadowLayerPlan& layer : plan.layers) {
            EXPECT_TRUE(isFinite(layer.lightFromWorld)) << plan.name << ": lightFromWorld";
            EXPECT_TRUE(isFinite(layer.clipFromLight)) << plan.name << ": clipFromLight";
            EXPECT_TRUE(std::isfinite(layer.depthScale) && layer.depthScale > 0.0f) << plan.name << ": depthScale";
            EXPECT_TRUE(std::isfinite(layer.depthNear) && layer.depthNear >= 0.0f) << plan.name << ": depthNear";
        }
    }
}

/// How far the depths stored for an open ground plane (y = `groundY`, |x|, |z| <= `halfSize`
/// around `centre`) lie from the exact linear depth of the plane at the texel centres, over the
/// texels whose centre ray meets the ground before any of `boxes`.
struct StoredDepthError {
    long long texels = 0;
    double maxAbs = 0.0;       ///< m
    double maxRelative = 0.0;  ///< |error| / exact depth
    double depthScale = 0.0;   ///< m, of the worst layer
};

template <typename Boxes>
StoredDepthError storedGroundDepthError(const ShadowSystem& shadows, std::size_t light, const glm::dvec3& centre,
                                        double halfSize, const Boxes& boxes) {
    StoredDepthError e;
    const ShadowLightPlan& plan = shadows.frame().lights.at(light);
    const int n = plan.mapSize;
    for (std::size_t k = 0; k < plan.layers.size(); ++k) {
        const ShadowLayerPlan& layer = plan.layers[k];
        const std::vector<float> stored = shadows.maps().readLayerDepth(light, static_cast<int>(k));
        const glm::dmat4 worldFromClip = glm::inverse(layer.clipFromLight * layer.lightFromWorld);
        const glm::dvec3 lightPosition(glm::inverse(layer.lightFromWorld)[3]);
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                // Rows of the texture start at the bottom, like NDC y.
                const glm::dvec2 ndc((x + 0.5) / n * 2.0 - 1.0, (y + 0.5) / n * 2.0 - 1.0);
                const glm::dvec4 a4 = worldFromClip * glm::dvec4(ndc, -1.0, 1.0);
                const glm::dvec4 b4 = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
                const glm::dvec3 a = glm::dvec3(a4) / a4.w;
                const glm::dvec3 b = glm::dvec3(b4) / b4.w;
                if (std::abs(b.y - a.y) < 1e-300) continue;
                const double t = (centre.y - a.y) / (b.y - a.y);
                if (!(t > 0.0 && t < 1.0)) continue;
                const glm::dvec3 p = a + t * (b - a);
                // Texels whose footprint reaches past the ground's edge may or may not be covered.
                const glm::dvec3 ray = glm::normalize(b - a);
                double texel = 2.0 / (layer.clipFromLight[0][0] * n);
                if (!layer.orthographic) texel *= std::max(-(layer.lightFromWorld * glm::dvec4(p, 1.0)).z, 0.0);
                const double margin = 2.0 * texel / std::max(std::abs(ray.y), 0.1);
                if (std::abs(p.x - centre.x) > halfSize - margin || std::abs(p.z - centre.z) > halfSize - margin)
                    continue;
                const AnalyticLight from{layer.orthographic ? LightType::Directional : LightType::Point, lightPosition,
                                         ray};
                if (!analyticallyLit(from, p, boxes)) continue;
                const glm::dvec3 ls(layer.lightFromWorld * glm::dvec4(p, 1.0));
                const double exact = layer.orthographic ? -ls.z : glm::length(ls);
                const double error = std::abs(static_cast<double>(stored[static_cast<std::size_t>(y) * n + x]) - exact);
                ++e.texels;
                if (error > e.maxAbs) {
                    e.maxAbs = error;
                    e.depthScale = layer.depthScale;
                }
                e.maxRelative = std::max(e.maxRelative, error / std::max(exact, 1e-30));
            }
        }
    }
    return e;
}

/// Sets the technique of every shadowed light of `scene`.
inline void setTechnique(Scene& scene, ShadowTechnique technique) {
    scene.world.view<Shadow>().each([&](Entity, Shadow& s) { s.technique = technique; });
}

/// Renders one frame per technique of `offeredShadowTechniques()` (one runner: the maps do not depend
/// on the technique), checks the frame invariants, and hands each frame to `inspect`.
template <typename Inspect>
void forEveryTechnique(Scene& scene, int width, int height, const std::string& what, Inspect inspect) {
    glContext();
    FrameRunner runner;
    for (ShadowTechnique technique : offeredShadowTechniques()) {
        setTechnique(scene, technique);
        const RenderedFrame frame = renderFrame(runner, scene, width, height);
        expectSaneFrame(frame.images, runner.shadows(), what + ", " + techniqueName(technique));
        inspect(technique, frame, runner);
    }
}

/// The grazing-light bound (grazing_light_test.cpp, second_depth_test.cpp): the largest fraction
/// of the pixels that must read lit allowed to read as shadowed, in two readings: visibility < 0.5
/// (false shadow, the acne measure of the soft-shadow tests) and visibility < 0.99 (any darkening
/// at all: a filter whose taps half fail reads 0.5-0.9 and escapes the first reading).
inline constexpr double kMaxAcneFraction = 0.001;
/// The grazing lights' elevations above the receiver (degrees), from steep to grazing.
inline constexpr std::array<double, 5> kGrazingElevationsDeg{10.0, 5.0, 2.0, 1.0, 0.5};
/// The grazing lights' azimuth (rad): no texel axis lines up with the light.
inline constexpr double kGrazingAzimuth = 0.4;

/// Unit direction of light travelling downwards at `elevationDeg` degrees above the horizon,
/// turned by kGrazingAzimuth about +Y.
inline glm::dvec3 grazingDirection(double elevationDeg) {
    const double e = elevationDeg * kPi / 180.0;
    return glm::normalize(
        glm::dvec3(std::cos(e) * std::cos(kGrazingAzimuth), -std::sin(e), std::cos(e) * std::sin(kGrazingAzimuth)));
}

/// The pixels that must read lit, and how many of them read shadowed or darkened.
struct AcneCount {
    int lit = 0;       ///< pixels that must read lit
    int dark = 0;      ///< of those, visibility < 0.5
    int darkened = 0;  ///< visibility < 0.99
    float lowest = 1.0f;
    [[nodiscard]] double darkFraction() const { return lit > 0 ? static_cast<double>(dark) / lit : 0.0; }
    [[nodiscard]] double darkenedFraction() const { return lit > 0 ? static_cast<double>(darkened) / lit : 0.0; }
};

/// Prints one measured figure in the form the README table quotes.
inline void reportFigure(const std::string& what, double value, const char* unit = "") {
    std::printf("[ measured ] %s: %.6g%s\n", what.c_str(), value, unit);
}

}  // namespace shadow::test
