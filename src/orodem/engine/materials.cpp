// Several materials in the engine (physics/materials.hpp for the rules).
//
// Each pair's law lives in pair columns (k_n, k_s, μ, cohesion), made at
// each rebuild with the dashpots (refresh_dashpots) from the two discs'
// materials, their damage and the pairs whose cohesion is lost; phase A reads
// them (phase_a.hpp PerPair) and adds each pair's plastic slip and marks its
// separation. At the next rebuild, before the pairs are re-sorted,
// absorb_slip turns the slip into damage (half of a pair's slip to each disc,
// a cluster's discs sharing the sum over the cluster), marks the broken
// pairs' cohesion lost, and heals. So a contact's friction follows the damage
// with the lag of one rebuild interval (a disc moves at most half the skin
// between rebuilds, 0.2 r_min by default: a small part of a weakening
// distance of a mean diameter); the same at any thread count (one thread, in
// slot order) and across a resume (the slip, separations, lost keys and the
// damage are in checkpoints).
#include <algorithm>

#include "orodem/core/bytes.hpp"
#include "orodem/engine/simulation.hpp"

namespace orodem {

void Simulation::absorb_slip() {
    ParticleStore& p = particles;
    const ContactStore& cs = contacts;
    MaterialState& st = material_state_;
    MaterialColumns& mc = material_columns_;
    const std::size_t n = p.size(), npairs = cs.size();
    const double dt_heal = time - st.damage_time;  // [s]
    st.damage_time = time;
    if (st.slip.size() != npairs || st.broke.size() != npairs) {
        st.slip.assign(npairs, 0.0);
        st.broke.assign(npairs, 0);
        return;
    }
    const double per_diameter = 0.5 / materials.mean_diameter;  // half a pair's slip to each disc, in d̄
    mc.add.assign(n, 0.0);
    mc.lost_now.clear();
    for (std::size_t k = 0; k < npairs; ++k) {
        if (cs.bonded[k]) continue;
        const std::uint32_t i = cs.i[k], j = cs.j[k];
        const double slip = st.slip[k];
        if (slip > 0.0) {
            mc.add[i] += per_diameter * slip;
            mc.add[j] += per_diameter * slip;
        }
        if (slip > 0.0 || st.broke[k]) {
            const PairLaw& pl = materials.pair(p.material[i], p.material[j]);
            if (pl.cohesion_loss && pl.law.cohesion > 0.0) mc.lost_now.push_back(cs.key[k]);
        }
    }
    // A cluster's discs share one damage: the sum over its discs.
    std::int32_t max_cluster = -1;
    for (std::size_t s = 0; s < n; ++s) max_cluster = std::max(max_cluster, p.cluster[s]);
    mc.cluster_add.assign(static_cast<std::size_t>(max_cluster + 1), 0.0);
    for (std::size_t s = 0; s < n; ++s)
        if (p.cluster[s] >= 0) mc.cluster_add[static_cast<std::size_t>(p.cluster[s])] += mc.add[s];
    const bool heal = materials.any_healing();
    for (std::size_t s = 0; s < n; ++s) {
        double d = p.damage[s] + (p.cluster[s] >= 0 ? mc.cluster_add[static_cast<std::size_t>(p.cluster[s])] : mc.add[s]);
        if (heal) d = std::max(0.0, d - materials.materials[p.material[s]].healing_rate * dt_heal);
        p.damage[s] = d;
    }
    if (!mc.lost_now.empty()) {
        std::vector<std::uint64_t>& lost = st.cohesion_lost;
        std::sort(mc.lost_now.begin(), mc.lost_now.end());
        const std::size_t old = lost.size();
        lost.insert(lost.end(), mc.lost_now.begin(), mc.lost_now.end());
        std::inplace_merge(lost.begin(), lost.begin() + static_cast<std::ptrdiff_t>(old), lost.end());
        lost.erase(std::unique(lost.begin(), lost.end()), lost.end());
    }
    std::fill(st.slip.begin(), st.slip.end(), 0.0);
    std::fill(st.broke.begin(), st.broke.end(), std::uint8_t{0});
}

void Simulation::refresh_material_columns() {
    const ParticleStore& p = particles;
    const ContactStore& cs = contacts;
    MaterialColumns& mc = material_columns_;
    const std::vector<std::uint64_t>& lost = material_state_.cohesion_lost;
    const std::size_t npairs = cs.size();
    const bool gamma_s_zero = zero_gamma_s(params.law);
    mc.k_n.resize(npairs);
    mc.k_s.resize(npairs);
    mc.mu.resize(npairs);
    mc.cohesion.resize(npairs);
    for (std::size_t k = 0; k < npairs; ++k) {
        const std::uint32_t i = cs.i[k], j = cs.j[k];
        const PairLaw& pl = materials.pair(p.material[i], p.material[j]);
        mc.k_n[k] = pl.law.k_n;
        mc.k_s[k] = pl.law.k_s;
        mc.mu[k] = weakened_mu(pl, 0.5 * (p.damage[i] + p.damage[j]));
        const bool gone = pl.cohesion_loss && std::binary_search(lost.begin(), lost.end(), cs.key[k]);
        mc.cohesion[k] = gone ? 0.0 : pl.law.cohesion;
        pair_dashpots(pl.law, p.mass.data(), p.inv_mass.data(), params.m_inertia_min, cs.i.data(), cs.j.data(), k,
                      k + 1, columns_.gamma_n.data(), gamma_s_zero ? nullptr : columns_.gamma_s.data());
    }
    MaterialState& st = material_state_;
    if (st.slip.size() != npairs) st.slip.assign(npairs, 0.0);
    if (st.broke.size() != npairs) st.broke.assign(npairs, 0);
}

void Simulation::reset_material_state() {
    std::fill(particles.damage.begin(), particles.damage.end(), 0.0);
    MaterialState& st = material_state_;
    std::fill(st.slip.begin(), st.slip.end(), 0.0);
    std::fill(st.broke.begin(), st.broke.end(), std::uint8_t{0});
    st.cohesion_lost.clear();
    st.damage_time = time;
    columns_.stale = true;
}

void Simulation::save_material_state(ByteWriter& w) const {
    const MaterialState& st = material_state_;
    w.put_vector(st.slip);
    w.put_vector(st.broke);
    w.put_vector(st.cohesion_lost);
    w.put(st.damage_time);
}

Simulation::MaterialState Simulation::read_material_state(ByteReader& r) {
    MaterialState st;
    r.get_vector(st.slip);
    r.get_vector(st.broke);
    r.get_vector(st.cohesion_lost);
    r.get(st.damage_time);
    return st;
}

void Simulation::restore_material_state(MaterialState&& m) {
    material_state_ = std::move(m);
    columns_.stale = true;
}

}  // namespace orodem
