// The Coulomb base (wedge.base_law = "coulomb"; boundary/coulomb_base.hpp):
// a spring-slider per disc against the belt, static and kinetic friction μ_bp.
//
// Material as test_boundaries.cpp: the config defaults (k_n = 1e8 N/m,
// k_s = k_n/3, restitution 0.5), ρ = 2500 kg/m³, discs of R = 0.5 m
// (m = 1963.5 kg) and dt = 0.1 sqrt(m/k_n) = 4.43e-4 s. The base spring's
// angular frequency is ω = sqrt(k_s/m) = 130 1/s and it is critically
// damped, so a disturbance dies as (1 + ωt) e^{-ωt}: below 1e-20 of itself
// after 0.45 s (1000 steps).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/coulomb_base.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/setup/scenario.hpp"
#include "default_disc.hpp"
#include "test_util.hpp"

using namespace orodem;

namespace {

using test::SerialOmp;

using test::default_dt;
using test::default_law;
using test::disc_mass;
using test::kG;
using test::kR;
using test::kRho;

struct Belt {
    Simulation sim;
    CoulombBase* base = nullptr;
};

/// discs on the base y = 0 (open ends, x from -64 to 4096 m) under gravity
/// (g_x, -g): g_x < 0 pulls every disc back against the belt with g_x/g of
/// its weight, as a block on a belt inclined by atan(-g_x/g).
Belt coulomb_belt(const std::vector<test::DiscSpec>& discs, double v_belt, double mu_bp, double g_x = 0.0) {
    Belt b;
    Simulation& sim = b.sim;
    for (const auto& d : discs) sim.particles.add(d.x, d.r, kRho, d.cluster);
    sim.params.law = default_law();
    sim.params.dt = default_dt();
    sim.params.gravity = {g_x, -kG};
    sim.params.skin = 0.4 * kR;
    Wall base;
    base.a = {-64.0, 0.0};
    base.b = {4096.0, 0.0};
    base.open_ends = true;
    sim.walls.push_back(base);
    auto law = std::make_unique<CoulombBase>(0, v_belt, mu_bp);
    b.base = law.get();
    sim.boundaries.push_back(std::move(law));
    sim.initialize();
    return b;
}

/// A disc resting on the base at x, at its static overlap m g / k_n.
test::DiscSpec resting(double x, std::int32_t cluster = -1) {
    return {{x, kR - disc_mass() * kG / default_law().k_n}, kR, {}, 0.0, cluster};
}

/// A 3-disc cluster (bonded): two discs on the base 2R apart, one on top of
/// them, each at rest; its id's discs are 3 k, 3 k + 1, 3 k + 2.
std::vector<test::DiscSpec> cluster_block(double x, std::int32_t id) {
    const double delta = disc_mass() * kG / default_law().k_n;
    return {resting(x, id), resting(x + 2.0 * kR, id), {{x + kR, kR - delta + std::sqrt(3.0) * kR}, kR, {}, 0.0, id}};
}

double base_normal(const Simulation& sim) { return -sim.wall_force(0).y; }  // the base is horizontal [N]

double mean_vx(const Simulation& sim) {
    double s = 0.0;
    for (std::size_t i = 0; i < sim.particles.size(); ++i) s += sim.particles.v[i].x;
    return s / static_cast<double>(sim.particles.size());
}

double mean_x(const Simulation& sim) {
    double s = 0.0;
    for (std::size_t i = 0; i < sim.particles.size(); ++i) s += sim.particles.x[i].x;
    return s / static_cast<double>(sim.particles.size());
}

}  // namespace

