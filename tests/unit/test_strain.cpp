// Local strain (analysis/strain.hpp) against imposed fields: affine ones
// (pure shear, simple shear, rotation, dilation) give their analytic
// Green-Lagrange measures to round-off and zero non-affine residual; a block
// cut by one fault concentrates shear and D²min on the fault.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "orodem/analysis/strain.hpp"

using namespace orodem;

namespace {

/// A jittered 30 x 20 lattice of spacing 1 m (a disordered packing's centres).
std::vector<Vec2> lattice() {
    std::vector<Vec2> x;
    for (int i = 0; i < 30; ++i)
        for (int j = 0; j < 20; ++j)
            x.push_back({i + 0.5 * (j % 2) + 0.13 * std::sin(7.0 * i + 3.0 * j), j * 0.87 + 0.11 * std::cos(5.0 * i - j)});
    return x;
}

std::vector<Vec2> map(const std::vector<Vec2>& x, double a, double b, double c, double d, Vec2 t = {}) {
    std::vector<Vec2> y;
    for (const Vec2& p : x) y.push_back(Vec2{a * p.x + b * p.y, c * p.x + d * p.y} + t);
    return y;
}

void expect_uniform(const StrainField& s, double shear, double vol, double rot) {
    for (std::size_t i = 0; i < s.shear.size(); ++i) {
        ASSERT_FALSE(std::isnan(s.shear[i])) << i;
        EXPECT_NEAR(s.shear[i], shear, 1e-12) << i;
        EXPECT_NEAR(s.volumetric[i], vol, 1e-12) << i;
        EXPECT_NEAR(s.rotation[i], rot, 1e-12) << i;
        EXPECT_LT(s.d2min[i], 1e-24) << i;
    }
}

}  // namespace

TEST(Strain, PureShearIsExact) {
    const auto x = lattice();
    const double e = 0.1, a = 1.0 + e;  // stretch along x, shorten along y, area kept
    const StrainField s = local_strain(x, map(x, a, 0.0, 0.0, 1.0 / a, {3.0, -2.0}), 2.5);
    const double exx = 0.5 * (a * a - 1.0), eyy = 0.5 * (1.0 / (a * a) - 1.0);
    expect_uniform(s, 0.5 * std::fabs(exx - eyy), 0.0, 0.0);
}

TEST(Strain, SimpleShearIsExact) {
    const auto x = lattice();
    const double g = 0.3;  // F = [[1, g], [0, 1]]: E = ½ [[0, g], [g, g²]]
    const StrainField s = local_strain(x, map(x, 1.0, g, 0.0, 1.0), 2.5);
    expect_uniform(s, std::sqrt(std::pow(g * g / 4.0, 2) + g * g / 4.0), 0.0, std::atan2(-g, 2.0));
}

TEST(Strain, ARigidRotationHasNoStrain) {
    const auto x = lattice();
    const double th = 0.7;
    const StrainField s = local_strain(x, map(x, std::cos(th), -std::sin(th), std::sin(th), std::cos(th), {5, 5}), 2.5);
    expect_uniform(s, 0.0, 0.0, th);
}

TEST(Strain, DilationIsTheAreaChange) {
    const auto x = lattice();
    const StrainField s = local_strain(x, map(x, 1.1, 0.0, 0.0, 1.2), 2.5);
    const double exx = 0.5 * (1.21 - 1.0), eyy = 0.5 * (1.44 - 1.0);
    expect_uniform(s, 0.5 * std::fabs(exx - eyy), 1.1 * 1.2 - 1.0, 0.0);
}

TEST(Strain, AFaultConcentratesShearAndNonAffineMotion) {
    // The block above the line y = 0.6 x − 3 moves by 0.5 m along it; the
    // rest stays. Discs farther than the neighbourhood radius from the fault
    // see no strain; discs on it carry all of it.
    const auto x = lattice();
    const Vec2 along = (1.0 / std::sqrt(1.0 + 0.36)) * Vec2{1.0, 0.6};
    std::vector<Vec2> y;
    for (const Vec2& p : x) y.push_back(p.y > 0.6 * p.x - 3.0 ? p + 0.5 * along : p);
    const StrainField s = local_strain(x, y, 2.5);
    double on = 0.0, off = 0.0;
    int n_on = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double dist = std::fabs(x[i].y - 0.6 * x[i].x + 3.0) / std::sqrt(1.36);
        if (std::isnan(s.shear[i])) continue;
        if (dist < 0.5) {
            on += s.shear[i];
            ++n_on;
        } else if (dist > 2.6) {
            off = std::max(off, s.shear[i]);
            EXPECT_LT(s.d2min[i], 1e-24) << i;
        }
    }
    ASSERT_GT(n_on, 10);
    std::printf("  mean shear on the fault %.3f, largest 2.6 m off it %.2e\n", on / n_on, off);
    EXPECT_GT(on / n_on, 0.05);
    EXPECT_LT(off, 1e-12);
}

TEST(Strain, TooFewOrCollinearNeighboursGiveNaN) {
    const std::vector<Vec2> line = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}};
    const StrainField s = local_strain(line, line, 2.5);
    for (double v : s.shear) EXPECT_TRUE(std::isnan(v));
    const std::vector<Vec2> far = {{0, 0}, {10, 0}, {0, 10}};
    EXPECT_TRUE(std::isnan(local_strain(far, far, 2.5).shear[0]));
}
