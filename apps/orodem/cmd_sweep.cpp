// orodem sweep and orodem resume. A sweep is one run per value of a config
// key, DIR/<key>=<value>/, then the overlay plots. The paper's sweeps take
// hours per member, so a sweep must survive what a single run survives:
// before the first member runs, DIR/sweep.toml records the sweep and every
// member's resolved config.toml is written, and `orodem resume DIR` then
// goes through the members in order: a finished one is kept, an interrupted
// one is resumed from its checkpoint (bit for bit as if never stopped), one
// not started yet is started. A member that goes unstable does not stop the
// others: it is reported, skipped on resume, and the sweep exits with 3.
// With --jobs N the members run N at a time, each in a child process
// (`orodem sweep-member DIR`, output in DIR/console.txt) with the cores
// shared among them; a packing they share is settled once first. With
// --scheduler slurm the members go to Slurm as one job array instead
// (run/slurm.hpp: DIR/slurm/array.sh runs `orodem sweep-member` per task, a
// shared packing is settled first by `orodem sweep-settle` in a job the array
// waits for), and `orodem resume DIR --scheduler slurm` submits the members
// that are neither finished, failed nor still in the queue.
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/series_reader.hpp"
#include "orodem/io/sweep_manifest.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/io/process.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/run_log.hpp"
#include "orodem/run/run_plots.hpp"
#include "orodem/run/runner.hpp"

