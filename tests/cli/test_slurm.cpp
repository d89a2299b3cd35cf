// `orodem sweep --scheduler slurm`: the members of a sweep as one Slurm job
// array. Against a real Slurm: one that already answers sinfo (left as it
// is), or, only when asked with ORODEM_TEST_START_SLURM=1 (CI's .ci/run
// asks), the single-node one of scripts/local-slurm (started here as root,
// stopped at the end): a test suite does not start daemons on a user's
// machine by itself. Where none can start the test says why and is
// skipped, never passed. The demo exp1 at S = 0.125 over two values of
// mu_bp (one shared packing: the settling job the array waits for); one
// member is cancelled (scancel) while it runs and continued by `orodem resume
// --scheduler slurm`; both end byte for byte as the same sweep with --jobs 1.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>

#include "cli/cli_util.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

const std::string kLocalSlurm = std::string(ORODEM_SOURCE_DIR) + "/scripts/local-slurm";

/// A Slurm to submit to for the length of a test: why_not is empty when one answers.
struct TestSlurm {
    bool started = false;  // started here by scripts/local-slurm: stopped at the end
    std::string why_not;
    TestSlurm() {
        if (run("timeout 10 sinfo -h") == 0) return;  // a running Slurm: used, left as it is
        const char* ask = std::getenv("ORODEM_TEST_START_SLURM");
        if (!ask || std::string(ask) != "1") {
            why_not = "no Slurm answers sinfo here; set ORODEM_TEST_START_SLURM=1 to let this test start a local one "
                      "(scripts/local-slurm, as root)";
            return;
        }
        if (::geteuid() != 0) {
            why_not = "no Slurm answers sinfo here, and scripts/local-slurm start (which would start one) needs root";
            return;
        }
        std::string out;
        if (run(quote(kLocalSlurm) + " start", &out) != 0) {
            why_not = "scripts/local-slurm start could not start a local Slurm:\n" + out;
            run(quote(kLocalSlurm) + " stop");  // what it may have started before it failed
            return;
        }
        started = true;
    }
    ~TestSlurm() {
        if (started) run(quote(kLocalSlurm) + " stop");
    }
};

/// Whether Slurm still has a pending or running task of the job `id`.
bool in_queue(const std::string& id) {
    std::string out;
    // squeue -j fails once the job has left the controller's memory: not in the queue.
    if (run("squeue -h -r -j " + id + " -o %i", &out) != 0) return false;
    return out.find_first_not_of(" \n") != std::string::npos;
}

/// Waits until the job `id` has left the queue, at most `limit_s`.
bool wait_for_job(const std::string& id, double limit_s) {
    const auto t0 = std::chrono::steady_clock::now();
    while (in_queue(id)) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > limit_s) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    return true;
}

/// The job id of "job id: N" in orodem's output; empty when missing.
std::string job_id(const std::string& out) {
    std::smatch m;
    return std::regex_search(out, m, std::regex("job id: ([0-9]+)")) ? m[1].str() : std::string();
}

}  // namespace

