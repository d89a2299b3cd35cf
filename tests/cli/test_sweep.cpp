// `orodem sweep`: one run per value into DIR/<key>=<value>/, the settled
// layer settled once and reused, and the overlay plot at the end; an
// interrupted sweep continued by `orodem resume DIR` ends as an uninterrupted one.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include "cli/checkpoint_util.hpp"
#include "cli/cli_util.hpp"
#include <stdlib.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/sweep_manifest.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

/// A new temporary folder holding tiny.toml (write_tiny_exp1); empty on failure.
fs::path tiny_dir() {
    char tmpl[] = "/tmp/orodem-sweep-XXXXXX";
    if (!mkdtemp(tmpl)) return {};
    write_tiny_exp1(tmpl);
    return tmpl;
}

/// The sequential sweep of dir/tiny.toml over wedge.mu_bp = 0.1, 0.5 into
/// dir/ref, with five outputs (S = 0 to 0.5: enough pictures for
/// expect_same_outputs); its exit status.
int reference_sweep(const fs::path& dir, std::string* out) {
    return run(std::string(ORODEM_EXE) + " sweep " + (dir / "tiny.toml").string() +
                   " --vary wedge.mu_bp=0.1,0.5 --out " + (dir / "ref").string() +
                   " --threads 1 --set wedge.output_ds=0.125",
               out);
}

}  // namespace

TEST(Sweep, OneRunPerValueReusingTheLayerThenPlots) {
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    std::string out;
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " sweep " + (dir / "tiny.toml").string() +
                  " --vary wedge.mu_bp=0.1,0.5 --out " + (dir / "sw").string() + " --threads 1", &out), 0)
        << out;
    for (const char* v : {"0.1", "0.5"}) {
        const fs::path r = dir / "sw" / (std::string("wedge.mu_bp=") + v);
        ASSERT_TRUE(fs::exists(r / "series.csv")) << r;
        EXPECT_NE(slurp(r / "config.toml").find(std::string("mu_bp = ") + v), std::string::npos) << r;
    }
    // The second member reuses the layer the first one settled.
    EXPECT_NE(slurp(dir / "sw" / "wedge.mu_bp=0.1" / "log.txt").find("settling a new packing"), std::string::npos);
    EXPECT_NE(slurp(dir / "sw" / "wedge.mu_bp=0.5" / "log.txt").find("packing reused"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "sw" / "plots.png"));
    // Progress: "run k of n" as each starts, then the runs done and the time left.
    EXPECT_NE(out.find("sweep: wedge.mu_bp = 0.1 (run 1 of 2) -> "), std::string::npos) << out;
    EXPECT_NE(out.find("sweep: wedge.mu_bp = 0.5 (run 2 of 2) -> "), std::string::npos) << out;
    EXPECT_NE(out.find("sweep: 1 of 2 runs done, 1 to go: about "), std::string::npos) << out;
    EXPECT_EQ(out.find("2 of 2 runs done"), std::string::npos) << out;
    // orodem measure on the sweep's folder: every member's rows, named in a first column.
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " measure " + (dir / "sw").string() + " 2>/dev/null", &out), 0) << out;
    EXPECT_EQ(out.rfind("run,S,H_over_h0,", 0), 0u) << out;
    EXPECT_NE(out.find("\nwedge.mu_bp=0.1,0.000000,"), std::string::npos) << out;
    EXPECT_NE(out.find("\nwedge.mu_bp=0.5,0.500"), std::string::npos) << out;
    EXPECT_EQ(count_lines(out), 1 + 2 * 3) << out;  // S = 0, 0.25, 0.5 each
    // orodem status on the sweep's folder: each member, both finished.
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + (dir / "sw").string(), &out), 0) << out;
    EXPECT_NE(out.find("run: " + (dir / "sw" / "wedge.mu_bp=0.1").string()), std::string::npos) << out;
    EXPECT_NE(out.find("run: " + (dir / "sw" / "wedge.mu_bp=0.5").string()), std::string::npos) << out;
    EXPECT_NE(out.find("state: finished"), out.rfind("state: finished")) << out;
    // A bad value anywhere in the list is refused before any run starts.
    EXPECT_EQ(run(std::string(ORODEM_EXE) + " sweep " + (dir / "tiny.toml").string() +
                  " --vary wedge.mu_bp=0.1,-1 --out " + (dir / "sw2").string() + " --threads 1", &out), 2)
        << out;
    EXPECT_FALSE(fs::exists(dir / "sw2"));
    fs::remove_all(dir);
}

