// Interrupt and resume (SPEC §4-§5, RELIABILITY-CHECKLIST 9-11) with the real
// binary: SIGTERM/SIGINT write a checkpoint and exit 143/130; `--resume`
// continues so that series.csv, run.pvd, every snapshot and every snapshot
// picture are byte-identical to an uninterrupted run; a corrupt newest
// checkpoint falls back to the older one; another config is refused (exit 2);
// a full disk gives exit 4 and never a corrupt checkpoint.
#include <gtest/gtest.h>

#include "cli/checkpoint_util.hpp"
#include "cli/cli_util.hpp"
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

class Resume : public ::testing::Test {
protected:
    static fs::path root_;
    static fs::path config_;
    static fs::path reference_;  // the uninterrupted run

    static void SetUpTestSuite() {
        root_ = fs::temp_directory_path() / ("orodem-resume-" + std::to_string(::getpid()));
        fs::remove_all(root_);
        fs::create_directories(root_);
        config_ = root_ / "tiny.toml";
        // A Coulomb base at v = 0.3 m/s; the plate is short on purpose (the trailing-wall test below;
        // `orodem run` warns of it on stderr: 4.7 h0 is asked for by S = 0.5).
        std::ofstream(config_) << "[run]\nexperiment = \"exp1\"\n"
                                  "[wedge]\nv = 0.3\ns_max = 0.5\noutput_ds = 0.1\npro_margin = 3.0\nretro_length = 3.0\n"
                                  "[packing]\nh0 = 6.0\nr_min = 0.5\nr_max = 1.0\ncache_dir = \""
                               << (root_ / "cache").string() << "\"\n";
        reference_ = root_ / "A";
        const Proc p = start({"run", config_.string(), "--out", reference_.string(), "--threads", "1"}, root_ / "A");
        ASSERT_EQ(wait_for(p), 0) << slurp(p.err);
    }
    /// Starts the tiny run into dir with a wall-time limit of 3 ms: it stops
    /// at the first look after it (exit 5).
    static Proc start_with_wall_limit(const fs::path& dir) {
        return start({"run", config_.string(), "--out", dir.string(), "--threads", "1", "--set",
                      "run.max_wall_minutes=0.00005"},
                     dir);
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(root_, ec);
    }
};
fs::path Resume::root_, Resume::config_, Resume::reference_;

}  // namespace

TEST_F(Resume, AfterSigtermOutputsAreByteIdenticalToAnUninterruptedRun) {
    const fs::path run = root_ / "B";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1"}, root_ / "B");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGTERM})) << "no checkpoint after step 0 appeared: " << slurp(p.err);
    ASSERT_EQ(wait_for(p), 143) << slurp(p.err);
    const std::string err = slurp(p.err);
    EXPECT_NE(err.find("interrupted by SIGTERM"), std::string::npos) << err;
    const std::string cmd = "resume with: orodem run " + run.string() + "/config.toml --out " + run.string() + " --resume";
    EXPECT_NE(err.find(cmd), std::string::npos) << err;
    ASSERT_LT(slurp(run / "series.csv").size(), slurp(reference_ / "series.csv").size()) << "was not interrupted";

    // Resume exactly as told (at another thread count: results do not depend on it).
    const Proc r = start({"run", run.string() + "/config.toml", "--out", run.string(), "--resume", "--threads", "2"},
                         root_ / "B-resume");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    expect_same_outputs(reference_, run);
    const std::string log = slurp(run / "log.txt");
    const std::size_t resumed = log.find("\nresumed by orodem");
    ASSERT_NE(resumed, std::string::npos) << log;
    EXPECT_LT(log.find("\ninterrupted by SIGTERM at step "), resumed) << log;  // kept by the resume
    EXPECT_LE(orodem::list_checkpoints((run / "checkpoint").string()).size(), 2u);
}

TEST_F(Resume, AResumeKeepsThePiecesHistoryButNotTheRowsBeyondTheCheckpoint) {
    // Piece 1 stopped by SIGTERM; piece 2 (simulated: its start line and one
    // row appended by hand) killed before its first checkpoint; piece 3 resumes
    // from piece 1's checkpoint and finishes.
    const fs::path run = root_ / "P";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1"}, root_ / "P");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGTERM})) << "no checkpoint after step 0 appeared: " << slurp(p.err);
    ASSERT_EQ(wait_for(p), 143) << slurp(p.err);
    const std::string killed_start = "resumed by orodem 0.0.0 from x.bin at step 1 (S = 0.0000) with 1 threads";
    {
        // What such a piece leaves: its lines in log.txt and their rows in events.csv.
        std::ofstream log(run / "log.txt", std::ios::app);
        log << killed_start << "\nS = 9.999: a row beyond the checkpoint\n";
        std::ofstream events(run / "events.csv", std::ios::app);
        events << "resume,1,0,,,,\"" << killed_start << "\"\noutput,2,9.999,,,1000,\"S = 9.999: a row beyond the "
                  "checkpoint\"\n";
    }
    const Proc r = start({"resume", run.string(), "--threads", "1"}, root_ / "P-resume");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    expect_same_outputs(reference_, run);
    const std::string log = slurp(run / "log.txt");
    const std::size_t stop = log.find("\ninterrupted by SIGTERM at step ");
    const std::size_t killed = log.find("\n" + killed_start + "\n");
    const std::size_t resumed = log.find("\nresumed by orodem", killed + 1);
    ASSERT_NE(stop, std::string::npos) << log;
    ASSERT_NE(killed, std::string::npos) << log;
    EXPECT_LT(stop, killed) << log;
    EXPECT_NE(resumed, std::string::npos) << log;
    EXPECT_EQ(log.find("S = 9.999"), std::string::npos) << log;  // rows beyond the checkpoint are written again
    std::string out;
    ASSERT_EQ(cli::run(std::string(ORODEM_EXE) + " status " + quote(run.string()), &out), 0) << out;
    EXPECT_NE(out.find(" in 2 of its 3 pieces (the others have no end line"), std::string::npos) << out;
}

