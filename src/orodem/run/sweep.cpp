// The sweep on this machine (sweep.hpp): the members' states, the packings
// settled first, and the scheduler (in order in this process, or in child
// processes watched with waitpid).
#include "orodem/run/sweep.hpp"

#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <thread>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/io/process.hpp"
#include "orodem/io/series_reader.hpp"
#include "orodem/run/run_plots.hpp"
#include "orodem/run/runner.hpp"

namespace orodem {

namespace fs = std::filesystem;

namespace {

/// run.threads of a member run in this process (0: as set before, all cores).
void use_member_threads(const Config& c) {
    if (c.run.threads > 0) omp_set_num_threads(c.run.threads);
}

/// "42 s", "17 min" or "3.5 h".
std::string rough_duration(double secs) {
    if (secs < 120.0) return fmt::format("{:.0f} s", secs);
    if (secs < 7200.0) return fmt::format("{:.0f} min", secs / 60.0);
    return fmt::format("{:.1f} h", secs / 3600.0);
}

/// A sweep's progress over its members: "run k of n" as each starts, and
/// after each that ends here, the runs done and the time left for the rest
/// at this process's pace so far (wall time since it began over the runs it
/// ran, kept ones not counted; with --jobs J that pace is J runs at a time).
class SweepProgress {
public:
    explicit SweepProgress(std::size_t n) : n_(n), t0_(std::chrono::steady_clock::now()) {}
    /// "run k of n" of member k (0-based).
    std::string position(std::size_t k) const { return fmt::format("run {} of {}", k + 1, n_); }
    /// Member k was kept (finished or failed before): not counted in the pace.
    void kept() { ++kept_; }
    /// A member run here has ended: the line to say, "" when none is left.
    std::string ended() {
        ++ran_;
        const std::size_t done = ran_ + kept_, left = n_ - std::min(n_, done);
        if (left == 0) return "";
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
        const double per = secs / static_cast<double>(ran_);
        return fmt::format("sweep: {} of {} runs done, {} to go: about {} more at this sweep's pace so far ({} a run)",
                           done, n_, left, rough_duration(per * static_cast<double>(left)), rough_duration(per));
    }

private:
    std::size_t n_, ran_ = 0, kept_ = 0;
    std::chrono::steady_clock::time_point t0_;
};

/// Runs, continues or keeps one member in this process; its exit status (0
/// when kept). position: "run k of n" in the start line, or "".
int run_member(const Config& c, const std::string& dir, const std::string& label, SweepObserver& obs,
               const std::string& position = "") {
    const std::string as = position.empty() ? label : fmt::format("{} ({})", label, position);
    // One writer: a member of an earlier sweep that was killed gets SIGTERM
    // (die_with_parent) and writes its shutdown checkpoint; give it a minute.
    const DirLock lock = lock_dir(dir, "the sweep member", 60.0);
    const MemberState st = member_state(dir);
    if (st == MemberState::finished || st == MemberState::failed) return report_done(st, dir, label, obs);
    if (st == MemberState::resume) {
        obs.say(fmt::format("sweep: {}: continuing {}", as, dir));
        return resume_run(c, derive_run_numbers(c), dir, obs.runs());
    }
    if (!is_wedge(c)) {
        // What an interrupted settling left, but the config and the output of a parallel sweep's child.
        std::vector<fs::path> partial;
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().filename() != "config.toml" && e.path().filename() != "console.txt") partial.push_back(e.path());
        for (const auto& q : partial) remove_path(q.string());
    }
    obs.say(fmt::format("sweep: {} -> {}", as, dir));
    return start_run_in(c, derive_run_numbers(c), dir, obs.runs());
}

/// The members in order in this process, each with its own config.toml.
int run_members_in_order(const Sweep& s, int threads, SweepObserver& obs) {
    std::vector<std::string> finished, failed;
    bool all_wedges = true;
    SweepProgress progress(s.size());
    for (std::size_t k = 0; k < s.size(); ++k) {
        const std::string& dir = s.dirs[k];
        const std::string label = s.label(k);
        const Config c = member_config(s.root, dir, threads);
        use_member_threads(c);
        all_wedges = all_wedges && is_wedge(c);
        int rc = 0;
        const MemberState before = member_state(dir);
        const bool kept = before == MemberState::finished || before == MemberState::failed;
        try {
            rc = run_member(c, dir, label, obs, progress.position(k));
        } catch (const InterruptedError&) {
            // While settling (not checkpointed): the member settles again when the sweep continues.
            obs.trouble(fmt::format("the sweep stopped at {}; continue it with: orodem resume {}", label, s.root));
            throw;
        } catch (const InstabilityError& e) {
            // The run has logged it and kept its last good state; the other members still run.
            obs.trouble(fmt::format("sweep: {}: unstable: {}", label, e.what()));
            rc = static_cast<int>(ExitCode::unstable);
        }
        if (kept) progress.kept();
        else if (rc == 0 || rc == static_cast<int>(ExitCode::unstable))
            if (const std::string line = progress.ended(); !line.empty()) obs.say(line);
        if (rc == static_cast<int>(ExitCode::unstable)) {
            failed.push_back(label);
            continue;
        }
        if (rc != 0) {
            // Interrupted, stopped at the wall-time limit or by a full disk: with a checkpoint.
            obs.trouble(fmt::format("the sweep stopped at {}; continue it with: orodem resume {}", label, s.root));
            return rc;
        }
        finished.push_back(dir);
    }
    return finish_sweep(s.root, s.manifest, finished, failed, all_wedges, obs);
}

/// Starts `exe sweep-member DIR [--threads T]` in its own process group (a
/// Ctrl-C on the terminal reaches the sweep, which passes it on once), output
/// appended to DIR/console.txt.
pid_t start_member(const std::string& exe, const std::string& dir, int threads) {
    std::vector<std::string> args = {exe, "sweep-member", dir};
    if (threads >= 0) {
        args.push_back("--threads");
        args.push_back(std::to_string(threads));
    }
    ChildIo io;
    io.log = dir + "/console.txt";
    io.append = true;
    io.new_group = true;
    io.parent_env = true;  // ORODEM_PARENT_PID: the member ends with this sweep (die_with_parent)
    pid_t pid = -1;
    if (const int rc = spawn_child(args, io, pid); rc != 0)
        throw IoError(fmt::format("cannot start {} for {}: {}", exe, dir, std::strerror(rc)));
    return pid;
}

/// A member running in a child process.
struct RunningMember {
    pid_t pid;
    std::size_t k;
};

/// The exit status of the first of `running` that has ended (removed from
/// it), with its member in k; -1 when none has ended yet.
int reap_member(std::vector<RunningMember>& running, std::size_t& k) {
    for (auto it = running.begin(); it != running.end(); ++it) {
        int status = 0;
        const pid_t done = ::waitpid(it->pid, &status, WNOHANG);
        if (done == 0 || (done < 0 && errno == EINTR)) continue;
        k = it->k;
        running.erase(it);
        if (done < 0) return 128;  // no longer our child: its status is lost
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    }
    return -1;
}

/// The members, j.jobs at a time in child processes. Each child writes only
/// its own member's folder; the order of the results does not depend on
/// which finishes first. A stop request stops the starting of members and is
/// passed on once to the running ones, which checkpoint; the sweep then
/// returns 128 + signal once they have.
int run_members_at_once(const Sweep& s, const LocalJobs& j, SweepObserver& obs) {
    const std::size_t n = s.size();
    const std::vector<Config> configs = member_configs(s, j.threads);
    const bool all_wedges = std::all_of(configs.begin(), configs.end(), [](const Config& c) { return is_wedge(c); });
    // Members that share a packing not cached yet would each settle it at the
    // same time: settle each such packing once first (log in DIR/log.txt).
    settle_packings(s, configs, packings_to_settle(configs, s.dirs, false), obs);
    const std::string exe = j.exe.empty() ? this_executable() : j.exe;
    const int child_threads = j.threads >= 0 ? j.threads : std::max(1, omp_get_num_procs() / j.jobs);
    std::vector<int> rc(n, -1);  // -1: not run
    std::vector<RunningMember> running;
    RunObserver& stop = obs.runs();
    StopWatch watch(stop);
    int forwarded = 0;
    std::size_t next = 0;
    SweepProgress progress(n);
    while (next < n || !running.empty()) {
        while (!stop.stop_requested() && running.size() < static_cast<std::size_t>(j.jobs) && next < n) {
            const std::size_t k = next++;
            const MemberState st = member_state(s.dirs[k]);
            if (st == MemberState::finished || st == MemberState::failed) {
                rc[k] = report_done(st, s.dirs[k], s.label(k), obs);
                progress.kept();
                continue;
            }
            running.push_back({start_member(exe, s.dirs[k], child_threads), k});
            obs.say(fmt::format("sweep: {} ({}) -> {} ({}, {} thread{}; its output in {}/console.txt)", s.label(k),
                                progress.position(k), s.dirs[k], st == MemberState::resume ? "continuing" : "starting", child_threads,
                                child_threads == 1 ? "" : "s", s.dirs[k]));
        }
        if (const int sig = stop.stop_requested(); sig && !forwarded) {
            forwarded = sig;
            for (const RunningMember& r : running) ::kill(r.pid, sig);
        }
        if (running.empty()) break;
        std::size_t k = 0;
        const int status = reap_member(running, k);
        if (status < 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            continue;
        }
        rc[k] = status;
        obs.say(fmt::format("sweep: {}: {}", s.label(k),
                            status == 0 ? "finished"
                                        : fmt::format("ended with exit status {} (see {}/console.txt)", status, s.dirs[k])));
        if (status == 0 || status == static_cast<int>(ExitCode::unstable))
            if (const std::string line = progress.ended(); !line.empty()) obs.say(line);
    }
    std::vector<std::string> finished, failed;
    int stop_rc = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (rc[k] == 0) finished.push_back(s.dirs[k]);
        else if (rc[k] == static_cast<int>(ExitCode::unstable)) failed.push_back(s.label(k));
        else if (stop_rc == 0) stop_rc = rc[k] < 0 ? 128 + forwarded : rc[k];
    }
    if (forwarded || stop_rc != 0) {
        obs.trouble(fmt::format("the sweep stopped{}; continue it with: orodem resume {}",
                                forwarded ? fmt::format(" ({})", stop_signal_name(forwarded))
                                          : std::string(),
                                s.root));
        return forwarded ? 128 + forwarded : stop_rc;
    }
    return finish_sweep(s.root, s.manifest, finished, failed, all_wedges, obs);
}

}  // namespace

