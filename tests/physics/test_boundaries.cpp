// The wedge experiments' boundary conditions (SPEC §2): the conveyor base
// (eq. 5 traction capped by μ_bp N), the Coulomb retroside (a stationary
// rough wall), the fixed retroside, the eq. 6 check, and make_wedge.
//
// Common material: the config defaults (k_n = 1e8 N/m, k_s = k_n/3,
// restitution 0.5, no tangential dashpot, μ_i = 0.3), ρ = 2500 kg/m³, discs
// of R = 0.5 m (m = 1963.5 kg) and the default timestep
// dt = 0.1 sqrt(m/k_n) = 4.43e-4 s, for which the eq. 6 bound is
// m g/(k_n dt) = 0.435 m/s.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/coulomb_base.hpp"
#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"
#include "layer_util.hpp"
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

Wall segment(Vec2 a, Vec2 b) {
    Wall w;
    w.a = a;
    w.b = b;
    return w;
}

Vec2 pos_of(const Simulation& sim, std::uint32_t id) { return sim.particles.x[sim.particles.slot_of_id[id]]; }
Vec2 vel_of(const Simulation& sim, std::uint32_t id) { return sim.particles.v[sim.particles.slot_of_id[id]]; }

}  // namespace

// ---------------------------------------------------------------------------
// 1. Conveyor base: one disc on a smooth open-ended base y = 0 with the eq. 5
// traction F = (g_b m/dt)(v' − v_x), |F| ≤ μ_bp N, gain g_b = 1.
//
// The disc starts at its static overlap m g/k_n at rest; the base is smooth
// and horizontal and the traction is horizontal, so N = m g to round-off
// throughout. The traction is evaluated with the half-step velocity
// v_{n+1/2} (forces follow the drift) and acts in two half kicks, so between
// consecutive force evaluations v_{n+3/2} = v_{n+1/2} + g_b (v' − v_{n+1/2})
// when uncapped: with g_b = 1 the disc is exactly at the belt speed after one
// uncapped step and the traction then vanishes (a free disc transmits
// nothing, so it does not lag). While |v' − v| > μ_bp N dt/m = μ_bp g dt
// (1.3e-3 m/s here) the cap binds and the disc accelerates at exactly
// μ_bp N/m = μ_bp g, reaching the belt after v'/(μ_bp g dt) ≈ 77 steps for
// v' = 0.1 m/s.
// ---------------------------------------------------------------------------

namespace {

struct BeltSim {
    Simulation sim;
    ConveyorTraction* base = nullptr;
};

/// A disc at x = -16 m on the base from -64 to 64 m (powers of two, so the
/// contact point is computed exactly). stop: a smooth fixed vertical wall
/// touching the disc's front (walls[1]).
BeltSim belt_sim(double v_belt, double mu_bp, bool stop, double drag_gain = 0.0) {
    const double m = disc_mass();
    const LawParams law = default_law();
    const double delta0 = m * kG / law.k_n;
    BeltSim b{test::make_sim({{{-16.0, kR - delta0}, kR}}, law, default_dt(), {0.0, -kG}, kRho)};
    Wall base = segment({-64.0, 0.0}, {64.0, 0.0});
    base.open_ends = true;
    b.sim.walls.push_back(base);
    if (stop) b.sim.walls.push_back(segment({-16.0 + kR, 0.0}, {-16.0 + kR, 10.0}));
    auto traction = std::make_unique<ConveyorTraction>(0, v_belt, mu_bp, 1.0, drag_gain);
    b.base = traction.get();
    b.sim.boundaries.push_back(std::move(traction));
    b.sim.initialize();
    return b;
}

/// Normal force of the base on the single disc [N]: the base is horizontal,
/// so it is the y component of the disc's force on the wall, reversed.
double base_normal(const Simulation& sim) { return -sim.wall_force(0).y; }

}  // namespace

TEST(ConveyorBase, DiscReachesBeltSpeedWithCappedAcceleration) {
    const SerialOmp serial;
    const double v_belt = 0.1, mu_bp = 0.3;
    BeltSim b = belt_sim(v_belt, mu_bp, false);
    Simulation& sim = b.sim;
    const double m = disc_mass(), dt = sim.params.dt;
    const double mg = m * kG;

    int capped_steps = 0, over_cap = 0, off_base = 0;
    double worst_cap_excess = 0.0;   // max (|T| - μN)/(μN)
    double worst_capped_gap = 0.0;   // max | |T| - μN | / (μN) over capped steps
    double worst_accel = 0.0;        // max |a/(μN/m) - 1| over consecutive capped steps
    double worst_n = 0.0;            // max |N/(m g) - 1|
    double worst_belt = 0.0;         // max |v - v'|/v' from step 200 on
    bool prev_capped = false;
    double prev_v = 0.0, prev_n = 0.0;
    const int n_steps = 2000;
    for (int s = 1; s <= n_steps; ++s) {
        sim.step();
        const double n = base_normal(sim);
        const double t = b.base->total_traction();
        const double v = vel_of(sim, 0).x;
        worst_n = std::max(worst_n, std::fabs(n / mg - 1.0));
        worst_cap_excess = std::max(worst_cap_excess, (std::fabs(t) - mu_bp * n) / (mu_bp * n));
        if (std::fabs(t) > mu_bp * n * (1.0 + 1e-14)) ++over_cap;
        if (b.base->discs_on_base() != 1) ++off_base;
        const bool capped = b.base->discs_sliding() == 1;
        if (capped) {
            ++capped_steps;
            worst_capped_gap = std::max(worst_capped_gap, std::fabs(std::fabs(t) - mu_bp * n) / (mu_bp * n));
            // Both half kicks of this step's velocity change come from capped
            // forces: a = (F_prev + F_now)/(2m).
            if (prev_capped) {
                const double a = (v - prev_v) / dt;
                const double a_ref = mu_bp * 0.5 * (prev_n + n) / m;
                worst_accel = std::max(worst_accel, std::fabs(a / a_ref - 1.0));
            }
        }
        if (s >= 200) worst_belt = std::max(worst_belt, std::fabs(v - v_belt) / v_belt);
        prev_capped = capped;
        prev_v = v;
        prev_n = n;
    }
    const double capped_ref = v_belt / (mu_bp * kG * dt);
    std::printf("  belt v'=%.3f mu_bp=%.2f: capped for %d steps (ref v'/(mu g dt) = %.2f), |N/mg-1| <= %.2e, "
                "cap excess %.2e, | |T|-muN |/muN when capped <= %.2e, |a/(muN/m)-1| <= %.2e, "
                "|v-v'|/v' after step 200 <= %.2e, final v = %.17g\n",
                v_belt, mu_bp, capped_steps, capped_ref, worst_n, worst_cap_excess, worst_capped_gap, worst_accel,
                worst_belt, vel_of(sim, 0).x);
    // N is the weight: the disc started at its static overlap and nothing
    // acts vertically but gravity and the base (1e-12: round-off of k_n δ).
    EXPECT_LT(worst_n, 1e-12);
    // The cap is applied to the same floats it is checked against: any
    // excess is round-off (1e-14 is ~50 ulp).
    EXPECT_EQ(over_cap, 0);
    EXPECT_LT(worst_capped_gap, 1e-14);
    // The disc is on the base in every step, also when it rides exactly at v'
    // and the traction is zero.
    EXPECT_EQ(off_base, 0);
    // Capped acceleration: Δv = F dt/m with F = μ_bp N; Δv ≈ 1.3e-3 m/s is a
    // difference of velocities ≲ 0.1 m/s, so round-off is ~1e-17/1.3e-3 ≈ 1e-14
    // of it; 1e-10 leaves room for N's 1e-12 variation.
    EXPECT_GT(capped_steps, 0);
    EXPECT_LT(worst_accel, 1e-10);
    // The cap binds until the disc is within μ g dt of v', i.e. for
    // v'/(μ g dt) steps, give or take the one partial step.
    EXPECT_NEAR(capped_steps, capped_ref, 1.5);
    // At the belt speed: the uncapped step with gain 1 lands on v' and the
    // traction then corrects any round-off in one step, so the error does not
    // accumulate: a few ulp of v' (1e-12 relative is ~5000 ulp).
    EXPECT_LT(worst_belt, 1e-12);
}

