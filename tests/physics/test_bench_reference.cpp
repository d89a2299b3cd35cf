// The contact law, wall, periodic boundary and integrator against an
// independent implementation: LAMMPS gran/hooke/history on the canonical
// 30,000-disc pile (../shared/bench/README.md). The reference kinetic
// energies are printed to 9 significant digits, so a correct implementation
// agrees to a relative 5e-9 (print resolution) plus round-off; we allow 1e-7,
// still 5 orders of magnitude below what a one-ulp-per-step algorithmic
// difference in the law grows to over 1000 steps of this chaotic pile.
#include <filesystem>

#include <gtest/gtest.h>

#include "orodem/io/pile_file.hpp"
#include "orodem/setup/bench_pile.hpp"

using namespace orodem;

TEST(BenchReference, KineticEnergyMatchesLammpsOver1000Steps) {
    const std::string pile = std::string(ORODEM_SHARED_DIR) + "/bench/settled.txt";
    if (!std::filesystem::exists(pile)) GTEST_SKIP() << "no " << pile;
    Simulation sim = make_bench_pile(read_pile_file(pile, BenchPile{}.density));
    ASSERT_EQ(sim.particles.size(), 30000u);
    sim.initialize();
    std::uint64_t done = 0;
    for (const BenchReference& ref : kBenchReference) {
        if (ref.step > 1000) break;
        sim.advance(ref.step - done);
        done = ref.step;
        EXPECT_NEAR(sim.kinetic_energy() / ref.kinetic_energy, 1.0, 1e-7) << "step " << ref.step;
    }
}
