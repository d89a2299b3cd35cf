// The subcommands of the orodem executable, one function each, called by
// main.cpp after CLI11 has parsed the arguments. Each returns the exit status
// and lets library errors propagate (main maps them to exit statuses).
#pragma once

#include <csignal>
#include <cstdint>
#include <string>
#include <vector>

namespace orodem {

struct CommonArgs {
    std::string config;
    std::vector<std::string> sets;
    int threads = -1;  // -1: from the config
};

struct Config;

int cmd_check(const CommonArgs& a);
/// resume: continue the run in out_arg from its newest usable checkpoint.
int cmd_run(const CommonArgs& a, const std::string& out_arg, bool resume = false);

/// The config of a, its --set and --threads applied (load_config: ConfigError if bad).
Config load(const CommonArgs& a);
/// A one-line warning when the wedge's incoming plate is shorter than
/// plate_estimate says the deformation front needs; "" otherwise.
std::string short_plate_warning(const Config& c);
/// Throws ConfigError unless c can run: a stable timestep, and the base law's checks (check_wedge_base).
void check_runnable(const Config& c);
/// Applies run.threads (0: all cores).
void set_threads(const Config& c);
/// A new run directory: `out` if given (absent or empty, else ConfigError), else
/// runs/<config stem>, runs/<stem>-2, ... whichever is free first.
std::string choose_run_dir(const std::string& out, const std::string& config_path);
/// Runs c from the beginning in dir (which exists: empty, or holding only its config.toml).
int start_run_in(const Config& c, const std::string& dir);
/// Continues the wedge run in dir from its newest usable checkpoint (from the
/// beginning when it has none); c must be its config.
int resume_run(const Config& c, const std::string& dir);
/// A log.txt line that ends a piece of a run ("finished: ... s wall",
/// "interrupted by ...", a wall-time or health stop): written by the run
/// loop, added up by orodem status, kept by a resume.
bool ends_a_piece(const std::string& line);
/// ends_a_piece, or a resumed piece's start line ("resumed by ...").
bool starts_or_ends_a_piece(const std::string& line);

/// SIGINT/SIGTERM while a run or a sweep goes on: the handler only records
/// the first signal (the run stops with a checkpoint); a second is ignored
/// so that the shutdown checkpoint gets written; a third ends the process at
/// once with the default action (every file is written atomically or line by
/// line, so nothing is left corrupt; at worst a *.tmp file stays behind).
class StopSignals {
public:
    StopSignals();
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;
    /// The signal received since construction, 0 if none.
    int pending() const;

private:
    struct sigaction old_int_ {}, old_term_ {};
};

/// Settles c's layer into its packing cache unless it is there already; the
/// log lines go to log_path.
void ensure_packing_cached(const Config& c, const std::string& log_path);

/// orodem sweep (cmd_sweep.cpp): one run per value of a key into DIR/<key>=<value>/,
/// recorded in DIR/sweep.toml, then the overlay plots.
/// jobs > 1: that many members at once, each in a child process.
int cmd_sweep(const CommonArgs& a, const std::string& vary, const std::string& out_arg, int jobs = 1);
/// orodem resume DIR: a sweep folder (with sweep.toml) continues its members in
/// order (finished ones kept, interrupted ones resumed, the rest started;
/// jobs of them at once); any other DIR is one run, resumed. threads < 0:
/// each run's own run.threads (with jobs > 1: the cores shared among the jobs).
int cmd_resume(const std::string& dir, int threads, int jobs = 1);
/// The hidden `orodem sweep-member DIR`: one member of a parallel sweep, run
/// or continued in the child process that the sweep started for it.
int cmd_sweep_member(const std::string& dir, int threads);
int cmd_bench_pile(const std::string& pile, std::uint64_t steps, int threads);

/// orodem plot (cmd_plot.cpp): the S plots of one or more runs into out
/// (default RUN_DIR/figures/plots.png for one run, <common parent>/plots.png
/// for several); with seeds, the runs that differ only in their seeds as one
/// mean curve each over a band from their lowest to their highest value.
int cmd_plot(const std::vector<std::string>& run_dirs, const std::string& out, bool seeds = false);

/// orodem render (cmd_render.cpp): horizon and displacement pictures of the
/// snapshots nearest each S of `at` (all when empty) into RUN_DIR/figures/.
int cmd_render(const std::string& run_dir, const std::vector<double>& at, const std::string& format, int width);
/// orodem measure (cmd_render.cpp): the wedge measures of each saved snapshot
/// of a wedge run, taken again, as CSV on standard output.
int cmd_measure(const std::string& run_dir);

/// orodem taper (cmd_taper.cpp): the critical surface slopes of a dry noncohesive
/// wedge (Dahlen 1984); exactly one of phi_b_deg and mu_b is given, the other is NaN.
int cmd_taper(double phi_deg, double phi_b_deg, double mu_b, double beta_deg);

/// orodem calibrate (cmd_calibrate.cpp): the calibration experiment of CONFIG into a new run
/// directory with report.md; check_calibration: what orodem check prints for one.
int cmd_calibrate(const CommonArgs& a, const std::string& out_arg);
int check_calibration(const Config& c);

/// orodem status (cmd_status.cpp): how far a wedge run got, how its last
/// piece ended, its newest checkpoint, the time left and how to continue it.
int cmd_status(const std::string& run_dir);
/// The last line of dir/log.txt that starts or ends a piece of the run
/// ("finished: ...", "interrupted by ...", "UNSTABLE: ...", "resumed by ...");
/// "" when there is none (not started, or killed before any).
std::string last_run_event(const std::string& dir);
/// True when last_run_event(dir) starts with prefix.
bool last_run_event_is(const std::string& dir, const char* prefix);
/// "42 s", "17 min" or "3.5 h".
std::string duration_text(double secs);

/// Throws ConfigError unless dir exists and holds a config.toml.
void require_run_dir(const std::string& dir);

}  // namespace orodem
