#include "orodem/boundary/conveyor_traction.hpp"

#include <cmath>

#include "orodem/engine/simulation.hpp"

namespace orodem {

void ConveyorTraction::apply_law(Simulation& sim, std::size_t c0, std::size_t c1, bool parallel) {
    ParticleStore& p = sim.particles;
    const double gain_over_dt = gain_ / sim.params.dt;       // γ_b / m_i [1/s]
    const double drag_over_dt = drag_gain_ / sim.params.dt;  // γ_d / m_i [1/s]
    for_each_base_contact(sim, c0, c1, parallel, [&](std::size_t c, std::size_t i, std::uint32_t, double normal, Vec2 u) {
        if (normal <= 0.0) return;
        const double gamma_b = gain_over_dt * p.mass[i];
        const double slip = v_belt_ - dot(p.v[i], u);  // [m/s]
        double f = gamma_b * slip;
        const double cap = mu_b_ * normal;
        const bool capped = std::fabs(f) > cap;
        if (capped) f = std::copysign(cap, f);
        if (drag_over_dt != 0.0) f += drag_over_dt * p.mass[i] * slip;  // uncapped drag (0 by default)
        set_slot(c, f, true, capped);  // touching even when it rides exactly at v' (zero traction)
        p.force[i] += f * u;
    });
}

}  // namespace orodem
