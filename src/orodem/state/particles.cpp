#include "orodem/state/particles.hpp"

#include <numbers>
#include <unordered_map>

namespace orodem {

std::size_t ParticleStore::add(Vec2 pos, double r, double density, std::int32_t cluster_id) {
    const double m = density * std::numbers::pi * r * r;
    const std::size_t slot = size();
    x.push_back(pos);
    v.push_back({});
    theta.push_back(0.0);
    omega.push_back(0.0);
    radius.push_back(r);
    mass.push_back(m);
    inv_mass.push_back(1.0 / m);
    inv_inertia.push_back(2.0 / (m * r * r));
    force.push_back({});
    torque.push_back(0.0);
    id.push_back(static_cast<std::uint32_t>(slot));
    cluster.push_back(cluster_id);
    flags.push_back(0);
    initial_depth.push_back(0.0);
    side.push_back(0);
    if (has_materials()) {
        material.push_back(0);
        layer.push_back(0);
        damage.push_back(0.0);
    }
    slot_of_id.push_back(static_cast<std::uint32_t>(slot));
    return slot;
}

void ParticleStore::rebuild_slot_map() {
    slot_of_id.assign(size(), 0);
    for (std::size_t s = 0; s < size(); ++s) slot_of_id[id[s]] = static_cast<std::uint32_t>(s);
}

void ParticleStore::compact(const std::vector<std::uint8_t>& keep) {
    auto keep_slots = [&](auto& col) {
        std::size_t w = 0;
        for (std::size_t s = 0; s < col.size(); ++s)
            if (keep[s]) col[w++] = col[s];
        col.resize(w);
    };
    for_each_column(keep_slots);
    if (has_materials()) for_each_material_column(keep_slots);
    // Dense renumbering keeps ids usable as array indices.
    std::unordered_map<std::int32_t, std::int32_t> cluster_map;
    for (std::size_t s = 0; s < size(); ++s) {
        id[s] = static_cast<std::uint32_t>(s);
        if (cluster[s] >= 0) {
            auto [it, inserted] =
                cluster_map.try_emplace(cluster[s], static_cast<std::int32_t>(cluster_map.size()));
            cluster[s] = it->second;
        }
    }
    rebuild_slot_map();
}

}  // namespace orodem
