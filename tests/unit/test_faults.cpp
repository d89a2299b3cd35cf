// Fault detection (analysis/faults.hpp) on synthetic displacement fields of
// a layer h0 = 15 m thick of discs 1.5 m apart (the demo's material): one
// fault of known dip, root and slip; two conjugate faults rooted at one
// point (a pop-up, as the S point makes); a diffuse pure shear with no fault.
// The tolerances are the issue's: dip within 2°, root within 0.2 h0.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "orodem/analysis/faults.hpp"
#include "orodem/analysis/strain.hpp"

using namespace orodem;

namespace {

constexpr double kH0 = 15.0;     // layer thickness [m]
constexpr double kD = 1.5;       // mean disc diameter [m]
constexpr double kPi = 3.14159265358979323846;

/// A jittered triangular lattice of spacing kD filling [-60, 60] x [0, h0].
std::vector<Vec2> layer() {
    std::vector<Vec2> x;
    const double dy = kD * std::sqrt(3.0) / 2.0;
    for (int j = 0; j * dy <= kH0; ++j)
        for (int i = 0; i * kD <= 120.0; ++i)
            x.push_back({-60.0 + i * kD + 0.5 * kD * (j % 2) + 0.15 * std::sin(7.1 * i + 3.3 * j),
                         0.3 + j * dy + 0.12 * std::cos(5.3 * i - 1.7 * j)});
    return x;
}

/// The up-dip direction of a fault with dip `dip` [deg] rising toward −x
/// (pro = true) or +x.
Vec2 up_dip(double dip, bool pro) {
    const double a = dip * kPi / 180.0;
    return {pro ? -std::cos(a) : std::cos(a), std::sin(a)};
}

/// p is in the hanging wall of that fault rooted at (x_root, 0).
bool above(Vec2 p, double x_root, double dip, bool pro) {
    const double t = std::tan(dip * kPi / 180.0);
    return p.y > (pro ? -(p.x - x_root) * t : (p.x - x_root) * t);
}

FaultScan scan_of(const std::vector<Vec2>& x0, const std::vector<Vec2>& x1) {
    const StrainField s = local_strain(x0, x1, 2.0 * kD);
    return detect_faults(x1, s.shear, fault_params(kD, kH0));
}

}  // namespace

TEST(Faults, OneFaultHasItsDipRootAndVergence) {
    for (const bool pro : {true, false})
        for (const double dip : {30.0, 45.0}) {
            const auto x0 = layer();
            const double x_root = pro ? 10.0 : -10.0, slip = 1.0;
            std::vector<Vec2> x1;
            for (const Vec2& p : x0) x1.push_back(above(p, x_root, dip, pro) ? p + slip * up_dip(dip, pro) : p);
            const FaultScan s = scan_of(x0, x1);
            ASSERT_EQ(s.faults.size(), 1u) << "pro " << pro << " dip " << dip;
            const Fault& f = s.faults[0];
            EXPECT_EQ(f.vergence, pro ? +1 : -1);
            EXPECT_NEAR(f.dip_deg, dip, 2.0);
            EXPECT_NEAR(f.root.x, x_root, 0.2 * kH0);
            EXPECT_LT(f.root.y, 0.2 * kH0);
            EXPECT_GT(f.tip.y, 0.8 * kH0);
            // Slip: 2 mean(γ) · width estimates the offset to within a factor 2.
            EXPECT_GT(f.slip, 0.5 * slip) << "pro " << pro << " dip " << dip;
            EXPECT_LT(f.slip, 2.0 * slip) << "pro " << pro << " dip " << dip;
        }
}

TEST(Faults, TwoConjugateFaultsRootedAtOnePointAreTwo) {
    // A pop-up: the wedge between a pro-vergent and a retro-vergent fault,
    // both rooted at x = 0 and dipping 35°, moves straight up by 0.8 m.
    const auto x0 = layer();
    std::vector<Vec2> x1;
    for (const Vec2& p : x0) x1.push_back(above(p, 0.0, 35.0, true) && above(p, 0.0, 35.0, false) ? p + Vec2{0.0, 0.8} : p);
    const FaultScan s = scan_of(x0, x1);
    ASSERT_EQ(s.faults.size(), 2u);
    int pro = 0, retro = 0;
    for (const Fault& f : s.faults) {
        (f.vergence > 0 ? pro : retro) += 1;
        EXPECT_NEAR(f.dip_deg, 35.0, 3.0);
        EXPECT_LT(std::fabs(f.root.x), 0.3 * kH0);
        EXPECT_LT(f.root.y, 0.2 * kH0);
    }
    EXPECT_EQ(pro, 1);
    EXPECT_EQ(retro, 1);
    EXPECT_EQ(classify_stage(s.faults, kH0), 1);
}