TEST_F(Resume, AfterSigintACorruptNewestCheckpointFallsBackToTheOlderOne) {
    const fs::path run = root_ / "C";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1"}, root_ / "C");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGINT})) << slurp(p.err);
    ASSERT_EQ(wait_for(p), 130) << slurp(p.err);
    auto files = orodem::list_checkpoints((run / "checkpoint").string());
    ASSERT_EQ(files.size(), 2u);
    std::string bytes = orodem::read_file(files[0].second);
    bytes[bytes.size() / 2] ^= 0x10;
    orodem::write_file_atomic(files[0].second, bytes);

    const Proc r = start({"resume", run.string(), "--threads", "1"}, root_ / "C-resume");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    const std::string err = slurp(r.err);
    EXPECT_NE(err.find("not used: payload checksum mismatch"), std::string::npos) << err;
    expect_same_outputs(reference_, run);
}

// The newest checkpoint truncated (a half-written file from a crash of the
// file system, say): the resume falls back to the older one, says so, and
// finishes with outputs byte-identical to an uninterrupted run.
TEST_F(Resume, ATruncatedNewestCheckpointFallsBackAndFinishesLikeAnUninterruptedRun) {
    const fs::path run = root_ / "T";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1"}, root_ / "T");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGTERM})) << slurp(p.err);
    ASSERT_EQ(wait_for(p), 143) << slurp(p.err);
    const auto files = orodem::list_checkpoints((run / "checkpoint").string());
    ASSERT_EQ(files.size(), 2u);
    fs::resize_file(files[0].second, fs::file_size(files[0].second) / 3);
    const Proc r = start({"resume", run.string(), "--threads", "1"}, root_ / "T-resume");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    EXPECT_HAS(slurp(r.err), "not used:");
    expect_same_outputs(reference_, run);
}

TEST_F(Resume, ASecondSignalIsIgnoredUntilTheShutdownCheckpointIsWritten) {
    const fs::path run = root_ / "D";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1"}, root_ / "D");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGTERM, SIGTERM})) << slurp(p.err);
    EXPECT_EQ(wait_for(p), 143);
    // The run stopped itself: its end line and the shutdown checkpoint are there.
    EXPECT_HAS(slurp(run / "log.txt"), "\ninterrupted by SIGTERM at step ");
    EXPECT_HAS(slurp(p.err), "checkpoint written to");
    const std::uint64_t hash = orodem::config_hash(orodem::load_config(config_.string()));
    const auto files = orodem::list_checkpoints((run / "checkpoint").string());
    ASSERT_FALSE(files.empty());
    for (const auto& [step, path] : files)
        EXPECT_NO_THROW(orodem::verify_checkpoint(orodem::read_file(path), hash)) << path;
}

// Off a terminal (the reference run's stdout is a file) the progress is one
// plain line per output: S, its percentage of s_max, and once a second has
// passed the rate and the time left (whether a second has passed depends on
// the machine, so the rate is checked only where it is printed); no carriage
// returns or escape codes.
// orodem faults reads the run's faults.csv, computes the same table from the
// snapshots alone (as for a run made before the table existed), and prints
// one output's table; a run directory without config.toml is refused.
TEST_F(Resume, FaultsPrintsTheTableAndComputesTheSameOneFromTheSnapshots) {
    int k = 0;
    auto run_orodem = [&](const std::vector<std::string>& args) {
        const Proc p = start(args, root_ / ("faults-" + std::to_string(++k)));
        Result r;
        r.status = wait_for(p);
        r.out = slurp(p.out);
        r.err = slurp(p.err);
        return r;
    };
    const std::string table = slurp(reference_ / "faults.csv");
    ASSERT_EQ(table.rfind("S,id,vergence,dip_deg,root_x_over_h0,", 0), 0u) << table;
    const Result csv = run_orodem({"faults", reference_.string(), "--csv"});
    ASSERT_EQ(csv.status, 0) << csv.err;
    EXPECT_EQ(csv.out, table);
    const Result again = run_orodem({"faults", reference_.string(), "--csv", "--recompute"});
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, table);
    const Result at = run_orodem({"faults", reference_.string(), "--at", "0.3"});
    ASSERT_EQ(at.status, 0) << at.err;
    EXPECT_HAS(at.out, "at S = 0.300\nthis output's faults show stage ");
    EXPECT_HAS(at.out, "pro-vergent");
    fs::create_directories(root_ / "not-a-run");
    const Result bad = run_orodem({"faults", (root_ / "not-a-run").string()});
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

