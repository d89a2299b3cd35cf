// Step loop kernels. Determinism argument: every parallel loop writes only
// slots owned by its iteration (a pair's f, c, ξ; a disc's force, torque, x,
// v), and every sum runs in an order fixed by the pair list (outgoing pairs in
// pair order, incoming pairs in pair order, walls in wall order), which the
// PairBuilder makes independent of the thread count. The only reduction is a
// max, which is exact.
#include "orodem/engine/simulation.hpp"

#include "orodem/core/bytes.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "orodem/core/hash.hpp"
#include "orodem/core/parallel.hpp"
#include "orodem/core/stealing_split.hpp"
#include "orodem/engine/pair_kernel.hpp"

namespace orodem {

BondTopology build_bond_topology(const ParticleStore& p) {
    BondTopology t;
    const std::size_t n = p.size();
    // Members of each cluster, in id order.
    std::int32_t max_cluster = -1;
    for (std::size_t s = 0; s < n; ++s) max_cluster = std::max(max_cluster, p.cluster[s]);
    std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(max_cluster + 1));
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::int32_t c = p.cluster[p.slot_of_id[id]];
        if (c >= 0) members[static_cast<std::size_t>(c)].push_back(id);
    }
    t.begin.assign(n + 1, 0);
    for (const auto& m : members)
        for (std::uint32_t a : m) t.begin[a + 1] = static_cast<std::uint32_t>(m.size() - 1);
    for (std::size_t a = 0; a < n; ++a) t.begin[a + 1] += t.begin[a];
    t.partner.resize(t.begin[n]);
    for (const auto& m : members)
        for (std::uint32_t a : m) {
            std::uint32_t k = t.begin[a];
            for (std::uint32_t b : m)
                if (b != a) t.partner[k++] = b;
        }
    return t;
}

PairBuilder::Settings Simulation::builder_settings() const {
    return {params.skin, params.periodic_x, params.period_x};
}

LawParams Simulation::wall_law(std::size_t w) const {
    LawParams l = params.law;
    l.tangential = walls[w].rough && l.tangential;
    l.mu = walls[w].mu;
    l.cohesion = 0.0;
    return l;
}

void Simulation::save_internals(ByteWriter& w) const {
    w.put_vector(builder_.x_ref());
    w.put(builder_.rebuild_count());
    w.put_vector(wall_shift_);
    w.put(max_disp2_);
    w.put(static_cast<std::uint8_t>(force_rebuild_ ? 1 : 0));
    w.put(awake_begin_);
    w.put(awake_end_);
    w.put(pairs_begin_);
    w.put(pairs_end_);
    w.put(last_rebuild_step_);
}

Simulation::Internals Simulation::read_internals(ByteReader& r) {
    Internals v;
    r.get_vector(v.x_ref);
    r.get(v.rebuilds);
    r.get_vector(v.wall_shift);
    r.get(v.max_disp2);
    v.force_rebuild = r.get<std::uint8_t>() != 0;
    r.get(v.awake_begin);
    r.get(v.awake_end);
    r.get(v.pairs_begin);
    r.get(v.pairs_end);
    r.get(v.last_rebuild_step);
    return v;
}

void Simulation::restore_internals(Internals&& v) {
    bonds = build_bond_topology(particles);
    wall_law_.clear();
    for (std::size_t w = 0; w < walls.size(); ++w) wall_law_.push_back(wall_law(w));
    builder_.x_ref() = std::move(v.x_ref);
    builder_.set_rebuild_count(v.rebuilds);
    builder_.set_built_order(particles.slot_of_id);  // checkpoints hold the lists in the slot order they were built in
    wall_shift_ = std::move(v.wall_shift);
    max_disp2_ = v.max_disp2;
    force_rebuild_ = v.force_rebuild;
    awake_begin_ = v.awake_begin;
    awake_end_ = v.awake_end;
    pairs_begin_ = v.pairs_begin;
    pairs_end_ = v.pairs_end;
    last_rebuild_step_ = v.last_rebuild_step;
    index_wall_discs();
    dashpots_stale_ = true;  // pairs and inverse masses restored: the per-pair dashpots follow
    in_slots_stale_ = true;
    set_drift_range();       // checkpoints are written between advance() calls: no drift lag
}

