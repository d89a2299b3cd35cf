// The push-wall sandbox (run.experiment = "sandbox", issue #67) with the real
// binary: the config errors are one line with exit 2 and write nothing; a
// tiny flat sandbox runs and, interrupted after a checkpoint and resumed,
// gives the bytes of an uninterrupted run; the tiny slope-cut wedge (GeoMod
// 2008 Exp. 1 at a small size) slides without changing its slope, pushed by
// a wall force of about μ_b times its weight.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli/checkpoint_util.hpp"
#include "cli/cli_util.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

class Sandbox : public OrodemTest {
protected:
    /// A flat layer 4 h0 long (h0 = 6 m), pushed to S = 0.5.
    fs::path config(const std::string& name, const std::string& extra = "") {
        const fs::path p = work_ / name;
        write(p, "[run]\nexperiment = \"sandbox\"\n"
                 "[wedge]\nv = 0.3\ns_max = 0.5\noutput_ds = 0.1\nmu_bp = 0.3\n"
                 "[sandbox]\nlength = 4.0\n"
                 "[packing]\nh0 = 6.0\ncache_dir = \"" + (work_ / "cache").string() + "\"\n" + extra);
        return p;
    }
};


}  // namespace

TEST_F(Sandbox, ConfigErrorsAreOneLineWithExit2AndWriteNothing) {
    struct Case {
        std::string set, says;
    };
    const std::vector<Case> cases = {
        {"--set sandbox.length=0.5", "sandbox.length"},
        {"--set sandbox.length=0.8 --set wedge.s_max=0.5", "sandbox.length"},
        {"--set sandbox.length=3 --set wedge.s_max=2.8", "must be at least wedge.s_max + 0.5"},
        {"--set sandbox.surface_slope_deg=70", "sandbox.surface_slope_deg"},
        {"--set sandbox.surface_slope_deg=-5", "sandbox.surface_slope_deg"},
        {"--set sandbox.width=3", "unknown key 'sandbox.width'"},
        {"--set wedge.pro_margin=4", "unknown key 'wedge.pro_margin'"},
        {"--set wedge.retro_length=4", "unknown key 'wedge.retro_length'"},
    };
    const fs::path cfg = config("sandbox.toml");
    int k = 0;
    for (const Case& c : cases) {
        const std::string out = "bad" + std::to_string(k++);
        const Result r = orodem("run " + quote(cfg.string()) + " --out " + out + " " + c.set);
        EXPECT_EQ(r.status, 2) << c.set << r.err;
        EXPECT_HAS(r.err, c.says);
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(work_ / out)) << c.set;
    }
    // [sandbox] belongs to the sandbox alone; [surface] is not for it yet.
    write(work_ / "exp1.toml", "[run]\nexperiment = \"exp1\"\n[sandbox]\nlength = 4.0\n");
    Result r = orodem("check exp1.toml");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_HAS(r.err, "only read by run.experiment = \"sandbox\"");
    const fs::path eroding = config("eroding.toml", "[surface]\nlaw = \"none\"\n");
    r = orodem("run " + quote(eroding.string()) + " --out E");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_HAS(r.err, "not available for run.experiment = \"sandbox\"");
    EXPECT_FALSE(fs::exists(work_ / "E"));
}

TEST_F(Sandbox, ATinySandboxRunsAndResumesToTheBytesOfAnUninterruptedRun) {
    const fs::path cfg = config("sandbox.toml");
    const Result a = orodem("run " + quote(cfg.string()) + " --out A --threads 1");
    ASSERT_EQ(a.status, 0) << a.err;
    const auto rows = csv_rows(slurp(work_ / "A" / "series.csv"));
    ASSERT_EQ(rows.size(), 7u);  // header and S = 0, 0.1, ..., 0.5
    const auto& h = rows.front();
    const std::size_t push = csv_column(h, "trailing_wall_push"), S = csv_column(h, "S");
    EXPECT_NEAR(std::stod(rows.back()[S]), 0.5, 1e-3);  // whole steps
    EXPECT_GT(std::stod(rows.back()[push]), 0.0) << "the wall does not push the layer";
    EXPECT_TRUE(fs::exists(work_ / "A" / "run.pvd"));
    EXPECT_TRUE(fs::exists(work_ / "A" / "faults.csv"));

    const fs::path run = work_ / "B";
    const Proc p = start({"run", cfg.string(), "--out", run.string(), "--threads", "1"}, work_ / "B");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGTERM})) << slurp(p.err);
    ASSERT_EQ(wait_for(p), 143) << slurp(p.err);
    ASSERT_LT(slurp(run / "series.csv").size(), slurp(work_ / "A" / "series.csv").size()) << "was not interrupted";
    const Result r = orodem("run " + quote((run / "config.toml").string()) + " --out B --resume --threads 2");
    ASSERT_EQ(r.status, 0) << r.err;
    expect_same_outputs(work_ / "A", run);
}