TEST_F(Resume, OffATerminalProgressIsOnePlainLinePerOutput) {
    const std::string out = slurp(root_ / "A.out");
    EXPECT_EQ(out.find('\r'), std::string::npos) << out;
    EXPECT_EQ(out.find('\033'), std::string::npos) << out;
    EXPECT_HAS(out, "S = 0.000 of 0.5 (0.0%)\n");
    EXPECT_HAS(out, "S = 0.500 of 0.5 (100.0%)");
    const std::size_t rate_at = out.find("steps/s");
    if (rate_at != std::string::npos) {
        EXPECT_EQ(out.rfind(", ", rate_at) + 2 < rate_at, true) << out;
        EXPECT_NE(out.find(" left\n", rate_at), std::string::npos) << out;
    }
    std::size_t lines = 0;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) lines += line.rfind("S = ", 0) == 0;
    EXPECT_EQ(lines, 6u) << out;  // S = 0, 0.1, ..., 0.5
}

// With its checkpoints gone (checkpoint/ deleted), a run that has outputs
// cannot be continued: resume refuses (exit 2) and changes nothing.
TEST_F(Resume, WithoutACheckpointARunWithOutputsIsRefusedAndLeftAsItWas) {
    const fs::path run = root_ / "G";
    fs::copy(reference_, run, fs::copy_options::recursive);
    fs::remove_all(run / "checkpoint");
    const Proc r = start({"resume", run.string()}, root_ / "G");
    EXPECT_EQ(wait_for(r), 2);
    const std::string err = slurp(r.err);
    EXPECT_HAS(err, "no checkpoint in");
    EXPECT_HAS(err, "nothing was changed");
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    expect_same_outputs(reference_, run);
    EXPECT_EQ(slurp(run / "log.txt"), slurp(reference_ / "log.txt"));
}

// Every checkpoint damaged: refused with exit 2, naming each file and why, nothing changed.
TEST_F(Resume, WithOnlyDamagedCheckpointsTheResumeIsRefusedAndChangesNothing) {
    const fs::path run = root_ / "U";
    fs::copy(reference_, run, fs::copy_options::recursive);
    for (const auto& [step, path] : orodem::list_checkpoints((run / "checkpoint").string()))
        fs::resize_file(path, fs::file_size(path) / 2);
    const std::string before = slurp(run / "log.txt");
    const Proc r = start({"resume", run.string()}, root_ / "U");
    EXPECT_EQ(wait_for(r), 2);
    const std::string err = slurp(r.err);
    EXPECT_HAS(err, "no usable checkpoint in");
    EXPECT_HAS(err, "nothing was changed");
    expect_same_outputs(reference_, run);
    EXPECT_EQ(slurp(run / "log.txt"), before);
}

TEST_F(Resume, AnotherConfigIsRefusedWithExit2) {
    const Proc r = start({"run", config_.string(), "--out", reference_.string(), "--resume", "--set", "wedge.mu_bp=0.4"},
                         root_ / "E");
    EXPECT_EQ(wait_for(r), 2);
    const std::string err = slurp(r.err);
    EXPECT_NE(err.find("differs from the run's config"), std::string::npos) << err;
    EXPECT_NE(err.find("mu_bp"), std::string::npos) << err;
    const Proc n = start({"run", config_.string(), "--resume"}, root_ / "F");
    EXPECT_EQ(wait_for(n), 2);
    EXPECT_NE(slurp(n.err).find("--resume needs --out DIR"), std::string::npos) << slurp(n.err);
}

TEST_F(Resume, AFullDiskGivesExit4AndNoCorruptCheckpoint) {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to mount a small tmpfs (a full disk); not run";
    const fs::path mnt = root_ / "full";
    fs::create_directories(mnt);
    const std::string mount = "mount -t tmpfs -o size=200k tmpfs '" + mnt.string() + "' 2>/dev/null";
    if (std::system(mount.c_str()) != 0) GTEST_SKIP() << "cannot mount a tmpfs here (no CAP_SYS_ADMIN); not run";
    const fs::path run = mnt / "run";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1"}, root_ / "G");
    const int rc = wait_for(p);
    const std::string err = slurp(p.err);
    const std::uint64_t hash = orodem::config_hash(orodem::load_config(config_.string()));
    std::vector<std::string> bad;
    if (fs::exists(run / "checkpoint"))
        for (const auto& e : fs::directory_iterator(run / "checkpoint")) {
            const std::string name = e.path().filename().string();
            if (name.find(".tmp-") != std::string::npos) bad.push_back(name + " (left-over temporary)");
        }
    for (const auto& [step, path] : orodem::list_checkpoints((run / "checkpoint").string())) {
        try {
            orodem::verify_checkpoint(orodem::read_file(path), hash);
        } catch (const std::exception& e) {
            bad.push_back(path + ": " + e.what());
        }
    }
    const std::string log = slurp(run / "log.txt");
    std::system(("umount '" + mnt.string() + "'").c_str());
    EXPECT_EQ(rc, 4) << err;
    EXPECT_NE(err.find("orodem: I/O error:"), std::string::npos) << err;
    // The stop has its end line (the free-space check stops the run before
    // the disk is full, so the log can still be written): orodem status says why.
    EXPECT_HAS(log, "\nstopped by an I/O error at step ");
    EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST_F(Resume, AnOverlapBeyondTheLimitStopsWithExit3AndKeepsTheLastGoodState) {
    // The layer starts at max overlap/R = 0.015 and passes 0.02 later on.
    const fs::path run = root_ / "H";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1", "--set",
                          "run.max_overlap_ratio=0.016", "--set", "run.warn_overlap_ratio=0.016"},
                         root_ / "H");
    EXPECT_EQ(wait_for(p), 3);
    const std::string err = slurp(p.err);
    EXPECT_NE(err.find("orodem: unstable: step "), std::string::npos) << err;
    EXPECT_NE(err.find(": overlap ("), std::string::npos) << err;
    EXPECT_NE(err.find("run.max_overlap_ratio = 0.016"), std::string::npos) << err;
    EXPECT_NE(err.find("Likely cause:"), std::string::npos) << err;
    EXPECT_NE(err.find("last good state: step "), std::string::npos) << err;
    EXPECT_NE(slurp(run / "log.txt").find("UNSTABLE: "), std::string::npos);
    const std::uint64_t hash =
        orodem::config_hash(orodem::load_config(config_.string(), {{"run.max_overlap_ratio", "0.016"},
                                                                   {"run.warn_overlap_ratio", "0.016"}}));
    const auto files = orodem::list_checkpoints((run / "checkpoint").string());
    ASSERT_FALSE(files.empty());
    for (const auto& [step, path] : files)
        EXPECT_NO_THROW(orodem::verify_checkpoint(orodem::read_file(path), hash)) << path;
    bool bad_state_snapshot = false;
    for (const auto& n : names_in(run / "snapshots")) bad_state_snapshot |= n.rfind("unstable-step", 0) == 0;
    EXPECT_TRUE(bad_state_snapshot);
}