void Simulation::initialize() {
    particles.rebuild_slot_map();
    bonds = build_bond_topology(particles);
    wall_law_.clear();
    for (std::size_t w = 0; w < walls.size(); ++w) wall_law_.push_back(wall_law(w));
    rebuild_pairs();
    compute_forces<false>();
}

void Simulation::rebuild_pairs() {
    catch_up_drift();
    SleepDecision d;  // all awake unless sleeping is on and there was motion to judge
    if (params.sleep.enabled && builder_.rebuild_count() > 0) {
        sleep_bounds(d);
        sleep_decision_ = d;
    }
    builder_.rebuild(particles, bonds, walls, builder_settings(), contacts, wall_contacts);
    wall_shift_.assign(walls.size(), Vec2{});
    max_disp2_ = 0.0;
    force_rebuild_ = false;
    last_rebuild_step_ = step_count;
    apply_sleep(d.x_lo, d.x_hi);
    index_wall_discs();
    dashpots_stale_ = true;
    in_slots_stale_ = true;
}

void Simulation::index_wall_discs() {
    wall_discs_.resize(walls.size());
    for (auto& l : wall_discs_) l.clear();  // keeps the capacity: no allocation once grown
    const WallContactStore& ws = wall_contacts;
    for (std::size_t i = 0; i + 1 < ws.begin.size(); ++i)
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k)
            wall_discs_[ws.wall[k]].push_back(static_cast<std::uint32_t>(i));
}

namespace {

/// [begin, end) of this thread of the region's team over n items, cut at multiples of
/// `align` items (no two threads write one cache line). Any split gives the
/// same results; this one is contiguous per thread.
std::pair<std::size_t, std::size_t> thread_range(std::size_t n, std::size_t align) {
    return StealingSplit::share(n, static_cast<std::size_t>(omp_get_num_threads()),
                                static_cast<std::size_t>(omp_get_thread_num()), align);
}

/// Phases A and B in a parallel region: chunks of at most this many pairs
/// and discs (StealingSplit), about 8 µs of work each on the pile, and at
/// least kPairChunkMin and kDiscChunkMin (a chunk's own cost, the bases' law
/// and the timers of the wedge step's phase B included, stays a few per cent).
constexpr std::size_t kPairChunk = 2048, kDiscChunk = 1024;
constexpr std::size_t kPairChunkMin = 512, kDiscChunkMin = 256;

/// The threads of a parallel region over n items with `if(n >= kParallelMin)`.
std::size_t team_for(std::size_t n) {
    return static_cast<long long>(n) >= kParallelMin ? static_cast<std::size_t>(omp_get_max_threads()) : 1;
}

std::size_t this_thread() { return static_cast<std::size_t>(omp_get_thread_num()); }

/// Inside a parallel region, called by every thread: phase A over the
/// pairs' chunks (this thread's share first), a barrier, the master's clock
/// read for the phase timers, then phase B over the discs' chunks.
void pairs_then_gather(const PairKernelData& kd, const GatherData& gd, StealingSplit& pairs, StealingSplit& discs,
                       double& t_pairs_done) {
    pairs.run(this_thread(), [&](std::size_t b, std::size_t e) { eval_pair_range(kd, b, e); });
#pragma omp barrier
#pragma omp master
    t_pairs_done = omp_get_wtime();
    discs.run(this_thread(), [&](std::size_t b, std::size_t e) { gather_range(gd, b, e); });
}

}  // namespace

