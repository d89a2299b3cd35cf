// Thread-count determinism (SPEC §5): the same simulation stepped at 1, 2, 3
// and 4 threads gives a bit-identical full state (x, v, θ, ω, ξ by key).
#include <omp.h>

#include <gtest/gtest.h>

#include "orodem/io/config.hpp"
#include "orodem/setup/scenario.hpp"

using namespace orodem;

namespace {
std::uint64_t hash_after(int threads, const std::string& kind, std::uint64_t steps) {
    omp_set_num_threads(threads);
    const Config c = parse_config("[run]\nexperiment = \"settle\"\n[packing]\nkind = \"" + kind +
                                      "\"\nlength = 40.0\nh0 = 6.0\n",
                                  "determinism.toml");
    Simulation sim = make_settle_simulation(c);
    sim.initialize();
    sim.advance(steps);  // falling and colliding: many rebuilds and re-sorts
    EXPECT_GT(sim.rebuild_count(), 3u);
    return sim.state_hash();
}
}  // namespace

TEST(Determinism, StateHashIdenticalAt1To4Threads) {
    for (const char* kind : {"clusters", "discs"}) {
        const std::uint64_t h1 = hash_after(1, kind, 3000);
        for (int t = 2; t <= 4; ++t) EXPECT_EQ(hash_after(t, kind, 3000), h1) << kind << " at " << t << " threads";
    }
    omp_set_num_threads(omp_get_num_procs());
}
