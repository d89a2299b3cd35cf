// The sweep's policy in process (run/sweep.hpp, run/sweep_slurm.hpp): --vary,
// the members' states from their run directories, the packings settled
// first, the scheduler (in order, and in child processes: a stand-in member
// program, a stop request passed on), and the Slurm decisions against a
// fake sbatch, squeue and sacct on PATH.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/io/sweep_manifest.hpp"
#include "orodem/run/slurm.hpp"
#include "orodem/run/sweep.hpp"
#include "orodem/run/sweep_slurm.hpp"
#include "test_util.hpp"
#include "unit/run_wing_util.hpp"

using namespace orodem;
using namespace orodem::test;

#define EXPECT_HAS(text, needle) \
    EXPECT_NE(std::string(text).find(needle), std::string::npos) << "missing \"" << (needle) << "\" in:\n" << (text)

namespace {

/// A sweep over key = values of the config text in t/base.toml, made in t/name
/// as orodem sweep makes it (every member's config.toml, then sweep.toml).
Sweep make_sweep(const TempFolder& t, const std::string& name, const std::string& config, const std::string& key,
                 const std::vector<std::string>& values) {
    write_text(t / "base.toml", config);
    std::vector<Config> configs;
    for (const auto& v : values) configs.push_back(load_config(t / "base.toml", {{key, v}}));
    return create_sweep(t / name, SweepManifest{t / "base.toml", key, values, {}, {}}, configs);
}

std::string settle_config(const fs::path& cache) {
    return "[run]\nexperiment = \"settle\"\n[packing]\nh0 = 6.0\ncache_dir = \"" + cache.string() + "\"\n";
}

void write_script(const fs::path& p, const std::string& text) {
    write_text(p, "#!/bin/sh\n" + text);
    fs::permissions(p, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read);
}

/// A stand-in for `orodem sweep-member DIR --threads T`: says what it was
/// given, then exits with the number in DIR/exit_with (0 without it); with
/// DIR/wait_for_term it says "ready" and waits for SIGTERM (then exits 143).
void write_fake_member(const fs::path& p) {
    write_script(p,
                 "echo \"member $*\"\n"
                 "d=\"$2\"\n"
                 "if [ -e \"$d/wait_for_term\" ]; then\n"
                 "  trap 'kill $p 2>/dev/null; echo \"got TERM\"; exit 143' TERM\n"
                 "  sleep 30 & p=$!\n"
                 "  echo ready\n"
                 "  wait $p\n"
                 "  exit 0\n"
                 "fi\n"
                 "[ -e \"$d/exit_with\" ] && exit \"$(cat \"$d/exit_with\")\"\n"
                 "exit 0\n");
}

/// sbatch, squeue and sacct as scripts first on PATH while in scope: sbatch
/// appends its arguments to sbatch.log and answers the id in next_id (then
/// one more), or refuses when the file `refuse` exists; squeue and sacct
/// print squeue.txt and sacct.txt, and fail without them.
class FakeSlurm {
public:
    explicit FakeSlurm(const fs::path& folder) : dir(folder), old_path_(std::getenv("PATH") ? std::getenv("PATH") : "") {
        const std::string d = "'" + dir.string() + "'";
        write_script(dir / "bin" / "sbatch", "echo \"$@\" >> " + d + "/sbatch.log\n"
                                             "if [ -e " + d + "/refuse ]; then\n"
                                             "  echo 'sbatch: error: invalid partition specified: nowhere' >&2; exit 1\n"
                                             "fi\n"
                                             "n=$(cat " + d + "/next_id)\n"
                                             "echo $((n + 1)) > " + d + "/next_id\n"
                                             "echo \"$n\"\n");
        for (const char* tool : {"squeue", "sacct"})
            write_script(dir / "bin" / tool, std::string("[ -e ") + d + "/" + tool + ".txt ] || exit 1\ncat " + d +
                                                 "/" + tool + ".txt\n");
        write_text(dir / "next_id", "1001\n");
        ::setenv("PATH", ((dir / "bin").string() + ":" + old_path_).c_str(), 1);
    }
    ~FakeSlurm() { ::setenv("PATH", old_path_.c_str(), 1); }
    FakeSlurm(const FakeSlurm&) = delete;
    FakeSlurm& operator=(const FakeSlurm&) = delete;
    std::string sbatch_log() const { return slurp(dir / "sbatch.log"); }