TEST(ConveyorBase, FrictionlessBaseExertsNoTraction) {
    const SerialOmp serial;
    const double v_belt = 0.1;
    BeltSim b = belt_sim(v_belt, 0.0, false);
    Simulation& sim = b.sim;
    const double x0 = pos_of(sim, 0).x;
    double worst_v = 0.0, worst_t = 0.0;
    int off_base = 0;
    for (int s = 0; s < 2000; ++s) {
        sim.step();
        worst_v = std::max(worst_v, std::fabs(vel_of(sim, 0).x));
        worst_t = std::max(worst_t, std::fabs(b.base->total_traction()));
        if (b.base->discs_on_base() != 1) ++off_base;
    }
    const double dx = pos_of(sim, 0).x - x0;
    std::printf("  mu_bp = 0, v' = %.2f: max |v_x| = %.3e m/s, max |traction| = %.3e N, x drift = %.3e m\n", v_belt,
                worst_v, worst_t, dx);
    // Cap μ_bp N = 0: no traction at all; nothing else acts along x (smooth
    // horizontal base, vertical gravity), so v_x stays zero to round-off of
    // the contact normal (1e-12 of the belt speed is far below anything the
    // traction would give: v' itself in one step).
    EXPECT_EQ(worst_t, 0.0);
    EXPECT_LT(worst_v, 1e-12 * v_belt);
    // Still on the base (pressed by its weight) though it gets no traction.
    EXPECT_EQ(off_base, 0);
    EXPECT_LT(std::fabs(dx), 1e-12);
}

TEST(ConveyorBase, DiscHeldByWallGetsExactlyMuN) {
    const SerialOmp serial;
    // A disc that cannot follow the belt (a fixed smooth wall in front of it):
    // the cap binds in every step and the base pushes it into the wall with
    // exactly μ_bp N; once the normal bounce against the wall has died away
    // the wall carries that force.
    const double v_belt = 0.1, mu_bp = 0.3;
    BeltSim b = belt_sim(v_belt, mu_bp, true);
    Simulation& sim = b.sim;
    const double mg = disc_mass() * kG;
    int not_capped = 0;
    double worst_gap = 0.0;
    const int n_steps = static_cast<int>(std::ceil(0.5 / sim.params.dt));
    for (int s = 0; s < n_steps; ++s) {
        sim.step();
        const double n = base_normal(sim);
        if (b.base->discs_sliding() != 1) ++not_capped;
        worst_gap = std::max(worst_gap, std::fabs(b.base->total_traction() - mu_bp * n) / (mu_bp * n));
    }
    const double f_wall = sim.wall_force(1).x;
    std::printf("  held disc: steps not capped %d of %d, max |T - muN|/muN = %.2e, wall force %.9g N "
                "(ref mu m g = %.9g N, err %.2e), disc v_x %.2e m/s\n",
                not_capped, n_steps, worst_gap, f_wall, mu_bp * mg, f_wall / (mu_bp * mg) - 1.0, vel_of(sim, 0).x);
    // The bounce against the wall: |v_x| ≲ (μ m g/k_n) sqrt(k_n/m) = 0.013 m/s,
    // always far more than μ g dt = 1.3e-3 m/s below v', so always capped.
    EXPECT_EQ(not_capped, 0);
    EXPECT_LT(worst_gap, 1e-14);
    // Normal damping (restitution 0.5: ζ = 0.215, ω = sqrt(k_n/m) = 226/s)
    // decays the bounce as exp(-ζ ω t) = 3e-11 after 0.5 s; 1e-6 is generous.
    EXPECT_NEAR(f_wall / (mu_bp * mg), 1.0, 1e-6);
}