// A disc dropped at rest on the belt slides with exactly μ_bp N (it
// accelerates at μ_bp g) until it reaches the belt, then sticks and moves at
// v' itself: no lag, unlike the eq. 5 traction, whose transmitted force
// needs one. Refuted by a sliding force off μ_bp N by more than 1e-12, or a
// velocity off v' by more than 1e-12 m/s once stuck.
TEST(CoulombBase, DiscReachesTheBeltSpeedExactlyAndStaysThere) {
    const SerialOmp serial;
    const double v_belt = 0.1, mu_bp = 0.3;
    Belt b = coulomb_belt({resting(0.0)}, v_belt, mu_bp);
    Simulation& sim = b.sim;
    const double dt = sim.params.dt;
    int sliding_steps = 0;
    double worst_slide = 0.0;  // max | |T| / (μ N) - 1 | over sliding steps
    for (int s = 0; s < 1000; ++s) {
        sim.step();
        if (b.base->discs_sliding() == 1) {
            ++sliding_steps;
            worst_slide = std::max(worst_slide, std::fabs(std::fabs(b.base->total_traction()) /
                                                          (mu_bp * base_normal(sim)) - 1.0));
        }
        ASSERT_EQ(b.base->discs_on_base(), 1u) << "step " << s;
    }
    // Sliding at μ_bp g would take v'/(μ_bp g dt) = 77 steps to reach the
    // belt; the spring catches the disc before (once its force is below μ N
    // it sticks, and the spring's elastic swing carries it the rest).
    const double at_most = v_belt / (mu_bp * kG * dt);
    std::printf("  sliding steps %d (at most v'/(mu_bp g dt) = %.1f), worst |T/(mu N) - 1| %.2e\n", sliding_steps,
                at_most, worst_slide);
    EXPECT_GT(sliding_steps, 0);
    EXPECT_LE(sliding_steps, at_most);
    EXPECT_LT(worst_slide, 1e-12);
    const double x0 = sim.particles.x[0].x, t0 = sim.time;
    double worst_v = 0.0;
    for (int s = 0; s < 4000; ++s) {
        sim.step();
        worst_v = std::max(worst_v, std::fabs(sim.particles.v[0].x - v_belt));
        ASSERT_EQ(b.base->discs_sliding(), 0u) << "stuck disc slipped at step " << s;
    }
    const double moved = sim.particles.x[0].x - x0, belt = v_belt * (sim.time - t0);
    std::printf("  stuck: worst |v - v'| %.2e m/s over 4000 steps; moved %.12g m, belt %.12g m\n", worst_v, moved, belt);
    EXPECT_LT(worst_v, 1e-12);
    EXPECT_NEAR(moved, belt, 1e-9 * belt);
    EXPECT_EQ(sim.particles.omega[0], 0.0);  // the belt grips the centre: no torque, no rolling
}

// A 3-disc cluster on a belt that pulls it back with a fraction a of its
// weight (gravity tilted): with a < μ_bp it is carried at v' (static
// friction holds it; the base transmits a m g, not μ_bp N); with a > μ_bp it
// slides back relative to the belt, the base transmitting exactly μ_bp N and
// the block accelerating at (a − μ_bp) g relative to it. Refuted by a mean
// velocity below 0.99 v' in the first case (at a = 0.2: any slip, or a
// velocity off v' by 1e-6 of it), or a traction off μ_bp N by more than 1e-9
// or an acceleration off by more than 1% in the second.
TEST(CoulombBase, BlockPulledBackBelowMuBpRidesAtTheBeltAboveItSlidesWithMuBpN) {
    const SerialOmp serial;
    const double v_belt = 0.1, mu_bp = 0.3;
    for (const double a : {0.2, 0.29, 0.31, 0.4}) {
        Belt b = coulomb_belt(cluster_block(0.0, 0), v_belt, mu_bp, -a * kG);
        Simulation& sim = b.sim;
        for (int s = 0; s < 2000; ++s) sim.step();  // past the start and the spring's transient
        const double x0 = mean_x(sim), v0 = mean_vx(sim), t0 = sim.time;
        double worst_cap = 0.0;  // max | |T| / (μ N) - 1 | while sliding
        std::size_t sliding = 0;
        const int n = 4000;
        for (int s = 0; s < n; ++s) {
            sim.step();
            sliding += b.base->discs_sliding();
            if (a > mu_bp)
                worst_cap = std::max(worst_cap, std::fabs(std::fabs(b.base->total_traction()) /
                                                          (mu_bp * base_normal(sim)) - 1.0));
        }
        const double T = sim.time - t0;
        const double v_mean = (mean_x(sim) - x0) / T;
        const double accel = (mean_vx(sim) - v0) / T;
        std::printf("  a = %.2f: mean velocity %.9g m/s (v' = %g), acceleration %.6g m/s^2, sliding disc-steps %zu, "
                    "worst |T/(mu N) - 1| %.2e, traction/N %.6f\n",
                    a, v_mean, v_belt, accel, sliding, worst_cap, b.base->total_traction() / base_normal(sim));
        if (a < mu_bp) {
            EXPECT_GE(v_mean, 0.99 * v_belt);
            // Static: the base gives what is asked, a, not μ_bp.
            EXPECT_NEAR(b.base->total_traction() / base_normal(sim), a, 1e-6);
            if (a == 0.2) {  // well below μ_bp nothing slips: the block rides at v' (its bonds still ring faintly)
                EXPECT_EQ(sliding, 0u);
                EXPECT_NEAR(v_mean, v_belt, 1e-6 * v_belt);
            }  // at 0.29 the front disc, less loaded (the pull tilts the block), slips now and then
        } else {
            EXPECT_EQ(sliding, static_cast<std::size_t>(2 * n));  // both base discs slide every step
            EXPECT_LT(worst_cap, 1e-9);
            EXPECT_NEAR(accel, -(a - mu_bp) * kG, 0.01 * (a - mu_bp) * kG);
        }
    }
}