    fs::path dir;

private:
    std::string old_path_;
};

}  // namespace

TEST(SweepLib, VaryIsAKeyAndDistinctValues) {
    const auto [key, values] = parse_vary("wedge.mu_bp=0.1,0.2,0.3");
    EXPECT_EQ(key, "wedge.mu_bp");
    EXPECT_EQ(values, (std::vector<std::string>{"0.1", "0.2", "0.3"}));
    for (const char* bad : {"wedge.mu_bp", "=0.1", "wedge.mu_bp=", "wedge.mu_bp=0.1,,0.2", "wedge.mu_bp=0.1,0.1"})
        EXPECT_THROW(parse_vary(bad), ConfigError) << bad;
    try {
        parse_vary("wedge.mu_bp=0.1,0.2,0.1");
        ADD_FAILURE() << "a value listed twice was taken";
    } catch (const ConfigError& e) {
        EXPECT_HAS(e.what(), "the value 0.1 is listed twice");
    }
}

TEST(SweepLib, MembersStatesComeFromTheirRunDirectories) {
    SerialOmp one_thread;  // the sweep sets the members' run.threads
    TempFolder t("sweep-states");
    ASSERT_FALSE(t.path.empty());
    const Sweep s = make_sweep(t, "sw", tiny_exp1(t.path / "cache"), "wedge.mu_bp", {"0.1", "0.2", "0.3", "0.4", "0.5", "0.6"});
    ASSERT_EQ(s.size(), 6u);
    EXPECT_EQ(s.dirs[1], (t.path / "sw" / "wedge.mu_bp=0.2").string());
    EXPECT_EQ(s.label(1), "wedge.mu_bp = 0.2");
    write_events(s.dirs[0], {kStartRow, output_row(0.5, 600), kFinishedRow});
    write_events(s.dirs[1], {kStartRow, output_row(0.1, 600), kInterruptedRow});
    write_events(s.dirs[2], {kStartRow, kUnstableRow});
    write_events(s.dirs[3], {kStartRow, output_row(0.1, 600)});  // killed: no end line
    EXPECT_EQ(member_state(s.dirs[0]), MemberState::finished);
    EXPECT_EQ(member_state(s.dirs[1]), MemberState::resume);
    EXPECT_EQ(member_state(s.dirs[2]), MemberState::failed);
    EXPECT_EQ(member_state(s.dirs[3]), MemberState::resume);
    EXPECT_EQ(member_state(s.dirs[4]), MemberState::start);
    EXPECT_EQ(member_state(s.dirs[5]), MemberState::start);

    // The sweep read back from its folder: the same members in the same order.
    const Sweep back = open_sweep(s.root);
    EXPECT_EQ(back.dirs, s.dirs);
    EXPECT_EQ(back.manifest.values, s.manifest.values);
    bool manifest = false;
    EXPECT_EQ(sweep_folders(s.root, manifest), s.dirs);
    EXPECT_TRUE(manifest);
    EXPECT_EQ(member_configs(s, 1).at(3).wedge.mu_bp, 0.4);
    EXPECT_EQ(member_configs(s, 1).at(3).run.threads, 1);

    // The two members still to start share one packing that is not cached:
    // it is settled once first (the first of them), also when only shared ones count.
    const std::vector<Config> configs = member_configs(s, -1);
    EXPECT_EQ(packings_to_settle(configs, s.dirs, false), std::vector<std::size_t>{4});
    EXPECT_EQ(packings_to_settle(configs, s.dirs, true), std::vector<std::size_t>{4});
    // A packing of its own a member settles itself; a cached one nobody settles.
    write_events(s.dirs[5], {kStartRow});
    EXPECT_EQ(packings_to_settle(configs, s.dirs, false), std::vector<std::size_t>{4});
    EXPECT_TRUE(packings_to_settle(configs, s.dirs, true).empty());
    write_text(packing_cache_path(configs[4]), "cached");
    EXPECT_TRUE(packings_to_settle(configs, s.dirs, false).empty());
    KeptLines kept;
    EXPECT_EQ(settle_shared_packings(s.root, 1, kept), 0);
    EXPECT_EQ(kept.out, std::vector<std::string>{"sweep: every packing the members share is cached already"});

    // A folder of runs without sweep.toml: its runs by name.
    fs::remove(sweep_manifest_path(s.root));
    EXPECT_EQ(sweep_folders(s.root, manifest), s.dirs);
    EXPECT_FALSE(manifest);
    EXPECT_THROW(open_sweep(s.root), ConfigError);
}

