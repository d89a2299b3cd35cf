// Erosion and sedimentation in the running wedge ([surface],
// run/surface_erosion.hpp) with the real binary on the tiny exp1 (h0 = 6 m):
// the ledger closes at every output, with and without sedimentation,
// eroded.csv lists every removed disc, an eroding (and a sedimenting) run
// interrupted and resumed gives the bytes of an uninterrupted one (1 and 2
// threads), and the config errors are one line with exit 2. (Without [surface] the outputs
// are those of earlier versions: tests/physics/test_golden.cpp and
// scripts/same-outputs.)
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/checkpoint_util.hpp"
#include "cli/cli_util.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

// Elevation law, fast enough that the tiny wedge loses particles from S ≈ 1.
const std::string kElevation = "[surface]\nlaw = \"elevation\"\nk = 2.0\n";
// The same with both forelands filled toward 0.3 h0 at 0.5 h0 per unit S
// (a reserve that lasts: in the tiny model a cluster is half a column's
// fill, and each column rounds its request to whole particles).
const std::string kSediment =
    kElevation + "sediment = \"both\"\nbase_level = 0.3\nsediment_rate = 0.5\nsediment_reserve = 20.0\n";
const std::string kLonger = " --set wedge.s_max=1.5 --set wedge.pro_margin=4 --set wedge.output_ds=0.1";

class Surface : public OrodemTest {
protected:
    fs::path config(const std::string& name, const std::string& extra) { return write_tiny_exp1_with(work_, name, extra); }
    /// A run of the tiny exp1 with `table`, stopped at its first checkpoint
    /// after step 0 (S = 1.2) at 1 thread and resumed at 2, gives the bytes of
    /// an uninterrupted run at `threads` (eroded.csv included); `reached`
    /// checks that the stopped run got far enough.
    void expect_resumed_run_same(const std::string& table, const char* threads,
                                 const std::function<void(const fs::path&)>& reached) {
        const fs::path cfg = config("surface.toml", table);
        std::string text = slurp(cfg);
        text.replace(text.find("[run]\n"), 6, "[run]\ncheckpoint_every_outputs = 12\n");
        write(cfg, text);
        ASSERT_EQ(orodem("run " + quote(cfg.string()) + " --out A --threads " + threads + kLonger).status, 0);
        const fs::path run = work_ / "B";
        const Proc p = start({"run", cfg.string(), "--out", run.string(), "--threads", "1", "--set", "wedge.s_max=1.5",
                              "--set", "wedge.pro_margin=4", "--set", "wedge.output_ds=0.1"},
                             root_ / "B");
        ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGTERM})) << slurp(p.err);
        ASSERT_EQ(wait_for(p), 143) << slurp(p.err);
        ASSERT_LT(slurp(run / "series.csv").size(), slurp(work_ / "A" / "series.csv").size()) << "was not interrupted";
        reached(run);
        if (HasFatalFailure()) return;
        const Result r = orodem("run " + quote((run / "config.toml").string()) + " --out B --resume --threads 2");
        ASSERT_EQ(r.status, 0) << r.err;
        expect_same_outputs(work_ / "A", run);
        EXPECT_EQ(slurp(run / "eroded.csv"), slurp(work_ / "A" / "eroded.csv"));
    }
};


/// The ledger of every row of series.csv (rows[0] its header) closes:
/// |influx − eroded + deposited − stored| ≤ 0.5% of the cumulative influx,
/// recomputed and as ledger_error says.
void expect_ledger_closes(const std::vector<std::vector<std::string>>& rows) {
    const auto& h = rows.front();
    const std::size_t in = csv_column(h, "influx_area"), er = csv_column(h, "eroded_area"), st = csv_column(h, "stored_area"),
                      dep = csv_column(h, "deposited_area"), err = csv_column(h, "ledger_error");
    for (std::size_t k = 1; k < rows.size(); ++k) {
        const double influx = std::stod(rows[k][in]), eroded = std::stod(rows[k][er]), stored = std::stod(rows[k][st]),
                     deposited = std::stod(rows[k][dep]);
        EXPECT_LE(std::fabs(influx - eroded + deposited - stored), 0.005 * influx + 1e-12) << "row " << k;
        EXPECT_LE(std::fabs(std::stod(rows[k][err])), 0.005 * influx + 1e-12) << "row " << k;
    }
}

}  // namespace

