// orodem status RUN_DIR: where a wedge run stands (or each run of a sweep's
// folder). Long runs go in pieces (interrupted, stopped at a wall-time limit,
// resumed days later), so this reads what the run directory already holds
// (run_state), writes nothing, and says: how far the run got (S and steps),
// how its last piece ended (the last event of events.csv), the newest
// checkpoint, the last measured rate with the time left at that rate, and
// the command that continues it. A sweep submitted to Slurm adds each
// member's job as squeue (and, where accounting is on, sacct) shows it, and
// the members counted as finished, running, pending in the queue,
// interrupted or failed (run/sweep_slurm.hpp).
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/sweep.hpp"
#include "orodem/run/sweep_slurm.hpp"

namespace orodem {

namespace {

/// Prints the status of the run in dir and returns its state. A sweep's
/// member (in_sweep) is continued with the sweep, not on its own, so it
/// prints no command of its own.
RunState print_run_status(const std::string& dir, bool in_sweep = false) {
    const RunStatus r = run_state(dir);
    const Config& c = r.config;
    if (!is_wedge(c))
        throw ConfigError(fmt::format("'{}' is a run of run.experiment = \"{}\"; orodem status reads the wedge "
                                      "experiments' run directories",
                                      dir, c.run.experiment));
    const std::string continue_with = !in_sweep ? "continue with: orodem resume " + dir + "\n" : "";
    const double h0 = c.packing.h0, v = c.wedge.v;
    if (r.state == RunState::not_started) {
        fmt::print("run: {} ({}, S_max = {:g})\nstate: not started yet\n{}", dir, c.run.experiment, c.wedge.s_max,
                   continue_with);
        return r.state;
    }
    fmt::print("run: {} ({}, S_max = {:g}, h0 = {:g} m, v' = {:g} m/s)\n", dir, c.run.experiment, c.wedge.s_max, h0,
               v);
    if (std::isfinite(r.S))
        fmt::print("progress: S = {:.3f} of {:g} ({:.1f}%) at the last output, step {:.0f} of about {:.3g}\n", r.S,
                   c.wedge.s_max, 100.0 * r.S / c.wedge.s_max, r.last_step, r.total_steps);
    else
        fmt::print("progress: no output yet (the packing may still be settling)\n");
    // No end line after the last start: still running, or killed (power cut, session end) after its last checkpoint.
    fmt::print("state: {}\n", r.state != RunState::no_end_line
                                  ? r.last->text
                                  : fmt::format("no end line: still running, or killed (log.txt last written {} ago)",
                                                std::isfinite(r.log_age_s) ? duration_text(r.log_age_s) : "?"));
    if (r.pieces_timed > 0)
        fmt::print("wall time: {} in {} of its {} piece{}{}\n", duration_text(r.wall_s), r.pieces_timed, r.pieces,
                   r.pieces == 1 ? "" : "s",
                   r.pieces_timed < r.pieces ? " (the others have no end line giving it: killed, or still running)"
                                             : "");
    if (!r.newest_checkpoint)
        fmt::print("newest checkpoint: none\n");
    else
        fmt::print("newest checkpoint: {} (step {}, S = {:.4f})\n", r.newest_checkpoint->second,
                   r.newest_checkpoint->first,
                   std::isfinite(r.dt) ? static_cast<double>(r.newest_checkpoint->first) * r.dt * v / h0 : std::nan(""));
    if (r.state != RunState::finished) {
        if (std::isfinite(r.rate) && r.rate > 0.0 && std::isfinite(r.total_steps) && std::isfinite(r.last_step))
            fmt::print("rate: {:.0f} steps/s (median of the last {} output{}); about {} left at that rate\n", r.rate,
                       r.rate_outputs, r.rate_outputs == 1 ? "" : "s",
                       duration_text((r.total_steps - r.last_step) / r.rate));
        fmt::print("{}", continue_with);
    }
    return r.state;
}

}  // namespace

int cmd_status(const std::string& dir) {
    // A sweep's folder (orodem sweep): the status of each member run, in the
    // sweep's order when it has its manifest (sweep.toml).
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec) && !std::filesystem::exists(dir + "/config.toml", ec)) {
        bool manifest = false;
        const std::vector<std::string> members = sweep_folders(dir, manifest);
        // A sweep submitted to Slurm: its array tasks are the members in sweep.toml's order.
        SweepTally tally;
        const SlurmQueue q = manifest ? sweep_queue(dir, tally.submitted) : SlurmQueue{};
        for (std::size_t k = 0; k < members.size(); ++k) {
            if (k) fmt::print("\n");
            const RunState st = print_run_status(members[k], manifest);
            const SlurmTaskState* t = q.task(k);
            tally.add(st, t, q.squeue);
            if (tally.submitted && t) fmt::print("slurm: job {} {} ({})\n", t->job, t->state, t->source);
            else if (tally.submitted) fmt::print("slurm: {}\n", q.squeue ? "not in the queue" : "squeue did not answer");
        }
        if (manifest)
            fmt::print("\nsweep: {} of {} runs finished{}{}\n", tally.finished, members.size(),
                       tally.submitted ? fmt::format(" (Slurm: {}{})", tally.counts_text(),
                                                     q.sacct ? "" : "; sacct has no record here, squeue only")
                                       : std::string(),
                       tally.can_continue()
                           ? "; continue it with: orodem resume " + dir + (tally.submitted ? " --scheduler slurm" : "")
                           : std::string());
        if (!members.empty()) return 0;
    }
    print_run_status(dir);
    return 0;
}

}  // namespace orodem
