// run_state: where a run stands by its own files, on run directories made by
// hand (finished, interrupted, failed, killed, never started, an older run
// with log.txt only) and on real ones made in this process, among them a
// run stopped by a stop request, which checkpoints and, resumed, ends
// byte-identical to an uninterrupted run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <memory>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/runner.hpp"
#include "test_util.hpp"
#include "unit/run_wing_util.hpp"

using namespace orodem;
using namespace orodem::test;

namespace {

/// A stop request (SIGTERM) once the run reached S = at.
class StopAtS : public QuietObserver {
public:
    explicit StopAtS(double at) : at_(at) {}
    void progress(const RunProgress& p) override {
        if (p.S >= at_) sig_ = SIGTERM;
    }
    int stop_requested() const override { return sig_; }

private:
    double at_;
    int sig_ = 0;
};

std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> v;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
}

/// series.csv, faults.csv, run.pvd, every snapshot and every snapshot picture byte for byte.
void expect_same_outputs(const fs::path& a, const fs::path& b) {
    for (const char* f : {"series.csv", "faults.csv", "run.pvd"}) EXPECT_TRUE(slurp(b / f) == slurp(a / f)) << b / f;
    ASSERT_EQ(names_in(b / "snapshots"), names_in(a / "snapshots"));
    EXPECT_GT(names_in(a / "snapshots").size(), 4u);
    for (const auto& n : names_in(a / "snapshots"))
        EXPECT_TRUE(slurp(b / "snapshots" / n) == slurp(a / "snapshots" / n)) << n;
    int pictures = 0;
    for (const auto& n : names_in(a / "figures")) {
        if (n.rfind("horizons_", 0) != 0 && n.rfind("displacement_", 0) != 0) continue;
        ++pictures;
        EXPECT_TRUE(slurp(b / "figures" / n) == slurp(a / "figures" / n)) << n;
    }
    EXPECT_GT(pictures, 5);
}

}  // namespace

TEST(RunState, HandMadeRunDirectories) {
    TempFolder t("run-state");
    ASSERT_FALSE(t.path.empty());
    const fs::path cache = t.path / "cache";
    hand_run(t.path / "never", cache, {});
    hand_run(t.path / "finished", cache, {kStartRow, output_row(0.25, 600), output_row(0.5, 650), kFinishedRow});
    write_text(t.path / "finished" / "series.csv", "step,time\n75000,1.5\n150000,3\n");
    hand_run(t.path / "interrupted", cache, {kStartRow, output_row(0.1, 700), output_row(0.2, 20), kInterruptedRow});
    write_text(t.path / "interrupted" / "checkpoint" / "ckpt-000000030000.bin", "");
    write_text(t.path / "interrupted" / "checkpoint" / "ckpt-000000076000.bin", "");
    hand_run(t.path / "unstable", cache, {kStartRow, kUnstableRow});
    hand_run(t.path / "stopped", cache, {kStartRow, "stopped,1,0.1,,1,,\"STOPPED: a disc left the domain\""});
    hand_run(t.path / "killed", cache, {kStartRow, output_row(0.1, 700)});
    hand_run(t.path / "killed_resumed", cache, {kStartRow, kInterruptedRow, kResumeRow, output_row(0.3, 900)});

    const RunStatus never = run_state((t.path / "never").string());
    EXPECT_EQ(never.state, RunState::not_started);
    EXPECT_EQ(never.config.run.experiment, "exp1");
    EXPECT_FALSE(never.last);

    const RunStatus fin = run_state((t.path / "finished").string());
    EXPECT_EQ(fin.state, RunState::finished);
    ASSERT_TRUE(fin.last);
    EXPECT_EQ(fin.last->kind, RunEvent::finished);
    EXPECT_EQ(fin.last->text, "finished: S = 0.500 after 150000 steps, 10.0 s wall");
    EXPECT_DOUBLE_EQ(fin.dt, 1e-4);
    EXPECT_DOUBLE_EQ(fin.S, 0.5);
    EXPECT_DOUBLE_EQ(fin.last_step, 150000.0);
    EXPECT_DOUBLE_EQ(fin.total_steps, 0.5 * 6.0 / (0.2 * 1e-4));
    EXPECT_DOUBLE_EQ(fin.rate, 650.0);  // of two outputs, the higher
    EXPECT_EQ(fin.rate_outputs, 2);
    EXPECT_DOUBLE_EQ(fin.wall_s, 10.0);
    EXPECT_EQ(fin.pieces, 1);
    EXPECT_EQ(fin.pieces_timed, 1);
    EXPECT_FALSE(fin.newest_checkpoint);

    const RunStatus in = run_state((t.path / "interrupted").string());
    EXPECT_EQ(in.state, RunState::interrupted);
    EXPECT_DOUBLE_EQ(in.rate, 700.0);  // the median of 700 and 20 is the higher
    EXPECT_TRUE(std::isnan(in.last_step));  // no series.csv
    ASSERT_TRUE(in.newest_checkpoint);
    EXPECT_EQ(in.newest_checkpoint->first, 76000u);
    EXPECT_EQ(in.newest_checkpoint->second, (t.path / "interrupted" / "checkpoint" / "ckpt-000000076000.bin").string());

    EXPECT_EQ(run_state((t.path / "unstable").string()).state, RunState::failed);
    EXPECT_EQ(run_state((t.path / "stopped").string()).state, RunState::failed);
    const RunStatus killed = run_state((t.path / "killed").string());
    EXPECT_EQ(killed.state, RunState::no_end_line);
    EXPECT_TRUE(std::isfinite(killed.log_age_s));
    EXPECT_GE(killed.log_age_s, 0.0);
    // Interrupted, resumed, then killed: its last piece has no end line.
    const RunStatus again = run_state((t.path / "killed_resumed").string());
    EXPECT_EQ(again.state, RunState::no_end_line);
    EXPECT_EQ(again.last->kind, RunEvent::resume);
    EXPECT_EQ(again.pieces, 2);
    EXPECT_EQ(again.pieces_timed, 1);
    EXPECT_DOUBLE_EQ(again.wall_s, 42.5);
}

