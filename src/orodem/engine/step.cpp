// Simulation::step(): one velocity-Verlet step over one of three paths, the
// same operations on the same slots in the same order on each, so the same
// results (tests/physics/test_golden.cpp pins them):
//   - no boundaries (settling, the pile): the walls move first (the kick and
//     drift do not read them), then kick and drift, phases A and B and the
//     second half kick in one parallel region, each disc kicked right after
//     its force is summed (step_without_hooks);
//   - boundaries, from one_region_min_awake awake discs on: the whole step
//     in one parallel region, the hooks on one thread between barriers,
//     the bases' forces per thread over its own discs
//     (step_hooks_in_one_region); one fork a step instead of four, about 1.35
//     times faster on 2 threads for a 10,000-disc wedge;
//   - boundaries, fewer awake discs: phase by phase (step_hooks_by_phase; the
//     barriers would cost more than the work: a demo-size wedge with about
//     1,000 awake discs ran 12% slower in one region).
// A rebuild step leaves the one-region paths after the drift and rebuilds
// outside them; it evaluates every pair and disc (fresh forces and
// diagnostics for the sleeping zones too), other steps the awake ones.
// Fewer barriers matter most on a loaded machine: a thread that is not
// running holds up every one.
#include <omp.h>

#include <cmath>

#include "orodem/engine/pair_kernel.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/engine/team.hpp"