// The optional uncapped drag γ_d (v' − v), γ_d = g_d m/dt (wedge.drag_gain).
// On a frictionless base it is the only horizontal force: between force
// evaluations the half-step slip v' − v shrinks by (1 − g_d), and the full-step
// velocity (a fixed blend of two consecutive half-step ones) by the same
// factor, so the slip ratio of consecutive steps is 1 − g_d to round-off.
TEST(ConveyorBase, DragAloneClosesTheSlipByOneMinusGdPerStep) {
    const SerialOmp serial;
    const double v_belt = 0.1, g_d = 0.25;
    BeltSim b = belt_sim(v_belt, 0.0, false, g_d);
    Simulation& sim = b.sim;
    double prev_slip = v_belt, worst = 0.0;
    int steps = 0;
    while (prev_slip > 1e-7 * v_belt) {
        sim.step();
        const double slip = v_belt - vel_of(sim, 0).x;
        if (steps > 0) worst = std::max(worst, std::fabs(slip / prev_slip - (1.0 - g_d)));
        prev_slip = slip;
        ASSERT_LT(++steps, 200);
        ASSERT_EQ(b.base->discs_on_base(), 1u);
        EXPECT_EQ(b.base->discs_sliding(), 1u);  // its capped part is held at μ_bp N = 0 while it slips
    }
    std::printf("  mu_bp = 0, g_d = %.2f: slip below 1e-7 v' after %d steps; max |ratio - (1 - g_d)| = %.2e\n", g_d,
                steps, worst);
    // 1e-7 v' is reached after ln(1e-7)/ln(0.75) = 56 steps (plus the first
    // step's half kick); the ratio of two slips >= 1e-8 m/s computed from
    // velocities of 0.1 m/s carries round-off of 1e-17/1e-8 = 1e-9.
    EXPECT_LE(steps, 58);
    EXPECT_LT(worst, 1e-8);
}

// A held disc (the wall in front of it) transmits the Coulomb cap plus the
// full drag at zero velocity: μ_bp m g + g_d m v'/dt, carried by the wall.
TEST(ConveyorBase, DiscHeldByWallGetsMuNPlusTheDrag) {
    const SerialOmp serial;
    const double v_belt = 0.1, mu_bp = 0.3, g_d = 0.05;
    BeltSim b = belt_sim(v_belt, mu_bp, true, g_d);
    Simulation& sim = b.sim;
    const double m = disc_mass(), dt = sim.params.dt;
    const double ref = mu_bp * m * kG + g_d * m * v_belt / dt;
    const int n_steps = static_cast<int>(std::ceil(0.5 / dt));
    int not_capped = 0;
    for (int s = 0; s < n_steps; ++s) {
        sim.step();
        if (b.base->discs_sliding() != 1) ++not_capped;
    }
    const double f_wall = sim.wall_force(1).x;
    std::printf("  held disc with drag: wall force %.9g N (ref mu m g + g_d m v'/dt = %.9g N, of which drag %.4g N; "
                "err %.2e), traction %.9g N\n",
                f_wall, ref, g_d * m * v_belt / dt, f_wall / ref - 1.0, b.base->total_traction());
    EXPECT_EQ(not_capped, 0);
    // The drag is 3.8 times μ m g here, so the stronger push bounces the disc
    // harder than in DiscHeldByWallGetsExactlyMuN; its decay is the same
    // exp(-ζ ω t) = 3e-11 over 0.5 s, and the drag itself damps further.
    EXPECT_NEAR(f_wall / ref, 1.0, 1e-6);
    EXPECT_NEAR(b.base->total_traction() / ref, 1.0, 1e-6);
}

// ---------------------------------------------------------------------------
// 2. Coulomb retroside (exp3): a stationary rough wall with μ_br holds a
// block until the horizontal push reaches μ_br N.
//
// Block: one 3-disc cluster (three bonded discs, R = 0.5 m, flat side down:
// two contacts with the wall, one disc on top), N = W = 3 m g. A single disc
// would roll instead of sliding. The push is applied as equal forces F/3 at
// the three disc centres (a horizontal body force acting at the centroid,
// height h = (1 + 1/√3) R above the wall). The wall's tangential force
// cannot exceed μ_br (N_front + N_rear) = μ_br W whatever the split of W
// between the two contacts, so the block slides at F = μ_br W. The push
// shifts load to the front contact, N_rear = W/2 - F h/(2R) (moments about
// the front contact), which stays positive up to F = μ_br W for
// μ_br < R/h = 0.63: μ_br = 0.4. The rear contact reaches its own limit
// first (at F = μ_br W/(1 + μ_br h/R) = 0.61 μ_br W) and slips a little,
// handing load to the front spring: at most the rear's share of F over k_s.
//
// Ramp: F = r t, r = 1.5 μ_br W / T, T = 20 s (the block's tangential mode,
// ω = sqrt(2 k_s/(3m)) ≈ 106/s, sees a quasi-static load). Onset: the first
// step in which the block's mean velocity exceeds v_th = 10 r/k_s. Stuck,
// the block moves only with its elastic deflection, which grows with F at
// ≲ 2 r/k_s (wall springs, bond springs and disc rotations in series, each
// no softer than one k_s carrying F), and the oscillation the ramp's start
// excites is of the same order: 10× is a safe margin. Sliding, it
// accelerates at (F - μ_br W)/M and reaches v_th when
// F - μ_br W = sqrt(2 M v_th r), i.e. 0.45% of μ_br W: a detection delay well
// inside the 2% tolerance.
//
// Stuck reference: the same ramp on a wall with μ = 10 (no contact can
// slip) gives the block's purely elastic displacement.
// ---------------------------------------------------------------------------

