// Golden hashes: the full dynamic state (Simulation::state_hash: x, v, θ, ω
// and ξ in id order) after a fixed scene is stepped, pinned to the values
// the engine gave when they were recorded. A change to the step, the kernels,
// the pair builder, the bases or the sleeping zones that is meant to leave
// every output the same must leave these the same; one that changes results
// on purpose (a physics change) updates them in the same commit and says so.
// The scenes cover each path of Simulation::step(): settling (no
// boundaries, the whole step in one parallel region), and an exp1 wedge with
// sleeping zones stepped phase by phase and in one region
// (one_region_min_awake 0), at one and two threads (the scene is small, so
// phase by phase it runs on one thread; the one-region path always forks,
// and splits its pairs and discs between the two). The canonical pile of
// ../shared/bench (the benchmark's hash) is pinned too where that folder is.
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <filesystem>

#include <gtest/gtest.h>

#include "orodem/io/config.hpp"
#include "orodem/io/pile_file.hpp"
#include "orodem/setup/bench_pile.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"
#include "layer_util.hpp"

using namespace orodem;

namespace {

// Recorded with the engine of main at cbe635d (the pile's also as
// `orodem bench pile --pile ../shared/bench/settled.txt --steps 1000`).
constexpr std::uint64_t kSettledLayer = 0x98642a96f6b87b17ULL;
constexpr std::uint64_t kWedgeAtS02 = 0x216591afa46aaa8cULL;
constexpr std::uint64_t kPileAt1000 = 0xde423d709bfd2a06ULL;

Config golden_config() {
    return parse_config("[run]\nexperiment = \"exp1\"\n[wedge]\nv = 0.2\nmu_bp = 0.3\ns_max = 1.0\n"
                        "pro_margin = 6.0\nretro_length = 3.0\nsleep = true\ninertia_floor = 1.5\n"
                        "[packing]\nkind = \"clusters\"\nr_min = 0.5\nr_max = 0.75\nh0 = 4.0\nseed = 7\n",
                        "golden.toml");
}

const ParticleStore& layer() {
    static const ParticleStore p = test::settled_cut_layer(golden_config());
    return p;
}

/// The wedge carried to S = 0.2 at `threads` threads, from one_region_min_awake awake discs on in one region.
std::uint64_t wedge_hash(int threads, std::size_t one_region_min_awake) {
    const Config c = golden_config();
    omp_set_num_threads(threads);
    WedgeSetup w = make_wedge(c, layer());
    w.sim.one_region_min_awake = one_region_min_awake;
    w.sim.initialize();
    w.sim.advance(static_cast<std::uint64_t>(std::llround(0.2 * c.packing.h0 / (c.wedge.v * w.sim.params.dt))));
    omp_set_num_threads(omp_get_num_procs());
    EXPECT_GT(w.sim.rebuild_count(), 3u);
    EXPECT_GT(w.sim.sleeping_count(), 0u) << "the scene should have sleeping discs";
    return w.sim.state_hash();
}

std::uint64_t layer_hash() {
    Simulation s;
    s.particles = layer();
    return s.state_hash();
}

}  // namespace

TEST(Golden, SettledLayer) {
    EXPECT_EQ(layer_hash(), kSettledLayer) << std::hex << "0x" << layer_hash();
}

TEST(Golden, WedgeStepPathsAndThreads) {
    for (int threads : {1, 2})
        for (std::size_t min_awake : {std::size_t{1} << 30, std::size_t{0}}) {
            const std::uint64_t h = wedge_hash(threads, min_awake);
            EXPECT_EQ(h, kWedgeAtS02) << std::hex << "0x" << h << " at " << std::dec << threads << " threads, "
                                      << (min_awake == 0 ? "one region" : "phase by phase");
        }
}

TEST(Golden, CanonicalPile) {
    const std::string pile = std::string(ORODEM_SHARED_DIR) + "/bench/settled.txt";
    if (!std::filesystem::exists(pile)) GTEST_SKIP() << "no " << pile;
    Simulation sim = make_bench_pile(read_pile_file(pile, BenchPile{}.density));
    sim.initialize();
    sim.advance(1000);
    EXPECT_EQ(sim.state_hash(), kPileAt1000) << std::hex << "0x" << sim.state_hash();
}