TEST(SweepLib, ANewSweepsFolderIsNewOrEmptyAndItsMembersAreRunnable) {
    TempFolder t("sweep-new");
    ASSERT_FALSE(t.path.empty());
    EXPECT_EQ(new_sweep_dir(t / "fresh", "configs/a.toml"), t / "fresh");
    const Sweep s = make_sweep(t, "sw", tiny_exp1(t.path / "cache"), "wedge.mu_bp", {"0.1"});
    try {
        new_sweep_dir(s.root, "configs/a.toml");
        ADD_FAILURE() << "a sweep's folder was taken for a new sweep";
    } catch (const ConfigError& e) {
        EXPECT_HAS(e.what(), "or continue the sweep in it with: orodem resume " + s.root);
    }
    write_text(t.path / "calib.toml", "[run]\nexperiment = \"biaxial\"\n");
    const Config calibration = load_config(t / "calib.toml");
    EXPECT_THROW(check_sweep_member(calibration), ConfigError);
    fs::remove(s.dirs[0] + "/config.toml");
    EXPECT_THROW(member_config(s.root, s.dirs[0], -1), ConfigError);
}

TEST(SweepLib, InOrderAFinishedMemberIsKeptAndAFailedOneSkipped) {
    SerialOmp one_thread;  // the sweep sets the members' run.threads
    TempFolder t("sweep-order");
    ASSERT_FALSE(t.path.empty());
    const Sweep failed = make_sweep(t, "failed", tiny_exp1(t.path / "cache"), "wedge.mu_bp", {"0.1", "0.2"});
    write_events(failed.dirs[0], {kStartRow, kUnstableRow});
    write_events(failed.dirs[1], {kStartRow, "stopped,1,0.1,,1,,\"STOPPED: a disc left the domain\""});
    KeptLines kept;
    EXPECT_EQ(run_sweep(failed, LocalJobs{1, 1, ""}, kept), 3);
    EXPECT_EQ(kept.err, (std::vector<std::string>{
                            "sweep: wedge.mu_bp = 0.1: ended with an error before (see " + failed.dirs[0] +
                                "/log.txt); skipped",
                            "sweep: wedge.mu_bp = 0.2: ended with an error before (see " + failed.dirs[1] +
                                "/log.txt); skipped",
                            "sweep: 2 of 2 runs went unstable (wedge.mu_bp = 0.1, wedge.mu_bp = 0.2); the plots "
                            "leave them out"}));
    EXPECT_EQ(kept.out, std::vector<std::string>{"sweep outputs in " + failed.root + "/"});

    // Settled layers are finished by their packing.bin; no S plots for them.
    const Sweep layers = make_sweep(t, "layers", settle_config(t.path / "cache"), "packing.seed", {"1", "2"});
    for (const auto& d : layers.dirs) write_text(d + "/packing.bin", "x");
    KeptLines kept2;
    EXPECT_EQ(run_sweep(layers, LocalJobs{1, 1, ""}, kept2), 0);
    EXPECT_EQ(kept2.out, (std::vector<std::string>{
                             "sweep: packing.seed = 1: finished already, kept (" + layers.dirs[0] + ")",
                             "sweep: packing.seed = 2: finished already, kept (" + layers.dirs[1] + ")",
                             "sweep outputs in " + layers.root + "/"}));
    EXPECT_TRUE(kept2.err.empty());
    // One member on its own (orodem sweep-member), as a parallel sweep's child runs it.
    KeptLines kept3;
    EXPECT_EQ(run_sweep_member(failed.dirs[0], 1, kept3), 3);
    EXPECT_EQ(run_sweep_member(layers.dirs[1], 1, kept3), 0);
    EXPECT_HAS(kept3.text(), "sweep: packing.seed=2: finished already, kept");
}