namespace {

/// Pushes a set of discs with a horizontal force ramped linearly in time,
/// shared equally among them.
class RampPush : public Boundary {
public:
    RampPush(std::vector<std::uint32_t> ids, double rate, double t0) : ids_(std::move(ids)), rate_(rate), t0_(t0) {}
    std::string_view name() const override { return "test-ramp-push"; }
    void add_forces(Simulation& sim) override {
        // Forces belong to the end of the step under way: t + dt.
        const double t = sim.time + sim.params.dt - t0_;
        force_ = t > 0.0 ? rate_ * t : 0.0;
        const double share = force_ / static_cast<double>(ids_.size());
        for (const std::uint32_t id : ids_) sim.particles.force[sim.particles.slot_of_id[id]].x += share;
    }
    double force() const { return force_; }

private:
    std::vector<std::uint32_t> ids_;
    double rate_;   // [N/s]
    double t0_;     // ramp start [s]
    double force_ = 0.0;  // total push this step [N]
};

struct PushRun {
    double onset = -1.0;     // push when sliding was detected [N]; -1: never
    double disp_90 = NAN;    // displacement when the push first reached 0.9 μ_br W [m]
    double disp_onset = NAN; // displacement at the onset [m]
    double disp_after = NAN; // displacement 2000 steps after the onset [m]
};

/// The cluster on a rough wall of friction mu_wall, pushed with F = rate t
/// after 0.5 s of rest; stops 2000 steps after the onset (velocity above
/// v_th) or when F reaches f_stop.
PushRun push_cluster(double mu_wall, double rate, double v_th, double f_90, double f_stop) {
    const LawParams law = default_law();
    const double m = disc_mass(), W = 3.0 * m * kG;
    const double delta0 = 0.5 * W / law.k_n;  // half the weight on each bottom contact
    const double h = kR - delta0;
    Simulation sim = test::make_sim({{{-kR, h}, kR, {}, 0.0, 0},
                                     {{kR, h}, kR, {}, 0.0, 0},
                                     {{0.0, h + std::sqrt(3.0) * kR}, kR, {}, 0.0, 0}},
                                    law, default_dt(), {0.0, -kG}, kRho);
    Wall wall = segment({-50.0, 0.0}, {50.0, 0.0});
    wall.rough = true;
    wall.mu = mu_wall;
    sim.walls.push_back(wall);
    // Let the bonds take the top disc's weight before pushing (the vertical
    // bounce decays with the normal damping in ~0.1 s).
    const double t_settle = 0.5;
    auto push = std::make_unique<RampPush>(std::vector<std::uint32_t>{0, 1, 2}, rate, t_settle);
    RampPush* pusher = push.get();
    sim.boundaries.push_back(std::move(push));
    sim.initialize();
    EXPECT_EQ(sim.bonds.bond_count(), 3u);

    auto centroid_x = [&]() { return (pos_of(sim, 0).x + pos_of(sim, 1).x + pos_of(sim, 2).x) / 3.0; };
    auto velocity_x = [&]() { return (vel_of(sim, 0).x + vel_of(sim, 1).x + vel_of(sim, 2).x) / 3.0; };
    while (sim.time < t_settle) sim.step();
    const double x0 = centroid_x();
    PushRun r;
    while (pusher->force() < f_stop) {
        sim.step();
        if (std::isnan(r.disp_90) && pusher->force() >= f_90) r.disp_90 = centroid_x() - x0;
        if (std::fabs(velocity_x()) > v_th) {
            r.onset = pusher->force();
            r.disp_onset = centroid_x() - x0;
            sim.advance(2000);
            r.disp_after = centroid_x() - x0;
            break;
        }
    }
    return r;
}

}  // namespace

TEST(CoulombRetroside, ClusterSlidesWhenPushReachesMuN) {
    const SerialOmp serial;
    const double mu_br = 0.4, T = 20.0;
    const LawParams law = default_law();
    const double M = 3.0 * disc_mass(), W = M * kG;
    const double limit = mu_br * W;
    const double rate = 1.5 * limit / T;
    const double v_th = 10.0 * rate / law.k_s;
    const PushRun r = push_cluster(mu_br, rate, v_th, 0.9 * limit, 1.5 * limit);
    const PushRun stuck = push_cluster(10.0, rate, v_th, 0.9 * limit, 0.9 * limit);
    const double elastic = limit / law.k_s;  // one wall spring carrying μ_br W [m]
    std::printf("  cluster on mu_br = %.2f: sliding onset at F = %.2f N = %.5f mu W (mu W = %.2f N; "
                "expected detection delay %.2e mu W); displacement at 0.9 mu W %.4e m (stuck, mu = 10: %.4e m, "
                "difference %.3e m; mu W/k_s = %.3e m), at onset %.4e m, 2000 steps later %.3e m\n",
                mu_br, r.onset, r.onset / limit, limit, std::sqrt(2.0 * M * v_th * rate) / limit, r.disp_90,
                stuck.disp_90, r.disp_90 - stuck.disp_90, elastic, r.disp_onset, r.disp_after);
    ASSERT_GT(r.onset, 0.0) << "the block never slid";
    EXPECT_NEAR(r.onset / limit, 1.0, 0.02);
    // The stuck block never reached v_th: the threshold is above the elastic motion.
    EXPECT_LT(stuck.onset, 0.0);
    // Below the limit there is no creep: the displacement is the elastic one
    // plus the rear contact's partial slip, at most its share of F over k_s
    // (< μ_br W/k_s). Sliding would instead move it by metres.
    EXPECT_GT(stuck.disp_90, 0.0);
    EXPECT_LT(std::fabs(r.disp_90 - stuck.disp_90), elastic);
    // Above the limit it slides away: in 2000 steps (0.89 s) of F - μ_br W
    // growing from ~0 at r, it moves r t³/(6M) ≈ 3.5 cm, ≫ the elastic scale.
    EXPECT_GT(r.disp_after - r.disp_onset, 10.0 * elastic);
}

// ---------------------------------------------------------------------------
// 3. Fixed retroside (exp1, exp2): a disc that touches the retroside base is
// held fixed from then on, however it is pushed.
//
// walls[0]: smooth retroside base y = 0, x ∈ [0, 20], open ends, with
// FixedRetroside; walls[1]: a smooth vertical wall moving at +0.1 m/s that
// reaches disc A at t ≈ 0.5 s and keeps driving into it (1e7 N by the end).
// Disc A drops onto the base and is fixed; disc B then drops onto A
// off-centre (hitting it obliquely), rolls off it and falls to the base,
// where it is fixed in turn.
// ---------------------------------------------------------------------------

