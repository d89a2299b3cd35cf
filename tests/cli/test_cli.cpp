// The orodem executable as a user meets it: exit statuses, one-line errors,
// run directories and the packing cache (SPEC §4, §5). Every test runs the
// real binary in a fresh temporary directory.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include "cli/cli_util.hpp"
#include <stdlib.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "orodem/io/config.hpp"
#include "orodem/setup/scenario.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

/// Every path below dir with its size, for "nothing was written" checks.
std::map<std::string, std::uintmax_t> listing(const fs::path& dir) {
    std::map<std::string, std::uintmax_t> m;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        m[fs::relative(e.path(), dir).string()] = e.is_regular_file() ? e.file_size() : 0;
    return m;
}

// A tiny layer that settles in well under a second.
std::string tiny_config(const fs::path& cache) {
    return "[run]\n"
           "experiment = \"settle\"\n"
           "[packing]\n"
           "kind = \"discs\"\n"
           "length = 20\n"
           "h0 = 4\n"
           "r_min = 0.5\n"
           "r_max = 1.0\n"
           "cache_dir = " + quote(cache.string()) + "\n";
}

const char* kMisspelled =
    "[run]\n"
    "experiment = \"settle\"\n"
    "[material]\n"
    "k_nn = 1e8\n";

class Cli : public OrodemTest {};

}  // namespace

TEST_F(Cli, HelpListsSubcommands) {
    const Result r = orodem("--help");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "run");
    EXPECT_HAS(r.out, "check");
    EXPECT_HAS(r.out, "Subcommands");
}

TEST_F(Cli, CheckOfMisspelledKeyExitsTwoWithOneLine) {
    write(work_ / "bad.toml", kMisspelled);
    const auto before = listing(work_);
    const Result r = orodem("check bad.toml");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "'material.k_nn'");
    EXPECT_HAS(r.err, "bad.toml:4:");
    EXPECT_HAS(r.err, "k_n,");  // the allowed keys
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(listing(work_), before);
}

TEST_F(Cli, BadArgumentsExitTwo) {
    write(work_ / "c.toml", tiny_config(root_ / "cache"));
    const auto before = listing(work_);
    EXPECT_EQ(orodem("frobnicate c.toml").status, 2);
    EXPECT_EQ(orodem("").status, 2);
    EXPECT_EQ(orodem("check").status, 2);
    EXPECT_EQ(orodem("run").status, 2);
    EXPECT_EQ(orodem("run c.toml --no-such-flag").status, 2);
    EXPECT_EQ(orodem("run c.toml --threads many").status, 2);
    EXPECT_EQ(orodem("check c.toml --set material.mu").status, 2);
    const Result bad_set = orodem("check c.toml --set material.k_nn=1");
    EXPECT_EQ(bad_set.status, 2);
    EXPECT_EQ(count_lines(bad_set.err), 1) << bad_set.err;
    EXPECT_HAS(bad_set.err, "material.k_nn");
    const Result missing = orodem("check no-such-file.toml");
    EXPECT_EQ(missing.status, 2);
    EXPECT_HAS(missing.err, "no-such-file.toml");
    EXPECT_EQ(listing(work_), before);
}

TEST_F(Cli, RunOfBadConfigCreatesNoRunDirectory) {
    write(work_ / "bad.toml", kMisspelled);
    const auto before = listing(work_);
    Result r = orodem("run bad.toml --out out");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "'material.k_nn'");
    r = orodem("run bad.toml");  // default run directory runs/bad
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(listing(work_), before);
    EXPECT_FALSE(fs::exists(work_ / "out"));
    EXPECT_FALSE(fs::exists(work_ / "runs"));
}

TEST_F(Cli, RunWithTimestepAboveLimitExitsTwoAndWritesNothing) {
    write(work_ / "c.toml", tiny_config(root_ / "cache"));
    const auto before = listing(work_);
    for (const char* cmd : {"run c.toml --out out --set numerics.dt=1.0", "check c.toml --set numerics.dt=1.0"}) {
        const Result r = orodem(cmd);
        EXPECT_EQ(r.status, 2) << cmd;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_HAS(r.err, "numerics.dt");
        EXPECT_HAS(r.err, "stability limit");
    }
    EXPECT_EQ(listing(work_), before);
    EXPECT_FALSE(fs::exists(root_ / "cache"));
}

