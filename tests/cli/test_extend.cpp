// orodem resume RUN --s-max S (docs/user-guide.md "Extending a run") with the
// real binary: a finished run extended to a larger S on the same incoming
// plate ends byte-identical to a run made from the start with wedge.s_max = S
// and wedge.pro_margin shortened by as much (its series, fault table,
// snapshots, run.pvd, config.toml and every picture); a plate too short for
// S, an S not beyond the run and a sweep's folder are refused with one line,
// exit 2, nothing changed.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli_util.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

class Extend : public OrodemTest {
protected:
    /// tiny.toml: S = 0.5 on a plate 7.5 h0 beyond the S point (s_max + pro_margin), outputs every 0.25.
    void SetUp() override {
        OrodemTest::SetUp();
        write(work_ / "tiny.toml", "[run]\nexperiment = \"exp1\"\n"
                                   "[wedge]\nv = 0.2\ns_max = 0.5\noutput_ds = 0.25\npro_margin = 7.0\n"
                                   "retro_length = 3.0\n[packing]\nh0 = 6.0\ncache_dir = \"" +
                                       (work_ / "cache").string() + "\"\n");
    }

    /// Every file of a run directory but log.txt, events.csv and checkpoint/, as (name, bytes).
    static std::vector<std::pair<std::string, std::string>> outputs(const fs::path& dir) {
        std::vector<std::pair<std::string, std::string>> v;
        for (const auto& e : fs::recursive_directory_iterator(dir)) {
            const std::string rel = fs::relative(e.path(), dir).string();
            if (!e.is_regular_file() || rel == "log.txt" || rel == "events.csv" || rel.rfind("checkpoint", 0) == 0)
                continue;
            v.emplace_back(rel, slurp(e.path()));
        }
        std::sort(v.begin(), v.end());
        return v;
    }
};

TEST_F(Extend, ToALargerSIsTheRunMadeWithItFromTheStart) {
    ASSERT_EQ(orodem("run tiny.toml --out ext/r --threads 1").status, 0);
    // From the start: S = 1 on the same plate (7.5 = 1 + 6.5); the same folder name (plots.png's title).
    Result r = orodem("run tiny.toml --out full/r --threads 1 --set wedge.s_max=1 --set wedge.pro_margin=6.5");
    ASSERT_EQ(r.status, 0) << r.err;
    r = orodem("resume ext/r --s-max 1 --threads 1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "extending ext/r from S = 0.5 to S = 1 (wedge.pro_margin 7 -> 6.5, the plate unchanged)");
    expect_same_outputs(work_ / "full" / "r", work_ / "ext" / "r");
    const auto a = outputs(work_ / "full" / "r"), b = outputs(work_ / "ext" / "r");
    ASSERT_EQ(a.size(), b.size());
    int strain_maps = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(b[i].first, a[i].first);
        EXPECT_TRUE(b[i].second == a[i].second) << b[i].first;  // config.toml, plots.png and strain maps too
        strain_maps += a[i].first.rfind("figures/strain_", 0) == 0 ? 1 : 0;
    }
    EXPECT_EQ(strain_maps, 4);
    EXPECT_HAS(slurp(work_ / "ext" / "r" / "log.txt"), "extended from wedge.s_max = 0.5 to 1 on the same plate");
    // The extended run is an ordinary run of its config.toml now.
    r = orodem("status ext/r");
    EXPECT_HAS(r.out, "S_max = 1,");
    r = orodem("resume ext/r --threads 1");
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(Extend, RefusedWhenThePlateIsTooShortOrSIsNotBeyondTheRun) {
    ASSERT_EQ(orodem("run tiny.toml --out r --threads 1").status, 0);
    const auto before = outputs(work_ / "r");
    const std::vector<std::string> ckpts = names_in(work_ / "r" / "checkpoint");
    // S = 2 would leave 5.5 h0 of plate ahead of the trailing wall; the estimate asks for 7.4 h0.
    Result r = orodem("resume r --s-max 2");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "the run's incoming plate is 7.5 h0 long (wedge.s_max + wedge.pro_margin = 0.5 + 7;");
    EXPECT_HAS(r.err, "at S = 2 it would leave 5.50 h0 ahead of the trailing wall, less than the 7.37 h0");
    EXPECT_HAS(r.err, "this plate can be extended to S = 1.25 at most");
    EXPECT_HAS(r.err, "nothing was changed");
    r = orodem("resume r --s-max 0.6");  // the next output (0.75) is not reached
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, "the run goes to S = 0.5 already");
    EXPECT_EQ(orodem("resume r --s-max 1 --jobs 2").status, 2);
    EXPECT_TRUE(outputs(work_ / "r") == before);
    EXPECT_EQ(names_in(work_ / "r" / "checkpoint"), ckpts);
    // A sweep's folder: each member is extended on its own.
    fs::create_directories(work_ / "sw");
    write(work_ / "sw" / "sweep.toml", "");
    r = orodem("resume sw --s-max 1");
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, "is a sweep's folder; --s-max extends one run");
}

}  // namespace
