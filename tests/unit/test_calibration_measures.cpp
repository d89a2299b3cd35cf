// The calibration measurements (analysis/calibration_measures.hpp) against
// hand calculations: the mobilized friction angle, window statistics, the
// least-squares line, the heap surface and the repose-angle fit on a
// hand-built triangular heap of discs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "orodem/analysis/calibration_measures.hpp"

using namespace orodem;

namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;

/// Discs of radius r on a hexagonal lattice filling the triangle with base
/// [−b, b] on y = 0 and flanks at angle theta: a disc is kept when its top
/// lies under the flank, y + r <= (b − |x|) tan θ.
ParticleStore triangular_heap(double theta_deg, double b, double r) {
    ParticleStore p;
    const double t = std::tan(theta_deg / kDeg);
    const double dy = std::sqrt(3.0) * r;
    for (int row = 0;; ++row) {
        const double y = r + dy * row;
        if (y + r > b * t) break;
        const double off = (row % 2) ? r : 0.0;
        for (int k = -1000; k <= 1000; ++k) {
            const double x = off + 2.0 * r * k;
            if (y + r <= (b - std::fabs(x)) * t) p.add({x, y}, r, 1.0);
        }
    }
    return p;
}
}  // namespace

TEST(CalibrationMeasures, MobilizedFrictionAngle) {
    EXPECT_NEAR(mobilized_friction_deg(3.0, 1.0), 30.0, 1e-12);  // (3 − 1)/(3 + 1) = 1/2
    EXPECT_NEAR(mobilized_friction_deg(1.0, 1.0), 0.0, 1e-12);
    // Coulomb: σ1/σ3 = (1 + sin φ)/(1 − sin φ) at φ = 40°.
    const double s = std::sin(40.0 / kDeg);
    EXPECT_NEAR(mobilized_friction_deg((1.0 + s) / (1.0 - s) * 2.0e5, 2.0e5), 40.0, 1e-10);
    EXPECT_TRUE(std::isnan(mobilized_friction_deg(0.0, 0.0)));
}

TEST(CalibrationMeasures, WindowStatistics) {
    const std::vector<double> x = {0.0, 0.1, 0.15, 0.17, 0.2, 0.25};
    const std::vector<double> y = {9.0, 9.0, 1.0, 2.0, 3.0, 9.0};
    const WindowStats w = window_stats(x, y, 0.15, 0.2);
    EXPECT_EQ(w.n, 3u);
    EXPECT_DOUBLE_EQ(w.mean, 2.0);
    EXPECT_DOUBLE_EQ(w.sd, 1.0);  // sample standard deviation of 1, 2, 3
    EXPECT_TRUE(std::isnan(window_stats(x, y, 0.3, 0.4).mean));
}

TEST(CalibrationMeasures, LineFitIsExactOnALine) {
    const std::vector<double> x = {1.0, 2.0, 4.0, 7.0};
    std::vector<double> y;
    for (double v : x) y.push_back(-3.0 + 0.5 * v);
    const LineFit f = fit_line(x, y);
    EXPECT_NEAR(f.slope, 0.5, 1e-14);
    EXPECT_NEAR(f.intercept, -3.0, 1e-14);
    EXPECT_NEAR(f.slope_se, 0.0, 1e-14);
    // y = 1, 0, 3, 2 at x = 0..3: slope Σ(x−x̄)(y−ȳ) / Σ(x−x̄)² = 3 / 5.
    const LineFit g = fit_line({0, 1, 2, 3}, {1, 0, 3, 2});
    EXPECT_NEAR(g.slope, 0.6, 1e-14);
    EXPECT_TRUE(std::isnan(fit_line({1.0}, {1.0}).slope));
}

TEST(CalibrationMeasures, HeapProfileTakesTheHighestFreeDiscPerColumn) {
    ParticleStore p;
    p.add({0.5, 1.0}, 0.5, 1.0);   // column 0, top 1.5
    p.add({0.6, 3.0}, 0.25, 1.0);  // column 0, top 3.25
    p.add({2.5, 1.0}, 0.5, 1.0);   // column 2, top 1.5
    const std::size_t fixed = p.add({2.5, 9.0}, 0.5, 1.0);
    p.fix(fixed);                  // a floor disc: not part of the heap
    const HeapProfile h = heap_profile(p, 0.5, 0.0, 4.0, 1.0);
    ASSERT_EQ(h.x.size(), 2u);     // the empty columns are left out
    EXPECT_DOUBLE_EQ(h.x[0], 0.5);
    EXPECT_DOUBLE_EQ(h.top[0], 3.25);
    EXPECT_DOUBLE_EQ(h.x[1], 2.5);
    EXPECT_DOUBLE_EQ(h.top[1], 1.5);
    EXPECT_DOUBLE_EQ(h.height, 2.75);
    EXPECT_DOUBLE_EQ(h.x_peak, 0.5);
}

TEST(CalibrationMeasures, ReposeFitReturnsTheConstructionAngleOfATriangularHeap) {
    // The column tops of a lattice-filled triangle follow its flanks within a
    // disc radius; over ~20 columns per flank the fitted slope is within 1°.
    for (double theta : {15.0, 25.0, 35.0}) {
        const double b = 60.0, r = 0.5;
        const ParticleStore p = triangular_heap(theta, b, r);
        const HeapProfile h = heap_profile(p, 0.0, -b - 1.0, b + 1.0, 2.0 * r);
        const ReposeFit f = fit_repose(h, 0.15, 0.85);
        EXPECT_GT(f.left.n, 10u) << theta;
        EXPECT_GT(f.right.n, 10u) << theta;
        EXPECT_NEAR(f.angle_left_deg, theta, 1.0) << theta;
        EXPECT_NEAR(f.angle_right_deg, theta, 1.0) << theta;
        EXPECT_NEAR(f.angle_deg, theta, 0.5) << theta;
        EXPECT_GT(f.left.slope, 0.0);  // rising to the peak
        EXPECT_LT(f.right.slope, 0.0);
    }
}

TEST(CalibrationMeasures, ReposeFitLeavesOutTheToeAndTheTop) {
    // A flat apron of discs at the toe and a tower at the top, on a 30° heap:
    // outside the fitted height window, so the angle stays 30°.
    const double theta = 30.0, b = 40.0, r = 0.5;
    ParticleStore p = triangular_heap(theta, b, r);
    for (int k = 0; k < 30; ++k) {
        p.add({-b - 2.0 - 1.0 * k, r}, r, 1.0);
        p.add({b + 2.0 + 1.0 * k, r}, r, 1.0);
    }
    const HeapProfile h = heap_profile(p, 0.0, -b - 40.0, b + 40.0, 2.0 * r);
    EXPECT_NEAR(fit_repose(h, 0.15, 0.85).angle_deg, theta, 0.5);
    // The fit over everything (the apron included) is much flatter.
    EXPECT_LT(fit_repose(h, 0.0, 1.0).angle_deg, theta - 3.0);
}
