// The tangential spring of the contact law (SPEC §1, eq. 1, [25]): history
// ξ = ∫ v_t dt, F_t = -k_s ξ (no tangential dashpot here), Coulomb limit
// |F_t| ≤ μ F_n + C, and on sliding ξ rescaled so the spring sits on the limit.
//
// References are exact: with γ_s = 0 and a constant tangential speed u the
// history after N steps of length dt is N u dt (a sum of identical terms), so
// the force is -k_s N u dt until |F_t| would exceed F_max, and F_max itself is
// μ(k_n δ) + C. The only error is floating-point rounding of sums of O(100)
// terms, hence the relative tolerance 1e-12 (1e4 ulp; still 1e9 times smaller
// than one step's force increment k_s u dt / F_max ~ 1e-2).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "orodem/physics/contact_law.hpp"
#include "test_util.hpp"

using namespace orodem;

namespace {

constexpr double kRel = 1e-12;

using test::SerialOmp;

LawParams spring_law(double mu, double cohesion) {
    LawParams law;
    law.k_n = 1.0e6;
    law.k_s = 5.0e5;
    law.mu = mu;
    law.cohesion = cohesion;
    return law;  // no damping: F_t = -k_s ξ exactly
}

// Drives the pair of eval_contact with tangential relative velocity `u` along
// t̂ at fixed overlap for `steps` steps; returns F_t·t̂ after the last step.
struct Driver {
    LawParams law;
    Vec2 n, t;
    double delta, dt;
    Vec2 xi{};
    PairForce last{};
    double step(double u) {
        const PairKinematics kin{n, delta, u * t, 0.0, 1.0};
        last = eval_contact<false>(law, kin, dt, xi);
        return dot(last.f, t);
    }
    double f_n() const { return dot(last.f, n); }
};

Driver make_driver(double mu, double cohesion) {
    const double a = 0.7;  // a tilted contact: both components of n̂ and t̂ matter
    Driver d{spring_law(mu, cohesion), {std::cos(a), std::sin(a)}, {-std::sin(a), std::cos(a)}, 1.0e-3, 1.0e-3};
    return d;
}

}  // namespace

// Below the Coulomb limit the spring is elastic: F_t = -k_s ξ with ξ the
// accumulated tangential displacement, and unloading to zero displacement
// leaves zero force (no permanent slip).
TEST(TangentialSpring, ElasticBelowLimitAndReversible) {
    Driver d = make_driver(0.4, 0.0);
    const double u = 0.01;                           // [m/s]
    const double inc = d.law.k_s * u * d.dt;         // 5 N per step
    const double f_max = d.law.mu * d.law.k_n * d.delta;  // 400 N
    const int n_load = 60;                           // 300 N < f_max
    for (int k = 1; k <= n_load; ++k) {
        const double ft = d.step(u);
        const double disp = k * u * d.dt;  // accumulated tangential displacement
        ASSERT_NEAR(ft, -d.law.k_s * disp, kRel * f_max) << "step " << k;
        ASSERT_NEAR(dot(d.xi, d.t), disp, kRel * disp);
        ASSERT_NEAR(d.f_n(), d.law.k_n * d.delta, kRel * f_max);
        // Torque convention: c = n̂ × F_t.
        ASSERT_NEAR(d.last.c, cross(d.n, ft * d.t), kRel * f_max);
    }
    EXPECT_LT(std::fabs(d.step(0.0)), f_max);
    EXPECT_NEAR(d.step(0.0), -inc * n_load, kRel * f_max);  // holding still: force stays
    for (int k = 1; k <= n_load; ++k) {
        const double ft = d.step(-u);
        ASSERT_NEAR(ft, -inc * (n_load - k), kRel * f_max) << "unloading step " << k;
    }
    // Back at zero displacement: zero force, zero history.
    EXPECT_NEAR(d.step(0.0), 0.0, kRel * f_max);
    EXPECT_NEAR(norm(d.xi), 0.0, kRel * f_max / d.law.k_s);
}