TEST(SweepLib, InChildProcessesEachMemberRunsOnceAndAnUnstableOneIsNamed) {
    TempFolder t("sweep-jobs");
    ASSERT_FALSE(t.path.empty());
    write_fake_member(t.path / "member");
    const Sweep s = make_sweep(t, "sw", settle_config(t.path / "cache"), "packing.seed", {"1", "2", "3", "4"});
    write_text(s.dirs[1] + "/exit_with", "3");
    write_text(s.dirs[3] + "/packing.bin", "x");  // finished: not started again
    KeptLines kept;
    EXPECT_EQ(run_sweep(s, LocalJobs{1, 2, (t.path / "member").string()}, kept), 3);
    const std::string text = kept.text();
    EXPECT_HAS(text, "sweep: packing.seed = 1 (run 1 of 4) -> " + s.dirs[0] + " (starting, 1 thread; its output in " +
                         s.dirs[0] + "/console.txt)");
    EXPECT_HAS(text, "sweep: packing.seed = 3 (run 3 of 4) -> ");
    // After each run that ends, but the last: the runs done and the time left at the pace so far.
    EXPECT_HAS(text, " runs done, ");
    EXPECT_HAS(text, " to go: about ");
    EXPECT_HAS(text, " more at this sweep's pace so far (");
    EXPECT_HAS(text, "sweep: packing.seed = 1: finished\n");
    EXPECT_HAS(text, "sweep: packing.seed = 2: ended with exit status 3 (see " + s.dirs[1] + "/console.txt)");
    EXPECT_HAS(text, "sweep: packing.seed = 3: finished\n");
    EXPECT_HAS(text, "sweep: packing.seed = 4: finished already, kept");
    EXPECT_HAS(text, "sweep: 1 of 4 runs went unstable (packing.seed = 2); the plots leave them out");
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(slurp(s.dirs[k] + "/console.txt"), "member sweep-member " + s.dirs[k] + " --threads 1\n");
    EXPECT_FALSE(fs::exists(s.dirs[3] + "/console.txt"));
}

TEST(SweepLib, AStopRequestStopsStartingMembersAndReachesTheRunningOnesOnce) {
    TempFolder t("sweep-stop");
    ASSERT_FALSE(t.path.empty());
    write_fake_member(t.path / "member");
    const Sweep s = make_sweep(t, "sw", settle_config(t.path / "cache"), "packing.seed", {"1", "2", "3"});
    // The first two members run until a SIGTERM ends them; the stop comes once the first is ready.
    for (int k : {0, 1}) write_text(s.dirs[k] + "/wait_for_term", "");
    const std::string console = s.dirs[0] + "/console.txt";
    StopWhen stop([&] { return slurp(console).find("ready") != std::string::npos; });
    KeptLines kept;
    kept.run = &stop;
    EXPECT_EQ(run_sweep(s, LocalJobs{1, 2, (t.path / "member").string()}, kept), 143);
    EXPECT_HAS(kept.text(), "sweep: packing.seed = 1: ended with exit status 143");
    EXPECT_EQ(kept.err, std::vector<std::string>{"the sweep stopped (SIGTERM); continue it with: orodem resume " + s.root});
    EXPECT_HAS(slurp(console), "got TERM");
    EXPECT_FALSE(fs::exists(s.dirs[2] + "/console.txt"));  // no member starts after the stop
}

