// The subcommands of the orodem executable, one function each in its own
// cmd_*.cpp, called by main.cpp after CLI11 has parsed the arguments. Each
// returns the exit status and lets library errors propagate (main maps them
// to exit statuses). A command calls the library (src/orodem/run/ for runs)
// and the shared CLI helpers of cli.hpp, never another command.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli.hpp"
#include "orodem/render/particle_view.hpp"
#include "orodem/run/slurm.hpp"

namespace orodem {

/// orodem check (cmd_check.cpp): the resolved config and its derived numbers.
int cmd_check(const CommonArgs& a);
/// orodem run (cmd_run.cpp); resume: continue the run in out_arg from its newest usable checkpoint.
int cmd_run(const CommonArgs& a, const std::string& out_arg, bool resume = false);

/// Where a sweep's members run: "local" (this machine, --jobs at a time) or
/// "slurm" (one job array, run/slurm.hpp). slurm_given: a Slurm option was
/// given on the command line (refused with the local scheduler).
struct SchedulerArgs {
    std::string scheduler = "local";
    SlurmOptions slurm;        // cpus_per_task 0: as in DIR/slurm/array.sh (resume)
    bool slurm_given = false;
};

/// orodem sweep (cmd_sweep.cpp): one run per value of a key into DIR/<key>=<value>/,
/// recorded in DIR/sweep.toml, then the overlay plots.
/// jobs > 1: that many members at once, each in a child process.
/// --scheduler slurm: the members submitted as one Slurm job array instead.
int cmd_sweep(const CommonArgs& a, const std::vector<std::string>& vary, const std::string& out_arg, int jobs = 1,
              const SchedulerArgs& s = {});
/// orodem resume DIR (cmd_sweep.cpp): a sweep folder (with sweep.toml) continues its members in
/// order (finished ones kept, interrupted ones resumed, the rest started;
/// jobs of them at once); any other DIR is one run, resumed. threads < 0:
/// each run's own run.threads (with jobs > 1: the cores shared among the jobs).
/// --scheduler slurm: the unfinished members submitted again as a job array.
int cmd_resume(const std::string& dir, int threads, int jobs = 1, const SchedulerArgs& s = {});
/// orodem resume DIR --s-max S (cmd_run.cpp): the wedge run in DIR extended to
/// S on the same incoming plate (run/runner.hpp extend_run); a refusal (exit
/// 2) changes nothing.
int cmd_extend(const std::string& dir, double s_max, int threads);
/// The hidden `orodem sweep-member DIR`: one member of a parallel sweep, run
/// or continued in the child process that the sweep started for it (or in
/// its Slurm array task).
int cmd_sweep_member(const std::string& dir, int threads);
/// The hidden `orodem sweep-settle DIR`: the packings that several members of
/// the sweep share, settled once (the Slurm job the array waits for).
int cmd_sweep_settle(const std::string& dir, int threads);
/// orodem bench-pile (cmd_bench.cpp): the canonical benchmark.
int cmd_bench_pile(const std::string& pile, std::uint64_t steps, int threads);

/// orodem plot (cmd_plot.cpp): the S plots of one or more runs into out
/// (run/run_plots.hpp).
int cmd_plot(const std::vector<std::string>& run_dirs, const std::string& out, bool seeds = false);

/// orodem render's arguments.
struct RenderArgs {
    std::string run_dir;
    std::vector<double> at;             // S of the snapshots to draw (nearest ones); empty: default
    std::string out;                    // one stacked figure (.png, .svg, .pdf); empty: a picture pair per snapshot
    std::string dir;                    // the picture pairs' folder; empty: RUN_DIR/figures/rendered
    std::string format = "png";         // the picture pairs' format
    orodem::ColorBy color_by = orodem::ColorBy::horizons;  // the stacked figure's colouring: horizons | displacement | strain | strain_total
    int width = 1600;                   // picture width [px]
    bool force = false;                 // replace existing files
    std::vector<double> xlim;           // --xlim A,B: x from A to B h0 from the S point; empty: the run's frame
    std::string title;                  // the pictures' title; empty: the experiment's name
};
/// orodem render (cmd_render.cpp): with `out`, one figure stacking the
/// snapshots nearest each S of `at` (four evenly spread when empty); without,
/// the horizon, displacement and strain pictures of those snapshots (all when empty)
/// into `dir`. Refuses (exit 2) to replace a file without `force`.
int cmd_render(const RenderArgs& a);

/// orodem movie's arguments.
struct MovieArgs {
    std::string run_dir;
    std::string out;                    // .mp4 or .gif
    orodem::ColorBy color_by = orodem::ColorBy::horizons;  // horizons | displacement | strain | strain_total
    int width = 1600;                   // frame width [px]
    double fps = 25.0;                  // the file's frame rate [1/s]
    double seconds = 10.0;              // its length [s]
    bool blend = false;                 // cross-fade between snapshots instead of holding each
    bool force = false;                 // replace an existing file
    std::vector<double> xlim;           // as RenderArgs
    std::string title;
};
/// orodem movie (cmd_render.cpp): every snapshot of the run, shown for
/// seconds / snapshots each at fps frames per second (held or cross-faded),
/// encoded by ffmpeg (exit 6 when it is not installed).
int cmd_movie(const MovieArgs& a);
/// orodem measure (cmd_measure.cpp): the wedge measures of each saved snapshot
/// of a wedge run, taken again, as CSV on standard output.
int cmd_measure(const std::string& run_dir);
/// orodem faults (cmd_faults.cpp): the fault table of a run at one output
/// (at: its S, NaN for the last), or every output as CSV.
int cmd_faults(const std::string& run_dir, double at, bool csv, bool recompute);

/// orodem taper (cmd_taper.cpp): the critical surface slopes of a dry noncohesive
/// wedge (Dahlen 1984); exactly one of phi_b_deg and mu_b is given, the other is NaN.
int cmd_taper(double phi_deg, double phi_b_deg, double mu_b, double beta_deg);

/// orodem calibrate (cmd_calibrate.cpp): the calibration experiment of CONFIG into a new run
/// directory with report.md.
int cmd_calibrate(const CommonArgs& a, const std::string& out_arg);

/// orodem status (cmd_status.cpp): how far a wedge run got, how its last
/// piece ended, its newest checkpoint, the time left and how to continue it.
int cmd_status(const std::string& run_dir);

}  // namespace orodem