TEST(Sweep, OverTheSeedsPlotsTheirMeanOverABand) {
    // `--vary run.seed=...`: one packing per seed, and plots.png draws the
    // ensemble (orodem plot --seeds) instead of one line per seed.
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    std::string out;
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " sweep " + (dir / "tiny.toml").string() + " --vary run.seed=1,2 --out " +
                  (dir / "sw").string() + " --threads 1", &out), 0)
        << out;
    EXPECT_NE(out.find("plot: mean of 2 seeds, band: lowest to highest: run.seed=1, run.seed=2"), std::string::npos)
        << out;
    EXPECT_TRUE(fs::exists(dir / "sw" / "plots.png"));
    // Each seed settled its own layer.
    EXPECT_NE(slurp(dir / "sw" / "run.seed=2" / "log.txt").find("settling a new packing"), std::string::npos);
    fs::remove_all(dir);
}

TEST(Sweep, SeveralVaryKeysRunTheProductGridAndPlotEachGroupOverItsSeeds) {
    // --vary twice: one run per combination, the first key slowest, in <key>=<value>,<key>=<value>/; with
    // run.seed among the keys plots.png draws each group of runs that differ only in their seeds as its mean.
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    const std::string sweep = std::string(ORODEM_EXE) + " sweep " + (dir / "tiny.toml").string() +
                              " --threads 1 --set wedge.s_max=0.25 --vary wedge.mu_bp=0.1,0.5 --vary run.seed=1,2";
    std::string out;
    ASSERT_EQ(run(sweep + " --out " + (dir / "sw").string(), &out), 0) << out;
    const char* order[] = {"wedge.mu_bp=0.1,run.seed=1", "wedge.mu_bp=0.1,run.seed=2", "wedge.mu_bp=0.5,run.seed=1",
                           "wedge.mu_bp=0.5,run.seed=2"};
    for (int k = 0; k < 4; ++k) {
        const fs::path r = dir / "sw" / order[k];
        ASSERT_TRUE(fs::exists(r / "series.csv")) << r;
        const std::string cfg = slurp(r / "config.toml");
        EXPECT_HAS(cfg, std::string("mu_bp = ") + (k < 2 ? "0.1" : "0.5"));
        EXPECT_HAS(cfg, std::string("seed = ") + (k % 2 == 0 ? "1" : "2"));
        EXPECT_HAS(out, fmt::format("(run {} of 4)", k + 1));
    }
    EXPECT_LT(out.find("sweep: wedge.mu_bp = 0.1, run.seed = 2 (run 2 of 4)"),
              out.find("sweep: wedge.mu_bp = 0.5, run.seed = 1 (run 3 of 4)"))
        << out;
    EXPECT_HAS(out, "(2 seeds): wedge.mu_bp=0.1,run.seed=1, wedge.mu_bp=0.1,run.seed=2");
    EXPECT_TRUE(fs::exists(dir / "sw" / "plots.png"));
    // The sweep's folder: resume finds every member finished; measure names each member in a quoted first cell.
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " resume " + (dir / "sw").string(), &out), 0) << out;
    EXPECT_HAS(out, "(wedge.mu_bp = 2 values x run.seed = 2 values)");
    EXPECT_HAS(out, "sweep: wedge.mu_bp = 0.5, run.seed = 2: finished already, kept");
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " measure " + (dir / "sw").string() + " 2>/dev/null", &out), 0) << out;
    EXPECT_HAS(out, "\n\"wedge.mu_bp=0.5,run.seed=2\",0.250");
    // One key twice: refused before anything is written.
    ASSERT_EQ(run(sweep + " --vary run.seed=3 --out " + (dir / "sw2").string(), &out), 2) << out;
    EXPECT_HAS(out, "--vary run.seed: the key is varied twice");
    EXPECT_FALSE(fs::exists(dir / "sw2"));
    fs::remove_all(dir);
}

