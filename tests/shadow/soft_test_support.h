// Helpers of the soft-shadow, cache and cascade tests: shadow settings per technique, the
// closed form of a disk light's penumbra over a straight edge, visibility profiles across an
// edge measured from the AOVs, and counts over ground pixels.
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <shadow/renderer.h>
#include <shadow/shadow_system.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "render/render_test_support.h"

namespace shadow::test {

inline constexpr double kPi = 3.14159265358979323846;

/// Shadow settings of `technique` with `mapSize` texels per edge and the rest at defaults.
inline Shadow shadowWith(ShadowTechnique technique, int mapSize = 1024) {
    Shadow s;
    s.technique = technique;
    s.mapSize = mapSize;
    return s;
}

/// Fraction of a disk of unit radius on the far side of a chord at signed distance `u` from the
/// centre (u in [-1, 1]): the circular-segment area (acos u - u sqrt(1 - u^2)) / pi. It is the
/// visible fraction of a disk emitter whose image is cut by a straight blocker edge, and the
/// fraction of PCF taps of a uniform disk kernel that fall on the lit side of a straight edge.
inline double circularSegmentFraction(double u) {
    u = std::clamp(u, -1.0, 1.0);
    return (std::acos(u) - u * std::sqrt(1.0 - u * u)) / kPi;
}

/// Width of the band where the visibility of a disk light across a straight edge lies in
/// (lo, hi), for a full penumbra width `fullWidth` (the disk's image diameter on the receiver).
/// Solved by bisection on the monotone circular-segment profile.
inline double diskEdgeBandWidth(double fullWidth, double lo, double hi) {
    auto solve = [](double fraction) {
        double a = -1.0;  // fraction 1
        double b = 1.0;   // fraction 0
        for (int i = 0; i < 100; ++i) {
            const double m = 0.5 * (a + b);
            (circularSegmentFraction(m) > fraction ? a : b) = m;
        }
        return 0.5 * (a + b);
    };
    return 0.5 * fullWidth * (solve(lo) - solve(hi));
}

/// A visibility profile along one world axis: the mean visibility of the selected pixels in
/// bins of equal width. Averaging over many pixels per bin removes the per-pixel rotation noise
/// of the PCF/PCSS sample patterns.
struct Profile {
    double start = 0.0;
    double binWidth = 0.0;
    std::vector<double> sum;
    std::vector<int> count;

    Profile(double from, double to, int bins)
        : start(from),
          binWidth((to - from) / bins),
          sum(static_cast<std::size_t>(bins), 0.0),
          count(static_cast<std::size_t>(bins), 0) {}

    void add(double coordinate, double value) {
        const int b = static_cast<int>(std::floor((coordinate - start) / binWidth));
        if (b < 0 || b >= static_cast<int>(sum.size())) return;
        sum[static_cast<std::size_t>(b)] += value;
        ++count[static_cast<std::size_t>(b)];
    }
    [[nodiscard]] int bins() const { return static_cast<int>(sum.size()); }
    [[nodiscard]] double centre(int b) const { return start + (b + 0.5) * binWidth; }
    [[nodiscard]] std::optional<double> mean(int b) const {
        const int n = count[static_cast<std::size_t>(b)];
        if (n == 0) return std::nullopt;
        return sum[static_cast<std::size_t>(b)] / n;
    }
    /// Smallest number of pixels in any bin.
    [[nodiscard]] int minCount() const { return *std::min_element(count.begin(), count.end()); }

    /// Where the profile, rising from dark to lit with the coordinate, first reaches `level`
    /// (linear interpolation between bin centres). Empty if it never does.
    [[nodiscard]] std::optional<double> firstCrossingUp(double level) const {
        std::optional<double> prevX;
        double prevV = 0.0;
        for (int b = 0; b < bins(); ++b) {
            const std::optional<double> v = mean(b);
            if (!v) continue;
            if (*v >= level) {
                if (!prevX) return centre(b);
                return *prevX + (level - prevV) / (*v - prevV) * (centre(b) - *prevX);
            }
            prevX = centre(b);
            prevV = *v;
        }
        return std::nullopt;
    }
};

/// Counts over the ground pixels accepted by `keep` (all ground pixels when empty).
struct GroundCounts {
    int ground = 0;    ///< ground pixels considered
    int dark = 0;      ///< visibility < 0.5
    int penumbra = 0;  ///< 0.05 < visibility < 0.95
    [[nodiscard]] double darkFraction() const { return ground > 0 ? static_cast<double>(dark) / ground : 0.0; }
    [[nodiscard]] double penumbraFraction() const { return ground > 0 ? static_cast<double>(penumbra) / ground : 0.0; }
};

inline GroundCounts countGround(const FrameImages& images, std::size_t light,
                                const std::function<bool(const glm::dvec3&)>& keep = {}) {
    GroundCounts c;
    const ImageF& v = images.visibility.at(light);
    for (int y = 0; y < v.height; ++y) {
        for (int x = 0; x < v.width; ++x) {
            if (!isGroundPixel(images, x, y)) continue;
            if (keep && !keep(positionAt(images, x, y))) continue;
            ++c.ground;
            const float value = v.at(x, y, 0);
            if (value < 0.5f) ++c.dark;
            if (value > 0.05f && value < 0.95f) ++c.penumbra;
        }
    }
    return c;
}

/// Whether ground point `p` lies inside the cone of half-angle `halfAngle` of a spot light at
/// `position` shining along unit `direction`.
inline bool insideCone(const glm::dvec3& p, const glm::dvec3& position, const glm::dvec3& direction, double halfAngle) {
    return glm::dot(glm::normalize(p - position), direction) > std::cos(halfAngle);
}

/// Lateral size (m) of one texel of an orthographic layer: extent / mapSize, with the extent
/// 2 / clipFromLight[0][0].
inline double orthoTexel(const ShadowLayerPlan& layer, int mapSize) {
    return 2.0 / (layer.clipFromLight[0][0] * mapSize);
}

}  // namespace shadow::test