TEST(FixedRetroside, DiscTouchingBaseNeverMovesAgain) {
    const SerialOmp serial;
    const LawParams law = default_law();
    const double dt = default_dt();
    const double xa = 5.0;
    const double yb = 0.5 + 0.005 + std::sqrt(1.0 - 0.3 * 0.3) + 0.05;  // 5 cm above touching A
    Simulation sim = test::make_sim({{{xa, kR + 0.005}, kR, {0.0, -0.2}},  // A: 5 mm above the base
                                     {{xa + 0.3, yb}, kR}},                // B
                                    law, dt, {0.0, -kG}, kRho);
    Wall base = segment({0.0, 0.0}, {20.0, 0.0});
    base.open_ends = true;
    sim.walls.push_back(base);
    const double v_pusher = 0.1;
    Wall pusher = segment({xa - kR - 0.05, 0.0}, {xa - kR - 0.05, 5.0});
    pusher.velocity = {v_pusher, 0.0};
    sim.walls.push_back(pusher);
    auto fixed = std::make_unique<FixedRetroside>(0);
    FixedRetroside* fr = fixed.get();
    sim.boundaries.push_back(std::move(fixed));
    sim.initialize();

    const ParticleStore& p = sim.particles;
    auto is_fixed = [&](std::uint32_t id) { return (p.flags[p.slot_of_id[id]] & kFlagFixed) != 0; };
    auto touches_base = [&](std::uint32_t id) {
        const std::size_t s = p.slot_of_id[id];
        const WallContactStore& ws = sim.wall_contacts;
        for (std::uint32_t k = ws.begin[s]; k < ws.begin[s + 1]; ++k)
            if (ws.wall[k] == 0 && (ws.f[k].x != 0.0 || ws.f[k].y != 0.0)) return true;
        return false;
    };
    EXPECT_EQ(fr->fixed_count(), 0u);

    std::vector<std::int64_t> fixed_at(2, -1);  // step at which each disc was fixed
    std::vector<Vec2> fixed_pos(2);
    int moved_after_fixing = 0, touching_not_fixed = 0, fixed_before_touch = 0;
    double b_travel_free = 0.0;   // B's largest distance from its start while A is fixed and B is free [m]
    double a_push_max = 0.0;      // largest force of the pusher on the discs [N]
    double ab_force_max = 0.0;    // largest A-B contact force while A is fixed [N]
    const Vec2 b0 = pos_of(sim, 1);
    const int n_steps = static_cast<int>(std::ceil(1.5 / dt));
    for (int s = 1; s <= n_steps; ++s) {
        const bool was_fixed[2] = {is_fixed(0), is_fixed(1)};
        sim.step();
        for (std::uint32_t id = 0; id < 2; ++id) {
            const bool touch = touches_base(id);
            if (touch && !is_fixed(id)) ++touching_not_fixed;
            if (!was_fixed[id] && is_fixed(id)) {
                if (!touch) ++fixed_before_touch;
                fixed_at[id] = s;
                fixed_pos[id] = pos_of(sim, id);
            }
            if (fixed_at[id] >= 0) {
                const Vec2 x = pos_of(sim, id), v = vel_of(sim, id);
                if (x.x != fixed_pos[id].x || x.y != fixed_pos[id].y || v.x != 0.0 || v.y != 0.0)
                    ++moved_after_fixing;
            }
        }
        if (fixed_at[0] >= 0 && !is_fixed(1)) b_travel_free = std::max(b_travel_free, norm(pos_of(sim, 1) - b0));
        a_push_max = std::max(a_push_max, -sim.wall_force(1).x);  // the wall pushes +x
        if (fixed_at[0] >= 0)
            for (std::size_t k = 0; k < sim.contacts.size(); ++k) ab_force_max = std::max(ab_force_max, norm(sim.contacts.f[k]));
    }
    const double steps_fixed_a = static_cast<double>(n_steps - fixed_at[0]);
    std::printf("  fixed retroside: A fixed at step %lld (t = %.4f s), B at step %lld (t = %.4f s); B travelled "
                "%.3f m while free; A-B contact force up to %.3e N, pusher force on fixed discs up to %.3e N; %d moves after fixing over %.0f "
                "steps of A; fixed count %zu\n",
                static_cast<long long>(fixed_at[0]), static_cast<double>(fixed_at[0]) * dt,
                static_cast<long long>(fixed_at[1]), static_cast<double>(fixed_at[1]) * dt, b_travel_free,
                ab_force_max, a_push_max, moved_after_fixing, steps_fixed_a, fr->fixed_count());
    // A falls 5 mm starting at 0.2 m/s: t = (sqrt(0.2² + 2 g 0.005) - 0.2)/g;
    // the first contact registers at the end of the step in which it happens.
    ASSERT_GE(fixed_at[0], 1);
    const double t_fall = (std::sqrt(0.2 * 0.2 + 2.0 * kG * 0.005) - 0.2) / kG;
    EXPECT_NEAR(static_cast<double>(fixed_at[0]) * dt, t_fall + 0.5 * dt, 0.5 * dt + 1e-12);
    // Every disc with a base contact force is fixed at the end of that step,
    // no disc is fixed without one, and a fixed disc's position stays
    // bit-identical (and its velocity zero) to the end.
    EXPECT_EQ(touching_not_fixed, 0);
    EXPECT_EQ(fixed_before_touch, 0);
    EXPECT_EQ(moved_after_fixing, 0);
    // It was pushed: by B (at least B's weight while B rested on it) and by
    // the pusher, which drives 0.1 m/s × ~1 s into it: k_n × ~0.1 m.
    EXPECT_GT(ab_force_max, disc_mass() * kG);
    EXPECT_GT(a_push_max, 0.5 * law.k_n * v_pusher * (1.5 - 0.55));
    // B, not touching the base, moved freely over and off A before it reached
    // the base: beside A it is at least (0.7, -1.0) m, 1.22 m, from its start.
    EXPECT_GT(b_travel_free, 1.0);
    ASSERT_GE(fixed_at[1], 1) << "B never reached the base";
    EXPECT_GT(fixed_at[1], fixed_at[0]);
    EXPECT_EQ(fr->fixed_count(), 2u);
}