TEST(SlurmLib, WhatIsSubmittedIsWhatIsNeitherDoneNorInTheQueue) {
    SlurmQueue q;
    q.squeue = true;
    q.tasks[0] = {"77_0", "RUNNING", "squeue"};
    q.tasks[1] = {"77_1", "RUNNING", "squeue"};
    q.tasks[2] = {"77_2", "PENDING", "squeue"};
    q.tasks[4] = {"77_4", "TIMEOUT", "sacct"};
    q.tasks[5] = {"77_5", "FAILED", "sacct"};
    const std::vector<MemberState> states = {MemberState::finished, MemberState::resume, MemberState::start,
                                             MemberState::failed,   MemberState::resume, MemberState::start,
                                             MemberState::start};
    const SlurmSubmission plan = slurm_submission(states, q);
    EXPECT_EQ(plan.submit, (std::vector<int>{4, 5, 6}));
    EXPECT_EQ(plan.queued, (std::vector<int>{1, 2}));
    EXPECT_EQ(slurm_submission(states, SlurmQueue{}).submit, (std::vector<int>{1, 2, 4, 5, 6}));
}

TEST(SlurmLib, AMembersStatusIsItsFilesAndItsArrayTask) {
    const SlurmTaskState running{"7_1", "RUNNING", "squeue"}, pending{"7_1", "PENDING", "squeue"},
        failed{"7_1", "FAILED", "sacct"}, timeout{"7_1", "TIMEOUT", "sacct"};
    EXPECT_EQ(member_status(RunState::finished, &running, true), MemberStatus::finished);
    EXPECT_EQ(member_status(RunState::failed, nullptr, true), MemberStatus::failed);
    EXPECT_EQ(member_status(RunState::interrupted, &running, true), MemberStatus::running);
    EXPECT_EQ(member_status(RunState::not_started, &pending, true), MemberStatus::pending);
    EXPECT_EQ(member_status(RunState::no_end_line, &failed, true), MemberStatus::failed);
    EXPECT_EQ(member_status(RunState::interrupted, &failed, true), MemberStatus::interrupted);
    EXPECT_EQ(member_status(RunState::no_end_line, &timeout, true), MemberStatus::interrupted);
    EXPECT_EQ(member_status(RunState::no_end_line, nullptr, true), MemberStatus::interrupted);
    EXPECT_EQ(member_status(RunState::no_end_line, nullptr, false), MemberStatus::running_or_killed);
    EXPECT_EQ(member_status(RunState::not_started, nullptr, true), MemberStatus::not_started);
    SweepTally tally;
    tally.submitted = true;
    tally.add(RunState::finished, nullptr, true);
    tally.add(RunState::interrupted, &running, true);
    tally.add(RunState::failed, nullptr, true);
    EXPECT_EQ(tally.counts_text(), "1 finished, 1 running, 1 failed");
    EXPECT_FALSE(tally.can_continue());  // what is left runs, or failed
    tally.add(RunState::no_end_line, nullptr, false);
    EXPECT_EQ(tally.counts_text(), "1 finished, 1 running, 1 failed, 1 running or killed");
    EXPECT_TRUE(tally.can_continue());
    EXPECT_EQ(tally.finished, 1u);
    EXPECT_EQ(tally.members, 4u);
    EXPECT_THROW(check_sweep_scheduler(false, true, -1, 1), ConfigError);
    EXPECT_THROW(check_sweep_scheduler(true, false, -1, 2), ConfigError);
    EXPECT_THROW(check_sweep_scheduler(true, false, 2, 1), ConfigError);
    EXPECT_NO_THROW(check_sweep_scheduler(true, true, -1, 1));
}