TEST(Slurm, ASweepAsAJobArrayEndsAsWithOneJobAlsoWhenCancelledAndResumed) {
    TestSlurm slurm;
    if (!slurm.why_not.empty()) GTEST_SKIP() << "Slurm tests skipped: " << slurm.why_not;
    char tmpl[] = "/tmp/orodem-slurm-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    const fs::path dir = tmpl;
    const std::string exe = ORODEM_EXE;
    const std::string sweep = exe + " sweep " + quote(std::string(ORODEM_SOURCE_DIR) + "/configs/demo/exp1.toml") +
                              " --vary wedge.mu_bp=0.3,0.5 --set wedge.s_max=0.125 --set wedge.output_ds=0.03125"
                              " --set packing.cache_dir=" + quote("\"" + (dir / "cache").string() + "\"");
    const fs::path sl = dir / "sl", ref = dir / "ref";
    std::string out;
    ASSERT_EQ(run(sweep + " --out " + quote(sl.string()) + " --scheduler slurm", &out), 0) << out;
    const std::string id = job_id(out);
    ASSERT_FALSE(id.empty()) << out;
    // The scripts, readable and resubmittable by hand, and the job list.
    const std::string array_sh = slurp(sl / "slurm" / "array.sh");
    EXPECT_HAS(array_sh, "#SBATCH --array=0-1");
    EXPECT_HAS(array_sh, "--threads \"${SLURM_CPUS_PER_TASK:-1}\"");
    EXPECT_HAS(slurp(sl / "slurm" / "jobs.csv"), id + ",array,\"0-1\"");
    EXPECT_HAS(slurp(sl / "slurm" / "jobs.csv"), ",settle,");  // both members share one packing

    // Member 1 cancelled while it runs: it checkpoints on Slurm's SIGTERM.
    const fs::path member1 = sl / "wedge.mu_bp=0.5";
    const auto t0 = std::chrono::steady_clock::now();
    bool cancelled = false;
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 180) {
        if (fs::exists(member1 / "log.txt") && slurp(member1 / "log.txt").find("exp1:") != std::string::npos) {
            ASSERT_EQ(run("scancel " + id + "_1", &out), 0) << out;
            cancelled = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ASSERT_TRUE(cancelled) << "member 1 did not start within 180 s; squeue:\n" << (run("squeue", &out), out);
    if (!wait_for_job(id, 240)) {
        run("scancel " + id);
        FAIL() << "job array " << id << " still in the queue after 240 s";
    }
    ASSERT_EQ(run(exe + " status " + quote(sl.string()), &out), 0) << out;
    EXPECT_HAS(out, "sweep: 1 of 2 runs finished (Slurm: 1 finished, 1 interrupted");
    EXPECT_HAS(out, "continue it with: orodem resume " + sl.string() + " --scheduler slurm");
    EXPECT_HAS(slurp(member1 / "log.txt"), "interrupted by SIGTERM");

    // Resumed through Slurm: only the unfinished member is submitted.
    ASSERT_EQ(run(exe + " resume " + quote(sl.string()) + " --scheduler slurm", &out), 0) << out;
    EXPECT_HAS(out, "tasks 1 (1 of 2 members");
    EXPECT_HAS(out, "wedge.mu_bp = 0.3: finished already, kept");
    const std::string id2 = job_id(out);
    ASSERT_FALSE(id2.empty()) << out;
    if (!wait_for_job(id2, 240)) {
        run("scancel " + id2);
        FAIL() << "job array " << id2 << " still in the queue after 240 s";
    }
    ASSERT_EQ(run(exe + " status " + quote(sl.string()), &out), 0) << out;
    EXPECT_HAS(out, "sweep: 2 of 2 runs finished (Slurm: 2 finished");

    // The same sweep on this machine, one member at a time (the packing cached above).
    ASSERT_EQ(run(sweep + " --out " + quote(ref.string()) + " --jobs 1 --threads 1", &out), 0) << out;
    for (const char* m : {"wedge.mu_bp=0.3", "wedge.mu_bp=0.5"}) expect_same_outputs(ref / m, sl / m);
    // The overlay of the members, as the local sweep draws it.
    ASSERT_EQ(run(exe + " plot " + quote(sl.string()), &out), 0) << out;
    EXPECT_TRUE(fs::exists(sl / "plots.png"));
    if (!HasFailure()) fs::remove_all(dir);
}

TEST(Slurm, WithoutSbatchNothingIsWrittenAndSlurmOptionsNeedTheScheduler) {
    // Runs everywhere: no Slurm needed.
    char tmpl[] = "/tmp/orodem-slurm-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    const fs::path dir = tmpl;
    write_tiny_exp1(dir);
    const std::string exe = ORODEM_EXE;
    const std::string sweep = exe + " sweep " + quote((dir / "tiny.toml").string()) + " --vary wedge.mu_bp=0.1,0.5";
    std::string out;
    EXPECT_EQ(run("PATH=/nonexistent " + sweep + " --out " + quote((dir / "a").string()) + " --scheduler slurm", &out),
              6)
        << out;
    EXPECT_HAS(out, "sbatch is not installed or not on PATH");
    EXPECT_FALSE(fs::exists(dir / "a"));
    EXPECT_EQ(run(sweep + " --out " + quote((dir / "b").string()) + " --time 1:00:00", &out), 2) << out;
    EXPECT_HAS(out, "go with --scheduler slurm");
    EXPECT_EQ(run(sweep + " --out " + quote((dir / "b").string()) + " --scheduler slurm --jobs 2", &out), 2) << out;
    EXPECT_EQ(run(sweep + " --out " + quote((dir / "b").string()) + " --scheduler slurm --threads 2", &out), 2) << out;
    EXPECT_HAS(out, "--cpus-per-task");
    EXPECT_FALSE(fs::exists(dir / "b"));
    fs::remove_all(dir);
}