// ---------------------------------------------------------------------------
// 4. Eq. 6: v' < m_min g/(k_n dt), checked before a run.
// ---------------------------------------------------------------------------

namespace {

std::string exp1_text(const std::string& v) {
    return "[run]\nexperiment = \"exp1\"\n[wedge]\nbase_law = \"traction\"\nv = " + v +
           "\ns_max = 1.0\npro_margin = 3.0\nretro_length = 2.0\n[packing]\nh0 = 4.0\n";
}

}  // namespace

TEST(Eq6, BeltSpeedBoundIsEnforced) {
    const Config c = parse_config(exp1_text("50.0"), "eq6.toml");
    const double bound = belt_speed_limit(c);
    // Independent recomputation: lightest disc r_min = 0.5 m of the default
    // clusters, dt from the default safety 0.1.
    const double m_min = c.material.density * M_PI * c.packing.r_min * c.packing.r_min;
    const double dt = 0.1 * std::sqrt(m_min / c.material.k_n);
    const double bound_ref = m_min * c.numerics.gravity / (c.material.k_n * dt);
    std::printf("  eq. 6 bound %.9g m/s (independent %.9g m/s)\n", bound, bound_ref);
    EXPECT_NEAR(bound / bound_ref, 1.0, 1e-12);

    std::string msg;
    try {
        check_belt_speed(c);
    } catch (const ConfigError& e) {
        msg = e.what();
    }
    std::printf("  v = 50: %s\n", msg.c_str());
    ASSERT_FALSE(msg.empty()) << "v = 50 m/s was accepted";
    EXPECT_NE(msg.find("wedge.v"), std::string::npos);
    EXPECT_NE(msg.find(fmt::format("{:g}", bound)), std::string::npos) << "the bound is not in the message";
    EXPECT_NE(msg.find("eq6.toml"), std::string::npos);
    EXPECT_THROW(make_wedge(c, ParticleStore{}), ConfigError);

    // Just below passes, at and just above fails (v' < bound strictly).
    auto with_v = [&](double v) { return parse_config(exp1_text(fmt::format("{:.17g}", v)), "eq6.toml"); };
    EXPECT_NO_THROW(check_belt_speed(with_v(bound * (1.0 - 1e-9))));
    EXPECT_THROW(check_belt_speed(with_v(bound)), ConfigError);
    EXPECT_THROW(check_belt_speed(with_v(bound * (1.0 + 1e-9))), ConfigError);
}

// ---------------------------------------------------------------------------
// 5. make_wedge. Geometry on a tiny hand-built layer: two hexagonal rows of
// R = 0.5 m discs filling x ∈ [0, L] edge to edge, L = (s_max + pro_margin +
// retro_length) h0 = (1 + 3 + 2) × 2 m = 12 m, cut at h0 = 2 m (cut_layer
// keeps both rows, drops a third). Dynamics on a generated, settled and cut
// layer (a perfect hexagonal layer cannot thrust: its straight bottom row
// only compresses between the trailing wall and the fixed retroside).
// ---------------------------------------------------------------------------

TEST(WedgeSetup, TinyLayerGeometry) {
    const Config c = parse_config(
        "[run]\nexperiment = \"exp1\"\n[wedge]\nv = 0.2\nmu_bp = 0.3\ns_max = 1.0\npro_margin = 3.0\n"
        "retro_length = 2.0\n[packing]\nkind = \"hexagonal\"\nr_min = 0.5\nr_max = 0.5\nh0 = 2.0\n",
        "tiny.toml");
    const double h0 = c.packing.h0, v = c.wedge.v;
    ASSERT_DOUBLE_EQ(c.packing.length, 12.0);
    ParticleStore layer;
    for (int i = 0; i < 12; ++i) layer.add({kR + i, kR}, kR, c.material.density);
    for (int i = 0; i < 11; ++i) layer.add({2.0 * kR + i, kR + std::sqrt(3.0) * kR}, kR, c.material.density);
    layer.add({kR, kR + 2.0 * std::sqrt(3.0) * kR}, kR, c.material.density);  // above h0: cut
    cut_layer(layer, h0);
    ASSERT_EQ(layer.size(), 23u);

    const WedgeSetup w = make_wedge(c, layer);
    const Simulation& sim = w.sim;
    const ParticleStore& p = sim.particles;
    const double pro = (c.wedge.s_max + c.wedge.pro_margin) * h0, retro = c.wedge.retro_length * h0;
    EXPECT_DOUBLE_EQ(w.pro_length, pro);
    EXPECT_DOUBLE_EQ(w.retro_length, retro);
    double lo = 1e300, hi = -1e300;
    int wrong_side = 0, retro_discs = 0;
    for (std::size_t s = 0; s < p.size(); ++s) {
        lo = std::min(lo, p.x[s].x - p.radius[s]);
        hi = std::max(hi, p.x[s].x + p.radius[s]);
        if (p.side[s] != (p.x[s].x > 0.0 ? 1 : 0)) ++wrong_side;
        retro_discs += p.side[s];
    }
    std::printf("  layer spans [%.12g, %.12g] m (ref [%g, %g]); %d retroside discs of %zu\n", lo, hi, -pro, retro,
                retro_discs, p.size());
    // The layer filled [0, L] edge to edge, shifted by -pro exactly (1e-12 m:
    // one subtraction's round-off).
    EXPECT_NEAR(lo, -pro, 1e-12);
    EXPECT_NEAR(hi, retro, 1e-12);
    EXPECT_EQ(wrong_side, 0);
    EXPECT_EQ(retro_discs, 4 + 3);  // bottom row x = 0.5..3.5, top row x = 1..3 (x = 0 is proside)
    ASSERT_EQ(sim.walls.size(), 4u);
    const Wall& pro_end = sim.walls[kWallProEnd];
    EXPECT_EQ(pro_end.velocity.x, v);
    EXPECT_EQ(pro_end.velocity.y, 0.0);
    EXPECT_EQ(pro_end.a.x, -pro);
    EXPECT_EQ(sim.walls[kWallRetroEnd].a.x, retro);
    EXPECT_EQ(sim.walls[kWallRetroEnd].velocity.x, 0.0);
    EXPECT_EQ(sim.walls[kWallProBase].b.x, 0.0);
    EXPECT_TRUE(sim.walls[kWallProBase].open_ends);
    EXPECT_FALSE(sim.walls[kWallProBase].rough);
    EXPECT_EQ(sim.walls[kWallRetro].a.x, 0.0);
    EXPECT_TRUE(sim.walls[kWallRetro].open_ends);
    EXPECT_FALSE(sim.walls[kWallRetro].rough);
    ASSERT_NE(w.base, nullptr);
    ASSERT_NE(w.fixed_retro, nullptr);
    EXPECT_EQ(w.base->v_belt(), v);
    EXPECT_EQ(w.base->mu_b(), c.wedge.mu_bp);

    // The same layer as exp3: the retroside base is a stationary Coulomb
    // base with μ_br (the default law), or a rough wall under the traction law.
    Config c3 = c;
    c3.run.experiment = "exp3";
    const WedgeSetup w3 = make_wedge(c3, layer);
    EXPECT_FALSE(w3.sim.walls[kWallRetro].rough);
    ASSERT_NE(w3.retro_base, nullptr);
    EXPECT_EQ(w3.retro_base->wall(), kWallRetro);
    EXPECT_EQ(w3.retro_base->v_belt(), 0.0);
    EXPECT_DOUBLE_EQ(w3.retro_base->mu_b(), c3.wedge.mu_br_over_mu_bp * c3.wedge.mu_bp);
    EXPECT_EQ(w3.base->name(), "coulomb-base");
    EXPECT_EQ(w3.fixed_retro, nullptr);
    c3.wedge.base_law = BaseLaw::traction;
    const WedgeSetup t3 = make_wedge(c3, layer);
    EXPECT_TRUE(t3.sim.walls[kWallRetro].rough);
    EXPECT_DOUBLE_EQ(t3.sim.walls[kWallRetro].mu, c3.wedge.mu_br_over_mu_bp * c3.wedge.mu_bp);
    EXPECT_EQ(t3.retro_base, nullptr);
    EXPECT_EQ(t3.base->name(), "conveyor-traction");
}

