#include "orodem/setup/scenario.hpp"

#include <unistd.h>

#include <limits>

#include <algorithm>
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
    if (m.damping_kind == DampingKind::coefficient) {
        l.damp_mass_n = m.damping_normal;
        l.damp_mass_s = m.damping_tangential;
    } else {
        const double zeta_n = m.damping_kind == DampingKind::restitution
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

MaterialConfig governing_material(const Config& c) {
    MaterialConfig m = c.material;
    for (const NamedMaterial& nm : c.materials) {
        m.density = std::min(m.density, nm.m.density);
        m.k_n = std::max(m.k_n, nm.m.k_n);
        m.k_s_over_k_n = std::max(m.k_s_over_k_n, nm.m.k_s_over_k_n);
    }
    return m;
}

double lightest_mass(const Config& c) {
    const double r = c.packing.kind == PackingKind::hexagonal ? c.packing.r_max : c.packing.r_min;
    return governing_material(c).density * std::numbers::pi * r * r;
}

double inertia_floor_mass(const Config& c) {
    if (!is_wedge(c) || !(c.wedge.inertia_floor > 1.0)) return 0.0;
    const double r = c.wedge.inertia_floor * c.packing.r_min;  // [m]
    return c.material.density * std::numbers::pi * r * r;
}

double inertia_floor_mean_mass_ratio(const Config& c) {
    const double a = c.packing.r_min, b = c.packing.r_max;  // [m]
    const double f_r = std::min(c.wedge.inertia_floor * a, b);  // the floor's radius F [m]
    if (inertia_floor_mass(c) == 0.0 || c.packing.kind == PackingKind::hexagonal || !(b > a) || !(f_r > a)) return 1.0;
    // (b - a) E[R²] and (b - a) E[max(R², F²)] for R uniform in [a, b].
    const double own = (b * b * b - a * a * a) / 3.0;
    const double floored = f_r * f_r * (f_r - a) + (b * b * b - f_r * f_r * f_r) / 3.0;
    return floored / own;
}

double lightest_inertial_mass(const Config& c) { return std::max(lightest_mass(c), inertia_floor_mass(c)); }

TimestepInfo timestep_for(const Config& c, bool with_floor) {
    try {
        const double m_min = with_floor ? lightest_inertial_mass(c) : lightest_mass(c);
        return choose_timestep(m_min, make_law(governing_material(c)), c.numerics.dt, c.numerics.safety);
    } catch (const ConfigError& e) {
        // Name the config key (SPEC §5); the physics layer does not know it.
        throw ConfigError(fmt::format("{}: key 'numerics.dt' = {:g}: {}", c.path, c.numerics.dt, e.what()));
    }
}

Simulation make_settle_simulation(const Config& c) {
    Simulation sim;
    sim.particles = generate_packing(c.packing, c.material.density);
    sim.params.law = with_damping_ratio(make_law(c.material), c.packing.settle_damping_ratio);
    sim.params.dt = timestep_for(c, false).dt;  // the packing is settled without the inertia floor
    sim.params.gravity = {0.0, -c.numerics.gravity};
    sim.params.skin = c.numerics.skin;
    const double L = c.packing.length;
    const double top = 1e3 * (c.packing.h0 + L);  // side walls reach far above the pack [m]
    sim.walls.push_back({{0.0, 0.0}, {L, 0.0}, {}, 0.0, true, true, c.packing.wall_mu});  // floor
    sim.walls.push_back({{0.0, 0.0}, {0.0, top}, {}, 0.0, false, false, 0.0});          // left
    sim.walls.push_back({{L, 0.0}, {L, top}, {}, 0.0, false, false, 0.0});              // right
    return sim;
}

double estimated_disc_count(const PackingConfig& pc) {
    // generate_packing fills 0.9 L (h0 + 3 r_max) with discs of mean area
    // π E[r²], r uniform in [r_min, r_max] (all r_max for hexagonal).
    const double target_area = 0.9 * pc.length * (pc.h0 + 3.0 * pc.r_max);  // [m²]
    const double a = pc.kind == PackingKind::hexagonal ? pc.r_max * pc.r_max
                                            : (pc.r_min * pc.r_min + pc.r_min * pc.r_max + pc.r_max * pc.r_max) / 3.0;
    double n = target_area / (M_PI * a);
    if (pc.kind == PackingKind::hexagonal) n += pc.length / (2.0 * pc.r_max);  // whole rows: up to one more
    return std::isfinite(n) ? n : std::numeric_limits<double>::infinity();
}

void check_disc_budget(const Config& c, const PackingConfig& sample, const std::string& what,
                       const std::string& keys) {
    const double n = estimated_disc_count(sample);
    const double pages = static_cast<double>(::sysconf(_SC_PHYS_PAGES));
    const double memory = pages * static_cast<double>(::sysconf(_SC_PAGESIZE));  // [bytes]
    const double need = n * kBytesPerDisc;
    if (n <= kMaxDiscs && (memory <= 0.0 || need <= 0.8 * memory)) return;
    throw ConfigError(fmt::format(
        "{}: {} ({:g} m long, {:g} m high, radii {:g}-{:g} m) would have about {:.3g} discs and need about "
        "{:.3g} GB; orodem runs at most {:.0e} discs and {:.3g} GB (80% of this machine's memory); lower {}",
        c.path, what, sample.length, sample.h0, sample.r_min, sample.r_max, n, need / 1e9, kMaxDiscs,
        0.8 * memory / 1e9, keys));
}

void check_model_size(const Config& c) {
    check_disc_budget(c, c.packing, "the layer",
                      is_wedge(c) ? "packing.h0, wedge.s_max, wedge.pro_margin or wedge.retro_length"
                                  : "packing.h0 or packing.length");
}

std::size_t generated_particle_count(const Config& c) {
    return generate_packing(c.packing, c.material.density).size();
}

}  // namespace orodem
