// orodem sweep and orodem resume: the command lines of a sweep (run/sweep.hpp;
// with --scheduler slurm run/sweep_slurm.hpp) and of a single run's resume,
// the hidden `orodem sweep-member DIR` (one member: a parallel sweep's child,
// a Slurm array task) and `orodem sweep-settle DIR` (the shared packings).
#include <algorithm>
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

/// The config of a member (key = value for each varied key): the varied values
/// applied as the last --sets, named as the user wrote them (--vary) when a
/// message is about one.
Config sweep_member(const CommonArgs& a, const SweepMember& member) {
    CommonArgs one = a;
    for (const auto& [key, value] : member) one.sets.push_back(key + "=" + value);
    Config c;
    try {
        c = load(one);
    } catch (const ConfigError& e) {
        const std::string msg = e.what();
        for (const auto& [key, value] : member)
            if (const std::string as_set = "--set " + key + "=" + value; msg.rfind(as_set, 0) == 0)
                throw ConfigError(fmt::format("--vary {} (the value {}){}", key, value, msg.substr(as_set.size())));
        throw;
    }
    check_sweep_member(c);
    return c;
}

}  // namespace

int cmd_sweep(const CommonArgs& a, const std::vector<std::string>& vary, const std::string& out_arg, int jobs,
              const SchedulerArgs& s) {
    const bool slurm = s.scheduler == "slurm";
    check_sweep_scheduler(slurm, s.slurm_given, a.threads, jobs, s.slurm);
    SweepManifest manifest{a.config, {}, {}, a.sets, {}};
    for (const std::string& text : vary) {  // several --vary: the product grid, the first key varying slowest
        auto [key, values] = parse_vary(text);
        const bool repeated = key == manifest.key || std::any_of(manifest.more.begin(), manifest.more.end(),
                                                                 [&](const SweepAxis& axis) { return axis.key == key; });
        if (repeated)
            throw ConfigError(fmt::format("--vary {}: the key is varied twice; give each key one --vary with all "
                                          "its values",
                                          key));
        if (manifest.key.empty()) manifest.key = key, manifest.values = std::move(values);
        else manifest.more.push_back(SweepAxis{key, std::move(values)});
    }
    std::vector<Config> configs;  // every member validated before anything is written
    for (const SweepMember& member : sweep_members(manifest)) configs.push_back(sweep_member(a, member));
    for (const Config& c : configs) check_run_time(c, check_runnable(c), a.force, "a run of the sweep");
    const std::string root = new_sweep_dir(out_arg, a.config);
    if (slurm) require_slurm_command("sbatch");  // without sbatch nothing is written
    const Sweep sweep = create_sweep(root, manifest, configs);
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
        fmt::print("continuing the sweep in {} ({})\n", dir, sweep_axes_text(sweep.manifest));
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