TEST(Sweep, InterruptedItContinuesWithResumeAndEndsAsAnUninterruptedSweep) {
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    const std::string tiny = (dir / "tiny.toml").string(), sw = (dir / "sw").string();
    std::string out;
    ASSERT_EQ(reference_sweep(dir, &out), 0) << out;

    // SIGINT while the first member runs: it checkpoints, the second has not started.
    const Proc p = start({"sweep", tiny, "--vary", "wedge.mu_bp=0.1,0.5", "--out", sw, "--threads", "1", "--set",
                          "wedge.output_ds=0.125"},
                         dir / "sw");
    ASSERT_TRUE(signal_after_checkpoint(p, dir / "sw" / "wedge.mu_bp=0.1", {SIGINT})) << slurp(p.err);
    ASSERT_EQ(wait_for(p), 130) << slurp(p.err);
    EXPECT_HAS(slurp(p.err), "the sweep stopped at wedge.mu_bp = 0.1; continue it with: orodem resume " + sw);
    EXPECT_EQ(names_in(dir / "sw" / "wedge.mu_bp=0.5"), std::vector<std::string>{"config.toml"});
    EXPECT_TRUE(fs::exists(dir / "sw" / "sweep.toml"));
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + sw, &out), 0) << out;
    EXPECT_HAS(out, "state: interrupted by SIGINT");
    EXPECT_HAS(out, "state: not started yet");
    EXPECT_HAS(out, "sweep: 0 of 2 runs finished; continue it with: orodem resume " + sw);
    // A new sweep into the folder is refused, and says how to continue it.
    EXPECT_EQ(run(std::string(ORODEM_EXE) + " sweep " + tiny + " --vary wedge.mu_bp=0.1,0.5 --out " + sw, &out), 2);
    EXPECT_HAS(out, "or continue the sweep in it with: orodem resume " + sw);

    // Continued at another thread count: the interrupted member resumes, the other starts.
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " resume " + sw + " --threads 2", &out), 0) << out;
    EXPECT_HAS(out, "sweep: wedge.mu_bp = 0.1 (run 1 of 2): continuing " + sw + "/wedge.mu_bp=0.1");
    EXPECT_HAS(out, "sweep: 1 of 2 runs done, 1 to go: about ");
    EXPECT_HAS(out, "sweep: wedge.mu_bp = 0.5 (run 2 of 2) -> " + sw + "/wedge.mu_bp=0.5");
    for (const char* m : {"wedge.mu_bp=0.1", "wedge.mu_bp=0.5"}) expect_same_outputs(dir / "ref" / m, dir / "sw" / m);
    EXPECT_HAS(slurp(dir / "sw" / "wedge.mu_bp=0.1" / "log.txt"), "resumed by orodem");
    EXPECT_TRUE(fs::exists(dir / "sw" / "plots.png"));

    // Nothing left to do: both kept as they are.
    const std::string before = slurp(dir / "sw" / "wedge.mu_bp=0.5" / "series.csv");
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " resume " + sw, &out), 0) << out;
    EXPECT_HAS(out, "sweep: wedge.mu_bp = 0.1: finished already, kept");
    EXPECT_HAS(out, "sweep: wedge.mu_bp = 0.5: finished already, kept");
    EXPECT_EQ(slurp(dir / "sw" / "wedge.mu_bp=0.5" / "series.csv"), before);
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " status " + sw, &out), 0) << out;
    EXPECT_HAS(out, "sweep: 2 of 2 runs finished\n");
    fs::remove_all(dir);
}