TEST(SlurmLib, AResumeSubmitsOnlyTheMembersNeitherFinishedFailedNorQueued) {
    TempFolder t("sweep-slurm");
    ASSERT_FALSE(t.path.empty());
    FakeSlurm slurm(t.path / "slurm-fake");
    const Sweep s = make_sweep(t, "sw", tiny_exp1(t.path / "cache"), "wedge.mu_bp", {"0.1", "0.2", "0.3", "0.4"});
    write_events(s.dirs[0], {kStartRow, output_row(0.5, 600), kFinishedRow});
    write_events(s.dirs[1], {kStartRow, output_row(0.1, 600), kInterruptedRow});
    // An earlier array: task 2 still runs, task 1 was cancelled, task 3 failed before it wrote anything.
    fs::create_directories(slurm_dir(s.root));
    record_slurm_job(s.root, SlurmJob{"77", "array", "0-3"});
    write_text(slurm.dir / "squeue.txt", "77|2|RUNNING\n99|0|RUNNING\n");
    write_text(slurm.dir / "sacct.txt", "77_0|COMPLETED\n77_1|CANCELLED by 0\n77_3|FAILED\n");
    SlurmOptions o;
    o.cpus_per_task = 0;  // as in array.sh
    o.time = "2:00:00";
    KeptLines kept;
    EXPECT_EQ(submit_sweep_slurm(s, o, false, kept), 0);
    EXPECT_EQ(kept.out, (std::vector<std::string>{
                            "sweep: wedge.mu_bp = 0.1: finished already, kept (" + s.dirs[0] + ")",
                            "sweep: wedge.mu_bp = 0.3: still in Slurm's queue as job 77_2 (RUNNING); not submitted again",
                            "sweep: wedge.mu_bp = 0.2 -> job 1001_1 (continuing)",
                            "sweep: wedge.mu_bp = 0.4 -> job 1001_3 (starting)",
                            "sweep: submitted job array 1001 to Slurm: tasks 1,3 (2 of 4 members; " + s.root +
                                "/slurm/array.sh, job ids in " + s.root + "/slurm/jobs.csv)",
                            "sweep: follow it with: orodem status " + s.root + "; when it is done: orodem plot " + s.root,
                            "job id: 1001"}));
    // One member to start: it settles its own packing, so no settling job.
    EXPECT_EQ(slurm.sbatch_log(), "--parsable --time=2:00:00 --array=1,3 " + s.root + "/slurm/array.sh\n");
    EXPECT_HAS(slurp(s.root + "/slurm/jobs.csv"), "1001,array,\"1,3\"");
    const std::string array_sh = slurp(s.root + "/slurm/array.sh");
    EXPECT_HAS(array_sh, "'wedge.mu_bp=0.4'  # task 3");
    EXPECT_HAS(array_sh, "#SBATCH --cpus-per-task=1\n");

    // What orodem status counts: task 1's newest job is 1001 (not in the fake queue: from 77's record).
    bool submitted = false;
    const SlurmQueue q = sweep_queue(s.root, submitted);
    EXPECT_TRUE(submitted);
    EXPECT_TRUE(q.squeue);
    EXPECT_TRUE(q.sacct);
    ASSERT_NE(q.task(1), nullptr);
    EXPECT_EQ(q.task(1)->state, "CANCELLED");
    SweepTally tally;
    tally.submitted = true;
    for (std::size_t k = 0; k < s.size(); ++k) tally.add(run_state(s.dirs[k]).state, q.task(k), q.squeue);
    EXPECT_EQ(tally.counts_text(), "1 finished, 1 running, 1 interrupted, 1 failed");
    EXPECT_TRUE(tally.can_continue());

    // Everything left in the queue: nothing submitted.
    write_text(slurm.dir / "squeue.txt", "1001|1|PENDING\n1001|3|RUNNING\n77|2|RUNNING\n");
    KeptLines again;
    EXPECT_EQ(submit_sweep_slurm(s, o, false, again), 0);
    EXPECT_HAS(again.text(), "sweep: every unfinished member is in Slurm's queue; nothing submitted (orodem status " +
                                 s.root + ")");
    EXPECT_EQ(slurm.sbatch_log(), "--parsable --time=2:00:00 --array=1,3 " + s.root + "/slurm/array.sh\n");
}

