// Thread-count determinism (SPEC §5): the same simulation stepped at 1, 2, 3
// and 4 threads gives a bit-identical full state (x, v, θ, ω, ξ by key).
// The system has well over kParallelMin discs and pairs, so every kernel
// really runs split across the threads.
#include <omp.h>

#include <gtest/gtest.h>

#include "orodem/core/parallel.hpp"
#include "orodem/io/config.hpp"
#include "orodem/setup/scenario.hpp"

using namespace orodem;

namespace {
std::uint64_t hash_after(int threads, const std::string& kind, std::uint64_t steps) {
    omp_set_num_threads(threads);
    const Config c = parse_config("[run]\nexperiment = \"settle\"\n[packing]\nkind = \"" + kind +
                                      "\"\nlength = 1200.0\nh0 = 6.0\n",
                                  "determinism.toml");
    Simulation sim = make_settle_simulation(c);
    sim.initialize();
    EXPECT_GT(sim.particles.size(), static_cast<std::size_t>(kParallelMin));
    sim.advance(steps);  // falling and colliding: many rebuilds and re-sorts
    EXPECT_GT(sim.rebuild_count(), 3u);
    return sim.state_hash();
}
}  // namespace

TEST(Determinism, StateHashIdenticalAt1To4Threads) {
    for (const char* kind : {"clusters", "discs"}) {
        const std::uint64_t h1 = hash_after(1, kind, 1500);
        for (int t = 2; t <= 4; ++t) EXPECT_EQ(hash_after(t, kind, 1500), h1) << kind << " at " << t << " threads";
    }
    omp_set_num_threads(omp_get_num_procs());
}