TEST(Sweep, ItsManifestReadsBackAndABrokenOneIsRefusedByName) {
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    const orodem::SweepManifest m{"configs/a \"b\".toml", "wedge.mu_bp", {"0.1", "0.5"}, {"wedge.s_max=2"}, {}};
    orodem::write_file_atomic(orodem::sweep_manifest_path(dir.string()), orodem::to_toml(m));
    const orodem::SweepManifest r = orodem::read_sweep_manifest(dir.string());
    EXPECT_EQ(r.config, m.config);
    EXPECT_EQ(r.key, m.key);
    EXPECT_EQ(r.values, m.values);
    EXPECT_EQ(r.sets, m.sets);
    EXPECT_EQ(orodem::sweep_member_dir("S", {{"wedge.mu_bp", "0.5"}}), "S/wedge.mu_bp=0.5");
    EXPECT_TRUE(r.more.empty());
    EXPECT_EQ(slurp(orodem::sweep_manifest_path(dir.string())).find("grid"), std::string::npos);  // one key: as before
    // A product grid: the further keys in [[grid]], read back; the members every combination, the first key slowest.
    const orodem::SweepManifest g{"a.toml", "wedge.mu_bp", {"0.1", "0.5"}, {}, {{"run.seed", {"1", "2", "3"}}}};
    orodem::write_file_atomic(orodem::sweep_manifest_path(dir.string()), orodem::to_toml(g));
    const orodem::SweepManifest gr = orodem::read_sweep_manifest(dir.string());
    ASSERT_EQ(gr.more.size(), 1u);
    EXPECT_EQ(gr.more[0].key, "run.seed");
    EXPECT_EQ(gr.more[0].values, g.more[0].values);
    const auto members = orodem::sweep_members(gr);
    ASSERT_EQ(members.size(), 6u);
    EXPECT_EQ(orodem::sweep_member_dir("S", members[1]), "S/wedge.mu_bp=0.1,run.seed=2");
    EXPECT_EQ(orodem::sweep_member_dir("S", members[3]), "S/wedge.mu_bp=0.5,run.seed=1");
    EXPECT_EQ(orodem::sweep_axes_text(gr), "wedge.mu_bp = 2 values x run.seed = 3 values");
    EXPECT_TRUE(orodem::varies_seed(gr));
    orodem::write_file_atomic(orodem::sweep_manifest_path(dir.string()), "config = \"x.toml\"\nvary = 3\n");
    try {
        orodem::read_sweep_manifest(dir.string());
        ADD_FAILURE() << "a manifest whose vary is a number was read";
    } catch (const orodem::ConfigError& e) {
        EXPECT_HAS(e.what(), "sweep.toml: 'vary' is missing or not a string");
    }
    // orodem resume on it: exit 2 and the same line.
    std::string out;
    EXPECT_EQ(run(std::string(ORODEM_EXE) + " resume " + dir.string(), &out), 2);
    EXPECT_HAS(out, "'vary' is missing or not a string");
    fs::remove_all(dir);
}

TEST(Sweep, AMemberThatFailsDoesNotStopTheOthersAndIsSkippedOnResume) {
    // run.domain_height = 0.5 h0 puts the top of the layer outside the domain
    // at step 0 (exit 3 for a single run); 0 is the default, no ceiling.
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    const std::string sw = (dir / "sw").string();
    std::string out;
    EXPECT_EQ(run(std::string(ORODEM_EXE) + " sweep " + (dir / "tiny.toml").string() +
                  " --vary run.domain_height=0.5,0 --out " + sw + " --threads 1", &out), 3)
        << out;
    EXPECT_HAS(out, "sweep: run.domain_height = 0.5: unstable:");
    EXPECT_HAS(out, "sweep: 1 of 2 runs went unstable (run.domain_height = 0.5); the plots leave them out");
    EXPECT_HAS(slurp(dir / "sw" / "run.domain_height=0" / "log.txt"), "finished:");
    EXPECT_TRUE(fs::exists(dir / "sw" / "plots.png"));
    EXPECT_EQ(run(std::string(ORODEM_EXE) + " resume " + sw, &out), 3) << out;
    EXPECT_HAS(out, "sweep: run.domain_height = 0.5: ended with an error before (see " + sw +
                        "/run.domain_height=0.5/log.txt); skipped");
    EXPECT_HAS(out, "sweep: run.domain_height = 0: finished already, kept");
    fs::remove_all(dir);
}