// The stationary base (v' = 0, exp3's retroside): a block pulled with less
// than μ N stays where it is, up to the spring's stretch a m g / k_s.
TEST(CoulombBase, StationaryBaseHoldsABlockBelowItsFriction) {
    const SerialOmp serial;
    Belt b = coulomb_belt(cluster_block(0.0, 0), 0.0, 0.5, -0.4 * kG);
    Simulation& sim = b.sim;
    const double x0 = mean_x(sim);
    for (int s = 0; s < 6000; ++s) sim.step();
    const double stretch = 0.4 * 3.0 * disc_mass() * kG / (2.0 * default_law().k_s);  // per base disc [m]
    std::printf("  moved %.3e m (spring stretch about %.3e m)\n", mean_x(sim) - x0, stretch);
    EXPECT_LT(std::fabs(mean_x(sim) - x0), 3.0 * stretch);
    EXPECT_LT(std::fabs(mean_vx(sim)), 1e-9);
}

namespace {

/// 5000 lone discs on the belt (more than kParallelMin, so the base's loop
/// runs in parallel) with different start velocities: some slide, some stick.
Belt many_discs() {
    std::vector<test::DiscSpec> d;
    for (int k = 0; k < 5000; ++k) {
        test::DiscSpec s = resting(0.8 * static_cast<double>(k) * 2.0 * kR);
        s.v = {0.3 * std::sin(0.7 * k), 0.0};
        d.push_back(s);
    }
    return coulomb_belt(d, 0.1, 0.3, -0.1 * kG);
}

}  // namespace

TEST(CoulombBase, IdenticalAtOneToFourThreads) {
    const int saved = omp_get_max_threads();
    std::uint64_t first = 0;
    for (int threads = 1; threads <= 4; ++threads) {
        omp_set_num_threads(threads);
        Belt b = many_discs();
        for (int s = 0; s < 300; ++s) b.sim.step();
        if (threads == 1) first = b.sim.state_hash();
        EXPECT_EQ(b.sim.state_hash(), first) << threads << " threads";
        EXPECT_GT(b.base->discs_sliding(), 0u);
        EXPECT_LT(b.base->discs_sliding(), b.base->discs_on_base());
    }
    omp_set_num_threads(saved);
}

namespace {

/// A boundary with a whole-system add_forces (the default ForceHook) that
/// adds nothing: the step then applies the bases on one thread between
/// barriers, as the boundaries that need it do.
class WholeNoOp : public Boundary {
public:
    std::string_view name() const override { return "test-whole-no-op"; }
    void add_forces(Simulation&) override {}
};

}  // namespace

