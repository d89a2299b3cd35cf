// Sleeping zones (engine/sleep.cpp): an incoming plate carried into a
// backstop (critical-wedge boundary conditions, a plate of 26 h0). With
// sleeping on, the far plate falls asleep; every sleeping disc moves exactly
// with the belt; the discs next to the backstop, where the wedge grows, stay
// awake; the push on the backstop and the wedge height agree with the run
// without sleeping; and a checkpoint of a run with sleeping zones restores
// and continues bit for bit, also at another thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "orodem/analysis/wedge_profile.hpp"
#include "orodem/boundary/basal_boundary.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"
#include "layer_util.hpp"
#include "test_util.hpp"

using namespace orodem;

namespace {

Config plate_config(bool sleep, const char* inertia_floor = "1.0", const char* more_wedge_keys = "") {
    return parse_config(std::string("[run]\nexperiment = \"critical-wedge\"\n[wedge]\nv = 0.2\nmu_bp = 0.3\n"
                                    "s_max = 1.0\npro_margin = 25.0\ninertia_floor = ") +
                            inertia_floor + "\n" + more_wedge_keys + "sleep = " + (sleep ? "true" : "false") +
                            "\n[packing]\nkind = \"clusters\"\nr_min = 0.5\nr_max = 0.75\n"
                            "h0 = 4.0\n",
                        "plate.toml");
}

const ParticleStore& settled_layer() {
    static const ParticleStore layer = test::settled_cut_layer(plate_config(false));
    return layer;
}

/// Mean horizontal push on the backstop over `steps` steps [N].
double mean_push(WedgeSetup& w, std::uint64_t steps) {
    double sum = 0.0;
    for (std::uint64_t k = 0; k < steps; ++k) {
        w.sim.step();
        sum += w.sim.wall_force(kWallRetro).x;
    }
    return sum / static_cast<double>(steps);
}

/// The sleeping plate carried to S = 0.3: zones in place, a wedge growing.
WedgeSetup sleeping_plate(const Config& c) {
    WedgeSetup w = make_wedge(c, settled_layer());
    w.sim.initialize();
    w.sim.advance(static_cast<std::uint64_t>(std::llround(0.3 * c.packing.h0 / (c.wedge.v * w.sim.params.dt))));
    return w;
}

/// An exact copy of w's simulation (same slots and zones) through a checkpoint.
WedgeSetup copy_through_checkpoint(const WedgeSetup& w, const Config& c) {
    const std::uint64_t hash = config_hash(c);
    WedgeSetup b = make_wedge(c, ParticleStore{});
    RunLoopState back;
    decode_checkpoint(encode_checkpoint(w.sim, RunLoopState{}, hash), hash, b.sim, back);
    return b;
}

}  // namespace

