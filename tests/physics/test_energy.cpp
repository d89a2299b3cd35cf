// Energy conservation of the undamped, frictionless model (RELIABILITY
// CHECKLIST #13): a dense, compressed box of polydisperse discs with random
// initial velocities, integrated by velocity Verlet at the default timestep.
//
// Set-up: no damping (all dashpot coefficients 0), no friction
// (LawParams::tangential = false: no tangential spring, no Coulomb force, so
// spins never change), smooth walls, no gravity. Then the model is a
// conservative system of piecewise-quadratic pair potentials ½ k_n δ² (δ > 0),
// and the exact total energy
//   E = ½ Σ m v² + ½ Σ I ω² + ½ k_n Σ_pairs δ² + ½ k_n Σ_walls δ²
// (Simulation::energies().total()) is constant. Velocity Verlet is
// symplectic: E is not conserved exactly but oscillates around a conserved
// "shadow" energy, with no secular drift for smooth forces; the kinks of the
// force at δ = 0 (contacts opening and closing) add small errors that are,
// on average, a gain (quantified below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "orodem/core/rng.hpp"
#include "orodem/physics/stability.hpp"
#include "test_util.hpp"

using namespace orodem;

namespace {

Wall smooth_line(Vec2 a, Vec2 b) {
    Wall w;
    w.a = a;
    w.b = b;
    w.infinite = true;
    w.rough = false;
    return w;
}

}  // namespace

