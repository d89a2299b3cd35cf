// orodem status RUN_DIR: where a wedge run stands (or each run of a sweep's
// folder). Long runs go in pieces
// (interrupted, stopped at a wall-time limit, resumed days later), so this
// reads what the run directory already holds, writes nothing, and says: how
// far the run got (S and steps), how its last piece ended (the last event
// of events.csv), the newest checkpoint, the last measured rate with the
// time left at that rate, and the command that continues it. A sweep
// submitted to Slurm (orodem sweep --scheduler slurm) adds each member's job
// as squeue (and, where accounting is on, sacct) shows it, and the members
// counted as finished, running, pending in the queue, interrupted or failed.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/sweep_manifest.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/run_log.hpp"
#include "orodem/run/slurm.hpp"

namespace orodem {

namespace fs = std::filesystem;

namespace {

/// The leading number of a series.csv row (its step); NaN when there is none.
double leading_number(const std::string& row) {
    char* end = nullptr;
    const double v = std::strtod(row.c_str(), &end);
    return end == row.c_str() ? std::nan("") : v;
}

/// Where a run stands by its own files.
enum class RunState {
    not_started,  // no log.txt yet
    no_end_line,  // started, no end line: running, or killed
    interrupted,  // its last piece ended with a checkpoint to continue from
    finished,
    failed        // unstable, or stopped by run.on_unstable: resuming repeats it
};

/// Prints the status of the run in dir and returns its state. A sweep's
/// member (in_sweep) is continued with the sweep, not on its own, so it
/// prints no command of its own.
RunState status_of_run(const std::string& dir, bool in_sweep = false) {
    require_run_dir(dir);
    const Config c = load_config(dir + "/config.toml");
    if (!is_wedge(c))
        throw ConfigError(fmt::format("'{}' is a run of run.experiment = \"{}\"; orodem status reads the wedge "
                                      "experiments' run directories",
                                      dir, c.run.experiment));
    // A sweep's members are continued with the sweep (cmd_status says so once).
    const std::string continue_with = !in_sweep ? "continue with: orodem resume " + dir + "\n" : "";
    if (!fs::exists(dir + "/log.txt")) {
        // A sweep writes every member's config.toml before the first one runs.
        fmt::print("run: {} ({}, S_max = {:g})\nstate: not started yet\n{}", dir, c.run.experiment, c.wedge.s_max,
                   continue_with);
        return RunState::not_started;
    }
    // events.csv (or, for a run started before it existed, log.txt read the
    // same way): the timestep, the last output (S and rate), the last event
    // that starts or ends a piece, and the wall time of the pieces that say it.
    const std::vector<EventRecord> events = read_events(dir);
    double dt = std::nan(""), S = std::nan("");
    std::vector<double> rates;  // steps/s of each output, in order
    double wall = 0.0;
    int pieces = 0, pieces_timed = 0;
    for (const EventRecord& e : events) {
        if (e.kind == RunEvent::start && std::isfinite(e.dt)) dt = e.dt;
        if (e.kind == RunEvent::output) {
            S = e.S;
            rates.push_back(e.steps_per_s);
        }
        if (e.kind == RunEvent::start || e.kind == RunEvent::resume) ++pieces;
        if (ends_a_piece(e.kind) && std::isfinite(e.wall_s)) {
            wall += e.wall_s;
            ++pieces_timed;
        }
    }
    const EventRecord* last = last_piece_event(events);
    const std::string last_event = last ? last->text : std::string();
    // series.csv: the step of the last row (exact; S in the log is rounded).
    double last_step = std::nan("");
    if (fs::exists(dir + "/series.csv")) {
        const std::string series = read_file(dir + "/series.csv");
        const std::size_t end = series.find_last_not_of('\n');
        const std::size_t begin = end == std::string::npos ? std::string::npos : series.rfind('\n', end);
        if (begin != std::string::npos) last_step = leading_number(series.substr(begin + 1));
    }
    // The rate of an output line is the wall clock since the one before, so a
    // run paused (SIGSTOP, a suspended machine) or shared with other work
    // shows one low rate: the estimate takes the median of the last three
    // (of two, the higher).
    const std::size_t n_rates = std::min<std::size_t>(rates.size(), 3);
    std::vector<double> last_rates(rates.end() - static_cast<std::ptrdiff_t>(n_rates), rates.end());
    std::sort(last_rates.begin(), last_rates.end());
    const double rate = last_rates.empty() ? std::nan("") : last_rates[n_rates / 2];
    const double h0 = c.packing.h0, v = c.wedge.v;
    const double total = std::isfinite(dt) ? c.wedge.s_max * h0 / (v * dt) : std::nan("");

    fmt::print("run: {} ({}, S_max = {:g}, h0 = {:g} m, v' = {:g} m/s)\n", dir, c.run.experiment, c.wedge.s_max, h0,
               v);
    if (std::isfinite(S))
        fmt::print("progress: S = {:.3f} of {:g} ({:.1f}%) at the last output, step {:.0f} of about {:.3g}\n", S,
                   c.wedge.s_max, 100.0 * S / c.wedge.s_max, last_step, total);
    else
        fmt::print("progress: no output yet (the packing may still be settling)\n");

    const bool finished = last && last->kind == RunEvent::finished;
    std::string state;
    if (last && ends_a_piece(last->kind)) {
        state = last_event;
    } else {
        // No end line after the last start: the process is still running, or
        // it was killed (power cut, session end) after its last checkpoint.
        std::error_code ec;
        const auto written = fs::last_write_time(dir + "/log.txt", ec);
        const double age =
            ec ? std::nan("")
               : std::chrono::duration<double>(fs::file_time_type::clock::now() - written).count();
        state = fmt::format("no end line: still running, or killed (log.txt last written {} ago)",
                            std::isfinite(age) ? duration_text(age) : std::string("?"));
    }
    fmt::print("state: {}\n", state);
    if (pieces_timed > 0)
        fmt::print("wall time: {} in {} of its {} piece{}{}\n", duration_text(wall), pieces_timed, pieces,
                   pieces == 1 ? "" : "s",
                   pieces_timed < pieces ? " (the others have no end line giving it: killed, or still running)" : "");

    const auto checkpoints = list_checkpoints(dir + "/checkpoint");
    if (checkpoints.empty()) {
        fmt::print("newest checkpoint: none\n");
    } else {
        const auto& [step, path] = checkpoints.front();  // newest first
        fmt::print("newest checkpoint: {} (step {}, S = {:.4f})\n", path, step,
                   std::isfinite(dt) ? static_cast<double>(step) * dt * v / h0 : std::nan(""));
    }
    if (!finished) {
        if (std::isfinite(rate) && rate > 0.0 && std::isfinite(total) && std::isfinite(last_step))
            fmt::print("rate: {:.0f} steps/s (median of the last {} output{}); about {} left at that rate\n", rate,
                       n_rates, n_rates == 1 ? "" : "s", duration_text((total - last_step) / rate));
        fmt::print("{}", continue_with);
    }
    if (finished) return RunState::finished;
    if (!last || !ends_a_piece(last->kind)) return RunState::no_end_line;
    if (last->kind == RunEvent::unstable || last->kind == RunEvent::stopped) return RunState::failed;
    return RunState::interrupted;
}

/// The array task ids of DIR/slurm/jobs.csv's array jobs, and the states Slurm gives them.
SlurmQueue sweep_queue(const std::string& dir, bool& submitted) {
    std::vector<std::string> ids;
    for (const SlurmJob& j : read_slurm_jobs(dir))
        if (j.kind == "array") ids.push_back(j.id);
    submitted = !ids.empty();
    return slurm_task_states(ids);
}

/// A sweep member's state, from its files and its array task (q: Slurm's
/// view, or none; in_queue_known: squeue answered, so none means not queued).
std::string member_state_name(RunState st, const SlurmTaskState* q, bool in_queue_known) {
    if (st == RunState::finished) return "finished";
    if (st == RunState::failed) return "failed";
    if (q && slurm_state_active(q->state)) return q->state == "PENDING" ? "pending" : "running";
    // Out of the queue: what its files say; a task that failed without a run's end line failed.
    if (q && (q->state == "FAILED" || q->state == "OUT_OF_MEMORY" || q->state == "NODE_FAIL") &&
        st != RunState::interrupted)
        return "failed";
    if (st == RunState::interrupted) return "interrupted";
    if (st == RunState::no_end_line) return q || in_queue_known ? "interrupted" : "running or killed";
    return "not started";
}

}  // namespace

int cmd_status(const std::string& dir) {
    // A sweep's folder (orodem sweep): the status of each member run, in the
    // sweep's order when it has its manifest (sweep.toml).
    std::error_code ec;
    if (fs::is_directory(dir, ec) && !fs::exists(fs::path(dir) / "config.toml", ec)) {
        std::vector<std::string> members;
        const bool manifest = fs::exists(sweep_manifest_path(dir), ec);
        if (manifest) {
            const SweepManifest m = read_sweep_manifest(dir);
            for (const auto& v : m.values) members.push_back(sweep_member_dir(dir, m, v));
        } else {
            for (const auto& e : fs::directory_iterator(dir, ec))
                if (e.is_directory() && fs::exists(e.path() / "config.toml")) members.push_back(e.path().string());
            std::sort(members.begin(), members.end());
        }
        // A sweep submitted to Slurm: its array tasks are the members in sweep.toml's order.
        bool submitted = false;
        const SlurmQueue q = manifest ? sweep_queue(dir, submitted) : SlurmQueue{};
        std::map<std::string, int> counts;
        int finished = 0;
        for (std::size_t k = 0; k < members.size(); ++k) {
            if (k) fmt::print("\n");
            const RunState st = status_of_run(members[k], manifest);
            finished += st == RunState::finished ? 1 : 0;
            if (!submitted) continue;
            const auto at = q.tasks.find(static_cast<int>(k));
            const SlurmTaskState* t = at == q.tasks.end() ? nullptr : &at->second;
            if (t)
                fmt::print("slurm: job {} {} ({})\n", t->job, t->state, t->source);
            else
                fmt::print("slurm: {}\n", q.squeue ? "not in the queue" : "squeue did not answer");
            ++counts[member_state_name(st, t, q.squeue)];
        }
        if (manifest) {
            std::string detail;
            for (const char* name : {"finished", "running", "pending", "interrupted", "failed", "running or killed",
                                     "not started"})
                if (counts[name] > 0) detail += fmt::format("{}{} {}", detail.empty() ? "" : ", ", counts[name], name);
            // Something to continue that is not in the queue (a failed member is not continued).
            const int waiting = counts["interrupted"] + counts["running or killed"] + counts["not started"];
            const bool left = finished < static_cast<int>(members.size());
            std::string next;
            if (left && (!submitted || waiting > 0))
                next = "; continue it with: orodem resume " + dir + (submitted ? " --scheduler slurm" : "");
            fmt::print("\nsweep: {} of {} runs finished{}{}\n", finished, members.size(),
                       submitted ? fmt::format(" (Slurm: {}{})", detail,
                                               q.sacct ? "" : "; sacct has no record here, squeue only")
                                 : std::string(),
                       next);
        }
        if (!members.empty()) return 0;
    }
    status_of_run(dir);
    return 0;
}

}  // namespace orodem