TEST(RunState, AnOlderRunsLogIsReadTheSameWayAndEventsCsvWinsOverIt) {
    TempFolder t("run-state-log");
    ASSERT_FALSE(t.path.empty());
    const fs::path dir = t.path / "old";
    hand_run(dir, t.path / "cache", {});
    write_text(dir / "log.txt",
               "orodem 0.1.0 run of c.toml (exp1) with 1 threads\n"
               "dt = 0.0001 s, stability limit 0.001 s (margin 10x), t_c = 20 steps\n"
               "S = 0.250: H/h0 = 0.1; 0 discs asleep; 700 steps/s\n"
               "S = 0.500: H/h0 = 0.1; 0 discs asleep; 20 steps/s\n"
               "S = 0.750: H/h0 = 0.1; 0 discs asleep; 900 steps/s\n"
               "interrupted by SIGTERM at step 100 (S = 0.7500) after 3000.0 s wall; checkpoint x.bin\n");
    RunStatus r = run_state(dir.string());
    EXPECT_EQ(r.state, RunState::interrupted);
    EXPECT_DOUBLE_EQ(r.dt, 1e-4);
    EXPECT_DOUBLE_EQ(r.S, 0.75);
    EXPECT_DOUBLE_EQ(r.rate, 700.0);  // the median of the last three
    EXPECT_EQ(r.rate_outputs, 3);
    EXPECT_DOUBLE_EQ(r.wall_s, 3000.0);
    // With events.csv the prose is not read.
    write_text(dir / "events.csv", "event,step,S,dt,wall_s,steps_per_s,text\n" + kStartRow + "\n" + kFinishedRow + "\n");
    r = run_state(dir.string());
    EXPECT_EQ(r.state, RunState::finished);
    EXPECT_TRUE(std::isnan(r.S));
}

TEST(RunState, ASettledLayerIsFinishedByItsPackingAndNotARunDirectoryIsRefused) {
    TempFolder t("run-state-layer");
    ASSERT_FALSE(t.path.empty());
    const fs::path dir = t.path / "layer";
    write_text(dir / "config.toml", "[run]\nexperiment = \"settle\"\n[packing]\nh0 = 6.0\n");
    write_text(dir / "log.txt", "settling\n");
    EXPECT_EQ(run_state(dir.string()).state, RunState::not_started);  // its settling starts again
    write_text(dir / "packing.bin", "x");
    EXPECT_EQ(run_state(dir.string()).state, RunState::finished);
    EXPECT_THROW(run_state((t.path / "nowhere").string()), ConfigError);
    fs::create_directories(t.path / "empty");
    EXPECT_THROW(run_state((t.path / "empty").string()), ConfigError);
}