TEST_F(Cli, CheckOfValidConfigPrintsDtAndCountAndWritesNothing) {
    const fs::path cache = root_ / "cache";
    const std::string text = tiny_config(cache);
    write(work_ / "c.toml", text);
    const auto before = listing(work_);
    const Result r = orodem("check c.toml");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const orodem::Config c = orodem::parse_config(text, "c.toml");
    const std::size_t n = orodem::generated_particle_count(c);
    EXPECT_GT(n, 10u);
    EXPECT_HAS(r.out, "dt");
    EXPECT_HAS(r.out, "particles");
    EXPECT_HAS(r.out, std::string(" ") + std::to_string(n) + " ");
    EXPECT_EQ(listing(work_), before);
    EXPECT_FALSE(fs::exists(cache));
}

TEST_F(Cli, RunWritesRunDirectoryAndReusesPacking) {
    const fs::path cache = root_ / "cache";
    write(work_ / "c.toml", tiny_config(cache));

    // First run: settles a new packing.
    Result r = orodem("run c.toml --out out1 --threads 1");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    const fs::path d = work_ / "out1";
    for (const char* f : {"config.toml", "log.txt", "series.csv", "packing.bin"})
        EXPECT_TRUE(fs::is_regular_file(d / f)) << f;
    const std::string series = slurp(d / "series.csv");
    EXPECT_EQ(series.rfind("step,time", 0), 0u) << series.substr(0, 200);
    EXPECT_GE(count_lines(series), 2) << "no data rows";
    EXPECT_NE(slurp(d / "log.txt").find("settl"), std::string::npos);
    for (const auto& e : fs::directory_iterator(d))  // no temporary left (<file>.tmp-<pid>-<n>)
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();

    // The written config is the resolved one and is itself a valid config.
    const std::string resolved = slurp(d / "config.toml");
    const orodem::Config rc = orodem::parse_config(resolved, "config.toml");
    EXPECT_EQ(orodem::to_toml(rc), resolved);
    EXPECT_EQ(rc.packing.kind, orodem::PackingKind::discs);
    EXPECT_EQ(rc.packing.length, 20.0);
    EXPECT_HAS(resolved, "k_n = ");  // a default, written out

    // The same --out again: refused, the earlier run untouched.
    const auto before = listing(work_);
    r = orodem("run c.toml --out out1");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "out1");
    EXPECT_EQ(listing(work_), before);

    // Another --out: the cached packing is reused, bit for bit.
    r = orodem("run c.toml --out out2 --threads 1");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_HAS(slurp(work_ / "out2" / "log.txt"), "packing reused");
    EXPECT_EQ(slurp(work_ / "out2" / "packing.bin"), slurp(d / "packing.bin"));
    EXPECT_EQ(slurp(work_ / "out2" / "config.toml"), resolved);

    // An empty existing directory is an acceptable --out.
    fs::create_directories(work_ / "empty");
    EXPECT_EQ(orodem("run c.toml --out empty --threads 1").status, 0);
    EXPECT_TRUE(fs::is_regular_file(work_ / "empty" / "packing.bin"));
}

TEST_F(Cli, RunWithoutOutPicksAFreshDirectoryUnderRuns) {
    write(work_ / "layer.toml", tiny_config(root_ / "cache"));
    ASSERT_EQ(orodem("run layer.toml --threads 1").status, 0);
    ASSERT_EQ(orodem("run layer.toml --threads 1").status, 0);
    EXPECT_TRUE(fs::is_regular_file(work_ / "runs" / "layer" / "config.toml"));
    EXPECT_TRUE(fs::is_regular_file(work_ / "runs" / "layer-2" / "config.toml"));
    EXPECT_FALSE(fs::exists(work_ / "runs" / "layer-3"));
}

TEST_F(Cli, SetOverridesReachTheResolvedConfig) {
    write(work_ / "c.toml", tiny_config(root_ / "cache"));
    const Result r = orodem("run c.toml --out o --threads 1 --set material.mu=0.45 --set run.seed=5");
    ASSERT_EQ(r.status, 0) << r.err;
    const orodem::Config c = orodem::parse_config(slurp(work_ / "o" / "config.toml"), "config.toml");
    EXPECT_EQ(c.material.mu, 0.45);
    EXPECT_EQ(c.run.seed, 5u);
    EXPECT_EQ(c.packing.seed, 5u);
    EXPECT_EQ(c.run.threads, 1);
}