namespace orodem {

namespace fs = std::filesystem;

namespace {

/// Splits "key=v1,v2,..." into the key and its values.
std::pair<std::string, std::vector<std::string>> parse_vary(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw ConfigError(fmt::format("--vary '{}': expected key=v1,v2,..., e.g. --vary wedge.mu_bp=0.1,0.2,0.3", text));
    std::vector<std::string> values;
    std::string rest = text.substr(eq + 1);
    for (std::size_t pos = 0;;) {
        const auto comma = rest.find(',', pos);
        values.push_back(rest.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    for (const auto& v : values)
        if (v.empty()) throw ConfigError(fmt::format("--vary '{}': empty value in the list", text));
    for (std::size_t i = 0; i < values.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (values[i] == values[j])
                throw ConfigError(fmt::format("--vary '{}': the value {} is listed twice; each value is one run",
                                              text, values[i]));
    return {text.substr(0, eq), values};
}

/// What a member needs.
enum class MemberState { start, resume, finished, failed };

MemberState member_state(const Config& c, const std::string& dir) {
    if (!is_wedge(c)) {
        // A settled layer is not checkpointed: done when its packing is written, else settled again.
        return fs::exists(dir + "/packing.bin") ? MemberState::finished : MemberState::start;
    }
    if (!fs::exists(dir + "/log.txt")) return MemberState::start;
    const std::vector<EventRecord> events = read_events(dir);
    const EventRecord* last = last_piece_event(events);
    if (last && last->kind == RunEvent::finished) return MemberState::finished;
    // Resuming would repeat the same failure from the same state.
    if (last && (last->kind == RunEvent::unstable || last->kind == RunEvent::stopped)) return MemberState::failed;
    return MemberState::resume;
}

/// Says that a member needs no run; its exit status (0 kept, 3 failed before).
int report_done(MemberState st, const std::string& dir, const std::string& label) {
    if (st == MemberState::finished) {
        fmt::print("sweep: {}: finished already, kept ({})\n", label, dir);
        return 0;
    }
    fmt::print(stderr, "orodem: sweep: {}: ended with an error before (see {}/log.txt); skipped\n", label, dir);
    return static_cast<int>(ExitCode::unstable);
}

/// Runs, continues or keeps one member; its exit status (0 when kept).
int run_member(const Config& c, const std::string& dir, const std::string& label) {
    const MemberState st = member_state(c, dir);
    if (st == MemberState::finished || st == MemberState::failed) return report_done(st, dir, label);
    if (st == MemberState::resume) {
        fmt::print("sweep: {}: continuing {}\n", label, dir);
        TerminalObserver terminal;
        return resume_run(c, derive_run_numbers(c), dir, terminal);
    }
    if (!is_wedge(c)) {
        // What an interrupted settling left, but the config and the output of a parallel sweep's child.
        std::vector<fs::path> partial;
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().filename() != "config.toml" && e.path().filename() != "console.txt") partial.push_back(e.path());
        for (const auto& q : partial) remove_path(q.string());
    }
    fmt::print("sweep: {} -> {}\n", label, dir);
    TerminalObserver terminal;
    return start_run_in(c, derive_run_numbers(c), dir, terminal);
}

/// A member's config, from its config.toml (threads >= 0 overrides run.threads).
Config member_config(const std::string& root, const std::string& dir, int threads) {
    if (!fs::exists(dir + "/config.toml"))
        throw ConfigError(fmt::format("{}/config.toml: missing; the sweep folder {} was changed since orodem sweep "
                                      "wrote it, so it cannot be continued",
                                      dir, root));
    CommonArgs one;
    one.config = dir + "/config.toml";
    one.threads = threads;
    Config c = load(one);
    check_runnable(c);
    return c;
}

/// The end of a sweep: the overlay plots of the members that finished, and
/// the exit status (3 when some went unstable, naming them).
int finish_sweep(const std::string& root, const SweepManifest& m, const std::vector<std::string>& dirs,
                 const std::vector<std::string>& failed, bool all_wedges) {
    // A sweep over the seeds is an ensemble: its mean over the seeds' band.
    if (all_wedges && !dirs.empty()) {
        const RunPlot p = plot_runs(dirs, root + "/plots.png", is_seed_key(m.key));
        for (const std::string& n : p.notes) fmt::print("plot: {}\n", n);
        fmt::print("plot: {}\n", p.path);
    }
    fmt::print("sweep outputs in {}/\n", root);
    if (failed.empty()) return 0;
    std::string list;
    for (const auto& f : failed) list += (list.empty() ? "" : ", ") + f;
    fmt::print(stderr, "orodem: sweep: {} of {} runs went unstable ({}); the plots leave them out\n", failed.size(),
               m.values.size(), list);
    return static_cast<int>(ExitCode::unstable);
}

std::string member_label(const SweepManifest& m, const std::string& value) {
    return fmt::format("{} = {}", m.key, value);
}

/// The members whose packing is settled before the members run, one per
/// packing: wedge members still to be started whose packing is not cached
/// yet; only_shared: only the packings that two or more of them use (a
/// packing of its own a member settles itself).
std::vector<std::size_t> packings_to_settle(const std::vector<Config>& configs, const std::vector<std::string>& dirs,
                                            bool only_shared) {
    std::vector<std::size_t> first;  // the first member of each packing
    std::vector<int> users;
    std::vector<std::string> caches;
    for (std::size_t k = 0; k < configs.size(); ++k) {
        if (!is_wedge(configs[k]) || member_state(configs[k], dirs[k]) != MemberState::start) continue;
        const std::string cache = packing_cache_path(configs[k]);
        const auto at = std::find(caches.begin(), caches.end(), cache);
        if (at != caches.end()) {
            ++users[static_cast<std::size_t>(at - caches.begin())];
            continue;
        }
        caches.push_back(cache);
        users.push_back(1);
        first.push_back(k);
    }
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < first.size(); ++i)
        if (!fs::exists(caches[i]) && (!only_shared || users[i] > 1)) out.push_back(first[i]);
    return out;
}

/// Settles the packings of the members `which` into their caches (log in DIR/log.txt).
void settle_packings(const std::string& root, const SweepManifest& m, const std::vector<Config>& configs,
                     const std::vector<std::size_t>& which) {
    for (const std::size_t k : which) {
        fmt::print("sweep: settling the packing of {} first ({})\n", member_label(m, m.values[k]),
                   packing_cache_path(configs[k]));
        std::fflush(stdout);
        TerminalObserver terminal;
        ensure_packing_cached(configs[k], root, terminal);
    }
}

/// This executable, to start the members of a parallel sweep.
std::string self_exe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw IoError(fmt::format("cannot find this executable (/proc/self/exe: {})", ec.message()));
    return p.string();
}

/// Starts `orodem sweep-member DIR [--threads T]` in its own process group
/// (a Ctrl-C on the terminal reaches the sweep, which passes it on once),
/// output appended to DIR/console.txt.
pid_t start_member(const std::string& exe, const std::string& dir, int threads) {
    const std::string console = dir + "/console.txt";
    std::vector<std::string> args = {exe, "sweep-member", dir};
    if (threads >= 0) {
        args.push_back("--threads");
        args.push_back(std::to_string(threads));
    }
    ChildIo io;
    io.log = console;
    io.append = true;
    io.new_group = true;
    pid_t pid = -1;
    if (const int rc = spawn_child(args, io, pid); rc != 0)
        throw IoError(fmt::format("cannot start {} for {}: {}", exe, dir, std::strerror(rc)));
    return pid;
}

/// The members, `jobs` at a time in child processes. Each child writes only
/// its own member's folder; the order of the results does not depend on
/// which finishes first. A signal stops the starting of members and is passed
/// on once to the running ones, which checkpoint; the sweep then exits with
/// 128 + signal once they have.
int run_members_parallel(const std::string& root, const SweepManifest& m, int threads, int jobs) {
    const std::size_t n = m.values.size();
    std::vector<std::string> dirs(n);
    std::vector<Config> configs;
    bool all_wedges = true;
    for (std::size_t k = 0; k < n; ++k) {
        dirs[k] = sweep_member_dir(root, m, m.values[k]);
        configs.push_back(member_config(root, dirs[k], threads));
        all_wedges = all_wedges && is_wedge(configs.back());
    }
    // Members that share a packing not cached yet would each settle it at the
    // same time: settle each such packing once first (log in DIR/log.txt).
    settle_packings(root, m, configs, packings_to_settle(configs, dirs, false));
    const std::string exe = self_exe();
    const int child_threads = threads >= 0 ? threads : std::max(1, omp_get_num_procs() / jobs);
    std::vector<int> rc(n, -1);
    std::vector<pid_t> running;  // by slot k: pid, or -1
    std::vector<std::size_t> running_k;
    StopSignals signals;
    int forwarded = 0;
    std::size_t next = 0;
    while (next < n || !running.empty()) {
        while (!signals.pending() && running.size() < static_cast<std::size_t>(jobs) && next < n) {
            const std::size_t k = next++;
            const std::string label = member_label(m, m.values[k]);
            const MemberState st = member_state(configs[k], dirs[k]);
            if (st == MemberState::finished || st == MemberState::failed) {
                rc[k] = report_done(st, dirs[k], label);
                continue;
            }
            running.push_back(start_member(exe, dirs[k], child_threads));
            running_k.push_back(k);
            fmt::print("sweep: {} -> {} ({}, {} thread{}; its output in {}/console.txt)\n", label, dirs[k],
                       st == MemberState::resume ? "continuing" : "starting", child_threads,
                       child_threads == 1 ? "" : "s", dirs[k]);
            std::fflush(stdout);
        }
        if (const int sig = signals.pending(); sig && !forwarded) {
            forwarded = sig;
            for (const pid_t p : running) ::kill(p, sig);
        }
        if (running.empty()) break;
        int status = 0;
        const pid_t done = ::waitpid(-1, &status, WNOHANG);
        if (done <= 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            continue;
        }
        const auto at = std::find(running.begin(), running.end(), done);
        if (at == running.end()) continue;
        const std::size_t slot = static_cast<std::size_t>(at - running.begin());
        const std::size_t k = running_k[slot];
        running.erase(at);
        running_k.erase(running_k.begin() + static_cast<std::ptrdiff_t>(slot));
        rc[k] = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
        fmt::print("sweep: {}: {}\n", member_label(m, m.values[k]),
                   rc[k] == 0 ? "finished" : fmt::format("ended with exit status {} (see {}/console.txt)", rc[k], dirs[k]));
        std::fflush(stdout);
    }
    std::vector<std::string> ok, failed;
    int stop_rc = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (rc[k] == 0) ok.push_back(dirs[k]);
        else if (rc[k] == static_cast<int>(ExitCode::unstable)) failed.push_back(member_label(m, m.values[k]));
        else if (stop_rc == 0) stop_rc = rc[k] < 0 ? 128 + forwarded : rc[k];
    }
    if (forwarded || stop_rc != 0) {
        fmt::print(stderr, "orodem: the sweep stopped{}; continue it with: orodem resume {}\n",
                   forwarded ? fmt::format(" ({})", forwarded == SIGINT ? "SIGINT" : "SIGTERM") : std::string(), root);
        return forwarded ? 128 + forwarded : stop_rc;
    }
    return finish_sweep(root, m, ok, failed, all_wedges);
}

/// The members of the sweep in root, in order (jobs > 1: that many at once);
/// then the overlay plots. The configs come from the members' config.toml
/// (threads >= 0 overrides run.threads).
int run_members(const std::string& root, const SweepManifest& m, int threads, int jobs) {
    if (jobs > 1) return run_members_parallel(root, m, threads, jobs);
    std::vector<std::string> dirs;
    std::vector<std::string> failed;
    bool all_wedges = true;
    for (const auto& v : m.values) {
        const std::string dir = sweep_member_dir(root, m, v);
        const std::string label = member_label(m, v);
        const Config c = member_config(root, dir, threads);
        set_threads(c);
        all_wedges = all_wedges && is_wedge(c);
        int rc = 0;
        try {
            rc = run_member(c, dir, label);
        } catch (const InterruptedError&) {
            // While settling (not checkpointed): the member settles again when the sweep continues.
            fmt::print(stderr, "orodem: the sweep stopped at {}; continue it with: orodem resume {}\n", label, root);
            throw;
        } catch (const InstabilityError& e) {
            // The run has logged it and kept its last good state; the other members still run.
            fmt::print(stderr, "orodem: sweep: {}: unstable: {}\n", label, e.what());
            rc = static_cast<int>(ExitCode::unstable);
        }
        if (rc == static_cast<int>(ExitCode::unstable)) {
            failed.push_back(label);
            continue;
        }
        if (rc != 0) {
            // Interrupted, stopped at the wall-time limit or by a full disk: with a checkpoint.
            fmt::print(stderr, "orodem: the sweep stopped at {}; continue it with: orodem resume {}\n", label, root);
            return rc;
        }
        dirs.push_back(dir);
    }
    return finish_sweep(root, m, dirs, failed, all_wedges);
}

/// The sweep's Slurm options, checked against the rest of the command line.
void check_scheduler_args(const SchedulerArgs& s, int threads, int jobs) {
    if (s.scheduler != "slurm") {
        if (s.slurm_given)
            throw ConfigError("--partition, --time, --cpus-per-task and --sbatch-arg go with --scheduler slurm");
        return;
    }
    if (jobs > 1)
        throw ConfigError(fmt::format("--jobs {} with --scheduler slurm: each member is its own array task, as "
                                      "many at once as the cluster allows; leave --jobs out",
                                      jobs));
    if (threads >= 0)
        throw ConfigError(fmt::format("--threads {} with --scheduler slurm: each member runs with as many threads "
                                      "as its CPUs; set them with --cpus-per-task",
                                      threads));
}

/// The members of the sweep in root that are not finished (nor failed),
/// submitted to Slurm as one job array (DIR/slurm/array.sh, written when
/// fresh or missing), after a settling job when they share a packing not
/// cached yet. With every member finished or failed: the overlay plots.
int submit_members_slurm(const std::string& root_arg, const SweepManifest& m, const SchedulerArgs& s, bool fresh) {
    std::string root = fs::absolute(root_arg).lexically_normal().string();
    while (root.size() > 1 && root.back() == '/') root.pop_back();
    const std::size_t n = m.values.size();
    std::vector<std::string> dirs(n), names(n);
    std::vector<Config> configs;
    bool all_wedges = true;
    for (std::size_t k = 0; k < n; ++k) {
        dirs[k] = sweep_member_dir(root, m, m.values[k]);
        names[k] = fs::path(dirs[k]).filename().string();
        configs.push_back(member_config(root, dirs[k], -1));
        all_wedges = all_wedges && is_wedge(configs.back());
    }
    std::vector<int> todo;
    std::vector<std::string> ok, failed;
    for (std::size_t k = 0; k < n; ++k) {
        const MemberState st = member_state(configs[k], dirs[k]);
        if (st == MemberState::finished) ok.push_back(dirs[k]);
        if (st == MemberState::failed) failed.push_back(member_label(m, m.values[k]));
        if (st == MemberState::finished || st == MemberState::failed) {
            if (!fresh) report_done(st, dirs[k], member_label(m, m.values[k]));
            continue;
        }
        todo.push_back(static_cast<int>(k));
    }
    if (todo.empty()) {
        fmt::print("sweep: no member left to run; nothing submitted\n");
        return finish_sweep(root_arg, m, ok, failed, all_wedges);
    }
    // A member still in the queue (a task of this sweep pending or running) is not submitted twice.
    std::vector<std::string> ids;
    for (const SlurmJob& j : read_slurm_jobs(root))
        if (j.kind == "array") ids.push_back(j.id);
    if (!ids.empty()) {
        const SlurmQueue q = slurm_task_states(ids);
        std::vector<int> rest;
        for (const int k : todo) {
            const auto at = q.tasks.find(k);
            if (at != q.tasks.end() && slurm_state_active(at->second.state))
                fmt::print("sweep: {}: still in Slurm's queue as job {} ({}); not submitted again\n",
                           member_label(m, m.values[static_cast<std::size_t>(k)]), at->second.job, at->second.state);
            else
                rest.push_back(k);
        }
        if (rest.empty()) {
            fmt::print("sweep: every unfinished member is in Slurm's queue; nothing submitted (orodem status {})\n",
                       root_arg);
            return 0;
        }
        todo = rest;
    }
    require_slurm_command("sbatch");
    const std::string sdir = slurm_dir(root), exe = self_exe();
    make_dirs(sdir);
    const std::string array_sh = sdir + "/array.sh", settle_sh = sdir + "/settle.sh";
    SlurmOptions written = s.slurm;
    if (written.cpus_per_task < 1) written.cpus_per_task = 1;
    if (fresh || !fs::exists(array_sh)) write_file_atomic(array_sh, slurm_array_script(root, names, exe, written));
    // On resume the options given again override the scripts' #SBATCH lines.
    std::vector<std::string> overrides;
    if (!fresh) {
        if (!s.slurm.partition.empty()) overrides.push_back("--partition=" + s.slurm.partition);
        if (!s.slurm.time.empty()) overrides.push_back("--time=" + s.slurm.time);
        if (s.slurm.cpus_per_task > 0) overrides.push_back(fmt::format("--cpus-per-task={}", s.slurm.cpus_per_task));
        for (const auto& a : s.slurm.sbatch_args) overrides.push_back(a);
    }
    const std::string again = fmt::format("; the sweep folder is ready: submit it again with orodem resume {} "
                                          "--scheduler slurm",
                                          root_arg);
    std::vector<std::string> array_args = overrides;
    // Among the members submitted now (one still in the queue settles its own packing when it runs).
    std::vector<Config> todo_configs;
    std::vector<std::string> todo_dirs;
    for (const int k : todo) {
        todo_configs.push_back(configs[static_cast<std::size_t>(k)]);
        todo_dirs.push_back(dirs[static_cast<std::size_t>(k)]);
    }
    const std::vector<std::size_t> settle = packings_to_settle(todo_configs, todo_dirs, true);
    if (!settle.empty()) {
        if (fresh || !fs::exists(settle_sh)) write_file_atomic(settle_sh, slurm_settle_script(root, exe, written));
        std::string id;
        try {
            id = sbatch(overrides, settle_sh);
        } catch (const SchedulerError& e) {
            throw SchedulerError(e.what() + again);
        }
        record_slurm_job(root, SlurmJob{id, "settle", ""});
        fmt::print("sweep: submitted job {} to settle the packing {} members share ({}/slurm/settle.sh)\n", id,
                   settle.size() == 1 ? "that several" : "s that several", root_arg);
        array_args.push_back("--dependency=afterok:" + id);
    }
    const std::string tasks = array_ranges(todo);
    array_args.push_back("--array=" + tasks);
    std::string id;
    try {
        id = sbatch(array_args, array_sh);
    } catch (const SchedulerError& e) {
        throw SchedulerError(e.what() + again);
    }
    record_slurm_job(root, SlurmJob{id, "array", tasks});
    for (const int k : todo)
        fmt::print("sweep: {} -> job {}_{} ({})\n", member_label(m, m.values[static_cast<std::size_t>(k)]), id, k,
                   member_state(configs[static_cast<std::size_t>(k)], dirs[static_cast<std::size_t>(k)]) ==
                           MemberState::resume
                       ? "continuing"
                       : "starting");
    fmt::print("sweep: submitted job array {} to Slurm: tasks {} ({} of {} members; {}/slurm/array.sh, job ids in "
               "{}/slurm/jobs.csv)\n",
               id, tasks, todo.size(), n, root_arg, root_arg);
    fmt::print("sweep: follow it with: orodem status {}; when it is done: orodem plot {}\n", root_arg, root_arg);
    fmt::print("job id: {}\n", id);
    return 0;
}

}  // namespace