TEST(EnergyConservation, DenseBoxNoDampingNoFriction) {
    // A triangular lattice of 18 x 17 = 306 polydisperse discs, R uniform in
    // [0.8, 1.0] m, at spacing a = 1.75 m < mean R_i + R_j = 1.8 m, in a box
    // of four smooth walls that leave the outer discs overlapping them: the
    // packing is compressed (positive pressure) and nearly every disc touches
    // its neighbours.
    const double rho = 1.0, k_n = 1.0e5;
    const double a = 1.75, dy = a * std::sqrt(3.0) / 2.0, x0 = 0.85;
    const int rows = 18, cols = 17;
    Rng rng(1);

    LawParams law;
    law.k_n = k_n;
    law.k_s = 0.0;
    law.mu = 0.0;
    law.tangential = false;  // frictionless: no tangential force, no history
    // all damping coefficients stay 0 (LawParams defaults)

    Simulation sim = test::make_sim({}, law, 0.0, {0.0, 0.0}, rho);
    double r_min = 1e300, m_min = 1e300;
    for (int row = 0; row < rows; ++row)
        for (int col = 0; col < cols; ++col) {
            const double r = rng.uniform(0.8, 1.0);
            const std::size_t s =
                sim.particles.add({x0 + a * col + (row % 2 ? 0.5 * a : 0.0), x0 + dy * row}, r, rho);
            r_min = std::min(r_min, r);
            m_min = std::min(m_min, sim.particles.mass[s]);
        }
    const double W = x0 + a * (cols - 1) + 0.5 * a + x0;
    const double H = x0 + dy * (rows - 1) + x0;
    sim.walls.push_back(smooth_line({0.0, 0.0}, {W, 0.0}));  // floor
    sim.walls.push_back(smooth_line({0.0, H}, {W, H}));      // lid
    sim.walls.push_back(smooth_line({0.0, 0.0}, {0.0, H}));  // left
    sim.walls.push_back(smooth_line({W, 0.0}, {W, H}));      // right
    sim.params.skin = 0.4 * r_min;
    const TimestepInfo ts = choose_timestep(m_min, law, 0.0, kDefaultSafety);
    ASSERT_DOUBLE_EQ(ts.dt, kDefaultSafety * std::sqrt(m_min / k_n));  // k_max = k_n (smooth)
    sim.params.dt = ts.dt;

    // Preparation (not measured): 3000 steps (~140 collision times) with a
    // normal damping ratio of 0.5 relax the lattice to a compressed
    // equilibrium. Then the damping is switched off and random velocities are
    // given, scaled so that the kinetic energy is 2% of the elastic energy:
    // the discs vibrate with an amplitude ~ sqrt(0.02) ≈ 14% of the typical
    // overlap, so contacts persist (only the weakest open and close). That
    // matters because a contact opening or closing inside a step is a kink of
    // the force, where Verlet is not symplectic: a lone binary collision at
    // this dt gains on average +1.6e-3 of its energy (measured for this law
    // with an independent 1D Verlet, uniformly random contact phase), so a
    // gas-like box drifts by far more than 1e-4, whatever the code.
    sim.params.law.damp_sqrt_n = 2.0 * 0.5 * std::sqrt(k_n);
    sim.initialize();
    sim.advance(3000);
    sim.params.law = law;
    for (std::size_t s = 0; s < sim.particles.size(); ++s)
        sim.particles.v[s] = {rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
    const double scale = std::sqrt(0.02 * sim.energies().elastic / sim.energies().kinetic_translational);
    for (std::size_t s = 0; s < sim.particles.size(); ++s) sim.particles.v[s] = scale * sim.particles.v[s];
    sim.initialize();  // re-caches the (now undamped) wall law; forces at t = 0

    const std::size_t contacts0 = sim.touching_contacts();
    const EnergyReport e0 = sim.energies();
    const double E0 = e0.total();
    ASSERT_GT(contacts0, 2 * sim.particles.size()) << "the box should start densely in contact";

    // drift   := |mean E over steps 1..1000 - mean E over steps 99001..100000| / E0
    // max_dev := max |E - E0| / E0 over every step of the two windows and
    //            every 10th step in between (energies() costs as much as a step).
    const std::uint64_t n_steps = 100000, window = 1000;
    double sum_first = 0.0, sum_last = 0.0, max_dev = 0.0;
    for (std::uint64_t s = 1; s <= n_steps; ++s) {
        sim.step();
        const bool first = s <= window, last = s > n_steps - window;
        if (!first && !last && s % 10 != 0) continue;
        const double E = sim.energies().total();
        ASSERT_TRUE(std::isfinite(E)) << "step " << s;
        if (first) sum_first += E;
        if (last) sum_last += E;
        max_dev = std::max(max_dev, std::fabs(E - E0) / E0);
    }
    const double drift = std::fabs(sum_last - sum_first) / static_cast<double>(window) / E0;
    const std::size_t contacts1 = sim.touching_contacts();
    std::printf("[ energy ] N = %zu, dt = %.4g s, E0 = %.6g J (kinetic %.3g, elastic %.3g), "
                "contacts %zu -> %zu, rebuilds %llu\n"
                "[ energy ] drift = %.3e (%.3e of the initial kinetic energy), max |E - E0|/E0 = %.3e\n",
                sim.particles.size(), ts.dt, E0, e0.kinetic_translational, e0.elastic, contacts0,
                contacts1, static_cast<unsigned long long>(sim.rebuild_count()), drift,
                drift * E0 / e0.kinetic_translational, max_dev);

    // The premise held: contacts persisted (at most 5% of them opened for good).
    EXPECT_GT(static_cast<double>(contacts1), 0.95 * static_cast<double>(contacts0));
    // The requirement (RELIABILITY #13, zero damping): drift below 1e-4 of E0
    // over 1e5 steps at the default safety factor.
    EXPECT_LT(drift, 1.0e-4);
    // Instantaneous deviation: for a Verlet harmonic mode the energy
    // oscillates about the shadow energy with relative amplitude at most
    // (ω dt)²/4 of that mode's energy, and the stiffest mode of the packing
    // has ω² ≤ 2 z_max k_n / m_min = 12 k_n/m_min (Gershgorin, stability.hpp),
    // so |E - E0|/E0 ≤ 12 · 0.1² / 4 = 0.03 even if all energy sat in it.
    EXPECT_LT(max_dev, 12.0 * kDefaultSafety * kDefaultSafety / 4.0);
}