std::pair<std::string, std::vector<std::string>> parse_vary(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw ConfigError(fmt::format("--vary '{}': expected key=v1,v2,..., e.g. --vary wedge.mu_bp=0.1,0.2,0.3", text));
    std::vector<std::string> values;
    const std::string rest = text.substr(eq + 1);
    for (std::size_t pos = 0;;) {
        const auto comma = rest.find(',', pos);
        values.push_back(rest.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    refuse_control_characters("--vary", text);
    for (const auto& v : values) {
        if (v.empty()) throw ConfigError(fmt::format("--vary '{}': empty value in the list", text));
        // A value names its member's folder (KEY=VALUE inside the sweep's): no path in it.
        if (v.find('/') != std::string::npos || v.find('\\') != std::string::npos || v == "." || v == "..")
            throw ConfigError(fmt::format("--vary '{}': the value {} holds a path ('/', '\\', '.' or '..'); a value "
                                          "names its run's folder inside the sweep's, so it may not",
                                          text, v));
    }
    for (std::size_t i = 0; i < values.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (same_toml_value(values[i], values[j]))
                throw ConfigError(fmt::format("--vary '{}': the value {} is listed twice; each value is one run",
                                              text, values[i]));
    return {text.substr(0, eq), values};
}

std::string Sweep::label(std::size_t k) const {
    std::string text;
    for (const auto& [key, value] : members[k]) text += fmt::format("{}{} = {}", text.empty() ? "" : ", ", key, value);
    return text;
}

Sweep sweep_in(const std::string& root, const SweepManifest& m) {
    Sweep s{root, m, {}, sweep_members(m)};
    for (const SweepMember& member : s.members) s.dirs.push_back(sweep_member_dir(root, member));
    return s;
}

Sweep open_sweep(const std::string& root) { return sweep_in(root, read_sweep_manifest(root)); }

std::vector<std::string> sweep_folders(const std::string& dir, bool& manifest) {
    std::error_code ec;
    manifest = fs::exists(sweep_manifest_path(dir), ec);
    if (manifest) return open_sweep(dir).dirs;
    std::vector<std::string> members;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_directory() && fs::exists(e.path() / "config.toml")) members.push_back(e.path().string());
    std::sort(members.begin(), members.end());
    return members;
}

std::string new_sweep_dir(const std::string& out_arg, const std::string& config_path) {
    refuse_control_characters("--out", out_arg);
    if (out_arg.empty()) return choose_run_dir("", fs::path(config_path).stem().string() + "-sweep");
    if (fs::exists(out_arg) && !fs::is_empty(out_arg))
        throw ConfigError(fmt::format("--out {}: directory exists and is not empty; choose a new directory{}", out_arg,
                                      fs::exists(sweep_manifest_path(out_arg))
                                          ? fmt::format(", or continue the sweep in it with: orodem resume {}", out_arg)
                                          : std::string()));
    return out_arg;
}

void check_sweep_member(const Config& c) {
    if (is_calibration(c))
        throw ConfigError(fmt::format("{}: run.experiment = \"{}\" is a calibration experiment, which sweeps its own "
                                      "[calibrate] lists: run it with orodem calibrate",
                                      c.path, c.run.experiment));
    check_runnable(c);
}

Sweep create_sweep(const std::string& root, const SweepManifest& m, const std::vector<Config>& configs) {
    const Sweep s = sweep_in(root, m);
    make_dirs(root);
    for (std::size_t k = 0; k < s.size(); ++k) {
        make_dirs(s.dirs[k]);
        write_file_atomic(s.dirs[k] + "/config.toml", to_toml(configs[k]));
    }
    write_file_atomic(sweep_manifest_path(root), to_toml(m));
    return s;
}

Config member_config(const std::string& root, const std::string& dir, int threads) {
    if (!fs::exists(dir + "/config.toml"))
        throw ConfigError(fmt::format("{}/config.toml: missing; the sweep folder {} was changed since orodem sweep "
                                      "wrote it, so it cannot be continued",
                                      dir, root));
    std::vector<Override> ov;
    if (threads >= 0) ov.emplace_back("run.threads", std::to_string(threads));
    Config c = load_config(dir + "/config.toml", ov);
    check_runnable(c);
    return c;
}

std::vector<Config> member_configs(const Sweep& s, int threads) {
    std::vector<Config> configs;
    for (const auto& dir : s.dirs) configs.push_back(member_config(s.root, dir, threads));
    return configs;
}

MemberState member_state(RunState s) {
    switch (s) {
        case RunState::not_started: return MemberState::start;
        case RunState::finished: return MemberState::finished;
        case RunState::failed: return MemberState::failed;  // resuming would repeat the same failure
        case RunState::no_end_line:
        case RunState::interrupted: break;
    }
    return MemberState::resume;
}

MemberState member_state(const std::string& dir) { return member_state(run_state(dir).state); }

std::vector<std::size_t> packings_to_settle(const std::vector<Config>& configs, const std::vector<std::string>& dirs,
                                            bool only_shared) {
    std::vector<std::size_t> first;  // the first member of each packing
    std::vector<int> users;
    std::vector<std::string> caches;
    for (std::size_t k = 0; k < configs.size(); ++k) {
        if (!is_wedge(configs[k]) || member_state(dirs[k]) != MemberState::start) continue;
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

void settle_packings(const Sweep& s, const std::vector<Config>& configs, const std::vector<std::size_t>& which,
                     SweepObserver& obs) {
    for (const std::size_t k : which) {
        obs.say(fmt::format("sweep: settling the packing of {} first ({})", s.label(k), packing_cache_path(configs[k])));
        ensure_packing_cached(configs[k], s.root, obs.runs());
    }
}

int settle_shared_packings(const std::string& root, int threads, SweepObserver& obs) {
    const Sweep s = open_sweep(root);
    const std::vector<Config> configs = member_configs(s, threads);
    if (!configs.empty()) use_member_threads(configs.front());
    const std::vector<std::size_t> which = packings_to_settle(configs, s.dirs, true);
    if (which.empty()) obs.say("sweep: every packing the members share is cached already");
    settle_packings(s, configs, which, obs);
    return 0;
}

int run_sweep_member(const std::string& dir, int threads, SweepObserver& obs) {
    // A member started by a local sweep ends with it (SIGTERM: a checkpoint
    // and a stop) when the sweep dies, however it dies.
    if (!die_with_parent()) return 128 + SIGTERM;
    const Config c = member_config(fs::path(dir).parent_path().string(), dir, threads);
    use_member_threads(c);
    return run_member(c, dir, fs::path(dir).filename().string(), obs);
}

int run_sweep(const Sweep& s, const LocalJobs& j, SweepObserver& obs) {
    return j.jobs > 1 ? run_members_at_once(s, j, obs) : run_members_in_order(s, j.threads, obs);
}

int finish_sweep(const std::string& root, const SweepManifest& m, const std::vector<std::string>& finished_dirs,
                 const std::vector<std::string>& failed_labels, bool all_wedges, SweepObserver& obs) {
    // A sweep over the seeds is an ensemble: its mean over the seeds' band.
    if (all_wedges && !finished_dirs.empty()) {
        const RunPlot p = plot_runs(finished_dirs, root + "/plots.png", varies_seed(m));
        for (const std::string& note : p.notes) obs.say("plot: " + note);
        obs.say("plot: " + p.path);
    }
    obs.say(fmt::format("sweep outputs in {}/", root));
    if (failed_labels.empty()) return 0;
    std::string list;
    for (const auto& f : failed_labels) list += (list.empty() ? "" : ", ") + f;
    obs.trouble(fmt::format("sweep: {} of {} runs went unstable ({}); the plots leave them out", failed_labels.size(),
                            sweep_members(m).size(), list));
    return static_cast<int>(ExitCode::unstable);
}

int report_done(MemberState st, const std::string& dir, const std::string& label, SweepObserver& obs) {
    if (st == MemberState::finished) {
        obs.say(fmt::format("sweep: {}: finished already, kept ({})", label, dir));
        return 0;
    }
    obs.trouble(fmt::format("sweep: {}: ended with an error before (see {}/log.txt); skipped", label, dir));
    return static_cast<int>(ExitCode::unstable);
}

std::string this_executable() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw IoError(fmt::format("cannot find this executable (/proc/self/exe: {})", ec.message()));
    return p.string();
}

}  // namespace orodem
