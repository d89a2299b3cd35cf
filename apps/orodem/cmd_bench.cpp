// orodem bench-pile PILE: the canonical benchmark of docs/benchmarks.md, the
// settled pile of the LAMMPS comparison stepped and timed, its kinetic energy
// checked against the LAMMPS reference.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/pile_file.hpp"
#include "orodem/run/wedge_run.hpp"
#include "orodem/setup/bench_pile.hpp"

#include "commands.hpp"

namespace orodem {

/// The canonical benchmark: run `steps` steps of the settled pile, check the
/// kinetic energy against the LAMMPS reference, print the speed.
int cmd_bench_pile(const std::string& pile, std::uint64_t steps, int threads) {
    if (threads > 0) omp_set_num_threads(threads);
    const ParticleStore discs = read_pile_file(pile, BenchPile{}.density);
    Simulation sim = make_bench_pile(discs);
    sim.initialize();
    // Times the step loop only, as LAMMPS's "Loop time" (set-up excluded).
    const auto t0 = std::chrono::steady_clock::now();
    double worst = 0.0;
    std::uint64_t done = 0;
    for (const BenchReference& ref : kBenchReference) {
        if (ref.step > steps) break;
        sim.advance(ref.step - done);
        done = ref.step;
        const double ke = sim.kinetic_energy();
        const double rel = std::fabs(ke - ref.kinetic_energy) / ref.kinetic_energy;
        worst = std::max(worst, rel);
        fmt::print("step {:6d}: kinetic energy {:.9g} (LAMMPS {:.9g}, rel. diff {:.2e})\n", ref.step, ke,
                   ref.kinetic_energy, rel);
    }
    sim.advance(steps - done);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double n = static_cast<double>(sim.particles.size());
    fmt::print("discs {} steps {} threads {} loop time {:.3f} s\n", sim.particles.size(), steps,
               omp_get_max_threads(), secs);
    fmt::print("timesteps/s {:.1f}  particle-steps/s {:.3e}  rebuilds {}\n", double(steps) / secs,
               n * double(steps) / secs, sim.rebuild_count());
    fmt::print("pairs {} ({:.2f} per disc)\n", sim.contacts.size(), double(sim.contacts.size()) / n);
    fmt::print("phases: {}\n", phase_breakdown(sim.phase_times()));
    fmt::print("state hash {:016x} (identical at any thread count)\n", sim.state_hash());
    fmt::print("reference check: worst relative kinetic-energy difference {:.2e} ({})\n", worst,
               worst < 1e-6 ? "matches" : "DIFFERS");
    return worst < 1e-6 ? 0 : static_cast<int>(ExitCode::unstable);
}

}  // namespace orodem
