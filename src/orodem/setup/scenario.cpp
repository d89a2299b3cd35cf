#include "orodem/setup/scenario.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "orodem/core/error.hpp"

#include "orodem/setup/packing.hpp"

namespace orodem {

LawParams make_law(const MaterialConfig& m) {
    LawParams l;
    l.k_n = m.k_n;
    l.k_s = m.k_s_over_k_n * m.k_n;
    l.mu = m.mu;
    l.cohesion = m.cohesion;
    l.clamp_normal = m.clamp_normal;
    l.tangential = l.k_s > 0.0;
    if (m.damping_kind == "coefficient") {
        l.damp_mass_n = m.damping_normal;
        l.damp_mass_s = m.damping_tangential;
    } else {
        const double zeta_n = m.damping_kind == "restitution"
                                  ? damping_ratio_from_restitution(m.damping_normal)
                                  : m.damping_normal;
        l.damp_sqrt_n = 2.0 * zeta_n * std::sqrt(l.k_n);
        l.damp_sqrt_s = 2.0 * m.damping_tangential * std::sqrt(l.k_s);
    }
    return l;
}

LawParams with_damping_ratio(LawParams law, double zeta) {
    law.damp_mass_n = law.damp_mass_s = 0.0;
    law.damp_sqrt_n = 2.0 * zeta * std::sqrt(law.k_n);
    law.damp_sqrt_s = 2.0 * zeta * std::sqrt(law.k_s);
    return law;
}

double lightest_mass(const Config& c) {
    const double r = c.packing.kind == "hexagonal" ? c.packing.r_max : c.packing.r_min;
    return c.material.density * std::numbers::pi * r * r;
}

TimestepInfo timestep_for(const Config& c) {
    try {
        return choose_timestep(lightest_mass(c), make_law(c.material), c.numerics.dt, c.numerics.safety);
    } catch (const ConfigError& e) {
        // Name the config key (SPEC §5); the physics layer does not know it.
        throw ConfigError(fmt::format("{}: key 'numerics.dt' = {:g}: {}", c.path, c.numerics.dt, e.what()));
    }
}

Simulation make_settle_simulation(const Config& c) {
    Simulation sim;
    sim.particles = generate_packing(c.packing, c.material.density);
    sim.params.law = with_damping_ratio(make_law(c.material), c.packing.settle_damping_ratio);
    sim.params.dt = timestep_for(c).dt;
    sim.params.gravity = {0.0, -c.numerics.gravity};
    sim.params.skin = c.numerics.skin;
    const double L = c.packing.length;
    const double top = 1e3 * (c.packing.h0 + L);  // side walls reach far above the pack [m]
    sim.walls.push_back({{0.0, 0.0}, {L, 0.0}, {}, 0.0, true, true, c.packing.wall_mu});  // floor
    sim.walls.push_back({{0.0, 0.0}, {0.0, top}, {}, 0.0, false, false, 0.0});          // left
    sim.walls.push_back({{L, 0.0}, {L, top}, {}, 0.0, false, false, 0.0});              // right
    return sim;
}

std::size_t generated_particle_count(const Config& c) {
    return generate_packing(c.packing, c.material.density).size();
}

}  // namespace orodem