int cmd_sweep(const CommonArgs& a, const std::string& vary, const std::string& out_arg, int jobs,
              const SchedulerArgs& s) {
    check_scheduler_args(s, a.threads, jobs);
    const auto [key, values] = parse_vary(vary);
    // Validate every member of the sweep before writing anything.
    std::vector<Config> configs;
    for (const auto& v : values) {
        CommonArgs one = a;
        one.sets.push_back(key + "=" + v);
        Config c;
        try {
            c = load(one);
        } catch (const ConfigError& e) {
            // The varied value is applied as the last --set: name it as the
            // user wrote it, --vary, when the message is about it.
            const std::string msg = e.what(), as_set = "--set " + key + "=" + v;
            if (msg.rfind(as_set, 0) == 0)
                throw ConfigError(fmt::format("--vary {} (the value {}){}", key, v, msg.substr(as_set.size())));
            throw;
        }
        if (is_calibration(c))
            throw ConfigError(fmt::format("{}: run.experiment = \"{}\" is a calibration experiment, which sweeps "
                                          "its own [calibrate] lists: run it with orodem calibrate", c.path,
                                          c.run.experiment));
        check_runnable(c);
        configs.push_back(std::move(c));
    }
    const std::string stem = fs::path(a.config).stem().string();
    const std::string root = out_arg.empty() ? choose_run_dir("", stem + "-sweep") : out_arg;
    if (!out_arg.empty() && fs::exists(root) && !fs::is_empty(root))
        throw ConfigError(fmt::format("--out {}: directory exists and is not empty; choose a new directory{}", root,
                                      fs::exists(sweep_manifest_path(root))
                                          ? fmt::format(", or continue the sweep in it with: orodem resume {}", root)
                                          : std::string()));
    // Without sbatch nothing is written.
    if (s.scheduler == "slurm") require_slurm_command("sbatch");
    SweepManifest m{a.config, key, values, a.sets};
    make_dirs(root);
    for (std::size_t k = 0; k < values.size(); ++k) {
        const std::string dir = sweep_member_dir(root, m, values[k]);
        make_dirs(dir);
        write_file_atomic(dir + "/config.toml", to_toml(configs[k]));
    }
    write_file_atomic(sweep_manifest_path(root), to_toml(m));
    if (s.scheduler == "slurm") return submit_members_slurm(root, m, s, true);
    return run_members(root, m, a.threads, jobs);
}