TEST_F(Resume, InitialOverlapsAreReportedAndRefusedAboveTheLimitUnlessAllowed) {
    // The settled tiny layer starts at max overlap/R = 0.015 (see above).
    const fs::path run = root_ / "I";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1", "--set",
                          "run.max_overlap_ratio=0.002", "--set", "run.warn_overlap_ratio=0.001"},
                         root_ / "I");
    EXPECT_EQ(wait_for(p), 2);
    std::string err = slurp(p.err);
    const std::string plate = "orodem: warning: wedge.pro_margin = 3 h0 is shorter";  // the short plate, said first
    if (err.rfind(plate, 0) == 0) err = err.substr(err.find('\n') + 1);
    EXPECT_EQ(count_lines(err), 1) << err;
    EXPECT_NE(err.find("the initial layer is not settled: worst overlap/R = 0.01"), std::string::npos) << err;
    EXPECT_NE(err.find("run.allow_initial_overlap = true"), std::string::npos) << err;
    EXPECT_NE(slurp(run / "log.txt").find("initial overlaps: "), std::string::npos);
    EXPECT_FALSE(fs::exists(run / "series.csv"));

    // Allowed: step 0 is written, then the first health check (step 1000) stops the run.
    const fs::path allowed = root_ / "I2";
    const Proc q = start({"run", config_.string(), "--out", allowed.string(), "--threads", "1", "--set",
                          "run.max_overlap_ratio=0.002", "--set", "run.warn_overlap_ratio=0.001", "--set",
                          "run.allow_initial_overlap=true"},
                         root_ / "I2");
    EXPECT_EQ(wait_for(q), 3) << slurp(q.err);
    EXPECT_NE(slurp(q.err).find("step 1000 "), std::string::npos) << slurp(q.err);
    EXPECT_NE(slurp(allowed / "log.txt").find("warning: starting anyway"), std::string::npos);
    EXPECT_EQ(count_lines(slurp(allowed / "series.csv")), 2);  // header and step 0
}

TEST_F(Resume, AnOverlapAboveTheWarningLevelIsReportedOnceOnStderrAndAtEveryOutputInTheLog) {
    const fs::path run = root_ / "J";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1", "--set",
                          "run.warn_overlap_ratio=0.001"},
                         root_ / "J");
    ASSERT_EQ(wait_for(p), 0) << slurp(p.err);
    const std::string err = slurp(p.err);
    EXPECT_NE(err.find("orodem: warning: largest overlap/R = 0.01"), std::string::npos) << err;
    EXPECT_NE(err.find("above run.warn_overlap_ratio = 0.001"), std::string::npos) << err;
    EXPECT_NE(err.find(") m and "), std::string::npos) << "the warning names the pair and where: " << err;
    EXPECT_NE(err.find(" above it; the run stops at"), std::string::npos) << err;
    EXPECT_EQ(err.find("orodem: warning: largest overlap"), err.rfind("orodem: warning: largest overlap"))
        << "more than one overlap warning: " << err;
    EXPECT_NE(err.find("(further warnings in log.txt only)"), std::string::npos) << err;
    const std::string log = slurp(run / "log.txt");
    int warnings = 0;
    for (std::size_t at = log.find("warning: largest overlap/R"); at != std::string::npos;
         at = log.find("warning: largest overlap/R", at + 1))
        ++warnings;
    EXPECT_EQ(warnings, count_lines(slurp(run / "series.csv")) - 1);  // one per output row
    // The warning changes nothing: the outputs are those of the reference run.
    EXPECT_EQ(slurp(run / "series.csv"), slurp(reference_ / "series.csv"));
}

