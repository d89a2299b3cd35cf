// `orodem sweep`: one run per value into DIR/<key>=<value>/, the settled
// layer settled once and reused, and the overlay plot at the end.
#include <gtest/gtest.h>

#include "cli/cli_util.hpp"
#include <stdlib.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

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
