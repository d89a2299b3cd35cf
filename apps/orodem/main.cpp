// orodem command line: parses arguments with CLI11, hands typed values to the
// library and maps errors to exit statuses (0 ok, 1 internal, 2 bad config or
// arguments, 3 unstable, 4 I/O). The only place that prints to the terminal.
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/io/pile_file.hpp"
#include "orodem/setup/bench_pile.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"

namespace fs = std::filesystem;
using namespace orodem;

namespace {

struct CommonArgs {
    std::string config;
    std::vector<std::string> sets;
    int threads = -1;  // -1: from the config
};

Config load(const CommonArgs& a) {
    std::vector<Override> ov;
    for (const auto& s : a.sets) ov.push_back(parse_override(s));
    if (a.threads >= 0) ov.push_back({"run.threads", std::to_string(a.threads)});
    return load_config(a.config, ov);
}

void set_threads(const Config& c) {
    if (c.run.threads > 0) omp_set_num_threads(c.run.threads);
}

/// A new run directory: `out` if given (must be absent or empty), else
/// runs/<config stem>, runs/<stem>-2, ... whichever is free first.
std::string choose_run_dir(const std::string& out, const std::string& config_path) {
    auto usable = [](const fs::path& p) { return !fs::exists(p) || (fs::is_directory(p) && fs::is_empty(p)); };
    if (!out.empty()) {
        if (!usable(out))
            throw ConfigError(fmt::format("--out {}: directory exists and is not empty; choose a new directory "
                                          "(runs are never overwritten)", out));
        return out;
    }
    const std::string stem = fs::path(config_path).stem().string();
    for (int k = 1;; ++k) {
        const fs::path p = fs::path("runs") / (k == 1 ? stem : fmt::format("{}-{}", stem, k));
        if (usable(p)) return p.string();
    }
}

int cmd_check(const CommonArgs& a) {
    const Config c = load(a);
    const TimestepInfo t = timestep_for(c);
    const std::size_t n = generated_particle_count(c);
    std::cout << to_toml(c);
    fmt::print("# derived\n");
    fmt::print("particles generated    = {} discs ({})\n", n, c.packing.kind);
    fmt::print("layer                  = {:g} m long, h0 = {:g} m\n", c.packing.length, c.packing.h0);
    fmt::print("dt                     = {:.6g} s ({})\n", t.dt, c.numerics.dt > 0 ? "requested" : "automatic");
    fmt::print("stability limit        = {:.6g} s (margin {:.2f}x)\n", t.dt_crit, t.margin());
    fmt::print("collision time t_c     = {:.6g} s ({:.1f} steps)\n", t.t_collision, t.t_collision / t.dt);
    fmt::print("packing cache          = {}\n", packing_cache_path(c));
    return 0;
}

int cmd_run(const CommonArgs& a, const std::string& out_arg) {
    const Config c = load(a);
    const TimestepInfo t = timestep_for(c);
    set_threads(c);
    const std::string dir = choose_run_dir(out_arg, c.path);
    make_dirs(dir);
    write_file_atomic(dir + "/config.toml", to_toml(c));
    LineFile log(dir + "/log.txt");
    const bool tty = ::isatty(STDOUT_FILENO);
    log.line(fmt::format("orodem {} run of {} with {} threads", ORODEM_VERSION, c.path, omp_get_max_threads()));
    log.line(fmt::format("dt = {:.6g} s, stability limit {:.6g} s (margin {:.2f}x), t_c = {:.1f} steps",
                         t.dt, t.dt_crit, t.margin(), t.t_collision / t.dt));

    const std::string cache = packing_cache_path(c);
    std::string why;
    auto cached = load_packing(cache, packing_key(c), c.material.density, &why);
    if (cached) {
        log.line(fmt::format("packing reused from {} ({} discs)", cache, cached->size()));
        fmt::print("packing reused from {}\n", cache);
    } else {
        log.line(fmt::format("settling a new packing ({})", why));
        Simulation sim = make_settle_simulation(c);
        sim.initialize();
        log.line(fmt::format("generated {} discs; settling", sim.particles.size()));
        LineFile series(dir + "/series.csv");
        series.line("step,time,kinetic_energy,ke_ratio,contacts,max_overlap_ratio");
        const auto t0 = std::chrono::steady_clock::now();
        const SettleProgress done = settle(sim, c.packing, c.run.output_interval, [&](const SettleProgress& s) {
            series.line(fmt::format("{},{:.9g},{:.9g},{:.6g},{},{:.6g}", s.step, s.time, s.kinetic_energy,
                                    s.ke_ratio, s.contacts, sim.max_overlap_ratio()));
            if (tty) {
                const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                fmt::print("\rsettling: t = {:.3f} s, step {}, E_kin/(M g h0) = {:.2e} (target {:.1e}), {:.0f} steps/s   ",
                           s.time, s.step, s.ke_ratio, c.packing.settle_ke_ratio, double(s.step) / std::max(secs, 1e-9));
                std::fflush(stdout);
            }
        });
        if (tty) fmt::print("\n");
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        log.line(fmt::format("settled after {} steps ({:.4g} s simulated, {:.1f} s wall, {:.3g} disc-steps/s); "
                             "E_kin/(M g h0) = {:.3g}, max overlap/R = {:.4f}",
                             done.step, done.time, secs, double(done.step) * double(sim.particles.size()) / secs,
                             done.ke_ratio, sim.max_overlap_ratio()));
        cut_layer(sim.particles, c.packing.h0);
        save_packing(cache, sim.particles, packing_key(c));
        log.line(fmt::format("cut to h0 = {:g} m: {} discs; saved to {}", c.packing.h0, sim.particles.size(), cache));
        cached = std::move(sim.particles);
    }
    save_packing(dir + "/packing.bin", *cached, packing_key(c));
    const double surface = mean_surface_height(*cached, 0.0, c.packing.length, 2.0 * c.packing.r_max);
    log.line(fmt::format("layer: {} discs, mean surface height {:.4g} m (h0 = {:g} m)", cached->size(), surface, c.packing.h0));
    fmt::print("layer of {} discs ready, mean surface {:.3g} m\n", cached->size(), surface);
    fmt::print("outputs in {}/ (config.toml, log.txt, series.csv, packing.bin)\n", dir);
    return 0;
}

/// The canonical benchmark: run `steps` steps of the settled pile, check the
/// kinetic energy against the LAMMPS reference, print the speed.
int cmd_bench_pile(const std::string& pile, std::uint64_t steps, int threads) {
    if (threads > 0) omp_set_num_threads(threads);
    const ParticleStore discs = read_pile_file(pile, BenchPile{}.density);
    Simulation sim = make_bench_pile(discs);
    const auto t0 = std::chrono::steady_clock::now();
    sim.initialize();
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
    fmt::print("reference check: worst relative kinetic-energy difference {:.2e} ({})\n", worst,
               worst < 1e-6 ? "matches" : "DIFFERS");
    return worst < 1e-6 ? 0 : static_cast<int>(ExitCode::unstable);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"orodem: discrete element model of doubly vergent orogenic wedges (Naylor et al. 2005)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", ORODEM_VERSION);