void Simulation::refresh_dashpots() {
    const ParticleStore& p = particles;
    const ContactStore& cs = contacts;
    const std::size_t npairs = cs.size();
    const bool gamma_s_zero = zero_gamma_s(params.law);
    pair_gamma_n_.resize(npairs);  // allocates only when the pair list outgrows every earlier one
    if (gamma_s_zero)
        pair_gamma_s_ = {};  // every γ_s is +0: no column (PairKernelData::gamma_s null)
    else
        pair_gamma_s_.resize(npairs);
    pair_r_i_.resize(npairs);
    pair_r_j_.resize(npairs);
#pragma omp parallel if(static_cast<long long>(npairs) >= kParallelMin)
    {
        const auto [b, e] = thread_range(npairs, 64);
        if (b < e) {
            pair_dashpots(params.law, p.mass.data(), p.inv_mass.data(), params.m_inertia_min, cs.i.data(), cs.j.data(), b, e,
                          pair_gamma_n_.data(), gamma_s_zero ? nullptr : pair_gamma_s_.data());
            pair_radii(p.radius.data(), cs.i.data(), cs.j.data(), b, e, pair_r_i_.data(), pair_r_j_.data());
        }
    }
    dashpots_stale_ = false;
    dashpots_epoch_ = p.inertia_epoch;
}

PairKernelData Simulation::pair_kernel_data(bool update_history) {
    ParticleStore& p = particles;
    ContactStore& cs = contacts;
    const bool gamma_s_zero = zero_gamma_s(params.law);
    if (dashpots_stale_ || dashpots_epoch_ != p.inertia_epoch || pair_gamma_n_.size() != cs.size() ||
        (!gamma_s_zero && pair_gamma_s_.size() != cs.size()))
        refresh_dashpots();
    return {p.x.data(),      p.v.data(),           p.omega.data(),        pair_r_i_.data(), pair_r_j_.data(), cs.i.data(),
            cs.j.data(),     cs.shift.data(),      cs.bonded.data(),      pair_gamma_n_.data(),
            gamma_s_zero ? nullptr : pair_gamma_s_.data(), cs.xi.data(),    cs.f.data(),           cs.c.data(),     params.period_x,
            params.dt,       params.law,           update_history,        p.size()};
}

GatherData Simulation::gather_data(bool update_history, bool kick) {
    ParticleStore& p = particles;
    const ContactStore& cs = contacts;
    WallContactStore& ws = wall_contacts;
    if (in_slots_stale_ || in_slots_.size() != 4 * p.size()) {
        in_slots_.resize(4 * p.size());  // allocates only when the discs outnumber every earlier count
        incoming_slots(cs.in_begin.data(), cs.in_pair.data(), p.size(), in_slots_.data());
        in_slots_stale_ = false;
    }
    return {p.x.data(),       p.v.data(),          p.omega.data(),       p.radius.data(),  p.mass.data(),
            p.inv_mass.data(), p.inv_inertia.data(), p.force.data(),     p.torque.data(),  cs.begin.data(),
            cs.in_begin.data(), cs.in_pair.data(),  in_slots_.data(),   cs.f.data(),         cs.c.data(),      cs.size(),
            ws.begin.data(),  ws.wall.data(),      ws.xi.data(),         ws.f.data(),      ws.c.data(),
            walls.data(),     wall_law_.data(),    params.gravity,       params.dt,        params.m_inertia_min,
            update_history,   kick};
}

template <bool kUpdateHistory>
void Simulation::pair_forces(bool all) {
    // Phase A: every candidate pair (or every awake one) evaluates the law
    // into its own slots (engine/pair_kernel.hpp: SIMD lanes, bit-identical
    // to one pair at a time).
    const PairKernelData kd = pair_kernel_data(kUpdateHistory);
    const std::size_t first = all ? 0 : pairs_begin_;
    const std::size_t npairs = (all ? contacts.size() : pairs_end_) - first;
#pragma omp parallel if(static_cast<long long>(npairs) >= kParallelMin)
    {
        const auto [b, e] = thread_range(npairs, 64);
        if (b < e) eval_pair_range(kd, first + b, first + e);
    }
}

template <bool kUpdateHistory, bool kKick>
void Simulation::gather_forces(bool all) {
    // Phase B: per disc (every one, or every awake one), in a fixed order,
    // gravity, its owned then incoming pairs' forces, its wall contacts
    // (evaluated here), and with kKick the second half kick (engine/pair_kernel.hpp).
    const GatherData gd = gather_data(kUpdateHistory, kKick);
    const std::size_t first = all ? 0 : awake_begin_;
    const std::size_t n = (all ? particles.size() : awake_end_) - first;
#pragma omp parallel if(static_cast<long long>(n) >= kParallelMin)
    {
        const auto [b, e] = thread_range(n, 8);
        if (b < e) gather_range(gd, first + b, first + e);
    }
}

