// A sweep on Slurm (sweep_slurm.hpp): which members are submitted, the
// submission itself, and the members' states as orodem status counts them.
#include "orodem/run/sweep_slurm.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

namespace fs = std::filesystem;

void check_sweep_scheduler(bool slurm, bool slurm_options, int threads, int jobs, const SlurmOptions& o) {
    // Each is written into the batch scripts: a newline there would be a line of its own.
    refuse_control_characters("--partition", o.partition);
    refuse_control_characters("--time", o.time);
    for (const auto& a : o.sbatch_args) refuse_control_characters("--sbatch-arg", a);
    if (!slurm) {
        if (slurm_options)
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

SlurmSubmission slurm_submission(const std::vector<MemberState>& states, const SlurmQueue& q) {
    SlurmSubmission out;
    for (std::size_t k = 0; k < states.size(); ++k) {
        if (states[k] == MemberState::finished || states[k] == MemberState::failed) continue;
        const SlurmTaskState* t = q.task(k);
        (t && slurm_state_active(t->state) ? out.queued : out.submit).push_back(static_cast<int>(k));
    }
    return out;
}

SlurmQueue sweep_queue(const std::string& sweep_dir, bool& submitted) {
    std::vector<std::string> ids;
    for (const SlurmJob& j : read_slurm_jobs(sweep_dir))
        if (j.kind == "array") ids.push_back(j.id);
    submitted = !ids.empty();
    return slurm_task_states(ids);
}

int submit_sweep_slurm(const Sweep& given, const SlurmOptions& o, bool fresh, SweepObserver& obs) {
    const std::string& shown = given.root;  // as the person gave it
    std::string root = fs::absolute(shown).lexically_normal().string();
    while (root.size() > 1 && root.back() == '/') root.pop_back();
    const Sweep s = sweep_in(root, given.manifest);
    const std::size_t n = s.size();
    const std::vector<Config> configs = member_configs(s, -1);
    bool all_wedges = true;
    std::vector<MemberState> states;
    std::vector<std::string> names, finished, failed;
    for (std::size_t k = 0; k < n; ++k) {
        all_wedges = all_wedges && is_wedge(configs[k]);
        names.push_back(fs::path(s.dirs[k]).filename().string());
        const MemberState st = states.emplace_back(member_state(s.dirs[k]));
        if (st == MemberState::finished) finished.push_back(s.dirs[k]);
        if (st == MemberState::failed) failed.push_back(s.label(k));
        if ((st == MemberState::finished || st == MemberState::failed) && !fresh) report_done(st, s.dirs[k], s.label(k), obs);
    }
    if (slurm_submission(states, SlurmQueue{}).submit.empty()) {
        obs.say("sweep: no member left to run; nothing submitted");
        return finish_sweep(shown, s.manifest, finished, failed, all_wedges, obs);
    }
    // A member still in the queue (a task of this sweep pending or running) is not submitted twice.
    bool submitted_before = false;
    const SlurmQueue q = sweep_queue(root, submitted_before);
    const SlurmSubmission plan = slurm_submission(states, q);
    for (const int k : plan.queued) {
        const SlurmTaskState* t = q.task(static_cast<std::size_t>(k));
        obs.say(fmt::format("sweep: {}: still in Slurm's queue as job {} ({}); not submitted again",
                            s.label(static_cast<std::size_t>(k)), t->job, t->state));
    }
    if (plan.submit.empty()) {
        obs.say(fmt::format("sweep: every unfinished member is in Slurm's queue; nothing submitted (orodem status {})",
                            shown));
        return 0;
    }
    require_slurm_command("sbatch");
    const std::string sdir = slurm_dir(root), exe = this_executable();
    make_dirs(sdir);
    const std::string array_sh = sdir + "/array.sh", settle_sh = sdir + "/settle.sh";
    SlurmOptions written = o;
    if (written.cpus_per_task < 1) written.cpus_per_task = 1;
    if (fresh || !fs::exists(array_sh)) write_file_atomic(array_sh, slurm_array_script(root, names, exe, written));
    // On resume the options given again override the scripts' #SBATCH lines.
    std::vector<std::string> overrides;
    if (!fresh) {
        if (!o.partition.empty()) overrides.push_back("--partition=" + o.partition);
        if (!o.time.empty()) overrides.push_back("--time=" + o.time);
        if (o.cpus_per_task > 0) overrides.push_back(fmt::format("--cpus-per-task={}", o.cpus_per_task));
        for (const auto& a : o.sbatch_args) overrides.push_back(a);
    }
    const std::string again = fmt::format("; the sweep folder is ready: submit it again with orodem resume {} "
                                          "--scheduler slurm",
                                          shown);
    auto submit = [&](const std::vector<std::string>& args, const std::string& script) {
        try {
            return sbatch(args, script);
        } catch (const SchedulerError& e) {
            throw SchedulerError(e.what() + again);
        }
    };
    std::vector<std::string> array_args = overrides;
    // Among the members submitted now (one still in the queue settles its own packing when it runs).
    std::vector<Config> todo_configs;
    std::vector<std::string> todo_dirs;
    for (const int k : plan.submit) {
        todo_configs.push_back(configs[static_cast<std::size_t>(k)]);
        todo_dirs.push_back(s.dirs[static_cast<std::size_t>(k)]);
    }
    const std::vector<std::size_t> settle = packings_to_settle(todo_configs, todo_dirs, true);
    if (!settle.empty()) {
        if (fresh || !fs::exists(settle_sh)) write_file_atomic(settle_sh, slurm_settle_script(root, exe, written));
        const std::string id = submit(overrides, settle_sh);
        record_slurm_job(root, SlurmJob{id, "settle", ""});
        obs.say(fmt::format("sweep: submitted job {} to settle the packing {} members share ({}/slurm/settle.sh)", id,
                            settle.size() == 1 ? "that several" : "s that several", shown));
        array_args.push_back("--dependency=afterok:" + id);
    }
    const std::string tasks = array_ranges(plan.submit);
    array_args.push_back("--array=" + tasks);
    const std::string id = submit(array_args, array_sh);
    record_slurm_job(root, SlurmJob{id, "array", tasks});
    for (const int k : plan.submit)
        obs.say(fmt::format("sweep: {} -> job {}_{} ({})", s.label(static_cast<std::size_t>(k)), id, k,
                            states[static_cast<std::size_t>(k)] == MemberState::resume ? "continuing" : "starting"));
    obs.say(fmt::format("sweep: submitted job array {} to Slurm: tasks {} ({} of {} members; {}/slurm/array.sh, job "
                        "ids in {}/slurm/jobs.csv)",
                        id, tasks, plan.submit.size(), n, shown, shown));
    obs.say(fmt::format("sweep: follow it with: orodem status {}; when it is done: orodem plot {}", shown, shown));
    obs.say(fmt::format("job id: {}", id));
    return 0;
}

const char* member_status_name(MemberStatus s) {
    static constexpr const char* kNames[kMemberStatuses] = {"finished", "running",           "pending",    "interrupted",
                                                            "failed",   "running or killed", "not started"};
    return kNames[static_cast<std::size_t>(s)];
}

MemberStatus member_status(RunState st, const SlurmTaskState* task, bool squeue_answered) {
    if (st == RunState::finished) return MemberStatus::finished;
    if (st == RunState::failed) return MemberStatus::failed;
    if (task && slurm_state_active(task->state))
        return slurm_state_pending(task->state) ? MemberStatus::pending : MemberStatus::running;
    // Out of the queue: what its files say; a task that failed without a run's end line failed.
    if (task && slurm_state_failed(task->state) && st != RunState::interrupted) return MemberStatus::failed;
    if (st == RunState::interrupted) return MemberStatus::interrupted;
    if (st == RunState::no_end_line)
        return task || squeue_answered ? MemberStatus::interrupted : MemberStatus::running_or_killed;
    return MemberStatus::not_started;
}

void SweepTally::add(RunState st, const SlurmTaskState* task, bool squeue_answered) {
    ++members;
    if (st == RunState::finished) ++finished;
    if (submitted) ++counts[static_cast<std::size_t>(member_status(st, task, squeue_answered))];
}

std::string SweepTally::counts_text() const {
    std::string text;
    for (std::size_t s = 0; s < kMemberStatuses; ++s)
        if (counts[s] > 0)
            text += fmt::format("{}{} {}", text.empty() ? "" : ", ", counts[s],
                                member_status_name(static_cast<MemberStatus>(s)));
    return text;
}

bool SweepTally::can_continue() const {
    const auto count = [&](MemberStatus s) { return counts[static_cast<std::size_t>(s)]; };
    const int waiting =
        count(MemberStatus::interrupted) + count(MemberStatus::running_or_killed) + count(MemberStatus::not_started);
    return finished < members && (!submitted || waiting > 0);
}

}  // namespace orodem
