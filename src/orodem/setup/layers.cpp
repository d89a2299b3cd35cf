#include "orodem/setup/layers.hpp"

#include <numbers>
#include <vector>

#include "orodem/setup/scenario.hpp"

namespace orodem {

MaterialTable material_table(const Config& c) {
    MaterialTable t;
    const double v_per_h0 = c.wedge.v / c.packing.h0;  // S per second [1/s]
    for (const NamedMaterial& nm : c.materials) {
        MaterialLaw m;
        m.law = make_law(nm.m);
        m.density = nm.m.density;
        m.mu_residual = nm.mu_residual;
        m.weakening_distance = nm.weakening_distance;
        m.healing_rate = nm.healing * v_per_h0;
        m.cohesion_loss = nm.cohesion_loss;
        t.materials.push_back(m);
    }
    const std::size_t n = t.materials.size();
    t.pairs.resize(n * n);
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b) {
            double mu = -1.0, mu_res = -1.0;
            for (const FrictionPair& fp : c.friction_pairs)
                if ((fp.a == c.materials[a].name && fp.b == c.materials[b].name) ||
                    (fp.b == c.materials[a].name && fp.a == c.materials[b].name))
                    mu = fp.mu, mu_res = fp.mu_residual;
            t.pairs[a * n + b] = mix_materials(t.materials[a], t.materials[b], mu, mu_res);
        }
    t.mean_diameter = c.packing.r_min + c.packing.r_max;
    return t;
}

std::uint8_t material_id(const Config& c, const std::string& name) {
    for (std::size_t k = 0; k < c.materials.size(); ++k)
        if (c.materials[k].name == name) return static_cast<std::uint8_t>(k);
    return 0;  // not reached: the loader refuses unknown names
}

void assign_material(const Config& c, ParticleStore& p, const std::string& name) {
    const std::size_t n = p.size();
    const std::uint8_t id = material_id(c, name);
    p.material.assign(n, id);
    p.layer.assign(n, 0);
    p.damage.assign(n, 0.0);
    const double rho = c.materials[id].m.density;  // [kg/m³]
    for (std::size_t s = 0; s < n; ++s) {
        p.mass[s] = rho * std::numbers::pi * p.radius[s] * p.radius[s];
        if (!(p.flags[s] & (kFlagFixed | kFlagAsleep))) p.set_free_inertia(s);
    }
}

MaterialTable with_damping_ratio(MaterialTable t, double zeta) {
    for (MaterialLaw& m : t.materials) m.law = with_damping_ratio(m.law, zeta);
    for (PairLaw& pl : t.pairs) pl.law = with_damping_ratio(pl.law, zeta);
    return t;
}

void assign_layers(const Config& c, ParticleStore& p, double unit) {
    const std::size_t n = p.size();
    const double h0 = unit > 0.0 ? unit : c.packing.h0;  // [m]
    // Each particle's mean position: a cluster's discs together.
    std::int32_t max_cluster = -1;
    for (std::size_t s = 0; s < n; ++s) max_cluster = std::max(max_cluster, p.cluster[s]);
    std::vector<Vec2> sum(static_cast<std::size_t>(max_cluster + 1));
    std::vector<int> count(sum.size(), 0);
    for (std::size_t s = 0; s < n; ++s)
        if (p.cluster[s] >= 0) {
            sum[static_cast<std::size_t>(p.cluster[s])] += p.x[s];
            ++count[static_cast<std::size_t>(p.cluster[s])];
        }
    p.material.assign(n, 0);
    p.layer.assign(n, 0);
    p.damage.assign(n, 0.0);
    for (std::size_t s = 0; s < n; ++s) {
        Vec2 at = p.x[s];
        if (p.cluster[s] >= 0) {
            const auto k = static_cast<std::size_t>(p.cluster[s]);
            at = (1.0 / count[k]) * sum[k];
        }
        const bool retro = at.x > 0.0;
        const std::vector<LayerConfig>& stack = retro ? c.retro_layers : c.layers;
        std::size_t l = 0;
        double top = stack[0].thickness * h0;  // top of band l above the base [m]
        while (l + 1 < stack.size() && at.y >= top) top += stack[++l].thickness * h0;
        p.layer[s] = static_cast<std::uint8_t>(l);
        p.material[s] = material_id(c, stack[l].material);
        const double rho = c.materials[p.material[s]].m.density;  // [kg/m³]
        p.mass[s] = rho * std::numbers::pi * p.radius[s] * p.radius[s];
        if (!(p.flags[s] & (kFlagFixed | kFlagAsleep))) p.set_free_inertia(s);
    }
}

}  // namespace orodem