void Simulation::reset_splits(std::size_t npairs, std::size_t ndiscs, std::size_t team) {
    // Chunks of about an eighth of a thread's share (StealingSplit::chunk_for):
    // with the fixed 2,048 pairs and 1,024 discs an intermediate-size wedge at
    // two threads (about 15,000 awake pairs, 7 chunks) waited 7-11% of phases
    // A and B at their barriers, with these 4-7% (docs/benchmarks.md, "What
    // was done" 27). The pile keeps the largest. Pairs cut at 64, discs at 8.
    pair_split_.reset(npairs, team, 64, StealingSplit::chunk_for(npairs, team, 64, kPairChunkMin, kPairChunk));
    disc_split_.reset(ndiscs, team, 8, StealingSplit::chunk_for(ndiscs, team, 8, kDiscChunkMin, kDiscChunk));
}

void Simulation::pair_forces_gather_kick() {
    // Phases A and B and the second half kick in one parallel region: one
    // fork and join fewer per step, which matters most when the machine is
    // loaded (a thread that is not running holds up every join). The split
    // into ranges is the one pair_forces() and gather_forces() use.
    const PairKernelData kd = pair_kernel_data(true);
    const GatherData gd = gather_data(true, true);
    const std::size_t npairs = contacts.size(), n = particles.size();
    reset_splits(npairs, n, team_for(n));
    double t_pairs_done = 0.0;
#pragma omp parallel if(static_cast<long long>(n) >= kParallelMin)
    pairs_then_gather(kd, gd, pair_split_, disc_split_, t_pairs_done);
    pairs_done_at_ = t_pairs_done;
}

// Out-of-line instances for bench/bench_kernels.cpp (KernelBench).
template void Simulation::pair_forces<true>(bool);
template void Simulation::gather_forces<true, false>(bool);

template <bool kUpdateHistory>
void Simulation::compute_forces() {
    pair_forces<kUpdateHistory>();
    gather_forces<kUpdateHistory, false>();
}

namespace {

/// The integrator's per-disc passes (kick_drift_range, kick_range) run over
/// chunks of this many discs in an omp for (the rebuild test's maximum
/// reduced over the threads). Any split gives the same results: a disc's
/// own operations, and a maximum is exact in any order. Small, as the static
/// split gives a thread up to one chunk more than the other: with 1,024
/// the first of two threads drifted an intermediate-size wedge 1.3-1.6
/// times as long as the second.
constexpr long long kKickChunk = 128;

/// The number of kKickChunk chunks of discs [b, e), and chunk c's discs.
long long kick_chunks(long long b, long long e) { return (e - b + kKickChunk - 1) / kKickChunk; }
std::pair<std::size_t, std::size_t> kick_chunk(long long b, long long e, long long c) {
    return {static_cast<std::size_t>(b + c * kKickChunk), static_cast<std::size_t>(std::min(e, b + (c + 1) * kKickChunk))};
}

}  // namespace

KickData Simulation::kick_data() {
    ParticleStore& p = particles;
    return {p.x.data(),     p.v.data(),        p.omega.data(),       p.theta.data(),
            p.force.data(), p.torque.data(),   p.inv_mass.data(),    p.inv_inertia.data(),
            builder_.x_ref().data(), params.dt, 0.5 * params.dt};
}

bool Simulation::drift_range(long long& b, long long& e) const {
    // Inside advance(), the discs outside the drift range (sleeping or fixed,
    // constant velocity) fall behind and catch up later (engine/sleep.cpp).
    const long long n = static_cast<long long>(particles.size());
    const bool lazy = defer_drift_ && (drift_begin_ > 0 || static_cast<long long>(drift_end_) < n);
    b = lazy ? drift_begin_ : 0;
    e = lazy ? drift_end_ : n;
    return lazy;
}

