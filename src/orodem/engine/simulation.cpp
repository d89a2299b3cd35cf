// Simulation's set-up and saved state: the bond topology, initialize(), the
// neighbour rebuild, and the internals checkpoints carry. The step is in
// engine/step.cpp, its phases in engine/phases.cpp, the diagnostics in
// engine/diagnostics.cpp, the sleeping zones in engine/sleep.cpp.
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
    w.put(awake_.disc_begin);
    w.put(awake_.disc_end);
    w.put(awake_.pair_begin);
    w.put(awake_.pair_end);
    w.put(awake_.last_rebuild_step);
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
    awake_.disc_begin = v.awake_begin;
    awake_.disc_end = v.awake_end;
    awake_.pair_begin = v.pairs_begin;
    awake_.pair_end = v.pairs_end;
    awake_.last_rebuild_step = v.last_rebuild_step;
    index_wall_discs();
    columns_.stale = true;  // pairs and inverse masses restored: the per-pair dashpots follow
    columns_.in_slots_stale = true;
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
    if (has_materials()) absorb_slip();  // the old pair list's slip into damage (engine/materials.cpp)
    builder_.rebuild(particles, bonds, walls, builder_settings(), contacts, wall_contacts);
    wall_shift_.assign(walls.size(), Vec2{});
    max_disp2_ = 0.0;
    force_rebuild_ = false;
    awake_.last_rebuild_step = step_count;
    apply_sleep(d.x_lo, d.x_hi);
    index_wall_discs();
    columns_.stale = true;
    columns_.in_slots_stale = true;
}

void Simulation::index_wall_discs() {
    wall_discs_.resize(walls.size());
    for (auto& l : wall_discs_) l.clear();  // keeps the capacity: no allocation once grown
    const WallContactStore& ws = wall_contacts;
    for (std::size_t i = 0; i + 1 < ws.begin.size(); ++i)
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k)
            wall_discs_[ws.wall[k]].push_back(static_cast<std::uint32_t>(i));
}

}  // namespace orodem
