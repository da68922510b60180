// The closed forms the reference is judged by, judged themselves against numeric integration.
#include "reference/closed_forms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace shadow::reference {
namespace {

/// Length of [lo, hi] ∩ ∪ intervals (intervals may overlap).
double unionLength(double lo, double hi, std::vector<std::pair<double, double>> intervals) {
    std::sort(intervals.begin(), intervals.end());
    double length = 0.0;
    double covered = lo;
    for (auto [a, b] : intervals) {
        a = std::max(a, covered);
        b = std::min(b, hi);
        if (b > a) {
            length += b - a;
            covered = b;
        }
    }
    return length;
}

/// Area of the disk ∩ ∪ rects by the midpoint rule over x of the vertical chord's covered
/// length: an independent, slow route to the same number. The x range is split at every
/// rectangle edge so the integrand is continuous on each piece.
double numericArea(const glm::dvec2& c, double r, const std::vector<Rect>& rects, int steps) {
    std::vector<double> cuts{c.x - r, c.x + r};
    for (const Rect& rect : rects) {
        for (const double x : {rect.min.x, rect.max.x}) {
            if (x > c.x - r && x < c.x + r) cuts.push_back(x);
        }
    }
    std::sort(cuts.begin(), cuts.end());
    double area = 0.0;
    for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
        const double h = (cuts[piece + 1] - cuts[piece]) / steps;
        for (int k = 0; k < steps; ++k) {
            const double x = cuts[piece] + (k + 0.5) * h;
            const double s = std::sqrt(std::max(r * r - (x - c.x) * (x - c.x), 0.0));
            std::vector<std::pair<double, double>> spans;
            for (const Rect& rect : rects) {
                if (x >= rect.min.x && x <= rect.max.x) spans.emplace_back(rect.min.y, rect.max.y);
            }
            area += unionLength(c.y - s, c.y + s, spans) * h;
        }
    }
    return area;
}

TEST(ClosedForms, DiskRectAreaOfSpecialCases) {
    const glm::dvec2 c(0.3, -0.2);
    const double r = 0.7;
    const double disk = std::numbers::pi * r * r;
    const double big = 10.0;
    EXPECT_NEAR(diskRectArea(c, r, {{-big, -big}, {big, big}}), disk, 1e-12);
    EXPECT_NEAR(diskRectArea(c, r, {{c.x, -big}, {big, big}}), disk / 2, 1e-12);
    EXPECT_NEAR(diskRectArea(c, r, {{c.x, c.y}, {big, big}}), disk / 4, 1e-12);
    EXPECT_EQ(diskRectArea(c, r, {{c.x + r, -big}, {big, big}}), 0.0);
    EXPECT_EQ(diskRectArea(c, r, {{1.0, 1.0}, {0.0, 2.0}}), 0.0);  // empty rectangle
    // A square inscribed in the disk lies wholly inside it.
    const double a = r / std::sqrt(2.0);
    EXPECT_NEAR(diskRectArea(c, r, {{c.x - a, c.y - a}, {c.x + a, c.y + a}}), 2.0 * r * r, 1e-12);
}

TEST(ClosedForms, DiskRectAreaMatchesNumericIntegration) {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    double worst = 0.0;
    for (int trial = 0; trial < 60; ++trial) {
        const glm::dvec2 c(u(rng), u(rng));
        const double r = 0.2 + 0.5 * (u(rng) + 1.5);
        glm::dvec2 p(u(rng), u(rng));
        glm::dvec2 q(u(rng), u(rng));
        const Rect rect{glm::min(p, q), glm::max(p, q)};
        const double exact = diskRectArea(c, r, rect);
        const double numeric = numericArea(c, r, {rect}, 50000);
        worst = std::max(worst, std::abs(exact - numeric));
        ASSERT_NEAR(exact, numeric, 1e-6) << "trial " << trial;
    }
    std::printf("[ measured ] disk ∩ rectangle: worst |closed form − numeric| = %.2e over 60 cases\n", worst);
}

TEST(ClosedForms, UnionAreaMatchesNumericIntegration) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int trial = 0; trial < 30; ++trial) {
        std::vector<Rect> rects;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec2 p(u(rng), u(rng));
            const glm::dvec2 q(u(rng), u(rng));
            rects.push_back({glm::min(p, q), glm::max(p, q)});
        }
        const glm::dvec2 c(0.5 * u(rng), 0.5 * u(rng));
        const double r = 0.3 + 0.4 * (u(rng) + 1.0);
        ASSERT_NEAR(diskRectUnionArea(c, r, rects), numericArea(c, r, rects, 20000), 1e-6) << "trial " << trial;
    }
}

TEST(ClosedForms, CircularSegmentFractionEnds) {
    EXPECT_DOUBLE_EQ(circularSegmentFraction(-1.0), 1.0);
    EXPECT_DOUBLE_EQ(circularSegmentFraction(0.0), 0.5);
    EXPECT_DOUBLE_EQ(circularSegmentFraction(1.0), 0.0);
    // A half-plane cut of a disk: the same number as the rectangle route.
    const double u0 = 0.37;
    EXPECT_NEAR(circularSegmentFraction(u0), diskRectArea({0, 0}, 1.0, {{u0, -2}, {2, 2}}) / std::numbers::pi, 1e-12);
}

TEST(ClosedForms, PlatesVisibilityUmbraAndFullLight) {
    const PlatesGeometry g;
    // Under the low plate's centre its 4x-enlarged image covers the whole disk.
    EXPECT_EQ(platesVisibility(g, {g.plates[0].center.x, 0.0, g.plates[0].center.z}), 0.0);
    // Far corner of the receiver: both images are far from the disk.
    EXPECT_EQ(platesVisibility(g, {3.9, 0.0, 3.9}), 1.0);
    // Above the plates nothing occludes.
    EXPECT_EQ(platesVisibility(g, {g.plates[0].center.x, 3.0, g.plates[0].center.z}), 1.0);
}

}  // namespace
}  // namespace shadow::reference
