// A sweep handed to Slurm (orodem sweep --scheduler slurm). The sweep folder
// is prepared as for a local sweep (sweep.toml, every member's config.toml);
// this module writes the two batch scripts into DIR/slurm/ and submits them:
//
//   array.sh   one array task per member: task k runs member k of sweep.toml
//              (`orodem sweep-member`, which keeps a finished member, resumes an
//              interrupted one from its checkpoint and starts the rest) with
//              --threads equal to its CPUs; console output into the member's
//              console.txt, Slurm's own into DIR/slurm/slurm-<job>_<task>.out.
//   settle.sh  the packings that several members share and that are not
//              cached yet, settled once (`orodem sweep-settle`); submitted
//              only when there are such, and the array then waits for it
//              (--dependency=afterok), so members never race to build a cache.
//
// Only standard sbatch options are used; a user can read, edit and resubmit
// the scripts by hand (`sbatch --array=1,3 DIR/slurm/array.sh`). Every
// submission is recorded in DIR/slurm/jobs.csv (job id, kind, array tasks),
// which `orodem status` and `orodem resume --scheduler slurm` read. The
// Slurm commands (sbatch, squeue, sacct) run as child processes; a missing
// one is a MissingToolError, a refusal a SchedulerError.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace orodem {

/// What each array task asks Slurm for (the sbatch options of array.sh).
struct SlurmOptions {
    std::string partition;                 // --partition; empty: the cluster's default partition
    std::string time;                      // --time, e.g. 12:00:00; empty: the partition's default limit
    int cpus_per_task = 1;                 // --cpus-per-task, and each member's --threads [-]
    std::vector<std::string> sbatch_args;  // further sbatch options, verbatim, e.g. --account=geo
    int signal_before_s = 120;             // SIGTERM this long before the time limit: a checkpoint [s]
};

/// One submission (a row of DIR/slurm/jobs.csv).
struct SlurmJob {
    std::string id;     // Slurm's job id (of the whole array)
    std::string kind;   // "array" or "settle"
    std::string tasks;  // the array's task ids, e.g. "0-4" or "1,3"; empty for settle
};

/// DIR/slurm, the folder of the scripts, the job list and Slurm's output.
std::string slurm_dir(const std::string& sweep_dir);

/// The text of array.sh for the members (their folder names in DIR, in
/// sweep.toml's order) of the sweep in the absolute path sweep_dir, run by
/// the executable exe.
std::string slurm_array_script(const std::string& sweep_dir, const std::vector<std::string>& members,
                               const std::string& exe, const SlurmOptions& o);

/// The text of settle.sh: `exe sweep-settle sweep_dir` on one node.
std::string slurm_settle_script(const std::string& sweep_dir, const std::string& exe, const SlurmOptions& o);

/// "0-3" for 0,1,2,3; "1,3,5-7" otherwise (ids ascending, distinct).
std::string array_ranges(const std::vector<int>& ids);

/// Throws MissingToolError (naming the Debian package) when `program` is not
/// on PATH.
void require_slurm_command(const std::string& program);

/// Submits `sbatch --parsable ARGS SCRIPT`; Slurm's job id. Throws
/// MissingToolError without sbatch, SchedulerError (with sbatch's message)
/// when it refuses.
std::string sbatch(const std::vector<std::string>& args, const std::string& script);

/// DIR/slurm/jobs.csv (empty when there is none); IoError/ConfigError when
/// it cannot be read or is not one.
std::vector<SlurmJob> read_slurm_jobs(const std::string& sweep_dir);
/// Adds one row to DIR/slurm/jobs.csv (the file rewritten atomically).
void record_slurm_job(const std::string& sweep_dir, const SlurmJob& job);

/// The tasks of the array jobs `ids` that Slurm knows, by array task id: the
/// state squeue shows (PENDING, RUNNING, COMPLETING, ...) or, for tasks that
/// left the queue, sacct's (COMPLETED, FAILED, TIMEOUT, CANCELLED, ...) where
/// accounting is on. A job's newest entry wins (ids in submission order).
struct SlurmTaskState {
    std::string job;     // "<array job id>_<task id>"
    std::string state;   // Slurm's state name
    std::string source;  // "squeue" or "sacct"
};
struct SlurmQueue {
    bool squeue = false;  // squeue answered
    bool sacct = false;   // sacct answered (accounting on)
    std::map<int, SlurmTaskState> tasks;  // by array task id, from the newest job that has it
    /// Task k's state; nullptr when Slurm knows no such task.
    const SlurmTaskState* task(std::size_t k) const {
        const auto at = tasks.find(static_cast<int>(k));
        return at == tasks.end() ? nullptr : &at->second;
    }
};
SlurmQueue slurm_task_states(const std::vector<std::string>& ids);

/// Whether a Slurm state means the task is still in the queue (pending,
/// running, completing, suspended, ...).
bool slurm_state_active(const std::string& state);
/// Whether it is waiting for resources (PENDING).
bool slurm_state_pending(const std::string& state);
/// Whether the task left the queue failed by Slurm's account (FAILED,
/// OUT_OF_MEMORY, NODE_FAIL); a time limit or a cancel is no failure.
bool slurm_state_failed(const std::string& state);

}  // namespace orodem