TEST(Sleep, FarPlateSleepsMovesWithTheBeltAndLeavesTheWedgeUnchanged) {
    const test::SerialOmp serial;
    const Config c_off = plate_config(false), c_on = plate_config(true);
    const double h0 = c_on.packing.h0, v = c_on.wedge.v;
    WedgeSetup off = make_wedge(c_off, settled_layer());
    WedgeSetup on = make_wedge(c_on, settled_layer());
    off.sim.initialize();
    on.sim.initialize();
    const double dt = on.sim.params.dt;
    // To S = 0.5 (the plate at belt speed, a wedge against the backstop), then
    // the push averaged over S = 0.5 ... 0.7.
    const auto steps = static_cast<std::uint64_t>(std::llround(0.5 * h0 / (v * dt)));
    const auto window = static_cast<std::uint64_t>(std::llround(0.2 * h0 / (v * dt)));
    off.sim.advance(steps);
    on.sim.advance(steps);
    const double push_off = mean_push(off, window), push_on = mean_push(on, window);
    const ParticleStore& p = on.sim.particles;
    const std::size_t asleep = on.sim.sleeping_count();
    std::size_t flagged = 0, wrong_velocity = 0, near_backstop = 0;
    for (std::size_t s = 0; s < p.size(); ++s) {
        if (!(p.flags[s] & kFlagAsleep)) continue;
        ++flagged;
        if (p.v[s].x != v || p.v[s].y != 0.0 || p.omega[s] != 0.0 || p.inv_mass[s] != 0.0) ++wrong_velocity;
        if (p.x[s].x > -2.0 * h0) ++near_backstop;
    }
    const WedgeMeasures m_off = measure_wedge(off.sim.particles, off.profile, v * off.sim.time);
    const WedgeMeasures m_on = measure_wedge(on.sim.particles, on.profile, v * on.sim.time);
    std::printf("  %zu discs, %zu asleep; push on the backstop %.6g N (sleeping) vs %.6g N; H/h0 %.4f vs %.4f\n",
                p.size(), asleep, push_on, push_off, m_on.H_over_h0, m_off.H_over_h0);
    // Most of the 26 h0 plate is more than the 2 h0 buffer from the wedge.
    EXPECT_GT(asleep, p.size() / 3);
    EXPECT_EQ(flagged, asleep);
    EXPECT_EQ(wrong_velocity, 0u);
    EXPECT_EQ(near_backstop, 0u);  // the wedge and the buffer stay awake

    // Rigid motion: a disc asleep at both ends of 200 steps (at most one
    // rebuild falls in them; they are thousands of steps apart) moved by
    // exactly 200 v dt, up to the round-off of 200 additions at |x| ~ 30 m.
    std::vector<Vec2> x0(p.size());
    std::vector<char> was_asleep(p.size());
    for (std::size_t s = 0; s < p.size(); ++s) {
        x0[p.id[s]] = p.x[s];
        was_asleep[p.id[s]] = (p.flags[s] & kFlagAsleep) != 0;
    }
    const std::uint64_t r_before = on.sim.rebuild_count();
    on.sim.advance(200);
    ASSERT_LE(on.sim.rebuild_count() - r_before, 1u);
    double worst = 0.0;
    int compared = 0;
    for (std::size_t s = 0; s < p.size(); ++s) {
        if (!(p.flags[s] & kFlagAsleep) || !was_asleep[p.id[s]]) continue;
        ++compared;
        worst = std::max(worst, std::hypot(p.x[s].x - x0[p.id[s]].x - 200.0 * v * dt, p.x[s].y - x0[p.id[s]].y));
    }
    EXPECT_GT(compared, 0);
    EXPECT_LT(worst, 1e-11);

    // The wedge does not notice: the push and the height agree with the run
    // without sleeping to within what grain-scale chaos allows (the two runs
    // diverge at the grain scale after a few thousand steps).
    EXPECT_NEAR(push_on / push_off, 1.0, 0.1);
    EXPECT_NEAR(m_on.H_over_h0, m_off.H_over_h0, 0.05);
}

TEST(Sleep, CheckpointWithSleepingZonesContinuesBitForBit) {
    const test::SerialOmp serial;
    const Config c = plate_config(true);
    WedgeSetup a = sleeping_plate(c);
    ASSERT_GT(a.sim.sleeping_count(), 0u);
    WedgeSetup b = copy_through_checkpoint(a, c);
    EXPECT_EQ(b.sim.sleeping_count(), a.sim.sleeping_count());
    const std::uint64_t r0 = a.sim.rebuild_count();
    for (int k = 0; k < 6000; ++k) {
        omp_set_num_threads(1);
        a.sim.step();
        omp_set_num_threads(k % 2 ? 3 : 2);
        b.sim.step();
        ASSERT_EQ(b.sim.state_hash(), a.sim.state_hash()) << "diverged at step " << a.sim.step_count;
    }
    EXPECT_GT(a.sim.rebuild_count(), r0);  // the zones were re-decided on the way
    EXPECT_EQ(b.sim.sleeping_count(), a.sim.sleeping_count());
    // The same through advance(), where the far sleepers drift lazily.
    const std::uint64_t r1 = a.sim.rebuild_count();
    for (int k = 0; k < 60; ++k) {
        omp_set_num_threads(1);
        a.sim.advance(100);
        omp_set_num_threads(k % 2 ? 3 : 2);
        b.sim.advance(100);
        ASSERT_EQ(b.sim.state_hash(), a.sim.state_hash()) << "diverged by step " << a.sim.step_count;
    }
    EXPECT_GT(a.sim.rebuild_count(), r1);
}