TEST_F(Surface, TheLedgerClosesAtEveryOutputAndErodedCsvListsEveryRemovedDisc) {
    const fs::path cfg = config("eroding.toml", kElevation);
    const Result r = orodem("run " + quote(cfg.string()) + " --out A --threads 2" + kLonger);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto rows = csv_rows(slurp(work_ / "A" / "series.csv"));
    ASSERT_GE(rows.size(), 16u);
    const auto& h = rows.front();
    const std::size_t in = csv_column(h, "influx_area"), er = csv_column(h, "eroded_area"), nd = csv_column(h, "eroded_discs"),
                      asked = csv_column(h, "erosion_asked"), S = csv_column(h, "S");
    expect_ledger_closes(rows);
    for (std::size_t k = 1; k < rows.size(); ++k) {
        EXPECT_NEAR(std::stod(rows[k][in]), std::stod(rows[k][S]), 1e-5) << k;
        EXPECT_EQ(std::stod(rows[k][csv_column(h, "deposited_area")]), 0.0) << k;
    }
    const auto& last = rows.back();
    const double eroded = std::stod(last[er]);
    EXPECT_GT(eroded, 0.0) << "nothing was eroded";
    // The taken area follows the asked one within the columns' remainders.
    EXPECT_NEAR(eroded, std::stod(last[asked]), 0.5 * std::stod(last[asked]));
    const auto e = csv_rows(slurp(work_ / "A" / "eroded.csv"));
    ASSERT_FALSE(e.empty());
    EXPECT_EQ(e.front().size(), 6u);
    EXPECT_EQ(e.size() - 1, static_cast<std::size_t>(std::stoul(last[nd])));
    for (std::size_t k = 1; k < e.size(); ++k) {
        EXPECT_GE(std::stod(e[k][3]), std::stod(e[k][4]) - 1e-12) << "max burial below the initial depth, row " << k;
        EXPECT_GT(std::stod(e[k][2]), 0.0);
    }
}

TEST_F(Surface, AnInterruptedErodingRunResumesToTheBytesOfAnUninterruptedOne) {
    // The checkpoint at S = 1.2 comes after the first particles were removed.
    expect_resumed_run_same(kElevation, "1", [](const fs::path& run) {
        ASSERT_GT(csv_rows(slurp(run / "eroded.csv")).size(), 1u) << "interrupted before any erosion";
    });
}

