// Micro-benchmarks of the phases of Simulation::step() on the canonical
// 30,000-disc pile (../shared/bench/README.md), each at 1 and 2 threads:
//   Rebuild      neighbour rebuild (sort by cell, pair and wall lists, history)
//   PairForces   phase A: the contact law per candidate pair
//   Gather       phase B: per-disc sums of pair forces, plus the wall contacts
//   KickDrift    first half kick and drift (with the rebuild trigger's max displacement)
//   Kick         second half kick
//   Conveyor     ConveyorTraction::add_forces with the floor as the belt
//   Step         one whole step()
// The state is the pile after 300 steps (contacts formed, history built up).
// Kernels that update history run on a copy restored outside the timing, so
// every iteration sees the same contacts. items_per_second counts discs
// (pairs for PairForces).
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <benchmark/benchmark.h>

#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/io/pile_file.hpp"
#include "orodem/setup/bench_pile.hpp"

namespace orodem {

/// The private phases of Simulation, for timing only (friend of Simulation).
struct KernelBench {
    static void rebuild(Simulation& s) { s.rebuild_pairs(); }
    static void pair_forces(Simulation& s) { s.pair_forces<true>(); }
    static void gather(Simulation& s) { s.gather_forces<true, false>(); }
    static void kick_drift(Simulation& s) { s.kick_drift(); }
    static void kick(Simulation& s) { s.kick(); }
};

}  // namespace orodem

using namespace orodem;

namespace {

/// A fresh pile after 300 steps (contacts formed, history built up), to be
/// timed at state.range(0) threads. Built anew for each benchmark so that no
/// benchmark sees another's leftovers (kicks pile up velocity).
std::unique_ptr<Simulation> setup(benchmark::State& state) {
    const std::string path = std::string(ORODEM_SHARED_DIR) + "/bench/settled.txt";
    if (!std::filesystem::exists(path)) {
        std::fprintf(stderr, "orodem_bench: no %s\n", path.c_str());
        std::exit(1);
    }
    omp_set_num_threads(omp_get_num_procs());
    auto sim = std::make_unique<Simulation>(make_bench_pile(read_pile_file(path, BenchPile{}.density)));
    sim->initialize();
    sim->advance(300);
    omp_set_num_threads(static_cast<int>(state.range(0)));
    return sim;
}

void finish(benchmark::State& state, std::size_t items) {
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(items));
    state.counters["threads"] = static_cast<double>(state.range(0));
}

void BM_Rebuild(benchmark::State& state) {
    auto sim = setup(state);
    for (auto _ : state) {
        KernelBench::rebuild(*sim);
        benchmark::ClobberMemory();
    }
    finish(state, sim->particles.size());
}

void BM_PairForces(benchmark::State& state) {
    auto sim = setup(state);
    const std::vector<Vec2> xi = sim->contacts.xi;
    for (auto _ : state) {
        KernelBench::pair_forces(*sim);
        benchmark::ClobberMemory();
        state.PauseTiming();
        sim->contacts.xi = xi;  // same history every iteration (no allocation: same size)
        state.ResumeTiming();
    }
    finish(state, sim->contacts.size());
}

void BM_Gather(benchmark::State& state) {
    auto sim = setup(state);
    KernelBench::pair_forces(*sim);
    const std::vector<Vec2> xi = sim->wall_contacts.xi;
    for (auto _ : state) {
        KernelBench::gather(*sim);
        benchmark::ClobberMemory();
        state.PauseTiming();
        sim->wall_contacts.xi = xi;
        state.ResumeTiming();
    }
    finish(state, sim->particles.size());
}

void BM_KickDrift(benchmark::State& state) {
    auto sim = setup(state);
    for (auto _ : state) {
        KernelBench::kick_drift(*sim);
        benchmark::ClobberMemory();
    }
    finish(state, sim->particles.size());
}

void BM_Kick(benchmark::State& state) {
    auto sim = setup(state);
    for (auto _ : state) {
        KernelBench::kick(*sim);
        benchmark::ClobberMemory();
    }
    finish(state, sim->particles.size());
}

void BM_Conveyor(benchmark::State& state) {
    auto sim = setup(state);
    ConveyorTraction belt(0, 0.1, 0.5, 1.0);  // the floor as a belt at v' = 0.1
    for (auto _ : state) {
        belt.add_forces(*sim);
        benchmark::ClobberMemory();
    }
    finish(state, sim->particles.size());
}

void BM_Step(benchmark::State& state) {
    auto sim = setup(state);
    for (auto _ : state) {
        sim->step();
        benchmark::ClobberMemory();
    }
    finish(state, sim->particles.size());
}

#define ORODEM_KERNEL(bm) BENCHMARK(bm)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime()
ORODEM_KERNEL(BM_Rebuild);
ORODEM_KERNEL(BM_PairForces);
ORODEM_KERNEL(BM_Gather);
ORODEM_KERNEL(BM_KickDrift);
ORODEM_KERNEL(BM_Kick);
ORODEM_KERNEL(BM_Conveyor);
ORODEM_KERNEL(BM_Step);

}  // namespace

BENCHMARK_MAIN();
