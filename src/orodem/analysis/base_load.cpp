#include "orodem/analysis/base_load.hpp"

#include <algorithm>

namespace orodem {

double base_load_by_id(const Simulation& sim, const std::vector<std::size_t>& base_walls, std::vector<double>& load) {
    const ParticleStore& p = sim.particles;
    const WallContactStore& ws = sim.wall_contacts;
    const double g = -sim.params.gravity.y;  // [m/s²]
    const std::size_t n = p.size();
    load.assign(n, 0.0);
    const auto is_base = [&](std::size_t w) {
        return std::find(base_walls.begin(), base_walls.end(), w) != base_walls.end();
    };
    double total = 0.0;
    for (std::size_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        const std::uint8_t fl = p.flags[s];
        if (fl & kFlagRemoved) continue;
        double q = 0.0;  // [N]
        if ((fl & kFlagAsleep) || !sim.in_awake_range(s)) {
            // A sleeping zone, fixed discs included: each disc its own
            // weight. A fixed disc there keeps the force of the last rebuild
            // step, which holds the column above it, whose discs count
            // themselves: counted twice before (base_load_ratio 1.1-1.2).
            q = p.mass[s] * g;
        } else {
            double base_y = 0.0;  // the base walls' force on the disc, y [N]
            if (s + 1 < ws.begin.size())
                for (std::uint32_t k = ws.begin[s]; k < ws.begin[s + 1]; ++k)
                    if (is_base(ws.wall[k])) base_y += ws.f[k].y;
            q = (fl & kFlagFixed) ? base_y - p.force[s].y : base_y;
        }
        load[id] = q;
        total += q;
    }
    return total;
}

double present_weight(const Simulation& sim) {
    const ParticleStore& p = sim.particles;
    const double g = -sim.params.gravity.y;
    double total = 0.0;
    for (std::size_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (!(p.flags[s] & kFlagRemoved)) total += p.mass[s] * g;
    }
    return total;
}

}  // namespace orodem