// The proside buffer (wedge.sleep_buffer_pro): the incoming plate's awake
// margin alone. The zones' last decision puts the proside bound exactly
// sleep_buffer_pro h0 left of the leftmost active disc (the rule of
// engine/sleep.cpp), 1 h0 with the key and 2 h0 (sleep_buffer) without it;
// every free disc left of the bound, less a cell column of rounding (2 r_max
// + skin, under 2 m here) and the belt's motion since the rebuild, sleeps,
// and none right of it does. A key that did nothing, or set the retroside's
// margin, fails the first check.
TEST(Sleep, ProsideBufferSetsTheIncomingPlatesAwakeMargin) {
    const test::SerialOmp serial;
    const Config c2 = plate_config(true), c1 = plate_config(true, "1.0", "sleep_buffer_pro = 1.0\n");
    ASSERT_DOUBLE_EQ(c2.wedge.sleep_buffer_pro, 2.0);  // absent: sleep_buffer
    ASSERT_DOUBLE_EQ(c1.wedge.sleep_buffer, 2.0);
    const double h0 = c2.packing.h0;
    for (const auto& [c, buffer] : {std::pair{c2, 2.0 * h0}, std::pair{c1, 1.0 * h0}}) {
        const WedgeSetup w = sleeping_plate(c);
        const Simulation::SleepDecision& d = w.sim.last_sleep_decision();
        ASSERT_TRUE(std::isfinite(d.active_min));
        EXPECT_DOUBLE_EQ(std::min(d.active_min, 0.0) - d.x_lo, buffer);
        EXPECT_TRUE(std::isinf(d.x_hi));  // the backstop: no retroside zone
        const ParticleStore& p = w.sim.particles;
        std::size_t wrong = 0, asleep = 0;
        for (std::size_t s = 0; s < p.size(); ++s) {
            if (p.flags[s] & kFlagFixed) continue;
            const bool sleeps = (p.flags[s] & kFlagAsleep) != 0;
            asleep += sleeps;
            if (sleeps && p.x[s].x > d.x_lo + 0.5 * h0) ++wrong;        // beyond the bound and its rounding
            if (!sleeps && p.x[s].x < d.x_lo - 0.5 * h0) ++wrong;       // further left than a column
        }
        std::printf("  buffer %.1f m: active from x = %.2f m, bound %.2f m, %zu asleep\n", buffer, d.active_min,
                    d.x_lo, asleep);
        EXPECT_GT(asleep, 0u);
        EXPECT_EQ(wrong, 0u);
    }
}

// The inertia floor (wedge.inertia_floor) with sleeping zones: every free
// disc, the woken ones included, moves with max(m, m_f); asleep and fixed
// ones have no inverse mass; a checkpoint restores the columns and
// make_wedge the floor, so the copy continues bit for bit on 2 threads.
TEST(Sleep, InertiaFloorHoldsForWokenDiscsAndThroughACheckpoint) {
    const test::SerialOmp serial;
    const Config c = plate_config(true, "1.3");
    const double m_f = inertia_floor_mass(c);
    ASSERT_GT(m_f, 0.0);
    auto floored_free_discs = [&](const Simulation& sim) {
        const ParticleStore& p = sim.particles;
        std::size_t floored = 0;
        for (std::size_t s = 0; s < p.size(); ++s) {
            if (p.flags[s] & (kFlagFixed | kFlagAsleep)) {
                EXPECT_EQ(p.inv_mass[s], 0.0);
                continue;
            }
            EXPECT_EQ(p.inv_mass[s], 1.0 / std::max(p.mass[s], m_f)) << "disc " << p.id[s];
            floored += p.mass[s] < m_f;
        }
        return floored;
    };
    WedgeSetup a = sleeping_plate(c);
    ASSERT_GT(a.sim.sleeping_count(), 0u);
    EXPECT_GT(floored_free_discs(a.sim), 0u);
    std::vector<std::uint8_t> was_asleep(a.sim.particles.size());
    for (std::size_t s = 0; s < a.sim.particles.size(); ++s)
        was_asleep[a.sim.particles.id[s]] = (a.sim.particles.flags[s] & kFlagAsleep) != 0;
    WedgeSetup b = copy_through_checkpoint(a, c);
    EXPECT_EQ(b.sim.params.m_inertia_min, m_f);
    for (int k = 0; k < 30; ++k) {
        omp_set_num_threads(1);
        a.sim.advance(100);
        omp_set_num_threads(2);
        b.sim.advance(100);
        ASSERT_EQ(b.sim.state_hash(), a.sim.state_hash()) << "diverged by step " << a.sim.step_count;
    }
    EXPECT_GT(floored_free_discs(a.sim), 0u);
    std::size_t woken = 0;
    for (std::size_t s = 0; s < a.sim.particles.size(); ++s)
        woken += was_asleep[a.sim.particles.id[s]] && !(a.sim.particles.flags[s] & kFlagAsleep);
    std::printf("  %zu discs woke after the checkpoint\n", woken);
}