// The base law applied per thread to its own discs inside the step's
// parallel region (ForceHook::by_disc_range), on one thread after phase B
// (a whole boundary beside it) and phase by phase: the same state and base
// tallies every step, for both base laws, at 1 to 3 threads.
TEST(CoulombBase, PerThreadBaseRangesMatchTheWholePass) {
    const int saved = omp_get_max_threads();
    for (int law = 0; law < 2; ++law)
        for (int threads = 1; threads <= 3; ++threads) {
            omp_set_num_threads(threads);
            Belt runs[3] = {many_discs(), many_discs(), many_discs()};
            BasalBoundary* base[3];
            for (int r = 0; r < 3; ++r) {
                if (law == 1) runs[r].sim.boundaries[0] = std::make_unique<ConveyorTraction>(0, 0.1, 0.3, 1.0);
                base[r] = static_cast<BasalBoundary*>(runs[r].sim.boundaries[0].get());
            }
            runs[0].sim.one_region_min_awake = 0;  // one region, per-thread ranges
            runs[1].sim.one_region_min_awake = 0;  // one region, the base on one thread
            runs[1].sim.boundaries.push_back(std::make_unique<WholeNoOp>());
            runs[2].sim.one_region_min_awake = std::numeric_limits<std::size_t>::max();  // phase by phase
            for (int s = 0; s < 200; ++s) {
                for (Belt& b : runs) b.sim.step();
                for (int r = 1; r < 3; ++r) {
                    ASSERT_EQ(base[r]->total_traction(), base[0]->total_traction()) << law << " " << threads << " " << r;
                    ASSERT_EQ(base[r]->discs_on_base(), base[0]->discs_on_base());
                    ASSERT_EQ(base[r]->discs_sliding(), base[0]->discs_sliding());
                }
            }
            for (int r = 1; r < 3; ++r) EXPECT_EQ(runs[r].sim.state_hash(), runs[0].sim.state_hash()) << law << " " << r;
            EXPECT_GT(base[0]->discs_sliding(), 0u);
            EXPECT_GT(base[0]->discs_on_base(), 4000u);
        }
    omp_set_num_threads(saved);
}

// A checkpoint taken while the block sticks (its springs stretched by the
// pull) continues bit for bit: the spring history is part of the state.
TEST(CoulombBase, ResumedMidStickContinuesBitForBit) {
    const SerialOmp serial;
    auto block = [] { return coulomb_belt(cluster_block(0.0, 0), 0.1, 0.3, -0.2 * kG); };
    Belt a = block();
    for (int s = 0; s < 1500; ++s) a.sim.step();
    ASSERT_EQ(a.base->discs_sliding(), 0u);
    double stretch = 0.0;
    for (const Vec2& xi : a.sim.wall_contacts.xi) stretch = std::max(stretch, norm(xi));
    ASSERT_GT(stretch, 1e-6);  // mid-stick: the springs hold the pull
    const std::string bytes = encode_checkpoint(a.sim, RunLoopState{}, 0);
    Belt b = block();
    RunLoopState run;
    decode_checkpoint(bytes, 0, b.sim, run);
    EXPECT_EQ(b.sim.state_hash(), a.sim.state_hash());
    for (int s = 0; s < 1500; ++s) {
        a.sim.step();
        b.sim.step();
    }
    EXPECT_EQ(b.sim.state_hash(), a.sim.state_hash());
    EXPECT_EQ(b.base->total_traction(), a.base->total_traction());
}

// The pure law (physics/contact_law.hpp) against hand values: below the
// limit the spring force; above it μ N with ξ rescaled onto it.
TEST(CoulombBase, SpringSliderLawByHand) {
    double xi = 0.0;
    // k_s = 100 N/m, γ = 10 N s/m, μ N = 0.3 * 50 = 15 N, slip 0.5 m/s for dt = 0.1 s.
    BaseSpringForce f = eval_base_spring(100.0, 10.0, 0.3, 50.0, 0.5, 0.1, xi);
    EXPECT_DOUBLE_EQ(xi, 0.05);
    EXPECT_DOUBLE_EQ(f.f, -100.0 * 0.05 - 10.0 * 0.5);  // -10 N, inside the limit
    EXPECT_FALSE(f.sliding);
    f = eval_base_spring(100.0, 10.0, 0.3, 50.0, 0.5, 0.1, xi);  // ξ = 0.1: -15 N... plus damping = -15 exactly
    EXPECT_FALSE(f.sliding);
    EXPECT_DOUBLE_EQ(f.f, -15.0);
    f = eval_base_spring(100.0, 10.0, 0.3, 50.0, 0.5, 0.1, xi);  // ξ = 0.15: -20 N, capped to -15 N
    EXPECT_TRUE(f.sliding);
    EXPECT_DOUBLE_EQ(f.f, -15.0);
    EXPECT_NEAR(100.0 * xi + 10.0 * 0.5, 15.0, 1e-12);  // the spring plus dashpot sit on the limit
}
