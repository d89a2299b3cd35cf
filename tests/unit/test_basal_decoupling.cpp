// The belt's decoupling point (analysis/basal_decoupling.hpp) on synthetic
// interval displacements of a base row of discs under a second row: a linear
// ramp of speed (exact: bin means of a linear field at bin-centred discs are
// the field at the bin centres, so the interpolated half-speed point is the
// ramp's own, to round-off), a step inside a bin (within half a bin), a layer
// carried up to the S point (0), nothing carried (NaN), and the upper row and
// the retroside ignored.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "orodem/analysis/basal_decoupling.hpp"

using namespace orodem;

namespace {

constexpr double kH0 = 15.0;         // layer thickness [m]
constexpr double kR = 0.75;          // disc radius [m]
constexpr double kBelt = 3.75;       // the belt's displacement over the interval, 0.25 h0 [m]
constexpr double kBin = 0.5 * kH0;   // bin width [m]

struct Interval {
    std::vector<Vec2> then, now;
    std::vector<double> radius;
};

/// A base row (lowest point on y = 0) and a row above it, discs 2R apart at
/// x = −(i + ½) 2R for i = 0..99 (bin-centred: five per bin), and a retroside
/// base row at x = +(i + ½) 2R. The base row moves u(x) kBelt, the upper row
/// and the retroside row the whole belt displacement (a layer the base does
/// not hold and a retroside pushed along would not change x_d).
Interval interval(const std::function<double(double)>& u) {
    Interval iv;
    for (int i = 0; i < 100; ++i) {
        const double x = -(i + 0.5) * 2.0 * kR;
        iv.then.push_back({x, kR});
        iv.now.push_back({x + u(x) * kBelt, kR});
        iv.then.push_back({x, 3.0 * kR + 0.1});
        iv.now.push_back({x + kBelt, 3.0 * kR + 0.1});
        iv.then.push_back({-x, kR});
        iv.now.push_back({-x + kBelt, kR});
        for (int k = 0; k < 3; ++k) iv.radius.push_back(kR);
    }
    return iv;
}

double x_d(const Interval& iv) { return basal_decoupling_x(iv.then, iv.now, iv.radius, kBelt, kBin); }

}  // namespace

TEST(BasalDecoupling, HalfSpeedPointOfALinearRampExactly) {
    // Carried (u = 1) upstream of −4 h0, held (u = 0) downstream of −2 h0: u = ½ at −3 h0.
    const auto ramp = [](double x) { return std::clamp((-2.0 * kH0 - x) / (2.0 * kH0), 0.0, 1.0); };
    EXPECT_NEAR(x_d(interval(ramp)) / kH0, -3.0, 1e-12);
}

TEST(BasalDecoupling, AStepInsideABinWithinHalfABin) {
    // Held downstream of −2.75 h0 (the centre of a bin), carried upstream of it.
    const auto step = [](double x) { return x < -2.75 * kH0 ? 1.0 : 0.0; };
    const double got = x_d(interval(step)) / kH0;
    EXPECT_NEAR(got, -2.75, 0.25);
    EXPECT_NE(got, -2.75);  // the bins do blur it: the test sees the interpolation, not a copy of the step
}

TEST(BasalDecoupling, CarriedUpToTheSPointGivesZeroAndNothingCarriedGivesNaN) {
    EXPECT_EQ(x_d(interval([](double) { return 0.98; })), 0.0);
    EXPECT_TRUE(std::isnan(x_d(interval([](double) { return 0.1; }))));
    // The belt did not move: no speeds to compare.
    const Interval iv = interval([](double) { return 1.0; });
    EXPECT_TRUE(std::isnan(basal_decoupling_x(iv.then, iv.now, iv.radius, 0.0, kBin)));
}

TEST(BasalDecoupling, TheBaseRowAloneDecides) {
    // Without the base row, only the carried upper row and retroside remain: no base disc, NaN.
    Interval iv = interval([](double) { return 0.0; });
    for (std::size_t k = 0; k < iv.then.size(); k += 3) iv.then[k] = iv.now[k] = {std::nan(""), std::nan("")};
    EXPECT_TRUE(std::isnan(x_d(iv)));
    // A base disc sitting 0.1 R above the base (beyond the 5% band) is not in the base row.
    Interval lifted = interval([](double x) { return x < -3.0 * kH0 ? 1.0 : 0.0; });
    for (std::size_t k = 0; k < lifted.then.size(); k += 3) lifted.then[k].y = 1.1 * kR;
    EXPECT_TRUE(std::isnan(x_d(lifted)));
}