// The wedge step in one parallel region, where each thread applies the base
// law to its own gathered discs (Boundary::ForceHook::by_disc_range) and the
// sleeping base discs' slots are skipped, against the phases one by one
// (the law over every base disc on one thread), from the same state: the
// same state, base traction and counts every step, at 2 and 3 threads.
TEST(Sleep, BaseForcesPerThreadRangeMatchThePhasesOneByOne) {
    const test::SerialOmp serial;
    const Config c = plate_config(true);
    WedgeSetup a = sleeping_plate(c), b = sleeping_plate(c);
    ASSERT_EQ(b.sim.state_hash(), a.sim.state_hash());
    ASSERT_GT(a.sim.sleeping_count(), 0u);
    a.sim.one_region_min_awake = std::numeric_limits<std::size_t>::max();  // phases one by one
    b.sim.one_region_min_awake = 0;                                        // one region
    ASSERT_NE(a.base, nullptr);
    ASSERT_NE(b.base, nullptr);
    const std::uint64_t r0 = a.sim.rebuild_count();
    std::size_t sleeping_on_base = 0;
    for (int k = 0; k < 1000; ++k) {
        omp_set_num_threads(2);
        a.sim.step();
        omp_set_num_threads(k % 2 ? 3 : 2);
        b.sim.step();
        ASSERT_EQ(b.sim.state_hash(), a.sim.state_hash()) << "diverged at step " << a.sim.step_count;
        ASSERT_EQ(b.base->total_traction(), a.base->total_traction()) << "step " << a.sim.step_count;
        ASSERT_EQ(b.base->discs_on_base(), a.base->discs_on_base()) << "step " << a.sim.step_count;
        ASSERT_EQ(b.base->discs_sliding(), a.base->discs_sliding()) << "step " << a.sim.step_count;
        if (k == 0)
            for (const std::uint32_t i : b.sim.wall_discs(b.base->wall()))
                sleeping_on_base += (b.sim.particles.flags[i] & kFlagAsleep) ? 1 : 0;
    }
    EXPECT_GT(a.sim.rebuild_count(), r0);  // rebuild steps (phase by phase in both) on the way
    EXPECT_GT(b.base->discs_on_base(), 0u);
    EXPECT_GT(sleeping_on_base, 0u);  // the ranges skipped sleeping base discs
}

TEST(Sleep, LazyDriftOfTheFarSleepersMatchesDriftingThemEveryStep) {
    // advance() drifts only the awake discs and the partners of awake pairs
    // each step; the other sleepers catch up at the end. Against step() one
    // by one (every disc drifts every step) from the same state, over a
    // window without a rebuild: the awake discs are bit for bit the same
    // (what they read was computed the same way), the sleepers differ by the
    // round-off of n additions against one product.
    const test::SerialOmp serial;
    const Config c = plate_config(true);
    WedgeSetup a = sleeping_plate(c);
    // Start right after a rebuild, so that the window below holds none.
    const std::uint64_t r0 = a.sim.rebuild_count();
    while (a.sim.rebuild_count() == r0) a.sim.step();
    WedgeSetup b = copy_through_checkpoint(a, c);
    const ParticleStore& pa = a.sim.particles;
    const ParticleStore& pb = b.sim.particles;
    ASSERT_GT(a.sim.sleeping_count(), pa.size() / 3);
    const std::uint64_t r1 = a.sim.rebuild_count();
    constexpr int kSteps = 200;  // rebuilds are about 500 steps apart here
    a.sim.advance(kSteps);
    for (int k = 0; k < kSteps; ++k) b.sim.step();
    ASSERT_EQ(a.sim.rebuild_count(), r1) << "a rebuild fell in the window";
    ASSERT_EQ(b.sim.rebuild_count(), r1);
    std::size_t awake = 0, awake_differ = 0, asleep = 0;
    double worst = 0.0;
    for (std::size_t s = 0; s < pa.size(); ++s) {
        if (pa.flags[s] & kFlagAsleep) {
            ++asleep;
            worst = std::max(worst, norm(pa.x[s] - pb.x[s]));
        } else {
            ++awake;
            if (pa.x[s].x != pb.x[s].x || pa.x[s].y != pb.x[s].y || pa.v[s].x != pb.v[s].x ||
                pa.v[s].y != pb.v[s].y || pa.omega[s] != pb.omega[s] || pa.theta[s] != pb.theta[s])
                ++awake_differ;
        }
    }
    std::printf("  %zu awake (%zu differ), %zu asleep: largest sleeper offset %.3g m after %d steps\n", awake,
                awake_differ, asleep, worst, kSteps);
    EXPECT_GT(awake, 0u);
    EXPECT_GT(asleep, 0u);
    EXPECT_EQ(awake_differ, 0u);
    // |x| ~ 30 m: n additions lose at most n ulp(30 m) = 200 * 3.6e-15 m.
    EXPECT_LT(worst, 1e-11);
}
