#include "orodem/boundary/conveyor_traction.hpp"

#include <cmath>

#include "orodem/core/bytes.hpp"
#include "orodem/core/parallel.hpp"
#include "orodem/engine/simulation.hpp"

namespace orodem {

void ConveyorTraction::add_forces(Simulation& sim) {
    // Only the discs with a candidate contact with the base (a few per cent
    // of them), listed by the engine at each rebuild in slot order.
    ParticleStore& p = sim.particles;
    const WallContactStore& ws = sim.wall_contacts;
    const Wall& w = sim.walls[wall_];
    const Vec2 u = (1.0 / norm(w.b - w.a)) * (w.b - w.a);
    const double gain_over_dt = gain_ / sim.params.dt;       // γ_b / m_i [1/s]
    const double drag_over_dt = drag_gain_ / sim.params.dt;  // γ_d / m_i [1/s]
    const std::vector<std::uint32_t>& discs = sim.wall_discs(wall_);
    const std::size_t n = discs.size();
    traction_.resize(n);  // no allocation once sized
    capped_.resize(n);
    touching_.resize(n);
    const long long nn = static_cast<long long>(n);
#pragma omp parallel for schedule(static) if(nn >= kParallelMin)
    for (long long ii = 0; ii < nn; ++ii) {
        const std::size_t c = static_cast<std::size_t>(ii);
        const std::size_t i = discs[c];
        traction_[c] = 0.0;
        capped_[c] = 0;
        touching_[c] = 0;
        if (p.inv_mass[i] == 0.0) continue;  // fixed (and sleeping) discs are not dragged
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k) {
            if (ws.wall[k] != wall_) continue;
            // Normal force of the base on the disc: the wall force minus its
            // tangential part (the base wall is smooth, so this is all of it).
            const double normal = ws.f[k].x * -u.y + ws.f[k].y * u.x;
            if (normal <= 0.0) continue;
            touching_[c] = 1;  // counted even when it rides exactly at v' (zero traction)
            const double gamma_b = gain_over_dt * p.mass[i];
            const double slip = v_belt_ - dot(p.v[i], u);  // [m/s]
            double f = gamma_b * slip;
            const double cap = mu_b_ * normal;
            if (std::fabs(f) > cap) {
                f = std::copysign(cap, f);
                capped_[c] = 1;
            }
            if (drag_over_dt != 0.0) f += drag_over_dt * p.mass[i] * slip;  // uncapped drag (0 by default)
            traction_[c] = f;
            p.force[i] += f * u;
        }
    }
    total_traction_ = deterministic_sum(n, [&](std::size_t c) { return traction_[c]; });
    on_base_ = 0;
    sliding_ = 0;
    for (std::size_t c = 0; c < n; ++c) {
        on_base_ += touching_[c];
        sliding_ += capped_[c];
    }
}

void ConveyorTraction::save_state(ByteWriter& w) const {
    w.put(total_traction_);
    w.put(static_cast<std::uint64_t>(on_base_));
    w.put(static_cast<std::uint64_t>(sliding_));
}

void ConveyorTraction::load_state(ByteReader& r) {
    total_traction_ = r.get<double>();
    on_base_ = static_cast<std::size_t>(r.get<std::uint64_t>());
    sliding_ = static_cast<std::size_t>(r.get<std::uint64_t>());
}

}  // namespace orodem