TEST(WedgeSetup, ConveyorCarriesIncomingPlate) {
    const SerialOmp serial;
    // The paper's material (random 3-disc clusters, R ∈ [0.5, 0.75] m), a
    // thin layer h0 = 3 m, and an incoming plate of (s_max + pro_margin) h0 =
    // 11 h0 as in the paper's set-up (pro_margin 10), long enough for the
    // basal traction to carry it into the wedge rather than the trailing wall
    // having to push it.
    const Config c = parse_config(
        "[run]\nexperiment = \"exp1\"\n[wedge]\nv = 0.2\nmu_bp = 0.3\ns_max = 1.0\npro_margin = 10.0\n"
        "retro_length = 2.0\n[packing]\nkind = \"clusters\"\nr_min = 0.5\nr_max = 0.75\nh0 = 3.0\n",
        "tiny.toml");
    const double h0 = c.packing.h0, v = c.wedge.v, g = c.numerics.gravity;
    Simulation settle_sim = make_settle_simulation(c);
    settle_sim.initialize();
    const SettleProgress sp = settle(settle_sim, c.packing, 0.05, {});
    ParticleStore layer = std::move(settle_sim.particles);
    cut_layer(layer, h0);
    double layer_lo = 1e300, layer_hi = -1e300;
    for (std::size_t s = 0; s < layer.size(); ++s) {
        layer_lo = std::min(layer_lo, layer.x[s].x - layer.radius[s]);
        layer_hi = std::max(layer_hi, layer.x[s].x + layer.radius[s]);
    }
    WedgeSetup w = make_wedge(c, layer);
    Simulation& sim = w.sim;
    const ParticleStore& p = sim.particles;
    const double pro = w.pro_length, retro = w.retro_length;
    double lo = 1e300, hi = -1e300, m_pro = 0.0;
    int wrong_side = 0;
    for (std::size_t s = 0; s < p.size(); ++s) {
        lo = std::min(lo, p.x[s].x - p.radius[s]);
        hi = std::max(hi, p.x[s].x + p.radius[s]);
        if (p.side[s] != (p.x[s].x > 0.0 ? 1 : 0)) ++wrong_side;
        if (p.x[s].x < 0.0) m_pro += p.mass[s];
    }
    std::printf("  settled in %llu steps; %zu discs; layer [%.6f, %.6f] m in the box [0, %g]; placed at "
                "[%.6f, %.6f] m (ref [%g, %g])\n",
                static_cast<unsigned long long>(sp.step), p.size(), layer_lo, layer_hi, c.packing.length, lo, hi,
                -pro, retro);
    // Shifted by -pro_length (1e-12 m: one subtraction's round-off) and so
    // inside [-pro, retro] up to the settled discs' overlap with the box's
    // side walls (≲ 1% of a radius: 1e-2 m is generous). The cut may leave a
    // gap at an end where a cluster's centre lay above h0.
    EXPECT_NEAR(lo, layer_lo - pro, 1e-12);
    EXPECT_NEAR(hi, layer_hi - pro, 1e-12);
    EXPECT_GT(lo, -pro - 1e-2);
    EXPECT_LT(hi, retro + 1e-2);
    EXPECT_EQ(wrong_side, 0);

    sim.initialize();
    const WallContactStore& ws = sim.wall_contacts;
    auto on_pro_base = [&](std::size_t s) {
        for (std::uint32_t k = ws.begin[s]; k < ws.begin[s + 1]; ++k)
            if (ws.wall[k] == kWallProBase && ws.f[k].y > 0.0) return true;
        return false;
    };
    // Every retroside disc that touches the base at the start is fixed after
    // the first step.
    std::size_t retro_touching = 0;
    for (std::size_t s = 0; s < p.size(); ++s)
        for (std::uint32_t k = ws.begin[s]; k < ws.begin[s + 1]; ++k)
            if (ws.wall[k] == kWallRetro && ws.f[k].y > 0.0) ++retro_touching;
    sim.step();
    EXPECT_GT(retro_touching, 0u);
    EXPECT_GE(w.fixed_retro->fixed_count(), retro_touching);
    int miscounted = 0;
    auto run = [&](int n) {
        for (int k = 0; k < n; ++k) {
            sim.step();
            std::size_t touching = 0;
            for (std::size_t s = 0; s < p.size(); ++s) touching += on_pro_base(s) ? 1 : 0;
            if (touching != w.base->discs_on_base()) ++miscounted;
        }
    };
    // 0.89 s of start-up (the plate compacts against the fixed retroside),
    // then a window of 1.77 s (0.35 m of convergence).
    run(1999);
    std::vector<std::uint32_t> far_ids;
    std::vector<double> x_start;
    for (std::size_t s = 0; s < p.size(); ++s)
        if (p.x[s].x < sim.walls[kWallProEnd].a.x + 2.0 * h0 && on_pro_base(s)) {
            far_ids.push_back(p.id[s]);
            x_start.push_back(p.x[s].x);
        }
    ASSERT_GE(far_ids.size(), 3u);
    const double t_start = sim.time;
    run(4000);
    const double window = sim.time - t_start;
    double mean = 0.0;
    std::printf("  far proside base discs' mean v_x/v' - 1 over %.3f s:", window);
    for (std::size_t k = 0; k < far_ids.size(); ++k) {
        const double dev = (pos_of(sim, far_ids[k]).x - x_start[k]) / (v * window) - 1.0;
        std::printf(" %.4f", dev);
        mean += dev / static_cast<double>(far_ids.size());
    }
    // Coulomb lag of the smallest disc under the mean column of the plate,
    // the largest a disc that rides the belt while transmitting μ_bp N can
    // fall behind (docs/experiments.md): μ_bp N dt/m with
    // N = (W_pro/L_pro) 2 r_min.
    const double m_min = c.material.density * M_PI * c.packing.r_min * c.packing.r_min;
    const double n_col = m_pro * g / pro * 2.0 * c.packing.r_min;
    const double lag = c.wedge.mu_bp * n_col * sim.params.dt / m_min / v;
    const double wall_moved = sim.walls[kWallProEnd].a.x + pro;
    std::printf("\n  mean %.4f (Coulomb lag bound %.4f, N_col/(m_min g) = %.2f); trailing wall moved %.15g m "
                "(v t = %.15g m); fixed retroside discs %zu (%zu touching at the start); discs on the base %zu, at the cap %zu; "
                "discs_on_base miscounted in %d steps\n",
                mean, lag, n_col / (m_min * g), wall_moved, v * sim.time, w.fixed_retro->fixed_count(), retro_touching,
                w.base->discs_on_base(), w.base->discs_sliding(), miscounted);
    // The far discs ride the belt: on average they neither lag by more than
    // the Coulomb lag nor run ahead of it (only the trailing wall, itself at
    // v', could push them faster).
    EXPECT_LT(std::fabs(mean), lag);
    // The wall moves by v dt each step: 6000 steps accumulate ~6000 ulp of 33 m.
    EXPECT_NEAR(wall_moved, v * sim.time, 1e-9);
    // discs_on_base() counts every disc the base pushes, including those
    // riding exactly at v' (zero traction).
    EXPECT_EQ(miscounted, 0);
}