/// Real runs of the tiny exp1, made once: one uninterrupted, one stopped at
/// S = 0.25 by a stop request and resumed, one that goes unstable at step 0.
class RealRuns : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        folder_ = std::make_unique<TempFolder>("run-state-real");
        const fs::path& root = folder_->path;
        write_text(root / "tiny.toml", tiny_exp1(root / "cache"));
        const Config c = load_config((root / "tiny.toml").string());
        const RunNumbers n = check_runnable(c);
        SerialOmp one_thread;
        QuietObserver quiet;
        fs::create_directories(root / "ref");
        ref_rc_ = start_run_in(c, n, (root / "ref").string(), quiet);
        fs::create_directories(root / "stopped");
        StopAtS stop(0.25);
        stop_rc_ = start_run_in(c, n, (root / "stopped").string(), stop);
        stopped_ = run_state((root / "stopped").string());
        resume_rc_ = resume_run(c, n, (root / "stopped").string(), quiet);
    }
    static void TearDownTestSuite() { folder_.reset(); }
    static fs::path path(const std::string& name) { return folder_->path / name; }

    static std::unique_ptr<TempFolder> folder_;
    static int ref_rc_, stop_rc_, resume_rc_;
    static RunStatus stopped_;  // the stopped run before its resume
};
std::unique_ptr<TempFolder> RealRuns::folder_;
int RealRuns::ref_rc_ = -1, RealRuns::stop_rc_ = -1, RealRuns::resume_rc_ = -1;
RunStatus RealRuns::stopped_;

TEST_F(RealRuns, AFinishedRun) {
    ASSERT_EQ(ref_rc_, 0);
    const RunStatus r = run_state(path("ref").string());
    EXPECT_EQ(r.state, RunState::finished);
    EXPECT_NEAR(r.S, 0.5, 1e-3);  // at the last output (whole steps)
    EXPECT_EQ(r.pieces, 1);
    EXPECT_EQ(r.pieces_timed, 1);
    EXPECT_NEAR(r.last_step, r.total_steps, 3.0);  // whole steps per output
    ASSERT_TRUE(r.newest_checkpoint);
    EXPECT_EQ(static_cast<double>(r.newest_checkpoint->first), r.last_step);
}

TEST_F(RealRuns, AStopRequestCheckpointsAndTheResumedRunEndsByteIdenticalToAnUninterruptedOne) {
    ASSERT_EQ(ref_rc_, 0);
    EXPECT_EQ(stop_rc_, 128 + SIGTERM);
    EXPECT_EQ(stopped_.state, RunState::interrupted);
    ASSERT_TRUE(stopped_.last);
    EXPECT_EQ(stopped_.last->kind, RunEvent::interrupted);
    EXPECT_NE(stopped_.last->text.find("interrupted by SIGTERM at step "), std::string::npos) << stopped_.last->text;
    EXPECT_NEAR(stopped_.S, 0.2, 1e-3);  // the last output before the stop
    EXPECT_LT(stopped_.S, 0.5);
    ASSERT_TRUE(stopped_.newest_checkpoint);
    EXPECT_GT(static_cast<double>(stopped_.newest_checkpoint->first), stopped_.last_step);  // between two outputs
    ASSERT_EQ(resume_rc_, 0);
    const RunStatus r = run_state(path("stopped").string());
    EXPECT_EQ(r.state, RunState::finished);
    EXPECT_EQ(r.pieces, 2);
    expect_same_outputs(path("ref"), path("stopped"));
}

TEST_F(RealRuns, ARunThatGoesUnstableHasFailed) {
    const fs::path dir = path("unstable");
    write_text(path("unstable.toml"), tiny_exp1(path("cache"), "domain_height = 0.5\n"));
    const Config c = load_config(path("unstable.toml").string());
    fs::create_directories(dir);
    SerialOmp one_thread;
    QuietObserver quiet;
    EXPECT_THROW(start_run_in(c, check_runnable(c), dir.string(), quiet), InstabilityError);
    EXPECT_EQ(run_state(dir.string()).state, RunState::failed);
}
