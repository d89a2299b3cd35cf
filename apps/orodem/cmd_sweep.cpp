// orodem sweep and orodem resume: the command lines of a sweep (run/sweep.hpp;
// with --scheduler slurm run/sweep_slurm.hpp) and of a single run's resume,
// the hidden `orodem sweep-member DIR` (one member: a parallel sweep's child,
// a Slurm array task) and `orodem sweep-settle DIR` (the shared packings).
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/sweep_manifest.hpp"
#include "orodem/run/runner.hpp"
#include "orodem/run/sweep.hpp"
#include "orodem/run/sweep_slurm.hpp"

namespace orodem {
namespace {

/// A sweep's lines on the terminal (stdout is line-buffered: main.cpp).
struct TerminalSweep final : SweepObserver {
    TerminalObserver terminal;
    void say(const std::string& line) override { fmt::print("{}\n", line); }
    void trouble(const std::string& line) override { fmt::print(stderr, "orodem: {}\n", line); }
    RunObserver& runs() override { return terminal; }
};

/// The config of the member key = value: the varied value applied as the last
/// --set, named as the user wrote it (--vary) when a message is about it.
Config sweep_member(const CommonArgs& a, const std::string& key, const std::string& value) {
    CommonArgs one = a;
    one.sets.push_back(key + "=" + value);
    Config c;
    try {
        c = load(one);
    } catch (const ConfigError& e) {
        const std::string msg = e.what(), as_set = "--set " + key + "=" + value;
        if (msg.rfind(as_set, 0) == 0)
            throw ConfigError(fmt::format("--vary {} (the value {}){}", key, value, msg.substr(as_set.size())));
        throw;
    }
    check_sweep_member(c);
    return c;
}

}  // namespace

int cmd_sweep(const CommonArgs& a, const std::string& vary, const std::string& out_arg, int jobs,
              const SchedulerArgs& s) {
    const bool slurm = s.scheduler == "slurm";
    check_sweep_scheduler(slurm, s.slurm_given, a.threads, jobs, s.slurm);
    const auto [key, values] = parse_vary(vary);
    std::vector<Config> configs;  // every member validated before anything is written
    for (const auto& v : values) configs.push_back(sweep_member(a, key, v));
    for (const Config& c : configs) check_run_time(c, check_runnable(c), a.force, "a run of the sweep");
    const std::string root = new_sweep_dir(out_arg, a.config);
    if (slurm) require_slurm_command("sbatch");  // without sbatch nothing is written
    const Sweep sweep = create_sweep(root, SweepManifest{a.config, key, values, a.sets}, configs);
    const DirLock lock = lock_dir(root, "the sweep folder");  // one sweep process per folder, to the end
    TerminalSweep terminal;
    if (slurm) return submit_sweep_slurm(sweep, s.slurm, true, terminal);
    return run_sweep(sweep, LocalJobs{a.threads, jobs, ""}, terminal);
}

int cmd_resume(const std::string& dir, int threads, int jobs, const SchedulerArgs& s) {
    const bool slurm = s.scheduler == "slurm";
    check_sweep_scheduler(slurm, s.slurm_given, threads, jobs, s.slurm);
    if (std::filesystem::exists(sweep_manifest_path(dir))) {
        const DirLock lock = lock_dir(dir, "the sweep folder");  // one sweep process per folder, to the end
        const Sweep sweep = open_sweep(dir);
        fmt::print("continuing the sweep in {} ({} = {} values)\n", dir, sweep.manifest.key, sweep.size());
        TerminalSweep terminal;
        if (slurm) return submit_sweep_slurm(sweep, s.slurm, false, terminal);
        return run_sweep(sweep, LocalJobs{threads, jobs, ""}, terminal);
    }
    if (slurm)
        throw ConfigError(fmt::format("--scheduler slurm: {} is not a sweep's folder (no sweep.toml); a single run "
                                      "is resumed with orodem resume {} inside a batch job of your own",
                                      dir, dir));
    // One run, continued with its own config.toml.
    const Config c = load_for_run(CommonArgs{dir + "/config.toml", {}, threads});
    const RunNumbers n = check_runnable(c);
    set_threads(c);
    TerminalObserver terminal;
    return resume_run(c, n, dir, terminal);
}

int cmd_sweep_member(const std::string& dir, int threads) {
    TerminalSweep terminal;
    return run_sweep_member(dir, threads, terminal);
}

int cmd_sweep_settle(const std::string& dir, int threads) {
    TerminalSweep terminal;
    return settle_shared_packings(dir, threads, terminal);
}

}  // namespace orodem