TEST_F(Resume, APlateDeformedBackToTheTrailingWallIsReportedOnce) {
    // The tiny run's plate is 3 h0 + S h0 long: by S = 0.5 its surface is
    // raised all the way back to the trailing wall, and the run says so once
    // on stderr and once in log.txt, naming wedge.pro_margin. The reference
    // run (same config) shows the same in its log. With a plate of 20 h0 the
    // deformation stays far from the wall and nothing is said.
    const std::string said = "warning: the prowedge reaches the trailing wall at S = ";
    const std::string ref_log = slurp(reference_ / "log.txt");
    const auto at = ref_log.find(said);
    ASSERT_NE(at, std::string::npos) << ref_log;
    EXPECT_EQ(at, ref_log.rfind(said)) << "said more than once: " << ref_log;
    EXPECT_NE(ref_log.find("raise wedge.pro_margin (now 3 h0)"), std::string::npos) << ref_log;
    // Never at S = 0, where no wedge has grown and the toe is a roughness bump's.
    EXPECT_NE(ref_log.substr(at + said.size(), 5), "0.000") << ref_log;

    const fs::path run = root_ / "W";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1"}, root_ / "W");
    ASSERT_EQ(wait_for(p), 0) << slurp(p.err);
    const std::string err = slurp(p.err);
    EXPECT_NE(err.find("orodem: " + said), std::string::npos) << err;
    EXPECT_EQ(err.find(said), err.rfind(said)) << err;

    const fs::path long_plate = root_ / "W2";
    const Proc q = start({"run", config_.string(), "--out", long_plate.string(), "--threads", "1", "--set",
                          "wedge.pro_margin=20"},
                         root_ / "W2");
    ASSERT_EQ(wait_for(q), 0) << slurp(q.err);
    EXPECT_EQ(slurp(q.err).find("trailing wall"), std::string::npos) << slurp(q.err);
    EXPECT_EQ(slurp(long_plate / "log.txt").find("trailing wall"), std::string::npos);
}

TEST_F(Resume, ADiscLeavingTheDomainStopsWithTheChosenPolicy) {
    // A ceiling at 0.5 h0 puts the top of the layer outside the domain at step 0.
    const fs::path run = root_ / "K";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1", "--set",
                          "run.domain_height=0.5"},
                         root_ / "K");
    EXPECT_EQ(wait_for(p), 3);
    std::string err = slurp(p.err);
    EXPECT_NE(err.find("left the domain (domain x in ["), std::string::npos) << err;
    EXPECT_NE(err.find("no earlier good state was kept"), std::string::npos) << err;
    EXPECT_EQ(count_lines(slurp(run / "series.csv")), 1);  // the header only: the bad state is not a row

    const fs::path stop = root_ / "K2";
    const Proc q = start({"run", config_.string(), "--out", stop.string(), "--threads", "1", "--set",
                          "run.domain_height=0.5", "--set", "run.on_domain_exit=\"stop\""},
                         root_ / "K2");
    EXPECT_EQ(wait_for(q), 3);
    err = slurp(q.err);
    EXPECT_NE(err.find("left the domain"), std::string::npos) << err;
    EXPECT_NE(err.find("run.on_domain_exit = \"stop\""), std::string::npos) << err;
    EXPECT_EQ(count_lines(slurp(stop / "series.csv")), 2);  // header and the row of the stopping step
    EXPECT_TRUE(fs::exists(stop / "snapshots" / "S00.000.vtu"));
    const std::uint64_t hash = orodem::config_hash(orodem::load_config(
        config_.string(), {{"run.domain_height", "0.5"}, {"run.on_domain_exit", "\"stop\""}}));
    const auto files = orodem::list_checkpoints((stop / "checkpoint").string());
    ASSERT_EQ(files.size(), 1u);
    EXPECT_NO_THROW(orodem::verify_checkpoint(orodem::read_file(files[0].second), hash));
    EXPECT_NE(slurp(stop / "log.txt").find("STOPPED: "), std::string::npos);
}