TEST(SlurmLib, ANewSweepSettlesItsSharedPackingInAJobTheArrayWaitsFor) {
    TempFolder t("sweep-slurm-new");
    ASSERT_FALSE(t.path.empty());
    FakeSlurm slurm(t.path / "slurm-fake");
    const Sweep s = make_sweep(t, "sw", tiny_exp1(t.path / "cache"), "wedge.mu_bp", {"0.1", "0.2"});
    SlurmOptions o;
    o.partition = "short";
    KeptLines kept;
    EXPECT_EQ(submit_sweep_slurm(s, o, true, kept), 0);
    EXPECT_EQ(slurm.sbatch_log(), "--parsable " + s.root + "/slurm/settle.sh\n--parsable --dependency=afterok:1001 "
                                  "--array=0-1 " + s.root + "/slurm/array.sh\n");
    EXPECT_HAS(kept.text(), "sweep: submitted job 1001 to settle the packing that several members share");
    EXPECT_HAS(kept.text(), "sweep: wedge.mu_bp = 0.2 -> job 1002_1 (starting)");
    EXPECT_HAS(slurp(s.root + "/slurm/settle.sh"), "#SBATCH --partition=short\n");
    EXPECT_HAS(slurp(s.root + "/slurm/jobs.csv"), "job_id,kind,tasks\n1001,settle,\"\"\n1002,array,\"0-1\"\n");

    // A refusal: Slurm's message and how to submit the ready folder again.
    write_text(slurm.dir / "refuse", "");
    try {
        submit_sweep_slurm(s, o, false, kept);
        ADD_FAILURE() << "a refused submission was taken";
    } catch (const SchedulerError& e) {
        EXPECT_HAS(e.what(), "sbatch: error: invalid partition specified: nowhere");
        EXPECT_HAS(e.what(), "submit it again with orodem resume " + s.root + " --scheduler slurm");
    }

    // Nothing left to run (both failed): nothing submitted, the sweep's end.
    for (const auto& d : s.dirs) write_events(d, {kStartRow, kUnstableRow});
    KeptLines done;
    EXPECT_EQ(submit_sweep_slurm(s, o, false, done), 3);
    EXPECT_HAS(done.text(), "sweep: no member left to run; nothing submitted\n");
    EXPECT_HAS(done.text(), "sweep: 2 of 2 runs went unstable");
}

TEST(SweepLib, SweptValuesAndSlurmOptionsThatWouldEscapeOrInjectAreRefused) {
    // A value names its member's folder: no path in it (a value '/../../esc' put a run outside the sweep).
    EXPECT_THROW(parse_vary("packing.cache_dir=\"/../../esc\""), ConfigError);
    EXPECT_THROW(parse_vary("run.seed=1,.."), ConfigError);
    EXPECT_THROW(parse_vary("wedge.mu_bp=0.1,0.2\n"), ConfigError);
    // The same value written twice (0.3 and 0.30) is one run, not two.
    EXPECT_THROW(parse_vary("wedge.mu_bp=0.3,0.30"), ConfigError);
    EXPECT_THROW(parse_vary("wedge.v=1000,1e3"), ConfigError);
    EXPECT_NO_THROW(parse_vary("wedge.mu_bp=0.3,0.31"));
    EXPECT_TRUE(same_toml_value("0.3", "0.30"));
    EXPECT_FALSE(same_toml_value("\"a\"", "\"b\""));
    // A newline in a Slurm option would be a line of its own in array.sh (an injected command, a lost --signal).
    SlurmOptions o;
    o.partition = "short\ntouch /tmp/injected";
    EXPECT_THROW(check_sweep_scheduler(true, true, -1, 1, o), ConfigError);
    o = SlurmOptions{};
    o.time = "1:00:00\r";
    EXPECT_THROW(check_sweep_scheduler(true, true, -1, 1, o), ConfigError);
    o = SlurmOptions{};
    o.sbatch_args = {"--account=geo", "--qos=x\n#SBATCH --signal=B:KILL"};
    EXPECT_THROW(check_sweep_scheduler(true, true, -1, 1, o), ConfigError);
    o.sbatch_args = {"--account=geo"};
    EXPECT_NO_THROW(check_sweep_scheduler(true, true, -1, 1, o));
}
