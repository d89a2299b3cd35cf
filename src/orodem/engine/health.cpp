#include "orodem/engine/health.hpp"

#include <cmath>

#include <fmt/format.h>

#include "orodem/engine/simulation.hpp"

namespace orodem {

OverlapSummary overlap_summary(const Simulation& sim, double threshold) {
    const ParticleStore& p = sim.particles;
    const ContactStore& cs = sim.contacts;
    OverlapSummary s;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        if (cs.bonded[k]) continue;
        const double ratio = sim.pair_overlap_ratio(k);
        if (ratio <= 0.0) continue;
        ++s.touching;
        if (ratio > threshold) ++s.above;
        if (ratio > s.worst) {
            s.worst = ratio;
            s.id_i = p.id[cs.i[k]];
            s.id_j = p.id[cs.j[k]];
            s.x_i = p.x[cs.i[k]];
            s.x_j = p.x[cs.j[k]];
        }
    }
    return s;
}

std::optional<HealthProblem> check_health(const Simulation& sim, const HealthLimits& lim) {
    const ParticleStore& p = sim.particles;
    const std::size_t n = p.size();
    // 1. Non-finite state.
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        const Vec2 x = p.x[s], v = p.v[s];
        const bool bad_x = !std::isfinite(x.x) || !std::isfinite(x.y);
        const bool bad_v = !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(p.omega[s]);
        if (bad_x || bad_v)
            return HealthProblem{bad_x ? "non-finite position" : "non-finite velocity", id, x,
                                 fmt::format("x = ({:g}, {:g}) m, v = ({:g}, {:g}) m/s, omega = {:g} rad/s", x.x,
                                             x.y, v.x, v.y, p.omega[s]),
                                 "the time step is too large for the stiffness or a force exploded; lower "
                                 "numerics.safety (or numerics.dt) or material.k_n"};
    }
    // 2. Overlap explosion.
    const ContactStore& cs = sim.contacts;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        if (cs.bonded[k]) continue;
        const std::uint32_t i = cs.i[k], j = cs.j[k];
        const double ratio = sim.pair_overlap_ratio(k);
        if (ratio > lim.max_overlap_ratio)
            return HealthProblem{"overlap", p.id[i], p.x[i],
                                 fmt::format("overlap {:.3f} of the smaller radius with disc {} at ({:g}, {:g}); "
                                             "limit run.max_overlap_ratio = {:g}",
                                             ratio, p.id[j], p.x[j].x, p.x[j].y, lim.max_overlap_ratio),
                                 "discs are driven into each other faster than the springs push back: lower "
                                 "wedge.v (eq. 6) or numerics.safety, or raise material.k_n"};
    }
    // 3. Speed and 4. domain.
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.flags[s] & kFlagRemoved) continue;  // eroded, parked below the base
        const Vec2 x = p.x[s];
        const double speed = norm(p.v[s]);
        if (lim.max_speed > 0.0 && speed > lim.max_speed)
            return HealthProblem{"speed", id, x,
                                 fmt::format("|v| = {:.4g} m/s above the bound {:.4g} m/s", speed, lim.max_speed),
                                 "a disc was shot out by an overlap explosion; lower numerics.safety or wedge.v"};
        if (x.x < lim.x_min || x.x > lim.x_max || x.y < lim.y_min || x.y > lim.y_max)
            return HealthProblem{"left the domain", id, x,
                                 fmt::format("domain x in [{:g}, {:g}] m, y in [{:g}, {:g}] m", lim.x_min, lim.x_max,
                                             lim.y_min, lim.y_max),
                                 "a disc escaped through a wall or was shot out; lower numerics.safety or "
                                 "wedge.v, or check the walls' positions"};
    }
    return std::nullopt;
}

}  // namespace orodem