TEST_F(Resume, ASignalWhileSettlingExitsCleanlyAndResumeStartsAgain) {
    // A packing seed of its own, so this run settles (the cache has only seed 1's layer).
    const fs::path run = root_ / "L";
    const Proc p = start({"run", config_.string(), "--out", run.string(), "--threads", "1", "--set", "packing.seed=7"},
                         root_ / "L");
    const auto t0 = std::chrono::steady_clock::now();
    while (slurp(run / "log.txt").find("settling") == std::string::npos &&
           std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    kill(p.pid, SIGINT);
    const int rc = wait_for(p);
    if (rc == 0) GTEST_SKIP() << "the settling ended before the signal arrived";
    EXPECT_EQ(rc, 130) << slurp(p.err);
    const std::string err = slurp(p.err);
    EXPECT_NE(err.find("orodem: interrupted: by SIGINT while settling the packing"), std::string::npos) << err;
    const std::string cmd = std::string("orodem run ") + run.string() + "/config.toml --out " + run.string() + " --resume";
    EXPECT_NE(err.find(cmd), std::string::npos) << err;
    EXPECT_TRUE(orodem::list_checkpoints((run / "checkpoint").string()).empty());

    const Proc r = start({"run", run.string() + "/config.toml", "--out", run.string(), "--resume", "--threads", "1"},
                         root_ / "L-resume");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    EXPECT_NE(slurp(r.out).find("has no checkpoint yet: starting the run from the beginning"), std::string::npos);
    EXPECT_EQ(count_lines(slurp(run / "series.csv")), count_lines(slurp(reference_ / "series.csv")));
}

TEST_F(Resume, AWallTimeLimitStopsWithExit5AndResumeFinishesTheSameRun) {
    const fs::path run = root_ / "M";
    const Proc p = start_with_wall_limit(run);
    ASSERT_EQ(wait_for(p), 5) << slurp(p.err);
    const std::string err = slurp(p.err);
    EXPECT_NE(err.find("stopped at the wall-time limit run.max_wall_minutes = 5e-05"), std::string::npos) << err;
    const std::string cmd = std::string("continue with: orodem run ") + run.string() + "/config.toml --out " +
                            run.string() + " --resume";
    EXPECT_NE(err.find(cmd), std::string::npos) << err;
    ASSERT_LT(slurp(run / "series.csv").size(), slurp(reference_ / "series.csv").size()) << "was not stopped";
    // The log ends with the stop and this piece's phase times (how fast it ran).
    const std::string log = slurp(run / "log.txt");
    const std::size_t stop_line = log.rfind("\nstopped at the wall-time limit");
    ASSERT_NE(stop_line, std::string::npos) << log;
    EXPECT_NE(log.find("\nstep phases (this process): integrate ", stop_line), std::string::npos) << log;
    // The limit does not enter the config hash: resume without it.
    const Proc r = start({"run", run.string() + "/config.toml", "--out", run.string(), "--resume", "--threads", "1",
                          "--set", "run.max_wall_minutes=0"},
                         root_ / "M-resume");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    expect_same_outputs(reference_, run);
    // The resume keeps the first piece's end line and phase times (they lie
    // beyond the checkpoint), so orodem status adds up both pieces.
    const std::string resumed_log = slurp(run / "log.txt");
    const std::size_t kept = resumed_log.find("\nstopped at the wall-time limit");
    const std::size_t phases = resumed_log.find("\nstep phases (this process): ");
    const std::size_t resumed = resumed_log.find("\nresumed by orodem");
    ASSERT_NE(kept, std::string::npos) << resumed_log;
    EXPECT_LT(kept, phases) << resumed_log;
    EXPECT_LT(phases, resumed) << resumed_log;
    EXPECT_NE(resumed_log.find("\nfinished: ", resumed), std::string::npos) << resumed_log;
    std::string out;
    ASSERT_EQ(cli::run(std::string(ORODEM_EXE) + " status " + quote(run.string()), &out), 0) << out;
    EXPECT_NE(out.find(" in 2 of its 2 pieces\n"), std::string::npos) << out;
}

TEST_F(Resume, StatusAddsUpTheWallTimeOfThePiecesWhoseEndLineGivesIt) {
    // A run in three pieces: stopped by SIGTERM after 3000 s, killed (no end
    // line), finished after 4200 s: 7200 s = 2.0 h in 2 of its 3 pieces.
    const fs::path dir = root_ / "wall";
    fs::create_directories(dir);
    for (const char* f : {"config.toml", "series.csv"}) fs::copy_file(reference_ / f, dir / f);
    write(dir / "log.txt",
          "orodem 0.1.0 run of c.toml (exp1) with 1 threads\n"
          "dt = 0.0001 s, stability limit 0.001 s (margin 10x), t_c = 20 steps\n"
          "S = 0.250: H/h0 = 0.1; 0 discs asleep; 900 steps/s\n"
          "interrupted by SIGTERM at step 100 (S = 0.2500) after 3000.0 s wall; checkpoint x.bin\n"
          "step phases (this process): integrate 1.000 s (100.0%)\n"
          "resumed by orodem 0.1.0 from x.bin at step 100 (S = 0.25) with 1 threads\n"
          "resumed by orodem 0.1.0 from x.bin at step 100 (S = 0.25) with 1 threads\n"
          "S = 0.500: H/h0 = 0.2; 0 discs asleep; 900 steps/s\n"
          "finished: S = 0.500 after 200 steps, 4200.0 s wall\n");
    std::string out;
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + quote(dir.string()), &out), 0) << out;
    EXPECT_NE(out.find("wall time: 2.0 h in 2 of its 3 pieces (the others have no end line giving it"),
              std::string::npos)
        << out;
    // The real end lines carry it: a wall-limited stop, then the finished reference.
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + quote(reference_.string()), &out), 0) << out;
    EXPECT_NE(out.find("wall time: "), std::string::npos) << out;
    EXPECT_NE(out.find(" in 1 of its 1 piece\n"), std::string::npos) << out;
}

TEST_F(Resume, StatusEstimatesTheTimeLeftFromTheMedianOfTheLastThreeRates) {
    // Killed at S = 1.0; its S = 0.5 output came after a pause (20 steps/s).
    const fs::path dir = root_ / "rate";
    fs::create_directories(dir);
    for (const char* f : {"config.toml", "series.csv"}) fs::copy_file(reference_ / f, dir / f);
    const std::string head =
        "orodem 0.1.0 run of c.toml (exp1) with 1 threads\n"
        "dt = 0.0001 s, stability limit 0.001 s (margin 10x), t_c = 20 steps\n"
        "S = 0.250: H/h0 = 0.1; 0 discs asleep; 700 steps/s\n";
    write(dir / "log.txt", head +
                               "S = 0.500: H/h0 = 0.1; 0 discs asleep; 20 steps/s\n"
                               "S = 0.750: H/h0 = 0.1; 0 discs asleep; 900 steps/s\n"
                               "S = 1.000: H/h0 = 0.1; 0 discs asleep; 800 steps/s\n");
    std::string out;
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + quote(dir.string()), &out), 0) << out;
    EXPECT_NE(out.find("rate: 800 steps/s (median of the last 3 outputs); about "), std::string::npos) << out;
    // Two outputs, the second after the pause: the higher one.
    write(dir / "log.txt", head + "S = 0.500: H/h0 = 0.1; 0 discs asleep; 20 steps/s\n");
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + quote(dir.string()), &out), 0) << out;
    EXPECT_NE(out.find("rate: 700 steps/s (median of the last 2 outputs); about "), std::string::npos) << out;
}