void Simulation::end_drift(bool lazy, double max_d2) {
    if (lazy) {
        ++drift_lag_;
        // Their displacement since the rebuild is the rigid motion u t of
        // their side: the rebuild test sees it without their positions.
        const double t = static_cast<double>(step_count + 1 - last_rebuild_step_) * params.dt;
        const SleepParams& sp = params.sleep;
        max_d2 = std::max(max_d2, t * t * std::max(norm2(sp.u_left), norm2(sp.u_right)));
    }
    max_disp2_ = max_d2;
}

void Simulation::kick_drift() {
    const KickData kd = kick_data();
    double max_d2 = max_disp2_;
    long long b = 0, e = 0;
    const bool lazy = drift_range(b, e);
    const long long chunks = kick_chunks(b, e);
#pragma omp parallel for schedule(static) if(e - b >= kParallelMin) reduction(max : max_d2)
    for (long long c = 0; c < chunks; ++c) {
        const auto [cb, ce] = kick_chunk(b, e, c);
        max_d2 = kick_drift_range(kd, cb, ce, max_d2);
    }
    end_drift(lazy, max_d2);
}

void Simulation::advance(std::uint64_t n) {
    defer_drift_ = params.sleep.enabled;
    for (std::uint64_t k = 0; k < n; ++k) step();
    defer_drift_ = false;
    catch_up_drift();
}

bool Simulation::step_in_one_region(double wall_move) {
    // kick_drift(), the rebuild test, pair_forces_gather_kick() in one
    // parallel region: two barriers a step (positions before phase A, forces
    // before phase B) and one fork, the fewest the data flow allows, which
    // matters most on a loaded machine (a thread that is not running holds
    // up every barrier). Every thread takes the same rebuild decision from
    // the reduced maximum; on a rebuild step the region ends after the drift
    // and step() rebuilds outside it (false).
    const KickData kk = kick_data();
    const PairKernelData kd = pair_kernel_data(true);
    const GatherData gd = gather_data(true, true);
    const std::size_t npairs = contacts.size(), n = particles.size();
    reset_splits(npairs, n, team_for(n));
    double max_d2 = max_disp2_;
    bool rebuild = false;
    double t_kicked = 0.0, t_pairs_done = 0.0;
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
            t_kicked = omp_get_wtime();
            rebuild = need;
        }
        if (!need) pairs_then_gather(kd, gd, pair_split_, disc_split_, t_pairs_done);
    }
    max_disp2_ = max_d2;
    kicked_at_ = t_kicked;
    pairs_done_at_ = t_pairs_done;
    return !rebuild;
}

