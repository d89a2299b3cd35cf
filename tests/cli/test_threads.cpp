// SPEC §5, issue #6 point 4: the same config and seed give byte-identical
// series.csv, snapshots and pictures at 1, 2, 3 and 4 threads. The layer has
// about 4,600 discs, above the size (core/parallel.hpp: kParallelMin = 4096)
// from which the step loop's disc and pair loops run in parallel, so every
// thread count really splits the work differently.
#include <gtest/gtest.h>

#include "cli/cli_util.hpp"

#include <string>

namespace fs = std::filesystem;
using namespace cli;

TEST(Threads, SeriesSnapshotsAndPicturesAreByteIdenticalAt1To4Threads) {
    std::string tmpl = (fs::temp_directory_path() / "orodem-threads-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    const fs::path root = tmpl;
    // A long thin layer: many discs, quick to settle, a few thousand steps.
    write(root / "wide.toml", "[run]\nexperiment = \"exp1\"\n"
                              "[wedge]\nv = 0.3\ns_max = 0.1\noutput_ds = 0.0125\npro_margin = 300.0\nretro_length = 6.0\n"
                              "[packing]\nh0 = 6.0\nr_min = 0.5\nr_max = 1.0\ncache_dir = \"" +
                                  (root / "cache").string() + "\"\n");
    // Sleeping zones (engine/sleep.cpp) change which slot and pair ranges
    // are stepped: the same comparison with them on, at 1 and 3 threads.
    for (int threads : {1, 3}) {
        const fs::path run = root / (std::string("sleep") + std::to_string(threads));
        const Proc p = start({"run", (root / "wide.toml").string(), "--out", run.string(), "--threads",
                              std::to_string(threads), "--set", "wedge.sleep=true", "--set",
                              "wedge.s_max=0.2"},
                             run.string());
        ASSERT_EQ(wait_for(p), 0) << slurp(p.err);
        if (threads > 1) expect_same_outputs(root / "sleep1", run);
        // The plate is at belt speed by S = 0.2 and most of it asleep.
        const std::string log = slurp(run / "log.txt");
        const auto at = log.rfind(" discs asleep");
        ASSERT_NE(at, std::string::npos);
        EXPECT_GT(std::stoul(log.substr(log.rfind("; ", at) + 2)), 1000u) << log.substr(log.rfind("; ", at));
    }
    for (int threads = 1; threads <= 4; ++threads) {
        const fs::path run = root / (std::string("t") + std::to_string(threads));
        const Proc p = start({"run", (root / "wide.toml").string(), "--out", run.string(), "--threads",
                              std::to_string(threads)},
                             run.string());
        ASSERT_EQ(wait_for(p), 0) << slurp(p.err);
        EXPECT_NE(slurp(run / "log.txt").find(std::string("with ") + std::to_string(threads) + " threads"), std::string::npos);
        if (threads == 1) {
            const std::string log = slurp(run / "log.txt");
            const auto at = log.find("exp1: ");
            ASSERT_NE(at, std::string::npos);
            EXPECT_GT(std::stoul(log.substr(at + 6)), 4096u) << "too few discs for the parallel loops";
        } else {
            expect_same_outputs(root / "t1", run);
        }
    }
    std::error_code ec;
    fs::remove_all(root, ec);
}