TEST_F(Resume, StatusReadsEventsCsvNotTheProseOfTheLog) {
    // A run of this orodem has events.csv: status takes the numbers from it
    // and does not parse log.txt (here prose that says something else).
    const fs::path dir = root_ / "events";
    fs::create_directories(dir);
    for (const char* f : {"config.toml", "series.csv"}) fs::copy_file(reference_ / f, dir / f);
    write(dir / "log.txt", "orodem 0.1.0 run of c.toml (exp1) with 1 threads\nS = 0.900: 5 discs asleep; 1 steps/s\n"
                           "finished: S = 0.900 after 1 steps, 1.0 s wall\n");
    write(dir / "events.csv",
          "event,step,S,dt,wall_s,steps_per_s,text\n"
          "start,0,,0.0001,,,\"orodem 0.1.0 run of c.toml (exp1) with 1 threads\"\n"
          "output,2500,0.25,,,600,\"S = 0.250\"\n"
          "output,5000,0.5,,,650,\"S = 0.500\"\n"
          "interrupted,5100,0.51,,42.5,,\"interrupted by SIGTERM at step 5100 (S = 0.5100) after 42.5 s wall; "
          "checkpoint x\"\n");
    std::string out;
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + quote(dir.string()), &out), 0) << out;
    EXPECT_NE(out.find("progress: S = 0.500 of 0.5"), std::string::npos) << out;
    EXPECT_NE(out.find("state: interrupted by SIGTERM at step 5100"), std::string::npos) << out;
    EXPECT_NE(out.find("wall time: 42 s in 1 of its 1 piece"), std::string::npos) << out;
    EXPECT_NE(out.find("rate: 650 steps/s (median of the last 2 outputs)"), std::string::npos) << out;
    EXPECT_NE(out.find("continue with: orodem resume"), std::string::npos) << out;
}

TEST_F(Resume, StatusSaysHowFarARunGotHowItEndedAndHowToContinueIt) {
    std::string out;
    // A finished run: 100%, its end line, nothing to continue.
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + quote(reference_.string()), &out), 0) << out;
    EXPECT_NE(out.find("progress: S = 0.500 of 0.5 (100.0%) at the last output, step "), std::string::npos) << out;
    EXPECT_NE(out.find("state: finished: S = 0.500 after "), std::string::npos) << out;
    EXPECT_EQ(out.find("continue with"), std::string::npos) << out;
    // A run stopped at a wall-time limit: how it ended, its checkpoint, the command.
    const fs::path stopped = root_ / "status";
    const Proc p = start_with_wall_limit(stopped);
    ASSERT_EQ(wait_for(p), 5) << slurp(p.err);
    const auto newest = orodem::list_checkpoints((stopped / "checkpoint").string()).front();  // newest first
    ASSERT_GT(newest.first, 0u);
    const std::string before = slurp(stopped / "log.txt");
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + quote(stopped.string()), &out), 0) << out;
    EXPECT_NE(out.find("state: stopped at the wall-time limit run.max_wall_minutes = 5e-05 at step"), std::string::npos)
        << out;
    EXPECT_NE(out.find(" s wall; checkpoint "), std::string::npos) << out;
    EXPECT_NE(out.find("wall time: "), std::string::npos) << out;
    EXPECT_NE(out.find("newest checkpoint: " + newest.second + " (step " + std::to_string(newest.first) + ", S = "),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("continue with: orodem resume " + stopped.string() + "\n"), std::string::npos) << out;
    EXPECT_EQ(slurp(stopped / "log.txt"), before);  // status writes nothing
    // Not a run directory: exit 2 and why.
    EXPECT_EQ(run(std::string(ORODEM_EXE) + " status " + quote((root_ / "nowhere").string()), &out), 2) << out;
    EXPECT_NE(out.find("no such run directory"), std::string::npos) << out;
}

/// A config of its own for the tests below (others in this suite rewrite tiny.toml), long enough (S = 2) that a
/// second process starts while the first runs, and its uninterrupted run.
fs::path long_config(const fs::path& root, fs::path& reference) {
    const fs::path cfg = root / "long.toml";
    std::ofstream(cfg) << "[run]\nexperiment = \"exp1\"\n"
                          "[wedge]\nv = 0.3\ns_max = 2.0\noutput_ds = 0.25\npro_margin = 6.0\nretro_length = 3.0\n"
                          "[packing]\nh0 = 6.0\nr_min = 0.5\nr_max = 1.0\ncache_dir = \""
                       << (root / "cache").string() << "\"\n";
    reference = root / "L-ref";
    if (!fs::exists(reference / "series.csv")) {
        const Proc p = start({"run", cfg.string(), "--out", reference.string(), "--threads", "1"}, root / "L-ref");
        EXPECT_EQ(wait_for(p), 0) << slurp(p.err);
    }
    return cfg;
}

TEST_F(Resume, SighupStopsWithACheckpointAndResumesByteIdentical) {
    // A closed terminal or SSH session (SIGHUP) is a stop with a checkpoint, as SIGTERM (exit 128 + 1).
    fs::path reference;
    const fs::path cfg = long_config(root_, reference);
    const fs::path run = root_ / "sighup";
    const Proc p = start({"run", cfg.string(), "--out", run.string(), "--threads", "1"}, root_ / "sighup");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGHUP})) << slurp(p.err);
    ASSERT_EQ(wait_for(p), 129) << slurp(p.err);
    EXPECT_NE(slurp(p.err).find("interrupted by SIGHUP"), std::string::npos) << slurp(p.err);
    const Proc r = start({"resume", run.string(), "--threads", "1"}, root_ / "sighup-resume");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    expect_same_outputs(reference, run);
}

