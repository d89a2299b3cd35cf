#include "orodem/analysis/rel_disp.hpp"

#include <algorithm>

namespace orodem {

std::vector<Vec2> positions_by_id(const ParticleStore& p) {
    std::vector<Vec2> x(p.size());
    for (std::size_t s = 0; s < p.size(); ++s) x[p.id[s]] = p.x[s];
    return x;
}

std::vector<double> relative_displacement_m(const Simulation& sim, const std::vector<Vec2>& x_then) {
    const ParticleStore& p = sim.particles;
    const ContactStore& cs = sim.contacts;
    std::vector<double> r(p.size(), 0.0);
    if (x_then.size() != p.size()) return r;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        const std::uint32_t i = cs.i[k], j = cs.j[k];
        const Vec2 di = p.x[i] - x_then[p.id[i]];
        const Vec2 dj = p.x[j] - x_then[p.id[j]];
        const double d = norm(di - dj);
        r[i] = std::max(r[i], d);
        r[j] = std::max(r[j], d);
    }
    return r;
}

std::vector<double> normalised(std::vector<double> v) {
    const double m = v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
    if (m > 0.0)
        for (double& x : v) x /= m;
    return v;
}

std::vector<double> relative_displacement(const Simulation& sim, const std::vector<Vec2>& x_then) {
    return normalised(relative_displacement_m(sim, x_then));
}

}  // namespace orodem