// At the limit |F_t| = μ F_n + C exactly; ξ is rescaled to F_max/k_s, so on
// reversal the force leaves the limit at once (one step's increment) and the
// zero-force position is shifted by the slip.
TEST(TangentialSpring, CoulombLimitAndSlidingRescale) {
    for (const double cohesion : {0.0, 150.0}) {
        Driver d = make_driver(0.4, cohesion);
        const double u = 0.01;
        const double inc = d.law.k_s * u * d.dt;                       // 5 N
        const double f_max = d.law.mu * d.law.k_n * d.delta + cohesion;  // 400 or 550 N
        const int n_stick = static_cast<int>(std::floor(f_max / inc));  // last elastic step
        const int n_load = 3 * n_stick;                                  // deep into sliding
        for (int k = 1; k <= n_load; ++k) {
            const double ft = d.step(u);
            if (k <= n_stick) {
                ASSERT_NEAR(ft, -inc * k, kRel * f_max) << "C=" << cohesion << " step " << k;
            } else {
                ASSERT_NEAR(ft, -f_max, kRel * f_max) << "C=" << cohesion << " step " << k;
                ASSERT_NEAR(norm(d.last.f - d.f_n() * d.n), f_max, kRel * f_max);
                // Sliding rescale: the spring alone sits on the limit.
                ASSERT_NEAR(d.law.k_s * dot(d.xi, d.t), f_max, kRel * f_max);
            }
        }
        // Reverse: the force magnitude drops by one increment at the very first step.
        const double first = d.step(-u);
        EXPECT_NEAR(first, -(f_max - inc), kRel * f_max) << "C=" << cohesion;
        // Unloading is elastic from the limit: zero force after f_max/inc steps
        // in all, i.e. a permanent slip of (n_load - f_max/inc) u dt.
        const double steps_to_zero = f_max / inc;  // 80 or 110 exactly
        const int n_back = static_cast<int>(std::lround(steps_to_zero));
        ASSERT_NEAR(steps_to_zero, n_back, 1e-9);
        for (int k = 2; k <= n_back; ++k) {
            const double ft = d.step(-u);
            ASSERT_NEAR(ft, -(f_max - inc * k), kRel * f_max) << "C=" << cohesion << " back " << k;
        }
        EXPECT_NEAR(d.step(0.0), 0.0, kRel * f_max);
        // Continue to the opposite limit: +F_max.
        for (int k = 1; k <= 2 * n_back; ++k) d.step(-u);
        EXPECT_NEAR(d.step(-u), f_max, kRel * f_max) << "C=" << cohesion;
    }
}

// The same through a Simulation: disc j held fixed with ParticleStore::fix,
// disc i pinned in place (fixed too, so δ and n̂ stay exactly constant) but
// given a prescribed spin, which slides its contact point at speed R_i ω_i.
// Checks the history stored in the ContactStore between steps, the force on
// both discs, the torques -R c on each, the limit with cohesion and the
// reversal from the limit.
TEST(TangentialSpring, ThroughSimulationWithSpinningDisc) {
    const SerialOmp serial;
    for (const double cohesion : {0.0, 150.0}) {
        LawParams law = spring_law(0.4, cohesion);
        const double R = 0.5, delta = 1.0e-3, dt = 1.0e-3;
        const double a = 0.7;
        const Vec2 n{std::cos(a), std::sin(a)};  // from j (id 0) to i (id 1)
        const Vec2 t{-n.y, n.x};
        Simulation sim =
            test::make_sim({{{0.0, 0.0}, R}, {(2.0 * R - delta) * n, R}}, law, dt, {0.0, 0.0}, 2500.0);
        sim.particles.fix(0);
        sim.particles.fix(1);
        const double omega = 0.02;  // [rad/s]: contact point speed R ω = 0.01 m/s
        sim.particles.omega[1] = omega;
        sim.initialize();

        // v_t of i's contact point relative to j: spin R ω along (n_y, -n_x) = -t̂.
        const double u = -R * omega;  // along t̂
        const double inc = law.k_s * std::fabs(u) * dt;
        const double f_n = law.k_n * delta;
        const double f_max = law.mu * f_n + cohesion;
        const int n_stick = static_cast<int>(std::floor(f_max / inc));
        auto force_on_i = [&]() {
            const auto& p = sim.particles;
            return p.force[p.slot_of_id[1]];
        };
        auto check_pair = [&](double ft_expected, const char* what, int k) {
            const auto& p = sim.particles;
            const std::size_t si = p.slot_of_id[1], sj = p.slot_of_id[0];
            const Vec2 fi = p.force[si];
            ASSERT_NEAR(dot(fi, n), f_n, 1e-9 * f_n) << what << k;  // δ is exact to ~1e-16 m
            ASSERT_NEAR(dot(fi, t), ft_expected, kRel * f_max) << what << k;
            ASSERT_NEAR(p.force[sj].x, -fi.x, kRel * f_max);
            ASSERT_NEAR(p.force[sj].y, -fi.y, kRel * f_max);
            const double c = cross(n, dot(fi, t) * t);
            ASSERT_NEAR(p.torque[si], -R * c, kRel * R * f_max);
            ASSERT_NEAR(p.torque[sj], -R * c, kRel * R * f_max);
        };
        // Loading: the force opposes the sliding of i's contact point (u < 0 → F_t·t̂ > 0).
        const int n_load = 2 * n_stick;
        for (int k = 1; k <= n_load; ++k) {
            sim.step();
            const double expected = k <= n_stick ? inc * k : f_max;
            check_pair(expected, "load step ", k);
            if (HasFatalFailure()) return;
        }
        EXPECT_NEAR(norm(force_on_i() - f_n * n), f_max, kRel * f_max);
        // Reverse the spin: the force leaves the limit at the first step.
        sim.particles.omega[sim.particles.slot_of_id[1]] = -omega;
        for (int k = 1; k <= 10; ++k) {
            sim.step();
            check_pair(f_max - inc * k, "reverse step ", k);
            if (HasFatalFailure()) return;
        }
        // Position held fixed throughout.
        EXPECT_EQ(sim.particles.x[sim.particles.slot_of_id[1]].x, ((2.0 * R - delta) * n).x);
    }
}
