// A sweep handed to Slurm (orodem sweep|resume --scheduler slurm) and what
// orodem status says of such a sweep's members: the policy. Which members
// are submitted (neither finished, failed nor still in Slurm's queue), the
// settling job the array waits for when members about to start share a
// packing not cached yet, and how a member's files and its array task
// together give its state. The mechanism (the batch scripts' text, sbatch,
// squeue, sacct, DIR/slurm/jobs.csv) is run/slurm.hpp; Slurm's state names
// are spelled only there.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "orodem/run/run_dir.hpp"
#include "orodem/run/slurm.hpp"
#include "orodem/run/sweep.hpp"

namespace orodem {

/// ConfigError when the scheduler's options do not fit the rest of the
/// command line: Slurm options without --scheduler slurm (slurm_options),
/// --jobs or --threads with it (each member is one array task, with as many
/// threads as its CPUs), or a control character in a Slurm option (each is
/// written into the batch scripts).
void check_sweep_scheduler(bool slurm, bool slurm_options, int threads, int jobs, const SlurmOptions& o = {});

/// The members to submit (array task k is member k), and those not submitted
/// again because their task is still in Slurm's queue.
struct SlurmSubmission {
    std::vector<int> submit;  // ascending
    std::vector<int> queued;  // ascending
};
/// The decision: every member that is neither finished nor failed, unless
/// Slurm shows its task in the queue (pending, running, ...). A task that
/// left the queue (completed, timed out, cancelled, failed) is submitted
/// again when its files say it is not finished.
SlurmSubmission slurm_submission(const std::vector<MemberState>& states, const SlurmQueue& q);

/// The array jobs of DIR/slurm/jobs.csv and the states Slurm gives their
/// tasks; submitted: the sweep went to Slurm (jobs.csv has an array job).
SlurmQueue sweep_queue(const std::string& sweep_dir, bool& submitted);

/// The members of s that are neither finished, failed nor still in the
/// queue, submitted to Slurm as one job array (DIR/slurm/array.sh, written
/// when fresh or missing), after a settling job when they share a packing
/// not cached yet; each submission recorded in DIR/slurm/jobs.csv. With no
/// member left to run, the overlay plots (finish_sweep). fresh: the sweep
/// was just made (orodem sweep); else it is continued (orodem resume), and
/// the options given override the scripts' #SBATCH lines. o.cpus_per_task 0:
/// as in array.sh. Throws MissingToolError without sbatch, SchedulerError
/// when Slurm refuses. Returns the exit status.
int submit_sweep_slurm(const Sweep& s, const SlurmOptions& o, bool fresh, SweepObserver& obs);

/// A member of a sweep on Slurm as orodem status counts it.
enum class MemberStatus { finished, running, pending, interrupted, failed, running_or_killed, not_started };
inline constexpr std::size_t kMemberStatuses = 7;
/// "finished", ..., "running or killed", "not started".
const char* member_status_name(MemberStatus s);
/// From the member's files (st) and its array task (task: Slurm's view, or
/// none; squeue_answered: none then means it is not in the queue).
MemberStatus member_status(RunState st, const SlurmTaskState* task, bool squeue_answered);

/// The members of a sweep counted for orodem status's last line.
struct SweepTally {
    bool submitted = false;  // the sweep went to Slurm
    std::size_t members = 0;
    std::size_t finished = 0;
    std::array<int, kMemberStatuses> counts{};  // by MemberStatus
    void add(RunState st, const SlurmTaskState* task, bool squeue_answered);
    /// The non-zero counts in MemberStatus's order: "1 finished, 1 interrupted".
    std::string counts_text() const;
    /// Whether something is left to continue that is not in Slurm's queue (a failed member is not continued).
    bool can_continue() const;
};

}  // namespace orodem
