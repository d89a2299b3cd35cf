// Simulation's diagnostics: energies, contact counts, overlaps, speeds,
// wall forces and the state hash. Read-only and outside the step; the sums
// are deterministic (fixed chunks, core/parallel.hpp), so they are the same
// at any thread count.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "orodem/core/hash.hpp"
#include "orodem/core/parallel.hpp"
#include "orodem/engine/simulation.hpp"

namespace orodem {

double Simulation::kinetic_energy() const {
    const ParticleStore& p = particles;
    const double m_min = params.m_inertia_min;
    return deterministic_sum(p.size(), [&](std::size_t i) { return 0.5 * p.inertial_mass(i, m_min) * norm2(p.v[i]); });
}

EnergyReport Simulation::energies() const {
    const ParticleStore& p = particles;
    EnergyReport e;
    e.kinetic_translational = kinetic_energy();
    e.kinetic_rotational = deterministic_sum(p.size(), [&](std::size_t i) {
        const double inertia = 0.5 * p.inertial_mass(i, params.m_inertia_min) * p.radius[i] * p.radius[i];
        return 0.5 * inertia * p.omega[i] * p.omega[i];
    });
    e.gravitational = deterministic_sum(p.size(), [&](std::size_t i) {
        return -p.mass[i] * dot(params.gravity, p.x[i]);
    });
    const ContactStore& cs = contacts;
    const double W = params.period_x;
    const LawParams& law = params.law;
    double elastic = deterministic_sum(cs.size(), [&](std::size_t k) {
        const Vec2 d = p.x[cs.i[k]] - (p.x[cs.j[k]] + Vec2{cs.shift[k] * W, 0.0});
        const double delta = p.radius[cs.i[k]] + p.radius[cs.j[k]] - norm(d);
        if (delta <= 0.0 && !cs.bonded[k]) return 0.0;
        return 0.5 * law.k_n * delta * delta + 0.5 * law.k_s * norm2(cs.xi[k]);
    });
    const WallContactStore& ws = wall_contacts;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k) {
            Vec2 cp;
            if (!wall_contact_point(walls[ws.wall[k]], p.x[i], cp)) continue;
            const double delta = p.radius[i] - norm(p.x[i] - cp);
            if (delta > 0.0)
                elastic += 0.5 * law.k_n * delta * delta + 0.5 * wall_law_[ws.wall[k]].k_s * norm2(ws.xi[k]);
        }
    e.elastic = elastic;
    return e;
}

std::size_t Simulation::touching_contacts() const {
    std::size_t count = 0;
    const ContactStore& cs = contacts;
    for (std::size_t k = 0; k < cs.size(); ++k)
        if (!cs.bonded[k] && (cs.f[k].x != 0.0 || cs.f[k].y != 0.0 || cs.xi[k].x != 0.0 || cs.xi[k].y != 0.0))
            ++count;
    for (std::size_t k = 0; k < wall_contacts.size(); ++k)
        if (wall_contacts.f[k].x != 0.0 || wall_contacts.f[k].y != 0.0) ++count;
    return count;
}

double Simulation::max_overlap_ratio() const {
    const ContactStore& cs = contacts;
    double worst = 0.0;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        if (cs.bonded[k]) continue;
        worst = std::max(worst, pair_overlap_ratio(k));
    }
    return worst;
}

double Simulation::mean_overlap_ratio() const {
    const ContactStore& cs = contacts;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        if (cs.bonded[k]) continue;
        const double ratio = pair_overlap_ratio(k);
        if (ratio > 0.0) {
            sum += ratio;
            ++count;
        }
    }
    return count ? sum / static_cast<double>(count) : 0.0;
}

double Simulation::max_speed() const {
    double m = 0.0;
    for (const Vec2& v : particles.v) m = std::max(m, norm2(v));
    return std::sqrt(m);
}

Vec2 Simulation::wall_force(std::size_t w) const {
    Vec2 f{};
    for (std::size_t k = 0; k < wall_contacts.size(); ++k)
        if (wall_contacts.wall[k] == w) f -= wall_contacts.f[k];
    return f;
}

std::uint64_t Simulation::state_hash() const {
    const ParticleStore& p = particles;
    Fnv1a h;
    for (std::uint32_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        h.add(p.x[s]); h.add(p.v[s]); h.add(p.theta[s]); h.add(p.omega[s]);
    }
    std::vector<std::pair<std::uint64_t, Vec2>> hist;
    for (std::size_t k = 0; k < contacts.size(); ++k) hist.emplace_back(contacts.key[k], contacts.xi[k]);
    for (std::size_t k = 0; k < wall_contacts.size(); ++k)
        hist.emplace_back(wall_contacts.key[k] | (1ULL << 63), wall_contacts.xi[k]);
    std::sort(hist.begin(), hist.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [key, xi] : hist) {
        if (xi.x == 0.0 && xi.y == 0.0) continue;
        h.add(key); h.add(xi);
    }
    h.add(step_count);
    return h.value();
}

}  // namespace orodem
