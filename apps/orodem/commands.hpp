// The subcommands of the orodem executable, one function each, called by
// main.cpp after CLI11 has parsed the arguments. Each returns the exit status
// and lets library errors propagate (main maps them to exit statuses).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace orodem {

struct CommonArgs {
    std::string config;
    std::vector<std::string> sets;
    int threads = -1;  // -1: from the config
};

int cmd_check(const CommonArgs& a);
/// resume: continue the run in out_arg from its newest usable checkpoint.
int cmd_run(const CommonArgs& a, const std::string& out_arg, bool resume = false);
int cmd_sweep(const CommonArgs& a, const std::string& vary, const std::string& out_arg);
int cmd_bench_pile(const std::string& pile, std::uint64_t steps, int threads);

/// orodem plot (cmd_plot.cpp): the S plots of one or more runs into out
/// (default RUN_DIR/figures/plots.png for one run, <common parent>/plots.png
/// for several); with seeds, the runs that differ only in their seeds as one
/// mean curve each over a band from their lowest to their highest value.
int cmd_plot(const std::vector<std::string>& run_dirs, const std::string& out, bool seeds = false);

/// orodem render (cmd_render.cpp): horizon and displacement pictures of the
/// snapshots nearest each S of `at` (all when empty) into RUN_DIR/figures/.
int cmd_render(const std::string& run_dir, const std::vector<double>& at, const std::string& format, int width);

/// orodem taper (cmd_taper.cpp): the critical surface slopes of a dry noncohesive
/// wedge (Dahlen 1984); exactly one of phi_b_deg and mu_b is given, the other is NaN.
int cmd_taper(double phi_deg, double phi_b_deg, double mu_b, double beta_deg);

/// orodem calibrate (cmd_calibrate.cpp): the calibration experiment of CONFIG into a new run
/// directory with report.md; check_calibration: what orodem check prints for one.
int cmd_calibrate(const CommonArgs& a, const std::string& out_arg);
struct Config;
int check_calibration(const Config& c);

/// orodem status (cmd_status.cpp): how far a wedge run got, how its last
/// piece ended, its newest checkpoint, the time left and how to continue it.
int cmd_status(const std::string& run_dir);
/// "42 s", "17 min" or "3.5 h".
std::string duration_text(double secs);

/// Throws ConfigError unless dir exists and holds a config.toml.
void require_run_dir(const std::string& dir);

}  // namespace orodem
