#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/core/bytes.hpp"
#include "orodem/core/parallel.hpp"

#include "orodem/engine/simulation.hpp"

namespace orodem {

void FixedRetroside::after_step(Simulation& sim) {
    // Only the discs with a candidate contact with the retroside base, in
    // slot order (serial: a few hundred at most); the count grows as they fix.
    ParticleStore& p = sim.particles;
    const WallContactStore& ws = sim.wall_contacts;
    for (const std::uint32_t i : sim.wall_discs(wall_)) {
        if (p.flags[i] & kFlagFixed) continue;
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k)
            if (ws.wall[k] == wall_ && (ws.f[k].x != 0.0 || ws.f[k].y != 0.0)) {
                p.fix(i);
                ++fixed_;
                break;
            }
    }
}

void FixedRetroside::save_state(ByteWriter& w) const { w.put(static_cast<std::uint64_t>(fixed_)); }

void FixedRetroside::load_state(ByteReader& r) { fixed_ = static_cast<std::size_t>(r.get<std::uint64_t>()); }

}  // namespace orodem