bool Simulation::boundary_step_in_one_region(double (&stamp)[6]) {
    // The boundary path of step() as one parallel region: the same
    // operations on the same slots in the same order as kick_drift(),
    // move_walls(), the hooks, pair_forces(false), gather_forces(false),
    // kick(), so the same results, with one fork a step instead of four:
    // about 1.35 times faster on 2 threads for a 10,000-disc wedge
    // (docs/benchmarks.md; step() calls it from one_region_min_awake awake
    // discs on). The hooks run on one thread between barriers (their loops
    // cover the few discs on a base; a nested region inside a hook runs on
    // one thread), except the add_forces of the by_disc_range boundaries
    // (the bases): when no boundary needs a whole add_forces, each thread
    // applies them to its own gathered discs and kicks those with no barrier
    // between, and their totals follow the kick's barrier, one barrier and
    // one single fewer (the same operations on each disc, the same tallies,
    // so the same results). A rebuild step ends the region after the
    // after_drift hooks and step() finishes it phase by phase, as before.
    const KickData kk = kick_data();
    long long db = 0, de = 0;
    const bool lazy = drift_range(db, de);
    const PairKernelData kd = pair_kernel_data(true);
    const GatherData gd = gather_data(true, false);
    const std::size_t pair0 = pairs_begin_, npairs = pairs_end_ - pairs_begin_;
    const std::size_t disc0 = awake_begin_, nawake = awake_end_ - awake_begin_;
    double max_d2 = max_disp2_;
    bool rebuild = false;
    bool by_range = true;  // no boundary needs a whole add_forces on one thread
    for (const auto& bd : boundaries) by_range = by_range && bd->force_hook() != Boundary::ForceHook::whole;
    const std::size_t team = static_cast<std::size_t>(omp_get_max_threads());
    reset_splits(npairs, nawake, team);
#pragma omp parallel
    {
        const long long chunks = kick_chunks(db, de);
#pragma omp for schedule(static) reduction(max : max_d2)
        for (long long c = 0; c < chunks; ++c) {
            const auto [cb, ce] = kick_chunk(db, de, c);
            max_d2 = kick_drift_range(kk, cb, ce, max_d2);
        }
#pragma omp single
        {
            stamp[0] = omp_get_wtime();
            end_drift(lazy, max_d2);
            const double wall_move = move_walls();
            for (auto& b : boundaries) b->after_drift(*this);
            rebuild = needs_rebuild(wall_move);
            if (by_range && !rebuild)
                for (auto& bd : boundaries)
                    if (bd->force_hook() == Boundary::ForceHook::by_disc_range) bd->begin_forces(*this);
            stamp[1] = omp_get_wtime();
        }  // (a barrier: every thread reads the same decision)
        if (!rebuild) {
            pair_split_.run(this_thread(), [&](std::size_t b, std::size_t e) { eval_pair_range(kd, pair0 + b, pair0 + e); });
#pragma omp barrier
#pragma omp master
            stamp[2] = omp_get_wtime();
            if (by_range) {
                // Chunk by chunk: the discs' gather, their base forces, their
                // second half kick (sleeping discs have inv_mass =
                // inv_inertia = 0). The master's clock reads time its own
                // chunks' parts (the other threads read no clock: about 1%
                // of a two-thread wedge step went to the clock reads).
                const bool timed = this_thread() == 0;
                double t_gather = 0.0, t_base = 0.0;
                disc_split_.run(this_thread(), [&](std::size_t b, std::size_t e) {
                    const double t0 = timed ? omp_get_wtime() : 0.0;
                    gather_range(gd, disc0 + b, disc0 + e);
                    const double t1 = timed ? omp_get_wtime() : 0.0;
                    for (auto& bd : boundaries)
                        if (bd->force_hook() == Boundary::ForceHook::by_disc_range)
                            bd->add_forces_range(*this, disc0 + b, disc0 + e);
                    if (timed) {
                        t_gather += t1 - t0;
                        t_base += omp_get_wtime() - t1;
                    }
                    kick_range(kk, disc0 + b, disc0 + e);
                });
#pragma omp master
                {
                    stamp[3] = stamp[2] + t_gather;
                    stamp[4] = stamp[3] + t_base;
                }
            } else {
                disc_split_.run(this_thread(), [&](std::size_t b, std::size_t e) { gather_range(gd, disc0 + b, disc0 + e); });
#pragma omp barrier
#pragma omp single
                {
                    stamp[3] = omp_get_wtime();
                    for (auto& bd : boundaries) bd->add_forces(*this);
                    stamp[4] = omp_get_wtime();
                }
                // The second half kick (sleeping discs have inv_mass = inv_inertia = 0).
                const auto [b, e] = thread_range(nawake, 8);
                if (b < e) kick_range(kk, disc0 + b, disc0 + e);
            }
#pragma omp barrier
#pragma omp master
            {
                stamp[5] = omp_get_wtime();
                if (by_range)
                    for (auto& bd : boundaries)
                        if (bd->force_hook() == Boundary::ForceHook::by_disc_range) bd->end_forces(*this);
                for (auto& bd : boundaries) bd->after_step(*this);
            }
        }
    }
    return !rebuild;
}

void Simulation::kick() {
    // Sleeping discs have inv_mass = inv_inertia = 0: only the awake range.
    const KickData kd = kick_data();
    const long long b = awake_begin_, e = awake_end_;
    const long long chunks = kick_chunks(b, e);
#pragma omp parallel for schedule(static) if(e - b >= kParallelMin)
    for (long long c = 0; c < chunks; ++c) {
        const auto [cb, ce] = kick_chunk(b, e, c);
        kick_range(kd, cb, ce);
    }
}

