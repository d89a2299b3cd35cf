// The run wing's records: the series column table (its header and formats
// are part of the run-directory contract), events.csv written with log.txt
// and read back, a log.txt of an older run read as events, and the
// result-neutral keys leaving the checkpoint hash and the config comparison.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <algorithm>
#include <limits>

#include <unistd.h>

#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/run/run_log.hpp"
#include "orodem/run/series_columns.hpp"

namespace fs = std::filesystem;
using namespace orodem;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("orodem-records-" + std::to_string(::getpid()) + "-" +
                                             std::to_string(reinterpret_cast<std::uintptr_t>(this)));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
};

}  // namespace

TEST(SeriesColumns, HeaderIsTheRunDirectoryContract) {
    // The header that every series.csv since the retroside columns carries
    // (README "Run directory"); python/orodem and older runs read it by name.
    EXPECT_EQ(series_header(),
              "step,time,S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,kinetic_energy,contacts,"
              "max_overlap_ratio,toe_pro_x_over_h0,toe_retro_x_over_h0,base_traction,discs_on_base,"
              "discs_sliding_on_base,fixed_discs,mean_overlap_ratio,max_speed,base_normal_force,trailing_wall_push,"
              "beta_inner_deg,beta_outer_deg,retro_break_x_over_h0,active_pro_faults,active_retro_faults,"
              "front_thrust_x_over_h0,stage,alpha_se_deg,beta_se_deg,section_push,decoupling_x_over_h0");
    EXPECT_EQ(series_header(true),
              "S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,toe_pro_x_over_h0,toe_retro_x_over_h0,"
              "beta_inner_deg,beta_outer_deg,retro_break_x_over_h0,alpha_se_deg,beta_se_deg,decoupling_x_over_h0");
}

TEST(SeriesColumns, RowFormatsAndLeadingColumns) {
    SeriesRow r;
    r.step = 123456789012ULL;
    r.time = 1.0 / 3.0;
    r.S = 0.25;
    r.h0 = 4.0;
    r.m.H_over_h0 = 1.5;
    r.m.alpha_deg = std::numeric_limits<double>::quiet_NaN();
    r.m.toe_pro_x = -10.0;  // -2.5 h0
    r.contacts = 77;
    const std::string line = series_line(r);
    EXPECT_EQ(line.rfind("123456789012,0.333333333,0.250000,1.5,nan,", 0), 0u) << line;
    EXPECT_NE(line.find(",77,"), std::string::npos) << line;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 31) << line;
    r.pro_faults = 2, r.retro_faults = 1, r.front_thrust_x = -12.0, r.stage = 2;
    r.m.alpha_se_deg = 0.25, r.m.beta_se_deg = 1.5, r.section_push = 2.5e7, r.decoupling_x = -10.0;
    const std::string tail = series_line(r);
    EXPECT_EQ(tail.substr(tail.size() - 31), ",2,1,-3,2,0.25,1.5,2.5e+07,-2.5") << tail;
    EXPECT_EQ(series_line(r, 3), "123456789012,0.333333333,0.250000");
    EXPECT_EQ(series_line(r, static_cast<std::size_t>(-1), true).rfind("0.250000,1.5,nan,0,0,0,-2.5,", 0), 0u);
}

TEST(RunLog, EventsAreWrittenWithTheLogAndReadBack) {
    TempDir d;
    const std::string dir = d.path.string();
    {
        RunLog log(dir);
        EventRecord start;
        start.kind = RunEvent::start;
        start.dt = 2.5e-4;
        start.text = "orodem 1.0 run of a.toml (exp1) with 2 threads";
        log.event(start);
        log.line("dt = 0.00025 s, \"quoted\", with, commas");
        EventRecord out;
        out.kind = RunEvent::output;
        out.step = 4000;
        out.S = 0.25;
        out.steps_per_s = 1234.5;
        out.text = "S = 0.250: H/h0 = 1.0";
        log.event(out);
        EventRecord end;
        end.kind = RunEvent::interrupted;
        end.step = 4100;
        end.S = 0.2563;
        end.wall_s = 12.5;
        end.text = "interrupted by SIGTERM at step 4100 (S = 0.2563) after 12.5 s wall; checkpoint \"x\", y";
        log.event(end);
    }
    const std::string text = read_file(dir + "/log.txt");
    EXPECT_NE(text.find("dt = 0.00025 s, \"quoted\", with, commas\n"), std::string::npos);
    const auto ev = read_events(dir);
    ASSERT_EQ(ev.size(), 3u);
    EXPECT_EQ(ev[0].kind, RunEvent::start);
    EXPECT_DOUBLE_EQ(ev[0].dt, 2.5e-4);
    EXPECT_EQ(ev[1].kind, RunEvent::output);
    EXPECT_EQ(ev[1].step, 4000u);
    EXPECT_DOUBLE_EQ(ev[1].steps_per_s, 1234.5);
    EXPECT_TRUE(std::isnan(ev[1].wall_s));
    EXPECT_EQ(ev[2].kind, RunEvent::interrupted);
    EXPECT_DOUBLE_EQ(ev[2].wall_s, 12.5);
    EXPECT_EQ(ev[2].text, "interrupted by SIGTERM at step 4100 (S = 0.2563) after 12.5 s wall; checkpoint \"x\", y");
    ASSERT_NE(last_piece_event(ev), nullptr);
    EXPECT_EQ(last_piece_event(ev)->kind, RunEvent::interrupted);
}

