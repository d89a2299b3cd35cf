#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/core/bytes.hpp"
#include "orodem/core/parallel.hpp"

#include "orodem/engine/simulation.hpp"

namespace orodem {

void FixedRetroside::after_step(Simulation& sim) {
    ParticleStore& p = sim.particles;
    const WallContactStore& ws = sim.wall_contacts;
    const long long n = static_cast<long long>(p.size());
    // Each iteration touches only its own disc.
#pragma omp parallel for schedule(static) if(n >= kParallelMin)
    for (long long ii = 0; ii < n; ++ii) {
        const std::size_t i = static_cast<std::size_t>(ii);
        if (p.flags[i] & kFlagFixed) continue;
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k)
            if (ws.wall[k] == wall_ && (ws.f[k].x != 0.0 || ws.f[k].y != 0.0)) {
                p.fix(i);
                break;
            }
    }
    std::size_t count = 0;
    for (std::size_t i = 0; i < p.size(); ++i) count += (p.flags[i] & kFlagFixed) ? 1 : 0;
    fixed_ = count;
}

void FixedRetroside::save_state(ByteWriter& w) const { w.put(static_cast<std::uint64_t>(fixed_)); }

void FixedRetroside::load_state(ByteReader& r) { fixed_ = static_cast<std::size_t>(r.get<std::uint64_t>()); }

}  // namespace orodem