TEST_F(Cli, CoarseTimestepRunsWithAWarning) {
    // safety 0.2 puts 11 steps in a collision (22.2 at the default 0.1).
    write(work_ / "coarse.toml", tiny_config(root_ / "cache") + "[numerics]\nsafety = 0.2\n");
    const Result r = orodem("run coarse.toml --out coarse");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.err, "orodem: warning: a collision (t_c = ");
    EXPECT_HAS(r.err, "spans only 11.1 steps");
    EXPECT_HAS(slurp(work_ / "coarse" / "log.txt"), "warning: a collision");
    write(work_ / "fine.toml", tiny_config(root_ / "cache"));
    const Result fine = orodem("run fine.toml --out fine");
    ASSERT_EQ(fine.status, 0) << fine.err;
    EXPECT_EQ(fine.err.find("warning"), std::string::npos) << fine.err;
}

namespace {

/// The number printed right after `key` in `out` (-1 when `key` is absent).
double number_after(const std::string& out, const std::string& key) {
    const std::size_t at = out.find(key);
    return at == std::string::npos ? -1.0 : std::stod(out.substr(at + key.size()));
}

}  // namespace

TEST_F(Cli, CheckEstimatesTheWorkOfAWedgeRunFromItsStepsDiscsAndSleeping) {
    // Paper-size Experiment 1: S = 8 h0 / (v' dt) steps; the work is steps x
    // discs x 0.8 (the cut to h0) x 0.45 awake with sleeping zones (the measured
    // paper-size run), all awake without.
    const std::string cfg = quote((fs::path(ORODEM_SOURCE_DIR) / "configs" / "exp1.toml").string());
    const Result on = orodem("check " + cfg), off = orodem("check " + cfg + " --set wedge.sleep=false");
    ASSERT_EQ(on.status, 0) << on.err;
    ASSERT_EQ(off.status, 0) << off.err;
    const double dt = number_after(on.out, "dt                     = ");
    const double discs = number_after(on.out, "particles generated    = ");
    const double steps = number_after(on.out, "steps to S = 8       = ");
    EXPECT_NEAR(steps, 8.0 * 55.0 / (0.6 * dt), 1e-3 * steps);  // v' = 0.6 m/s
    const std::size_t open = on.out.find('(', on.out.find("steps to S = 8")) + 1;
    // The work is printed to 3 significant digits (at most 0.5% off) and dt to
    // 6 (1e-5 relative), the discs exactly: 0.6% of the value.
    const double exact_steps = 8.0 * 55.0 / (0.6 * dt);
    const double awake_steps = exact_steps * discs * 0.8 * 0.45;
    EXPECT_NEAR(std::stod(on.out.substr(open)), awake_steps, 6e-3 * awake_steps);
    EXPECT_HAS(on.out, "awake disc-steps)");
    const std::size_t open_off = off.out.find('(', off.out.find("steps to S = 8")) + 1;
    const double all_steps = exact_steps * discs * 0.8;
    EXPECT_NEAR(std::stod(off.out.substr(open_off)), all_steps, 6e-3 * all_steps);
    EXPECT_EQ(off.out.find("awake"), std::string::npos) << off.out;
    EXPECT_HAS(on.out, "estimated run time     = ");
}

// Misleading inputs get a message about the real problem (exit 2, one line).
TEST_F(Cli, MessagesNameTheRealProblem) {
    const std::string cfg = quote((fs::path(ORODEM_SOURCE_DIR) / "configs" / "demo" / "exp1.toml").string());
    struct Case {
        std::string args, says;
    } cases[] = {
        {"frobnicate", "unknown command 'frobnicate'; the commands are run, resume"},
        {"check " + quote(ORODEM_SOURCE_DIR), "is a directory, not a config file"},
        {"run " + cfg + " --out " + quote((fs::path(ORODEM_SOURCE_DIR) / "README.md").string()),
         "README.md: is a file, not a directory"},
        {"check " + cfg + " --set wedge.v=-1", "--set wedge.v=-1: key 'wedge.v' = -1: must be a number > 0"},
        {"check " + cfg + " --set wedge.vee=1", "--set wedge.vee=1: unknown key 'wedge.vee'"},
        {"sweep " + cfg + " --vary wedge.v=-1,0.1 --out " + quote((work_ / "sw").string()),
         "--vary wedge.v (the value -1): key 'wedge.v' = -1: must be a number > 0"},
        {"run " + cfg + " --threads -1", "--threads"},
        {"check " + cfg + " --set packing.h0=1e308", "would have about inf discs"},
        {"check " + quote((fs::path(ORODEM_SOURCE_DIR) / "configs" / "calibrate" / "basal-friction.toml").string()) +
             " --set calibrate.block_height=1e7",
         "the calibration sample (30 m long, 1e+07 m high"},
        {"resume /nonexistent --threads -3", "--threads"},
    };
    for (const Case& k : cases) {
        const Result r = orodem(k.args);
        EXPECT_EQ(r.status, 2) << k.args << ": " << r.err;
        EXPECT_HAS(r.err, k.says);
    }
}

