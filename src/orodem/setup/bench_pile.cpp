#include "orodem/setup/bench_pile.hpp"

namespace orodem {

Simulation make_bench_pile(const ParticleStore& discs, const BenchPile& b) {
    Simulation sim;
    sim.particles = discs;
    sim.params.law.k_n = b.k_n;
    sim.params.law.k_s = b.k_t_over_k_n * b.k_n;
    sim.params.law.mu = b.mu;
    sim.params.law.damp_mass_n = b.gamma_n;
    sim.params.law.clamp_normal = false;
    sim.params.law.tangential = true;
    sim.params.dt = b.dt;
    sim.params.gravity = {0.0, -b.g};
    sim.params.skin = b.skin;
    sim.params.periodic_x = true;
    sim.params.period_x = b.width;
    // The floor y = 0: an infinite rough line with the same law and μ.
    sim.walls.push_back({{0.0, 0.0}, {1.0, 0.0}, {}, 0.0, true, true, b.mu});
    return sim;
}

}  // namespace orodem
