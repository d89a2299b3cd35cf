// A settled layer in the settling box of make_settle_simulation (rough floor,
// smooth side walls): the floor carries the whole weight.
//
// Reference: momentum balance. The forces on the discs are gravity Σ m g,
// the floor, and the side walls; disc-disc pairs and bonds cancel pairwise
// (Newton's third law). The side walls are smooth and vertical, so their
// force on a disc is horizontal: they carry no vertical load. Hence
//   F_floor,y - M g = Σ m a_y = dP_y/dt,
// and once the layer is at rest the floor's vertical force equals the weight
// M g = g Σ ρ π R_i², computed here independently from the radii.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"

using namespace orodem;

namespace {

void check_floor_carries_weight(PackingKind kind, std::uint64_t seed) {
    SCOPED_TRACE(name_of(kind));
    Config c;
    c.material.density = 2500.0;  // [kg/m³]
    c.material.k_n = 1.0e8;       // [N/m]
    c.material.k_s_over_k_n = 1.0 / 3.0;
    c.material.mu = 0.3;
    c.packing.kind = kind;
    c.packing.r_min = 0.5;    // [m]
    c.packing.r_max = 1.0;    // [m]
    c.packing.length = 20.0;  // [m]
    c.packing.h0 = 6.0;       // [m]: ~90 discs
    c.packing.seed = seed;
    c.numerics.gravity = 9.81;
    Simulation sim = make_settle_simulation(c);
    ASSERT_EQ(sim.walls.size(), 3u);
    ASSERT_FALSE(sim.walls[1].rough);
    ASSERT_FALSE(sim.walls[2].rough);
    sim.initialize();
    const ParticleStore& p = sim.particles;
    double M = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        M += c.material.density * std::numbers::pi * p.radius[i] * p.radius[i];
    const double g = c.numerics.gravity;
    const double weight = M * g;  // [N]

    // Settled by the project's own criterion (E_kin < 1e-6 M g h0), then
    // further to E_kin < 1e-9 M g h0.
    const SettleProgress s1 = settle(sim, c.packing, 0.05, nullptr);
    const double floor_ratio_1 = -sim.wall_force(0).y / weight;
    PackingConfig deep = c.packing;
    deep.settle_ke_ratio = 1e-9;
    deep.settle_max_steps = static_cast<std::int64_t>(s1.step) + 100000;
    const SettleProgress s2 = settle(sim, deep, 0.05, nullptr);
    const double floor_ratio_2 = -sim.wall_force(0).y / weight;

    // Reading: the floor force on the discs averaged over a window of
    // T = 0.25 s. Velocity Verlet gives P(t+T) - P(t) = Σ_steps dt (F_n +
    // F_n+1)/2 exactly, so with the trapezoid mean F̄ over the window,
    //   F̄_floor,y + F̄_sides,y - M g = ΔP_y / T,
    // and |ΔP_y| ≤ 2 max |P_y| ≤ 2 sqrt(2 M E_kin,max) (Cauchy-Schwarz).
    // The bound 2 sqrt(2 E_kin,max / M) / (g T) on the relative error is
    // computed from the measured E_kin and must itself be below the 0.5%
    // tolerance (it is ~3e-4 at E_kin = 1e-9 M g h0).
    const double dt = sim.params.dt;
    const auto n_window = static_cast<std::uint64_t>(std::ceil(0.25 / dt));
    const double T = static_cast<double>(n_window) * dt;
    Vec2 prev_floor = -1.0 * sim.wall_force(0);
    Vec2 prev_sides = -1.0 * (sim.wall_force(1) + sim.wall_force(2));
    Vec2 sum_floor{}, sum_sides{};
    double ke_max = sim.kinetic_energy();
    for (std::uint64_t k = 0; k < n_window; ++k) {
        sim.step();
        const Vec2 floor = -1.0 * sim.wall_force(0);  // force of the floor on the discs
        const Vec2 sides = -1.0 * (sim.wall_force(1) + sim.wall_force(2));
        sum_floor += (0.5 * dt) * (prev_floor + floor);
        sum_sides += (0.5 * dt) * (prev_sides + sides);
        prev_floor = floor;
        prev_sides = sides;
        ke_max = std::max(ke_max, sim.kinetic_energy());
    }
    const double mean_ratio = sum_floor.y / T / weight;
    const double bound = 2.0 * std::sqrt(2.0 * ke_max / M) / (g * T);
    const double mean_x_ratio = (sum_floor.x + sum_sides.x) / T / weight;
    const Vec2 left = sim.wall_force(1), right = sim.wall_force(2);
    std::printf("[ column ] %s: N = %zu; floor force / weight: %.5f when settled (step %llu, "
                "E_kin/(M g h0) = %.1e), %.6f at %.1e (step %llu), mean over %.2f s %.6f "
                "(momentum bound %.1e); side walls y %.1e %.1e N; mean x imbalance %.1e\n",
                name_of(kind), p.size(), floor_ratio_1, static_cast<unsigned long long>(s1.step), s1.ke_ratio,
                floor_ratio_2, s2.ke_ratio, static_cast<unsigned long long>(s2.step), T, mean_ratio, bound,
                left.y, right.y, mean_x_ratio);

    // The residual dynamics cannot account for more than the bound...
    EXPECT_LT(bound, 0.005);
    // ... so the floor carries the weight within the 0.5% requirement.
    EXPECT_NEAR(mean_ratio, 1.0, 0.005);
    // Smooth vertical walls: their force is horizontal up to the round-off of
    // the closest-point projection (~1e-16 relative, forces ~ weight).
    EXPECT_LT(std::fabs(sum_sides.y / T), 1e-9 * weight);
    EXPECT_LT(std::fabs(left.y), 1e-9 * weight);
    EXPECT_LT(std::fabs(right.y), 1e-9 * weight);
    // Horizontal balance: the floor's friction and the side walls' thrusts
    // cancel on average (same momentum argument along x, same bound).
    EXPECT_LT(std::fabs(mean_x_ratio), 0.005);
}

}  // namespace

TEST(SettledColumn, FloorCarriesTheWeightDiscs) { check_floor_carries_weight(PackingKind::discs, 3); }

TEST(SettledColumn, FloorCarriesTheWeightClusters) { check_floor_carries_weight(PackingKind::clusters, 3); }