// A config that is a device (/dev/zero never ends), a FIFO (opening it
// blocks until a writer comes) or is named with a newline (it would break
// log.txt, events.csv and status) is refused at once: exit 2, one line,
// nothing written. The shell's timeout makes a hang a failure, not a stall.
TEST_F(Cli, AConfigThatIsADeviceOrAFifoOrNamedWithANewlineIsRefusedInOneLine) {
    const fs::path fifo = work_ / "fifo.toml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& cfg : {std::string("/dev/zero"), fifo.string()}) {
        for (const std::string args : {"check " + quote(cfg), "run " + quote(cfg) + " --out r"}) {
            const Result r = orodem(args, "timeout 10");
            EXPECT_EQ(r.status, 2) << args << ": " << r.err;
            EXPECT_EQ(count_lines(r.err), 1) << r.err;
            EXPECT_HAS(r.err, "not a regular file");
            EXPECT_FALSE(fs::exists(work_ / "r"));
        }
    }
    write_tiny_exp1(work_, "a\nb.toml");
    const Result r = orodem("run " + quote((work_ / "a\nb.toml").string()) + " --out r");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "a?b.toml': holds a control character");
    EXPECT_FALSE(fs::exists(work_ / "r"));
}

// A run estimated above kLongRunHours (a week) on 2 threads, here a slow
// belt under a long plate, is refused by run and sweep before anything is
// written, naming --force; check says so; with --force it starts (stopped
// at once here by the wall-time limit, exit 5) and prints the estimate.
TEST_F(Cli, ARunEstimatedAboveAWeekNeedsForce) {
    write_tiny_exp1(work_);
    const std::string slow =
        " --set wedge.pro_margin=60 --set wedge.v=1e-6 --set wedge.s_max=4 --set wedge.output_ds=0.1";
    Result r = orodem("run tiny.toml --out r" + slow);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "more than 168 h");
    EXPECT_HAS(r.err, "--force");
    EXPECT_FALSE(fs::exists(work_ / "r"));
    r = orodem("sweep tiny.toml --vary wedge.mu_bp=0.1,0.3 --out sw" + slow);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_HAS(r.err, "a run of the sweep would take about");
    EXPECT_FALSE(fs::exists(work_ / "sw"));
    r = orodem("check tiny.toml" + slow);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "above 168 h: orodem run refuses it without --force");
    r = orodem("run tiny.toml --out r --force --set run.max_wall_minutes=0.005" + slow);
    EXPECT_EQ(r.status, 5) << r.err;
    EXPECT_HAS(r.out, "estimated run time: about");
}

// A layer of eleven million discs (below the size limit) is counted from its
// area, not generated: check answers at once (generating it took 5 s).
TEST_F(Cli, CheckOfAHugeLayerEstimatesItsDiscsInsteadOfGeneratingThem) {
    const std::string cfg = quote((fs::path(ORODEM_SOURCE_DIR) / "configs" / "settle.toml").string());
    const Result r = orodem("check " + cfg + " --set packing.length=1e6");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "(estimated from the layer's area, within 3%)");
    EXPECT_NEAR(number_after(r.out, "particles generated    = "), 1.13e7, 0.03 * 1.13e7);
}

TEST_F(Cli, CheckGivesTheInertialNumberAndWarnsOfAShortPlate) {
    // Paper-size Experiment 1: I = (v'/h0) (r_min + r_max) sqrt(1/(g h0)) =
    // (0.6/55) 1.5 / sqrt(9.81 55) = 7.04e-4. The plate: the critical taper
    // of the clusters' phi = 24.4 deg on phi_b = atan 0.1 is 2.40 deg (orodem
    // taper), so the front reaches h0 sqrt(16 / tan 2.40 deg) = 19.5 h0 by
    // S = 8 and 21.5 h0 is needed: pro_margin 22 passes, 20 is warned of.
    const std::string cfg = quote((fs::path(ORODEM_SOURCE_DIR) / "configs" / "exp1.toml").string());
    const Result ok = orodem("check " + cfg + " --set wedge.mu_bp=0.1");
    ASSERT_EQ(ok.status, 0) << ok.err;
    EXPECT_NEAR(number_after(ok.out, "inertial number I      = "), 0.6 / 55.0 * 1.5 / std::sqrt(9.81 * 55.0), 5e-3 * 7.04e-4);  // printed to 3 digits
    EXPECT_NEAR(number_after(ok.out, "the deformation front reaches about "),
                std::sqrt(16.0 / std::tan(2.40 * M_PI / 180.0)), 0.1);
    EXPECT_EQ(ok.err.find("warning"), std::string::npos) << ok.err;
    const Result short_plate = orodem("check " + cfg + " --set wedge.mu_bp=0.1 --set wedge.pro_margin=20");
    ASSERT_EQ(short_plate.status, 0) << short_plate.err;
    EXPECT_HAS(short_plate.err, "warning: wedge.pro_margin = 20 h0 is shorter than the 21.5 h0");
    EXPECT_HAS(ok.out, "(Coulomb base, mu_bp = 0.1)");
}