bool Simulation::needs_rebuild(double wall_move) const {
    return force_rebuild_ || std::sqrt(max_disp2_) + wall_move > 0.5 * params.skin;
}

double Simulation::move_walls() {
    double wall_move = 0.0;
    for (std::size_t w = 0; w < walls.size(); ++w) {
        const Vec2 dx = params.dt * walls[w].velocity;
        walls[w].a += dx;
        walls[w].b += dx;
        wall_shift_[w] += dx;
        wall_move = std::max(wall_move, norm(wall_shift_[w]));
    }
    return wall_move;
}

void Simulation::step() {
    const double dt = params.dt;
    double t0 = omp_get_wtime();
    auto lap = [&t0](double& acc) {
        const double t1 = omp_get_wtime();
        acc += t1 - t0;
        t0 = t1;
    };
    auto lap_to = [&t0](double& acc, double t1) {
        acc += t1 - t0;
        t0 = t1;
    };
    if (boundaries.empty()) {
        // No hook runs between the phases: the walls move first (the kick and
        // drift do not read them), then the rest in one parallel region, and
        // each disc is kicked right after its force is summed.
        const double wall_move = move_walls();
        lap(times_.boundaries);
        if (step_in_one_region(wall_move)) {
            lap_to(times_.integrate, kicked_at_);
            lap_to(times_.pair_forces, pairs_done_at_);
            lap(times_.gather);
        } else {
            lap_to(times_.integrate, kicked_at_);
            rebuild_pairs();
            ++times_.rebuilds;
            lap(times_.rebuild);
            pair_forces_gather_kick();
            lap_to(times_.pair_forces, pairs_done_at_);
            lap(times_.gather);
        }
    } else {
        // From one_region_min_awake awake discs on, a step without a rebuild
        // runs in one parallel region; below, the phases run one by one (the
        // barriers would cost more than the work: a demo-size wedge with about
        // 1,000 awake discs ran 12% slower in one region).
        double stamp[6] = {};
        bool drifted = false, done = false;
        if (awake_end_ - awake_begin_ >= one_region_min_awake) {
            done = boundary_step_in_one_region(stamp);
            drifted = true;
            lap_to(times_.integrate, stamp[0]);
            lap_to(times_.boundaries, stamp[1]);
        }
        if (done) {
            lap_to(times_.pair_forces, stamp[2]);
            lap_to(times_.gather, stamp[3]);
            lap_to(times_.boundaries, stamp[4]);
            lap_to(times_.integrate, stamp[5]);
            lap(times_.boundaries);
        } else {
            bool rebuilt = true;  // the region ended early: a rebuild is due
            if (!drifted) {
                kick_drift();
                lap(times_.integrate);
                const double wall_move = move_walls();
                for (auto& b : boundaries) b->after_drift(*this);
                lap(times_.boundaries);
                rebuilt = needs_rebuild(wall_move);
            }
            // A rebuild step evaluates every pair and disc (fresh forces and
            // diagnostics for the sleeping zones too); other steps the awake ones.
            if (rebuilt) {
                rebuild_pairs();
                ++times_.rebuilds;
            }
            lap(times_.rebuild);
            pair_forces<true>(rebuilt);
            lap(times_.pair_forces);
            gather_forces<true, false>(rebuilt);
            lap(times_.gather);
            for (auto& b : boundaries) b->add_forces(*this);
            lap(times_.boundaries);
            kick();
            lap(times_.integrate);
            for (auto& b : boundaries) b->after_step(*this);
            lap(times_.boundaries);
        }
    }
    ++times_.steps;
    ++step_count;
    time = static_cast<double>(step_count) * dt;
}

double Simulation::kinetic_energy() const {
    const ParticleStore& p = particles;
    const double m_min = params.m_inertia_min;
    return deterministic_sum(p.size(), [&](std::size_t i) { return 0.5 * p.inertial_mass(i, m_min) * norm2(p.v[i]); });
}