TEST(RunLog, AnOlderRunsLogIsReadAsEventsAndSeedsEventsCsv) {
    TempDir d;
    const std::string dir = d.path.string();
    write_file_atomic(dir + "/log.txt",
                      "orodem 0.9 run of a.toml (exp1) with 1 threads\n"
                      "dt = 0.0002 s, stability limit 0.001 s (margin 5.00x), t_c = 22.0 steps\n"
                      "S = 0.000: H/h0 = 0.1; 0 discs asleep; 0 steps/s\n"
                      "S = 0.250: H/h0 = 0.2; 10 discs asleep; 2500 steps/s\n"
                      "stopped at the wall-time limit run.max_wall_minutes = 1 at step 5000 (S = 0.3) after 61.5 s "
                      "wall; checkpoint c.bin\n"
                      "resumed by orodem 0.9 from c.bin at step 5000 (S = 0.3000) with 1 threads\n"
                      "UNSTABLE: step 6000 (S = 0.4): disc 3 ...\n");
    const auto ev = read_events(dir);  // no events.csv: from log.txt
    ASSERT_EQ(ev.size(), 6u);
    EXPECT_DOUBLE_EQ(ev[0].dt, 0.0002);
    EXPECT_DOUBLE_EQ(ev[2].S, 0.25);
    EXPECT_DOUBLE_EQ(ev[2].steps_per_s, 2500.0);
    EXPECT_EQ(ev[3].kind, RunEvent::time_limit);
    EXPECT_DOUBLE_EQ(ev[3].wall_s, 61.5);
    EXPECT_EQ(ev[4].kind, RunEvent::resume);
    EXPECT_EQ(last_piece_event(ev)->kind, RunEvent::unstable);
    { RunLog log(dir); }  // a resume by this orodem: events.csv made from the log first
    ASSERT_TRUE(fs::exists(d.path / "events.csv"));
    const auto again = read_events(dir);
    ASSERT_EQ(again.size(), ev.size());
    for (std::size_t k = 0; k < ev.size(); ++k) {
        EXPECT_EQ(again[k].kind, ev[k].kind) << k;
        EXPECT_EQ(again[k].text, ev[k].text) << k;
    }
}

TEST(ResultNeutralKeys, LeaveTheHashAndTheComparisonButTheOlderHashIsAccepted) {
    const std::string toml = "[run]\nexperiment = \"exp1\"\n";
    const Config base = parse_config(toml, "x.toml");
    for (const ResultNeutralKey& k : kResultNeutralKeys) {
        const std::string key = std::string(k.section) + "." + k.key;
        EXPECT_TRUE(is_result_neutral(key)) << key;
    }
    EXPECT_FALSE(is_result_neutral("wedge.v"));
    const Config other_cache = parse_config(toml, "x.toml", {{"packing.cache_dir", "\"/tmp/elsewhere\""}});
    const Config more_threads = parse_config(toml, "x.toml", {{"run.threads", "3"}, {"run.max_wall_minutes", "5"}});
    EXPECT_EQ(config_hash(other_cache), config_hash(base));
    EXPECT_EQ(config_hash(more_threads), config_hash(base));
    EXPECT_EQ(first_config_difference(base, other_cache), "");
    EXPECT_EQ(first_config_difference(base, more_threads), "");
    const Config faster = parse_config(toml, "x.toml", {{"wedge.v", "0.2"}});
    EXPECT_NE(config_hash(faster), config_hash(base));
    EXPECT_NE(first_config_difference(base, faster).find("[wedge] v = "), std::string::npos)
        << first_config_difference(base, faster);
    // Before the table, packing.cache_dir was hashed: such a checkpoint is accepted.
    const AcceptedHashes h = accepted_config_hashes(other_cache);
    EXPECT_EQ(h.current, config_hash(base));
    EXPECT_NE(h.earlier, h.current);
    EXPECT_TRUE(h.accepts(h.earlier));
    EXPECT_EQ(accepted_config_hashes(base).earlier, accepted_config_hashes(base).current);
}
