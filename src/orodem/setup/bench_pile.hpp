// The canonical performance problem (../shared/bench/README.md): 30,000
// polydisperse discs settled on a floor, periodic in x, LAMMPS
// gran/hooke/history law. Built from the engine's own parts: the benchmark's
// variants (raw damping coefficient times m_eff, no clamp at F_n = 0,
// k_t = 2/7 k_n, periodic x) are options of the one law and engine.
#pragma once

#include <string>

#include "orodem/engine/simulation.hpp"

namespace orodem {

struct BenchPile {
    double width = 400.0;      // period W [radius units]
    double k_n = 1.0e5;        // [force/length]
    double k_t_over_k_n = 2.0 / 7.0;
    double gamma_n = 200.0;    // F = m_eff γ_n v_n [1/time]
    double mu = 0.3;
    double dt = 2.5e-4;
    double skin = 0.2;
    double density = 1.0;      // mass per unit area
    double g = 1.0;
};

/// Reference kinetic energies (LAMMPS serial) at the given steps.
struct BenchReference {
    std::uint64_t step;
    double kinetic_energy;
};
inline constexpr BenchReference kBenchReference[] = {
    {250, 24.9563708}, {500, 15.3298299}, {1000, 23.3085338}, {1500, 39.9216261}, {2000, 56.7194459}};

/// Simulation of the pile with discs (id x y r per disc, ids in file order).
Simulation make_bench_pile(const ParticleStore& discs, const BenchPile& b = {});

}  // namespace orodem