TEST_F(Cli, CheckGivesTheBasalDragAtFullSlipInColumnWeights) {
    // g_d m v'/dt for a disc of the mean radius R over rho g h0 2R:
    // pi g_d R v' / (2 g h0 dt), here 0.2 pi 0.75 0.1 / (2 9.81 55 dt).
    const std::string cfg = quote((fs::path(ORODEM_SOURCE_DIR) / "configs" / "exp1.toml").string());
    const std::string traction = " --set wedge.base_law='\"traction\"' --set wedge.v=0.1 --set wedge.inertia_floor=1";
    const Result on = orodem("check " + cfg + traction + " --set wedge.drag_gain=0.2"),
                 off = orodem("check " + cfg + traction);
    ASSERT_EQ(on.status, 0) << on.err;
    ASSERT_EQ(off.status, 0) << off.err;
    const std::string key = "basal drag at full slip = ";
    ASSERT_NE(on.out.find(key), std::string::npos) << on.out;
    const double dt = number_after(on.out, "dt                     = ");
    const double expected = 0.2 * M_PI * 0.75 * 0.1 / (2.0 * 9.81 * 55.0 * dt);  // 0.231 at dt = 1.89e-4 s
    EXPECT_NEAR(number_after(on.out, key), expected, 5e-3 * expected);  // printed to 3 digits
    EXPECT_EQ(off.out.find(key), std::string::npos) << off.out;  // no drag, no line
}

TEST_F(Cli, EveryShippedConfigPassesCheck) {
    // configs/ (paper size), configs/demo/, configs/mid/, configs/calibrate/:
    // a schema change that breaks a shipped config fails here, not at a user.
    int checked = 0;
    for (const auto& e : fs::recursive_directory_iterator(fs::path(ORODEM_SOURCE_DIR) / "configs")) {
        if (e.path().extension() != ".toml") continue;
        const Result r = orodem("check " + quote(e.path().string()));
        EXPECT_EQ(r.status, 0) << e.path() << ": " << r.err;
        ++checked;
    }
    EXPECT_GE(checked, 14);
}

TEST_F(Cli, AnUnwritableCacheIsAWarningAndTheRunIsTheSame) {
    // A cache folder that cannot be made (under /proc: refused to root too): the run settles, warns once naming
    // packing.cache_dir, and goes on with the layer in memory; its outputs are those of a run with a cache.
    auto tiny = [](const std::string& cache) {
        return "[run]\nexperiment = \"exp1\"\n[wedge]\nv = 0.2\ns_max = 0.2\noutput_ds = 0.1\npro_margin = 3.0\n"
               "retro_length = 3.0\n[packing]\nh0 = 6.0\ncache_dir = " + quote(cache) + "\n";
    };
    write(work_ / "ro.toml", tiny("/proc/orodem-no-cache"));
    write(work_ / "rw.toml", tiny((root_ / "cache").string()));
    const Result ro = orodem("run ro.toml --out ro --threads 1");
    ASSERT_EQ(ro.status, 0) << ro.err;
    EXPECT_HAS(ro.err, "was not cached");
    EXPECT_HAS(ro.err, "packing.cache_dir");
    ASSERT_EQ(orodem("run rw.toml --out rw --threads 1").status, 0);
    EXPECT_EQ(slurp(work_ / "ro" / "series.csv"), slurp(work_ / "rw" / "series.csv"));
}

TEST_F(Cli, NanAndNegativeCountsOnTheCommandLineExitTwo) {
    // CLI11's ranges let NaN through (it compares false with both ends), and a negative step count wrapped to
    // 1.8e19 steps: each is refused at once with one line.
    for (const char* cmd : {"bench pile --steps -1", "bench pile --steps 0", "taper --phi 30 --mu-b nan",
                            "taper --phi nan --mu-b 0.3", "taper --phi 30 --phib inf"}) {
        const Result r = orodem(cmd);
        EXPECT_EQ(r.status, 2) << cmd << ": " << r.err;
    }
}
