// Relative displacement of neighbours (SPEC §3, [41]; analysis/rel_disp) on a
// known shear band: a hexagonal lattice of touching discs whose upper part
// (centres above y_b) slides rigidly by +d in x between two outputs.
// Neighbours are the contact store's candidate pairs (within R_i + R_j + skin):
// in this lattice, the six touching neighbours of each disc.
//
// Expected, exactly: every pair across y_b has |Δx_i − Δx_j| = d, every other
// pair 0, so discs in the two rows next to y_b get d / d = 1 and all other
// discs 0. All x coordinates and d are multiples of 1/4 (dyadic), so
// x + d − x == d and x − x == 0 hold exactly in floating point; the y
// coordinates (multiples of √3 r) are not moved. Hence EXPECT_EQ, not NEAR.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <vector>

#include "orodem/analysis/rel_disp.hpp"
#include "orodem/engine/simulation.hpp"
#include "test_util.hpp"

using namespace orodem;

namespace {

using test::SerialOmp;

constexpr double kR = 0.5;       // disc radius [m]; spacing 2r = 1
constexpr int kCols = 16, kRows = 10;
const double kRowDy = std::sqrt(3.0) * kR;  // hexagonal row spacing
constexpr int kBandRow = 5;                 // rows >= 5 move; y_b between rows 4 and 5

double row_y(int j) { return kR + j * kRowDy; }
int row_of(double y) { return static_cast<int>(std::lround((y - kR) / kRowDy)); }

/// Hexagonal lattice of touching discs, initialised (pairs listed), no gravity.
Simulation make_lattice() {
    Simulation sim;
    for (int j = 0; j < kRows; ++j)
        for (int i = 0; i < kCols; ++i)
            sim.particles.add({kR + 2 * kR * i + ((j % 2) ? kR : 0.0), row_y(j)}, kR, 2500.0);
    sim.params.law.k_n = 1e5;
    sim.params.law.k_s = 1e5;
    sim.params.law.mu = 0.3;
    sim.params.dt = 1e-4;
    sim.params.gravity = {0.0, 0.0};
    sim.params.skin = 0.4 * kR;  // next-nearest neighbours (at 2√3 r) are outside
    sim.initialize();
    return sim;
}

}  // namespace

TEST(RelDisp, ShearBandIsOneAndRigidBlocksAreZero) {
    SerialOmp serial;
    Simulation sim = make_lattice();
    ParticleStore& p = sim.particles;
    const double y_b = 0.5 * (row_y(kBandRow - 1) + row_y(kBandRow));
    const double d = 0.25;  // half a radius

    const std::vector<Vec2> then = positions_by_id(p);
    for (std::size_t s = 0; s < p.size(); ++s)
        if (p.x[s].y > y_b) p.x[s].x += d;
    const std::vector<double> rd = relative_displacement(sim, then);

    ASSERT_EQ(rd.size(), p.size());
    int ones = 0;
    for (std::size_t s = 0; s < p.size(); ++s) {
        const int row = row_of(p.x[s].y);
        EXPECT_GE(rd[s], 0.0);
        EXPECT_LE(rd[s], 1.0);
        if (row == kBandRow - 1 || row == kBandRow) {
            EXPECT_EQ(rd[s], 1.0) << "disc next to the band, row " << row << " x " << p.x[s].x;
            ++ones;
        } else {
            EXPECT_EQ(rd[s], 0.0) << "disc away from the band, row " << row << " x " << p.x[s].x;
        }
    }
    EXPECT_EQ(ones, 2 * kCols);
}

TEST(RelDisp, ScaledToTheIntervalMaximum) {
    // The band slides by d; one disc deep in the lower block (row 1) jitters
    // by d/2 in y. Its relative displacement against each of its (unmoved)
    // neighbours is d/2, so it and its six neighbours read exactly 0.5, the
    // band rows 1, the rest 0: the scale is the interval's maximum.
    SerialOmp serial;
    Simulation sim = make_lattice();
    ParticleStore& p = sim.particles;
    const double y_b = 0.5 * (row_y(kBandRow - 1) + row_y(kBandRow));
    const double d = 0.25;
    const std::vector<Vec2> then = positions_by_id(p);
    const Vec2 rattler_at{kR + 2 * kR * 8 + kR, row_y(1)};  // row 1 is shifted by r
    std::size_t rattler = p.size();
    for (std::size_t s = 0; s < p.size(); ++s) {
        if (p.x[s].x == rattler_at.x && p.x[s].y == rattler_at.y) rattler = s;
        if (p.x[s].y > y_b) p.x[s].x += d;
    }
    ASSERT_LT(rattler, p.size());
    const Vec2 r0 = p.x[rattler];
    p.x[rattler].y += 0.5 * d;
    const std::vector<double> rd = relative_displacement(sim, then);

    int halves = 0;
    for (std::size_t s = 0; s < p.size(); ++s) {
        const int row = row_of(p.x[s].y);
        const bool near_rattler = s == rattler || std::abs(norm(p.x[s] - r0) - 2 * kR) < 1e-9;
        if (row == kBandRow - 1 || row == kBandRow) {
            EXPECT_EQ(rd[s], 1.0);
        } else if (near_rattler) {
            // |(0, d/2) − 0| / d, computed as sqrt((d/2)²)/d: exact in binary.
            EXPECT_EQ(rd[s], 0.5) << "row " << row << " x " << p.x[s].x;
            ++halves;
        } else {
            EXPECT_EQ(rd[s], 0.0);
        }
    }
    EXPECT_EQ(halves, 7);  // the rattler and its six touching neighbours
}

TEST(RelDisp, RigidTranslationGivesZeroEverywhere) {
    // No relative motion at all: the interval maximum is 0, and the result
    // must be all zeros (not 0/0).
    SerialOmp serial;
    Simulation sim = make_lattice();
    ParticleStore& p = sim.particles;
    const std::vector<Vec2> then = positions_by_id(p);
    for (auto& x : p.x) x.x += 0.25;
    const std::vector<double> rd = relative_displacement(sim, then);
    for (double v : rd) EXPECT_EQ(v, 0.0);
}