EnergyReport Simulation::energies() const {
    const ParticleStore& p = particles;
    EnergyReport e;
    e.kinetic_translational = kinetic_energy();
    e.kinetic_rotational = deterministic_sum(p.size(), [&](std::size_t i) {
        const double inertia = 0.5 * p.inertial_mass(i, params.m_inertia_min) * p.radius[i] * p.radius[i];
        return 0.5 * inertia * p.omega[i] * p.omega[i];
    });
    e.gravitational = deterministic_sum(p.size(), [&](std::size_t i) {
        return -p.mass[i] * dot(params.gravity, p.x[i]);
    });
    const ContactStore& cs = contacts;
    const double W = params.period_x;
    const LawParams& law = params.law;
    double elastic = deterministic_sum(cs.size(), [&](std::size_t k) {
        const Vec2 d = p.x[cs.i[k]] - (p.x[cs.j[k]] + Vec2{cs.shift[k] * W, 0.0});
        const double delta = p.radius[cs.i[k]] + p.radius[cs.j[k]] - norm(d);
        if (delta <= 0.0 && !cs.bonded[k]) return 0.0;
        return 0.5 * law.k_n * delta * delta + 0.5 * law.k_s * norm2(cs.xi[k]);
    });
    const WallContactStore& ws = wall_contacts;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k) {
            Vec2 cp;
            if (!wall_contact_point(walls[ws.wall[k]], p.x[i], cp)) continue;
            const double delta = p.radius[i] - norm(p.x[i] - cp);
            if (delta > 0.0)
                elastic += 0.5 * law.k_n * delta * delta + 0.5 * wall_law_[ws.wall[k]].k_s * norm2(ws.xi[k]);
        }
    e.elastic = elastic;
    return e;
}

std::size_t Simulation::touching_contacts() const {
    std::size_t count = 0;
    const ContactStore& cs = contacts;
    for (std::size_t k = 0; k < cs.size(); ++k)
        if (!cs.bonded[k] && (cs.f[k].x != 0.0 || cs.f[k].y != 0.0 || cs.xi[k].x != 0.0 || cs.xi[k].y != 0.0))
            ++count;
    for (std::size_t k = 0; k < wall_contacts.size(); ++k)
        if (wall_contacts.f[k].x != 0.0 || wall_contacts.f[k].y != 0.0) ++count;
    return count;
}

double Simulation::max_overlap_ratio() const {
    const ContactStore& cs = contacts;
    double worst = 0.0;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        if (cs.bonded[k]) continue;
        worst = std::max(worst, pair_overlap_ratio(k));
    }
    return worst;
}

double Simulation::mean_overlap_ratio() const {
    const ContactStore& cs = contacts;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        if (cs.bonded[k]) continue;
        const double ratio = pair_overlap_ratio(k);
        if (ratio > 0.0) {
            sum += ratio;
            ++count;
        }
    }
    return count ? sum / static_cast<double>(count) : 0.0;
}

double Simulation::max_speed() const {
    double m = 0.0;
    for (const Vec2& v : particles.v) m = std::max(m, norm2(v));
    return std::sqrt(m);
}

Vec2 Simulation::wall_force(std::size_t w) const {
    Vec2 f{};
    for (std::size_t k = 0; k < wall_contacts.size(); ++k)
        if (wall_contacts.wall[k] == w) f -= wall_contacts.f[k];
    return f;
}

std::uint64_t Simulation::state_hash() const {
    const ParticleStore& p = particles;
    Fnv1a h;
    for (std::uint32_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        h.add(p.x[s]); h.add(p.v[s]); h.add(p.theta[s]); h.add(p.omega[s]);
    }
    std::vector<std::pair<std::uint64_t, Vec2>> hist;
    for (std::size_t k = 0; k < contacts.size(); ++k) hist.emplace_back(contacts.key[k], contacts.xi[k]);
    for (std::size_t k = 0; k < wall_contacts.size(); ++k)
        hist.emplace_back(wall_contacts.key[k] | (1ULL << 63), wall_contacts.xi[k]);
    std::sort(hist.begin(), hist.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [key, xi] : hist) {
        if (xi.x == 0.0 && xi.y == 0.0) continue;
        h.add(key); h.add(xi);
    }
    h.add(step_count);
    return h.value();
}

}  // namespace orodem
