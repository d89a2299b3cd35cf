#include "orodem/boundary/coulomb_base.hpp"

#include <cmath>

#include "orodem/engine/simulation.hpp"
#include "orodem/physics/contact_law.hpp"

namespace orodem {

void CoulombBase::apply_law(Simulation& sim, std::size_t c0, std::size_t c1, bool parallel) {
    ParticleStore& p = sim.particles;
    WallContactStore& ws = sim.wall_contacts;
    const double k_s = sim.params.law.k_s;                         // [N/m]
    const double damp = 2.0 * kBaseDampingRatio * std::sqrt(k_s);  // γ_s / sqrt(m_i) [sqrt(kg)/s]
    const double dt = sim.params.dt;
    const double m_min = sim.params.m_inertia_min;  // the dashpot acts on the inertial mass [kg]
    for_each_base_contact(sim, c0, c1, parallel, [&](std::size_t c, std::size_t i, std::uint32_t k, double normal, Vec2 u) {
        if (normal <= 0.0) {
            ws.xi[k] = {};  // not pressed on the base: no grip
            return;
        }
        const double slip = dot(p.v[i], u) - v_belt_;  // disc centre relative to the belt [m/s]
        double xi = dot(ws.xi[k], u);                  // [m]
        const BaseSpringForce bf = eval_base_spring(k_s, damp * std::sqrt(p.inertial_mass(i, m_min)), mu_b_, normal, slip, dt, xi);
        ws.xi[k] = xi * u;
        ws.f[k] += bf.f * u;
        p.force[i] += bf.f * u;
        set_slot(c, bf.f, true, bf.sliding);
    });
}

}  // namespace orodem
