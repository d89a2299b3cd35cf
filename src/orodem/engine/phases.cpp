// The phases of a step, each on its own (Simulation::step() runs them in
// the order of engine/simulation.hpp's header comment, or fused in one
// parallel region: engine/step.cpp): phase A (pair_forces: the law per pair
// into its own slots), phase B (gather_forces: per disc, in a fixed order),
// the integrator's kick and drift, the walls' motion and the rebuild test,
// and the column data the kernels read (engine/pair_kernel.hpp).
// Determinism: every parallel loop writes only slots owned by its
// iteration (a pair's f, c, ξ; a disc's force, torque, x, v), and every sum
// runs in an order fixed by the pair list (outgoing pairs in pair order,
// incoming pairs in pair order, walls in wall order), which the PairBuilder
// makes independent of the thread count. The only reduction is a max,
// which is exact.
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "orodem/engine/pair_kernel.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/engine/team.hpp"

namespace orodem {

using namespace team;

void Simulation::refresh_dashpots() {
    const ParticleStore& p = particles;
    const ContactStore& cs = contacts;
    const std::size_t npairs = cs.size();
    const bool gamma_s_zero = zero_gamma_s(params.law);
    columns_.gamma_n.resize(npairs);  // allocates only when the pair list outgrows every earlier one
    if (gamma_s_zero)
        columns_.gamma_s = {};  // every γ_s is +0: no column (PairKernelData::gamma_s null)
    else
        columns_.gamma_s.resize(npairs);
    columns_.r_i.resize(npairs);
    columns_.r_j.resize(npairs);
    if (has_materials()) {
        refresh_material_columns();  // each pair's own law and dashpots (engine/materials.cpp)
        pair_radii(p.radius.data(), cs.i.data(), cs.j.data(), 0, npairs, columns_.r_i.data(), columns_.r_j.data());
        columns_.stale = false;
        columns_.epoch = p.inertia_epoch;
        return;
    }
#pragma omp parallel if(static_cast<long long>(npairs) >= kParallelMin)
    {
        const auto [b, e] = thread_range(npairs, 64);
        if (b < e) {
            pair_dashpots(params.law, p.mass.data(), p.inv_mass.data(), params.m_inertia_min, cs.i.data(), cs.j.data(), b, e,
                          columns_.gamma_n.data(), gamma_s_zero ? nullptr : columns_.gamma_s.data());
            pair_radii(p.radius.data(), cs.i.data(), cs.j.data(), b, e, columns_.r_i.data(), columns_.r_j.data());
        }
    }
    columns_.stale = false;
    columns_.epoch = p.inertia_epoch;
}

PairKernelData Simulation::pair_kernel_data(bool update_history) {
    ParticleStore& p = particles;
    ContactStore& cs = contacts;
    const bool gamma_s_zero = zero_gamma_s(params.law);
    if (columns_.stale || columns_.epoch != p.inertia_epoch || columns_.gamma_n.size() != cs.size() ||
        (!gamma_s_zero && columns_.gamma_s.size() != cs.size()))
        refresh_dashpots();
    PairKernelData d{p.x.data(),      p.v.data(),           p.omega.data(),        columns_.r_i.data(), columns_.r_j.data(), cs.i.data(),
                     cs.j.data(),     cs.shift.data(),      cs.bonded.data(),      columns_.gamma_n.data(),
                     gamma_s_zero ? nullptr : columns_.gamma_s.data(), cs.xi.data(),    cs.f.data(),           cs.c.data(),     params.period_x,
                     params.dt,       params.law,           update_history,        p.size()};
    if (has_materials()) {
        MaterialColumns& mc = material_columns_;
        d.k_n_pair = mc.k_n.data();
        d.k_s_pair = mc.k_s.data();
        d.mu_pair = mc.mu.data();
        d.cohesion_pair = mc.cohesion.data();
        d.slip = material_state_.slip.data();
        d.broke = material_state_.broke.data();
    }
    return d;
}

GatherData Simulation::gather_data(bool update_history, bool kick) {
    ParticleStore& p = particles;
    const ContactStore& cs = contacts;
    WallContactStore& ws = wall_contacts;
    if (columns_.in_slots_stale || columns_.in_slots.size() != 4 * p.size()) {
        columns_.in_slots.resize(4 * p.size());  // allocates only when the discs outnumber every earlier count
        incoming_slots(cs.in_begin.data(), cs.in_pair.data(), p.size(), columns_.in_slots.data());
        columns_.in_slots_stale = false;
    }
    return {p.x.data(),       p.v.data(),          p.omega.data(),       p.radius.data(),  p.mass.data(),
            p.inv_mass.data(), p.inv_inertia.data(), p.force.data(),     p.torque.data(),  cs.begin.data(),
            cs.in_begin.data(), cs.in_pair.data(),  columns_.in_slots.data(),   cs.f.data(),         cs.c.data(),      cs.size(),
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
    const std::size_t first = all ? 0 : awake_.pair_begin;
    const std::size_t npairs = (all ? contacts.size() : awake_.pair_end) - first;
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
    const std::size_t first = all ? 0 : awake_.disc_begin;
    const std::size_t n = (all ? particles.size() : awake_.disc_end) - first;
#pragma omp parallel if(static_cast<long long>(n) >= kParallelMin)
    {
        const auto [b, e] = thread_range(n, 8);
        if (b < e) gather_range(gd, first + b, first + e);
    }
}

void Simulation::reset_splits(std::size_t npairs, std::size_t ndiscs, std::size_t threads) {
    // Chunks of about an eighth of a thread's share (StealingSplit::chunk_for):
    // with the fixed 2,048 pairs and 1,024 discs an intermediate-size wedge at
    // two threads (about 15,000 awake pairs, 7 chunks) waited 7-11% of phases
    // A and B at their barriers, with these 4-7% (docs/studies/kernel-history.md, "What
    // was done" 27). The pile keeps the largest. Pairs cut at 64, discs at 8.
    pair_split_.reset(npairs, threads, 64, StealingSplit::chunk_for(npairs, threads, 64, kPairChunkMin, kPairChunk));
    disc_split_.reset(ndiscs, threads, 8, StealingSplit::chunk_for(ndiscs, threads, 8, kDiscChunkMin, kDiscChunk));
}

// Out-of-line instances for bench/bench_kernels.cpp (KernelBench).
template void Simulation::pair_forces<true>(bool);
template void Simulation::gather_forces<true, false>(bool);

template <bool kUpdateHistory>
void Simulation::compute_forces() {
    pair_forces<kUpdateHistory>();
    gather_forces<kUpdateHistory, false>();
}
template void Simulation::compute_forces<false>();  // initialize()

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
    const bool lazy = awake_.defer_drift && (awake_.drift_begin > 0 || static_cast<long long>(awake_.drift_end) < n);
    b = lazy ? awake_.drift_begin : 0;
    e = lazy ? awake_.drift_end : n;
    return lazy;
}

void Simulation::end_drift(bool lazy, double max_d2) {
    if (lazy) {
        ++awake_.drift_lag;
        // Their displacement since the rebuild is the rigid motion u t of
        // their side: the rebuild test sees it without their positions.
        const double t = static_cast<double>(step_count + 1 - awake_.last_rebuild_step) * params.dt;
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

void Simulation::kick() {
    // Sleeping discs have inv_mass = inv_inertia = 0: only the awake range.
    const KickData kd = kick_data();
    const long long b = awake_.disc_begin, e = awake_.disc_end;
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
}  // namespace orodem