    CommonArgs run_args, check_args;
    std::string out;
    auto* run = app.add_subcommand("run", "Run the experiment of CONFIG into a new run directory");
    run->add_option("config", run_args.config, "TOML config file")->required();
    run->add_option("--out", out, "Output directory (new or empty); default runs/<config name>");
    run->add_option("--set", run_args.sets, "Override a config value, e.g. --set material.mu=0.5")->take_all();
    run->add_option("--threads", run_args.threads, "OpenMP threads (0 = all cores)");

    auto* check = app.add_subcommand("check", "Validate CONFIG and print the resolved config, particle count and dt; writes nothing");
    check->add_option("config", check_args.config, "TOML config file")->required();
    check->add_option("--set", check_args.sets, "Override a config value")->take_all();

    auto* bench = app.add_subcommand("bench", "Performance benchmarks");
    bench->require_subcommand(1);
    auto* pile = bench->add_subcommand("pile", "The canonical 30,000-disc pile of ../shared/bench (checks the LAMMPS reference)");
    std::string pile_file = "../shared/bench/settled.txt";
    std::uint64_t pile_steps = 20000;
    int pile_threads = 0;
    pile->add_option("--pile", pile_file, "Start state, 'id x y r' per line")->capture_default_str();
    pile->add_option("--steps", pile_steps, "Timesteps to run")->capture_default_str();
    pile->add_option("--threads", pile_threads, "OpenMP threads (0 = all cores)");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : static_cast<int>(ExitCode::config);
    }
    try {
        if (*run) return cmd_run(run_args, out);
        if (*check) return cmd_check(check_args);
        if (*pile) return cmd_bench_pile(pile_file, pile_steps, pile_threads);
    } catch (const ConfigError& e) {
        fmt::print(stderr, "orodem: error: {}\n", e.what());
        return static_cast<int>(ExitCode::config);
    } catch (const IoError& e) {
        fmt::print(stderr, "orodem: I/O error: {}\n", e.what());
        return static_cast<int>(ExitCode::io);
    } catch (const InstabilityError& e) {
        fmt::print(stderr, "orodem: unstable: {}\n", e.what());
        return static_cast<int>(ExitCode::unstable);
    } catch (const std::exception& e) {
        fmt::print(stderr, "orodem: internal error: {}\n", e.what());
        return static_cast<int>(ExitCode::internal);
    }
    return 0;
}