TEST(Sweep, WithTwoJobsTheRunsAreThoseOfASequentialSweepAlsoWhenInterrupted) {
    // --jobs 2: the members run in two child processes at once. A SIGTERM to
    // the sweep reaches both (they checkpoint); resumed with two jobs, every
    // member ends byte-identical to the sequential sweep's.
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    const std::string tiny = (dir / "tiny.toml").string(), sw = (dir / "sw").string();
    std::string out;
    ASSERT_EQ(reference_sweep(dir, &out), 0) << out;
    const Proc p = start({"sweep", tiny, "--vary", "wedge.mu_bp=0.1,0.5", "--out", sw, "--jobs", "2", "--threads", "1",
                          "--set", "wedge.output_ds=0.125"},
                         dir / "sw");
    ASSERT_TRUE(signal_after_checkpoint(p, dir / "sw" / "wedge.mu_bp=0.1", {SIGTERM})) << slurp(p.err);
    ASSERT_EQ(wait_for(p), 143) << slurp(p.out) << slurp(p.err);
    EXPECT_HAS(slurp(p.out), "sweep: wedge.mu_bp = 0.5 (run 2 of 2) -> " + sw + "/wedge.mu_bp=0.5 (starting, 1 thread");
    EXPECT_HAS(slurp(p.err), "the sweep stopped (SIGTERM); continue it with: orodem resume " + sw);
    EXPECT_HAS(slurp(dir / "sw" / "wedge.mu_bp=0.1" / "console.txt"), "interrupted by SIGTERM");
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " resume " + sw + " --jobs 2 --threads 1", &out), 0) << out;
    EXPECT_HAS(out, "sweep: wedge.mu_bp = 0.1 (run 1 of 2) -> " + sw + "/wedge.mu_bp=0.1 (continuing, 1 thread");
    for (const char* m : {"wedge.mu_bp=0.1", "wedge.mu_bp=0.5"}) expect_same_outputs(dir / "ref" / m, dir / "sw" / m);
    EXPECT_HAS(slurp(dir / "sw" / "wedge.mu_bp=0.1" / "log.txt"), "resumed by orodem");
    EXPECT_TRUE(fs::exists(dir / "sw" / "plots.png"));
    fs::remove_all(dir);
}

TEST(Sweep, KilledOrHungUpItsMembersEndWithItAndResumeFinishesTheSame) {
    // SIGKILL (or SIGHUP: the terminal closed) to a --jobs 2 sweep: its members get SIGTERM from the kernel
    // (die_with_parent), checkpoint and stop, so none is left running; a second sweep process on the folder is
    // refused while one runs; `orodem resume` then ends every member byte-identical to the sequential sweep's.
    const fs::path dir = tiny_dir();
    ASSERT_FALSE(dir.empty());
    const std::string tiny = (dir / "tiny.toml").string();
    std::string out;
    ASSERT_EQ(reference_sweep(dir, &out), 0) << out;
    for (const int sig : {SIGKILL, SIGHUP}) {
        const std::string name = sig == SIGKILL ? "sk" : "sh", sw = (dir / name).string();
        const Proc p = start({"sweep", tiny, "--vary", "wedge.mu_bp=0.1,0.5", "--out", sw, "--jobs", "2", "--threads",
                              "1", "--set", "wedge.output_ds=0.125"},
                             dir / name);
        ASSERT_TRUE(signal_after_checkpoint(p, dir / name / "wedge.mu_bp=0.1", {})) << slurp(p.err);
        if (sig == SIGKILL) {  // while it runs, a resume of the folder is refused
            EXPECT_EQ(run(std::string(ORODEM_EXE) + " resume " + sw + " 2>&1", &out), 2) << out;
            EXPECT_HAS(out, "the sweep folder '" + sw + "' is in use by another orodem (pid " + std::to_string(p.pid));
        }
        ::kill(p.pid, sig);
        wait_for(p);
        // The members are gone within seconds (their shutdown checkpoint written).
        bool alive = true;
        for (int k = 0; k < 200 && alive; ++k) {
            alive = run("pgrep -f '[s]weep-member " + sw + "/' >/dev/null") == 0;  // [s]: not pgrep's own shell
            if (alive) std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        EXPECT_FALSE(alive) << "a member of the " << name << " sweep outlived it";
        ASSERT_EQ(run(std::string(ORODEM_EXE) + " resume " + sw + " --jobs 2 --threads 1", &out), 0) << out;
        for (const char* m : {"wedge.mu_bp=0.1", "wedge.mu_bp=0.5"}) expect_same_outputs(dir / "ref" / m, dir / name / m);
    }
    fs::remove_all(dir);
}