TEST(Faults, ADiffusePureShearHasNoFault) {
    // 5% shortening along x with the area kept, plus grain-scale noise of
    // 2% of a diameter.
    const auto x0 = layer();
    std::vector<Vec2> x1;
    std::size_t k = 0;
    for (const Vec2& p : x0) {
        ++k;
        x1.push_back({0.95 * p.x + 0.03 * std::sin(12.9898 * static_cast<double>(k)),
                      p.y / 0.95 + 0.03 * std::cos(78.233 * static_cast<double>(k))});
    }
    const FaultScan s = scan_of(x0, x1);
    EXPECT_TRUE(s.faults.empty()) << s.faults.size() << " faults, threshold " << s.threshold;
}

TEST(Faults, TrackerKeepsIdsAndListsAbandonedFaults) {
    Fault a;
    a.vergence = +1, a.root = {-30.0, 0.0}, a.tip = {-50.0, 15.0}, a.dip_deg = 35.0;
    Fault b = a;
    b.vergence = -1, b.root = {0.0, 0.0}, b.tip = {20.0, 15.0};
    FaultTracker t;
    auto all = t.update({a, b}, 1.0, kH0);
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[0].id, 1);
    EXPECT_EQ(all[1].id, 2);
    // Next output: a moved 3 m (within one h0), b not found, a new far fault.
    Fault a2 = a;
    a2.root.x += 3.0, a2.tip.x += 3.0;
    Fault c = a;
    c.root.x = -120.0, c.tip.x = -140.0;
    all = t.update({c, a2}, 1.25, kH0);
    ASSERT_EQ(all.size(), 3u);
    EXPECT_EQ(all[0].id, 1);
    EXPECT_TRUE(all[0].active);
    EXPECT_DOUBLE_EQ(all[0].root.x, -27.0);
    EXPECT_DOUBLE_EQ(all[0].first_S, 1.0);
    EXPECT_EQ(all[1].id, 2);
    EXPECT_FALSE(all[1].active);
    EXPECT_EQ(all[2].id, 3);
    EXPECT_EQ(classify_stage(all, kH0), 2);
    const FaultCounts n = count_faults(all);
    EXPECT_EQ(n.pro, 2);
    EXPECT_EQ(n.retro, 0);
    EXPECT_DOUBLE_EQ(n.front_x, -120.0);
}

TEST(Strain, AccumulatedGradientsMultiplyInOrder) {
    // Two simple shears of 0.2 make one of 0.4; an undefined increment
    // changes nothing.
    const double nan = std::nan("");
    std::vector<Mat2> total(2);
    accumulate_gradient(total, {Mat2{1.0, 0.2, 0.0, 1.0}, Mat2{}});
    accumulate_gradient(total, {Mat2{1.0, 0.2, 0.0, 1.0}, Mat2{nan, nan, nan, nan}});
    EXPECT_DOUBLE_EQ(total[0].xy, 0.4);
    EXPECT_DOUBLE_EQ(total[0].xx, 1.0);
    EXPECT_DOUBLE_EQ(total[1].xx, 1.0);
    EXPECT_NEAR(strain_measures(total[0]).shear, std::sqrt(std::pow(0.16 / 4.0, 2) + 0.16 / 4.0), 1e-15);
}

TEST(Faults, AStageCountsOnceTwoOutputsInARowShowItAndIsKept) {
    // Per-output stages 1 1 2 1 2 2 3 2 1: reached 1 from the second output,
    // 2 from the sixth, never 3 (one output only), and never back.
    const int per_output[] = {1, 1, 2, 1, 2, 2, 3, 2, 1};
    const int want[] = {0, 1, 1, 1, 1, 2, 2, 2, 2};
    int reached = 0, last = 0;
    for (std::size_t k = 0; k < std::size(per_output); ++k) {
        reached = stage_reached(reached, last, per_output[k]);
        last = per_output[k];
        EXPECT_EQ(reached, want[k]) << "output " << k;
    }
}