int cmd_resume(const std::string& dir, int threads, int jobs, const SchedulerArgs& s) {
    check_scheduler_args(s, threads, jobs);
    if (fs::exists(sweep_manifest_path(dir))) {
        const SweepManifest m = read_sweep_manifest(dir);
        fmt::print("continuing the sweep in {} ({} = {} values)\n", dir, m.key, m.values.size());
        if (s.scheduler == "slurm") return submit_members_slurm(dir, m, s, false);
        return run_members(dir, m, threads, jobs);
    }
    if (s.scheduler == "slurm")
        throw ConfigError(fmt::format("--scheduler slurm: {} is not a sweep's folder (no sweep.toml); a single run "
                                      "is resumed with orodem resume {} inside a batch job of your own",
                                      dir, dir));
    // One run, continued with its own config.toml.
    CommonArgs a;
    a.config = dir + "/config.toml";
    a.threads = threads;
    const Config c = load_for_run(a);
    const RunNumbers n = check_runnable(c);
    set_threads(c);
    TerminalObserver terminal;
    return resume_run(c, n, dir, terminal);
}

int cmd_sweep_member(const std::string& dir, int threads) {
    const std::string root = fs::path(dir).parent_path().string();
    const Config c = member_config(root, dir, threads);
    set_threads(c);
    return run_member(c, dir, fs::path(dir).filename().string());
}

int cmd_sweep_settle(const std::string& dir, int threads) {
    const SweepManifest m = read_sweep_manifest(dir);
    std::vector<std::string> dirs;
    std::vector<Config> configs;
    for (const auto& v : m.values) {
        dirs.push_back(sweep_member_dir(dir, m, v));
        configs.push_back(member_config(dir, dirs.back(), threads));
    }
    if (!configs.empty()) set_threads(configs.front());
    const std::vector<std::size_t> which = packings_to_settle(configs, dirs, true);
    if (which.empty()) fmt::print("sweep: every packing the members share is cached already\n");
    settle_packings(dir, m, configs, which);
    return 0;
}

}  // namespace orodem