TEST_F(Surface, WithSedimentationTheLedgerClosesAtEveryOutputAndTheSnapshotsCarryThePaths) {
    const fs::path cfg = config("sedimenting.toml", kSediment);
    const Result r = orodem("run " + quote(cfg.string()) + " --out A --threads 2" + kLonger);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto rows = csv_rows(slurp(work_ / "A" / "series.csv"));
    ASSERT_GE(rows.size(), 16u);
    const auto& h = rows.front();
    const std::size_t er = csv_column(h, "eroded_area"), dep = csv_column(h, "deposited_area"),
                      nd = csv_column(h, "deposited_discs"), asked = csv_column(h, "deposit_asked");
    expect_ledger_closes(rows);
    // Deposits land without an overlap spike: no pair beyond run.warn_overlap_ratio (0.1 R) at any output.
    for (std::size_t k = 1; k < rows.size(); ++k)
        EXPECT_LT(std::stod(rows[k][csv_column(h, "max_overlap_ratio")]), 0.1) << "row " << k;
    const auto& last = rows.back();
    const double deposited = std::stod(last[dep]), eroded = std::stod(last[er]);
    EXPECT_GT(deposited, 0.0) << "nothing was deposited";
    EXPECT_GT(eroded, 0.0) << "nothing was eroded";
    EXPECT_GT(std::stoul(last[nd]), 0u);
    // The placed area follows the asked one within the columns' remainders
    // (at most half a particle each: 0.1 h0² here, 25 columns).
    EXPECT_NEAR(deposited, std::stod(last[asked]), 2.5);
    // The snapshots carry the paths (after every other array).
    const std::string snap = slurp(work_ / "A" / "snapshots" / "S01.500.vtu");
    for (const char* name : {"birth_S", "max_burial_depth", "erosion_S"})
        EXPECT_NE(snap.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
    EXPECT_LT(snap.find("Name=\"rel_disp_abs\""), snap.find("Name=\"birth_S\""));
    // eroded.csv: the birth S of each removed disc (0 for the layer's, the
    // deposition S for a deposit's) never after its erosion S.
    const auto e = csv_rows(slurp(work_ / "A" / "eroded.csv"));
    ASSERT_GT(e.size(), 1u);
    for (std::size_t k = 1; k < e.size(); ++k) EXPECT_LE(std::stod(e[k][5]), std::stod(e[k][2])) << "row " << k;
    // The pictures: growth strata by their deposition S, the largest burial depth.
    for (const std::string by : {"deposition", "burial"}) {
        const Result p = orodem("render A --out " + by + ".png --at 1.5 --color-by " + by);
        EXPECT_EQ(p.status, 0) << p.err;
        EXPECT_TRUE(fs::exists(work_ / (by + ".png"))) << by;
    }
}

TEST_F(Surface, AnInterruptedSedimentingRunResumesToTheBytesOfAnUninterruptedOne) {
    // Both forelands filled: the checkpoint at S = 1.2 comes after particles
    // were removed and deposited; the uninterrupted run at 2 threads.
    expect_resumed_run_same(kSediment, "2", [](const fs::path& run) {
        const auto rows = csv_rows(slurp(run / "series.csv"));
        ASSERT_GT(std::stod(rows.back()[csv_column(rows.front(), "deposited_area")]), 0.0) << "interrupted before any deposit";
        ASSERT_GT(csv_rows(slurp(run / "eroded.csv")).size(), 1u) << "interrupted before any erosion";
    });
}

TEST_F(Surface, ConfigErrorsAreOneLineWithExit2) {
    struct Case {
        std::string extra, says;
    };
    const std::vector<Case> cases = {
        {"[surface]\nk = 0.3\n", "missing required key 'surface.law'"},
        {"[surface]\nlaw = \"elevaton\"\n", "did you mean 'elevation'"},
        {"[surface]\nlaw = \"slope\"\nk = 0.3\n", "unknown key 'surface.k'"},
        {"[surface]\nlaw = \"elevation\"\nk = -1\n", "surface.k"},
        {"[surface]\nlaw = \"elevation\"\ninterval_steps = 0\n", "surface.interval_steps"},
        {"[surface]\nlaw = \"diffusion\"\nends = \"open\"\n", "surface.ends"},
        {"surface = 3\n", "must be a table [surface]"},
        {"[surface]\nlaw = \"none\"\nsediment = \"front\"\n", "surface.sediment"},
        {"[surface]\nlaw = \"none\"\nbase_level = 0.3\n", "unknown key 'surface.base_level'"},
        {"[surface]\nlaw = \"none\"\nsediment = \"pro\"\nsediment_rate = -1\n", "surface.sediment_rate"},
        {"[surface]\nlaw = \"none\"\nsediment = \"pro\"\nsediment_material = \"sand\"\n", "surface.sediment_material"},
    };
    int k = 0;
    for (const Case& c : cases) {
        const fs::path cfg = config("bad" + std::to_string(k++) + ".toml", "");
        // Top-level keys go before the first table.
        write(cfg, c.extra.rfind("[", 0) == 0 ? slurp(cfg) + c.extra : c.extra + slurp(cfg));
        const Result r = orodem("check " + quote(cfg.string()));
        EXPECT_EQ(r.status, 2) << c.extra << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << c.extra << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    // A table the wedge experiments alone read.
    write(work_ / "settle.toml", "[run]\nexperiment = \"settle\"\n[surface]\nlaw = \"none\"\n");
    const Result r = orodem("check settle.toml");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("only read by the wedge experiments"), std::string::npos) << r.err;
}

TEST_F(Surface, WithoutTheTableNothingIsResolvedAndTheColumnsAreTheOldOnes) {
    const fs::path plain = config("plain.toml", ""), off = config("off.toml", "[surface]\nlaw = \"none\"\n");
    ASSERT_EQ(orodem("run " + quote(plain.string()) + " --out A --threads 2").status, 0);
    ASSERT_EQ(orodem("run " + quote(off.string()) + " --out B --threads 2").status, 0);
    EXPECT_EQ(slurp(work_ / "A" / "config.toml").find("surface"), std::string::npos);
    EXPECT_FALSE(fs::exists(work_ / "A" / "eroded.csv"));
    // No paths in its snapshots: the growth strata cannot be drawn (exit 2, one line, nothing written).
    const Result p = orodem("render A --out strata.png --color-by deposition");
    EXPECT_EQ(p.status, 2) << p.err;
    EXPECT_NE(p.err.find("holds no birth_S array"), std::string::npos) << p.err;
    EXPECT_EQ(std::count(p.err.begin(), p.err.end(), '\n'), 1) << p.err;
    EXPECT_FALSE(fs::exists(work_ / "strata.png"));
    EXPECT_NE(slurp(work_ / "B" / "config.toml").find("[surface]"), std::string::npos);
    // law = "none": the same run, with the ledger's columns after the others.
    const auto a = csv_rows(slurp(work_ / "A" / "series.csv")), b = csv_rows(slurp(work_ / "B" / "series.csv"));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(b[k].size(), a[k].size() + 10) << k;
        EXPECT_TRUE(std::equal(a[k].begin(), a[k].end(), b[k].begin())) << k;
    }
}