TEST(WedgeSetup, OnAFrictionlessBaseTheTrailingWallAloneDrivesThePlate) {
    // μ_bp = 0: the belt exerts no traction and the trailing wall, moving at
    // v', is the only drive; series.csv reports its push on the plate as
    // trailing_wall_push = -wall_force(kWallProEnd).x. Newton for all discs
    // along x (the smooth base and gravity act along y, contacts cancel):
    // Δ(Σ m v_x) = Σ dt (push - F_backstop) over the steps.
    const SerialOmp serial;
    const Config c = parse_config(
        "[run]\nexperiment = \"critical-wedge\"\n[wedge]\nv = 0.2\nmu_bp = 0.0\ns_max = 1.0\npro_margin = 2.0\n"
        "[packing]\nkind = \"clusters\"\nr_min = 0.5\nr_max = 0.75\nh0 = 3.0\n",
        "frictionless.toml");
    WedgeSetup w = make_wedge(c, test::settled_cut_layer(c));
    Simulation& sim = w.sim;
    sim.initialize();
    const double dt = sim.params.dt;
    sim.advance(static_cast<std::uint64_t>(std::llround(0.3 * c.packing.h0 / (c.wedge.v * dt))));
    auto momentum = [&] {
        double m = 0.0;
        for (std::size_t s = 0; s < sim.particles.size(); ++s) m += sim.particles.mass[s] * sim.particles.v[s].x;
        return m;
    };
    const double p0 = momentum();
    double impulse = 0.0, push_sum = 0.0, back_sum = 0.0, scale = 0.0, largest = 0.0;
    constexpr int kSteps = 3000;
    for (int k = 0; k < kSteps; ++k) {
        sim.step();
        const double push = -sim.wall_force(kWallProEnd).x, back = sim.wall_force(kWallRetro).x;
        impulse += dt * (push - back);
        scale += dt * std::fabs(push);
        largest = std::max(largest, std::fabs(push) + std::fabs(back));
        push_sum += push;
        back_sum += back;
    }
    const double dp = momentum() - p0;
    std::printf("  mean push of the trailing wall %.6g N/m, on the backstop %.6g N/m; momentum change %.6g vs "
                "impulse %.6g N s/m (of %.6g)\n",
                push_sum / kSteps, back_sum / kSteps, dp, impulse, scale);
    EXPECT_GT(push_sum, 0.0);  // the wall pushes the plate toward the S point
    // Velocity Verlet applies the average of consecutive steps' forces: the
    // sums differ by half a step's net force at each end, at most one step's
    // impulse (3e-5 of the total here).
    EXPECT_NEAR(dp, impulse, dt * largest);
    // Quasi-static: what the wall puts in, the backstop takes (to 10%).
    EXPECT_NEAR(back_sum / push_sum, 1.0, 0.1);
}