TEST_F(Resume, TwoWritersOnOneRunDirectoryGiveOneExitTwoAndTheSameOutputs) {
    // run + resume, run + run --resume: the second is refused at once with the holder's pid (exit 2, nothing
    // changed), and the run ends byte-identical to an uninterrupted one.
    fs::path reference;
    const fs::path cfg = long_config(root_, reference);
    const fs::path run = root_ / "two-writers";
    const Proc p = start({"run", cfg.string(), "--out", run.string(), "--threads", "1"}, root_ / "two-writers");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {})) << slurp(p.err);  // running, with a checkpoint to resume from
    for (const std::vector<std::string>& second :
         {std::vector<std::string>{"resume", run.string()},
          std::vector<std::string>{"run", run.string() + "/config.toml", "--out", run.string(), "--resume"}}) {
        const Proc q = start(second, root_ / "two-writers-second");
        const int rc = wait_for(q);
        if (rc == 0) GTEST_SKIP() << "the first run ended before the second started (machine too fast for this test)";
        EXPECT_EQ(rc, 2) << slurp(q.err);
        EXPECT_NE(slurp(q.err).find("is in use by another orodem (pid " + std::to_string(p.pid) + ")"),
                  std::string::npos) << slurp(q.err);
    }
    ASSERT_EQ(wait_for(p), 0) << slurp(p.err);
    expect_same_outputs(reference, run);
}

TEST_F(Resume, StoppedBetweenTheFirstRowAndTheFirstCheckpointItStartsAgainAndEndsTheSame) {
    // A SIGKILL or a full disk right after the S = 0 row, before the first checkpoint: `orodem status` says to
    // resume, and resume starts the run again in place (the S = 0 row is what a start writes again), ending
    // byte-identical to the uninterrupted run.
    const fs::path run = root_ / "first-row";
    fs::copy(reference_, run, fs::copy_options::recursive);
    fs::remove_all(run / "checkpoint");
    const std::string series = slurp(run / "series.csv");
    std::size_t second = series.find('\n');
    second = series.find('\n', second + 1);
    std::ofstream(run / "series.csv", std::ios::trunc) << series.substr(0, second + 1);  // header and the S = 0 row
    const Proc r = start({"resume", run.string(), "--threads", "1"}, root_ / "first-row");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    EXPECT_HAS(slurp(r.out) + slurp(r.err), "no checkpoint yet: starting the run from the beginning");
    expect_same_outputs(reference_, run);
}

TEST_F(Resume, APowerLossThatCostRowsFallsBackToTheCheckpointThatFitsTheFiles) {
    // After a power loss the newest checkpoint can be on disk while the rows written just before it are not (a
    // disk may reorder writes): series.csv is then shorter than that checkpoint recorded. The resume falls back
    // to the newest checkpoint that fits the files on disk, says so, cuts the files back to it and ends
    // byte-identical to the uninterrupted run (it used to stop with exit 4).
    const fs::path run = root_ / "power-loss";
    fs::copy(reference_, run, fs::copy_options::recursive);
    ASSERT_GE(orodem::list_checkpoints((run / "checkpoint").string()).size(), 2u);
    std::string series = slurp(run / "series.csv");
    series.pop_back();
    series.erase(series.rfind('\n') + 1);  // the last row lost
    std::ofstream(run / "series.csv", std::ios::trunc) << series;
    const Proc r = start({"resume", run.string(), "--threads", "1"}, root_ / "power-loss");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    EXPECT_HAS(slurp(r.err), "series.csv is ");
    EXPECT_HAS(slurp(r.err), "shorter than the");
    EXPECT_HAS(slurp(run / "log.txt"), "an older checkpoint is used");
    expect_same_outputs(reference_, run);
}

TEST_F(Resume, AFinishedRunHasNothingToContinueAndIsLeftAsItWas) {
    // orodem resume on a finished run says so and changes nothing (it used to restore the last checkpoint,
    // append a resume piece to the log and draw the plots again).
    const fs::path run = root_ / "finished";
    fs::copy(reference_, run, fs::copy_options::recursive);
    const std::string log = slurp(run / "log.txt"), plots = slurp(run / "figures" / "plots.png");
    // The temporary files of a writer killed while writing (SIGKILL during a checkpoint) are removed.
    std::ofstream(run / "checkpoint" / "ckpt-000000000007.bin.tmp-4242-0") << "half";
    std::ofstream(run / "snapshots" / "S0.500.vtu.tmp-4242-1") << "half";
    const Proc r = start({"resume", run.string(), "--threads", "1"}, root_ / "finished");
    ASSERT_EQ(wait_for(r), 0) << slurp(r.err);
    EXPECT_HAS(slurp(r.out) + slurp(r.err), "finished already at S = 0.500: nothing to continue");
    EXPECT_EQ(slurp(run / "log.txt"), log);
    EXPECT_EQ(slurp(run / "figures" / "plots.png"), plots);
    EXPECT_FALSE(fs::exists(run / "checkpoint" / "ckpt-000000000007.bin.tmp-4242-0"));
    EXPECT_FALSE(fs::exists(run / "snapshots" / "S0.500.vtu.tmp-4242-1"));
    expect_same_outputs(reference_, run);
}