namespace orodem {

using namespace team;

namespace {

/// Inside a parallel region, called by every thread: phase A over the
/// pairs' chunks (this thread's share first), a barrier, the master's lap,
/// then phase B over the discs' chunks.
void pairs_then_gather(const PairKernelData& kd, const GatherData& gd, StealingSplit& pairs, StealingSplit& discs,
                       PhaseClock& clock) {
    pairs.run(this_thread(), [&](std::size_t b, std::size_t e) { eval_pair_range(kd, b, e); });
#pragma omp barrier
#pragma omp master
    clock.lap(&PhaseTimes::pair_forces);
    discs.run(this_thread(), [&](std::size_t b, std::size_t e) { gather_range(gd, b, e); });
}

}  // namespace

void Simulation::step() {
    PhaseClock clock(times_);
    if (boundaries.empty())
        step_without_hooks(clock);
    else if (awake_.disc_end - awake_.disc_begin >= one_region_min_awake)
        step_hooks_in_one_region(clock);
    else
        step_hooks_by_phase(clock, false);
    ++times_.steps;
    ++step_count;
    time = static_cast<double>(step_count) * params.dt;
}

void Simulation::advance(std::uint64_t n) {
    awake_.defer_drift = params.sleep.enabled;
    for (std::uint64_t k = 0; k < n; ++k) step();
    awake_.defer_drift = false;
    catch_up_drift();
}

void Simulation::step_without_hooks(PhaseClock& clock) {
    const double wall_move = move_walls();
    clock.lap(&PhaseTimes::boundaries);
    if (!step_in_one_region(wall_move, clock)) {
        rebuild_pairs();
        ++times_.rebuilds;
        clock.lap(&PhaseTimes::rebuild);
        pair_forces_gather_kick(clock);
    }
    clock.lap(&PhaseTimes::gather);
}

void Simulation::step_hooks_in_one_region(PhaseClock& clock) {
    if (boundary_step_in_one_region(clock))
        clock.lap(&PhaseTimes::boundaries);
    else
        step_hooks_by_phase(clock, true);  // drift, walls and after_drift done; a rebuild is due
}

void Simulation::step_hooks_by_phase(PhaseClock& clock, bool drifted) {
    bool rebuilt = true;
    if (!drifted) {
        kick_drift();
        clock.lap(&PhaseTimes::integrate);
        const double wall_move = move_walls();
        for (auto& b : boundaries) b->after_drift(*this);
        clock.lap(&PhaseTimes::boundaries);
        rebuilt = needs_rebuild(wall_move);
    }
    if (rebuilt) {
        rebuild_pairs();
        ++times_.rebuilds;
    }
    clock.lap(&PhaseTimes::rebuild);
    pair_forces<true>(rebuilt);
    clock.lap(&PhaseTimes::pair_forces);
    gather_forces<true, false>(rebuilt);
    clock.lap(&PhaseTimes::gather);
    for (auto& b : boundaries) b->add_forces(*this);
    clock.lap(&PhaseTimes::boundaries);
    kick();
    clock.lap(&PhaseTimes::integrate);
    for (auto& b : boundaries) b->after_step(*this);
    clock.lap(&PhaseTimes::boundaries);
}

bool Simulation::step_in_one_region(double wall_move, PhaseClock& clock) {
    // kick_drift(), the rebuild test, pair_forces_gather_kick() in one
    // parallel region: two barriers a step (positions before phase A, forces
    // before phase B) and one fork, the fewest the data flow allows. Every
    // thread takes the same rebuild decision from the reduced maximum; on a
    // rebuild step the region ends after the drift (false).
    const KickData kk = kick_data();
    const PairKernelData kd = pair_kernel_data(true);
    const GatherData gd = gather_data(true, true);
    const std::size_t npairs = contacts.size(), n = particles.size();
    reset_splits(npairs, n, team_for(n));
    double max_d2 = max_disp2_;
    bool rebuild = false;
#pragma omp parallel if(static_cast<long long>(n) >= kParallelMin)
    {
        const long long nn = static_cast<long long>(n), chunks = kick_chunks(0, nn);
#pragma omp for schedule(static) reduction(max : max_d2)
        for (long long c = 0; c < chunks; ++c) {
            const auto [cb, ce] = kick_chunk(0, nn, c);
            max_d2 = kick_drift_range(kk, cb, ce, max_d2);
        }
        // (the loop's barrier: max_d2 is final and every position is in place)
        const bool need = force_rebuild_ || std::sqrt(max_d2) + wall_move > 0.5 * params.skin;
#pragma omp master
        {
            clock.lap(&PhaseTimes::integrate);
            rebuild = need;
        }
        if (!need) pairs_then_gather(kd, gd, pair_split_, disc_split_, clock);
    }
    max_disp2_ = max_d2;
    return !rebuild;
}

void Simulation::pair_forces_gather_kick(PhaseClock& clock) {
    // Phases A and B and the second half kick in one parallel region (a
    // rebuild step of step_without_hooks).
    const PairKernelData kd = pair_kernel_data(true);
    const GatherData gd = gather_data(true, true);
    const std::size_t npairs = contacts.size(), n = particles.size();
    reset_splits(npairs, n, team_for(n));
#pragma omp parallel if(static_cast<long long>(n) >= kParallelMin)
    pairs_then_gather(kd, gd, pair_split_, disc_split_, clock);
}

// kick_drift(), move_walls(), the after_drift hooks, pair_forces(false),
// gather_forces(false), the add_forces hooks, kick(), the after_step hooks,
// as step_hooks_by_phase runs them, in one region. When no boundary needs a
// whole add_forces (by_range), each thread applies the bases' to its own
// gathered discs and kicks those with no barrier between (the same
// operations on each disc, the same tallies).
bool Simulation::boundary_step_in_one_region(PhaseClock& clock) {
    const KickData kk = kick_data();
    long long db = 0, de = 0;
    const bool lazy = drift_range(db, de);
    const PairKernelData kd = pair_kernel_data(true);
    const GatherData gd = gather_data(true, false);
    const std::size_t pair0 = awake_.pair_begin, disc0 = awake_.disc_begin;
    bool by_range = true;
    for (const auto& bd : boundaries) by_range = by_range && bd->force_hook() != Boundary::ForceHook::whole;
    reset_splits(awake_.pair_end - pair0, awake_.disc_end - disc0, static_cast<std::size_t>(omp_get_max_threads()));
    double max_d2 = max_disp2_;
    bool rebuild = false;
#pragma omp parallel
    {
        const long long chunks = kick_chunks(db, de);
#pragma omp for schedule(static) reduction(max : max_d2)
        for (long long c = 0; c < chunks; ++c) {
            const auto [cb, ce] = kick_chunk(db, de, c);
            max_d2 = kick_drift_range(kk, cb, ce, max_d2);
        }
#pragma omp single
        rebuild = hooks_after_drift(lazy, max_d2, by_range, clock);
        // (the single's barrier: every thread reads the same decision)
        if (!rebuild) {
            pair_split_.run(this_thread(), [&](std::size_t b, std::size_t e) { eval_pair_range(kd, pair0 + b, pair0 + e); });
#pragma omp barrier
#pragma omp master
            clock.lap(&PhaseTimes::pair_forces);
            if (by_range)
                gather_bases_kick(gd, kk, disc0, clock);
            else
                gather_hooks_kick(gd, kk, disc0, clock);
#pragma omp barrier
#pragma omp master
            hooks_after_step(by_range, clock);
        }
    }
    return !rebuild;
}

bool Simulation::hooks_after_drift(bool lazy, double max_d2, bool by_range, PhaseClock& clock) {
    // On one thread, after the drift: the walls, the after_drift hooks, the
    // rebuild test and (no rebuild) the bases' begin_forces. True: a rebuild is due.
    clock.lap(&PhaseTimes::integrate);
    end_drift(lazy, max_d2);
    const double wall_move = move_walls();
    for (auto& b : boundaries) b->after_drift(*this);
    const bool rebuild = needs_rebuild(wall_move);
    if (by_range && !rebuild)
        for (auto& bd : boundaries)
            if (bd->force_hook() == Boundary::ForceHook::by_disc_range) bd->begin_forces(*this);
    clock.lap(&PhaseTimes::boundaries);
    return rebuild;
}

void Simulation::gather_bases_kick(const GatherData& gd, const KickData& kk, std::size_t disc0, PhaseClock& clock) {
    // Every thread, chunk by chunk: the discs' gather, their base forces,
    // their second half kick (sleeping discs have inv_mass = inv_inertia =
    // 0). The master's clock reads time its own chunks' parts; the other
    // threads read no clock (about 1% of a two-thread wedge step went to
    // clock reads).
    const bool timed = this_thread() == 0;
    double t_gather = 0.0, t_base = 0.0;
    disc_split_.run(this_thread(), [&](std::size_t b, std::size_t e) {
        const double t0 = timed ? omp_get_wtime() : 0.0;
        gather_range(gd, disc0 + b, disc0 + e);
        const double t1 = timed ? omp_get_wtime() : 0.0;
        for (auto& bd : boundaries)
            if (bd->force_hook() == Boundary::ForceHook::by_disc_range) bd->add_forces_range(*this, disc0 + b, disc0 + e);
        if (timed) {
            t_gather += t1 - t0;
            t_base += omp_get_wtime() - t1;
        }
        kick_range(kk, disc0 + b, disc0 + e);
    });
    if (timed) {
        clock.add(&PhaseTimes::gather, t_gather);
        clock.add(&PhaseTimes::boundaries, t_base);
    }
}

void Simulation::gather_hooks_kick(const GatherData& gd, const KickData& kk, std::size_t disc0, PhaseClock& clock) {
    // Every thread: its chunks of phase B, then (one thread, between
    // barriers) the add_forces hooks, then its share of the second half kick.
    disc_split_.run(this_thread(), [&](std::size_t b, std::size_t e) { gather_range(gd, disc0 + b, disc0 + e); });
#pragma omp barrier
#pragma omp single
    {
        clock.lap(&PhaseTimes::gather);
        for (auto& bd : boundaries) bd->add_forces(*this);
        clock.lap(&PhaseTimes::boundaries);
    }
    const auto [b, e] = thread_range(awake_.disc_end - disc0, 8);
    if (b < e) kick_range(kk, disc0 + b, disc0 + e);
}

void Simulation::hooks_after_step(bool by_range, PhaseClock& clock) {
    // On the master, after the kick's barrier: the bases' totals (by_range)
    // and the after_step hooks.
    clock.lap(&PhaseTimes::integrate);
    if (by_range)
        for (auto& bd : boundaries)
            if (bd->force_hook() == Boundary::ForceHook::by_disc_range) bd->end_forces(*this);
    for (auto& bd : boundaries) bd->after_step(*this);
}

}  // namespace orodem
