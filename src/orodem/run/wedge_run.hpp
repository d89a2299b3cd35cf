// The run loop of a wedge experiment: steps the simulation to s_max and, at
// every output interval, checks its health, writes the series row, the
// snapshot and its two pictures, keeps the state as the last good one and
// (every run.checkpoint_every_outputs) a checkpoint. Between chunks of at
// most 100 steps it looks at the stop request, the wall-time limit and the
// wall-clock checkpoint timer; every 1000 steps it checks the state.
// Chunking changes no result: the outputs are byte-identical whatever the
// chunk, the thread count or the pieces a run is done in.
//
// Read run() first: it is the whole loop. Each member below does one thing
// named in it. Everything the run writes goes through io/ and render/;
// everything it says to a person goes through the RunObserver.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "orodem/analysis/faults.hpp"
#include "orodem/analysis/strain.hpp"
#include "orodem/engine/health.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/run/thread_governor.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/render/particle_view.hpp"
#include "orodem/run/observer.hpp"
#include "orodem/run/run_log.hpp"
#include "orodem/run/surface_erosion.hpp"
#include "orodem/run/wedge_flexure.hpp"
#include "orodem/setup/wedge.hpp"

namespace orodem {

struct PhaseTimes;

/// "integrate 6.1%, rebuild 0.4%, ..." with the seconds per phase of step().
std::string phase_breakdown(const PhaseTimes& t);

class WedgeRun {
public:
    /// A run of c on w (built by make_wedge) in dir, whose log is `log`;
    /// resumed: the loop state restored from a checkpoint (w.sim restored too),
    /// or null for a run from step 0.
    WedgeRun(const Config& c, WedgeSetup& w, const std::string& dir, RunLog& log, RunObserver& observer,
             const RunLoopState* resumed);
    /// Runs to s_max. Returns 0, 128 + signal when stopped by a stop request
    /// (after a checkpoint), or ExitCode::time_limit at run.max_wall_minutes.
    /// Throws InstabilityError (exit 3) after writing the bad state, IoError.
    int run();

private:
    void start_from_layer();           // step 0: initialize, report the initial overlaps
    void continue_from_checkpoint();   // a resumed run: run.pvd and the last good state
    std::uint64_t next_output_step() const;
    void advance_to(std::uint64_t step);
    void output();                     // one output: check, row, pictures, warnings, checkpoint
    void check();                      // health check; throws InstabilityError, or sets stop_for_
    void measure_structures();         // strain over the interval, finite strain, faults (faults.csv)
    WedgeMeasures write_row();
    void draw();
    void warn_if_plate_too_short(const WedgeMeasures& m);
    void warn_if_overlapping();
    void keep_as_last_good();          // and the checkpoint when one is due
    void stop_if_left_domain();
    void check_space_left();
    std::string state_bytes();
    std::string save_checkpoint(const std::string& bytes);
    bool checkpoint_timer_due(std::uint64_t next_output) const;
    bool wall_time_limit_reached() const;
    void stop_with_checkpoint(RunEvent kind, const std::string& why, const char* continue_label);
    void finish();
    /// A log.txt line that is an event of events.csv, at this step and S.
    void event(RunEvent kind, std::string text, double wall_s = std::nan(""), double steps_per_s = std::nan(""));
    double S() const;
    double interval_m() const;  // the belt's displacement since the last snapshot (0 before the first) [m]
    double elapsed() const;

    const Config& c_;
    WedgeSetup& w_;
    Simulation& sim_;
    std::string dir_;
    RunLog& log_;
    RunObserver& obs_;
    const bool resumed_;
    const double h0_;                   // [m]
    const std::uint64_t cfg_hash_;
    // The thread count of each chunk (run/thread_governor.hpp); off with
    // ORODEM_ADAPT_THREADS=0 or one thread.
    const bool adapt_threads_;
    ThreadGovernor threads_;
    RunLoopState st_;
    bool initial_overlap_allowed_ = false;  // run.allow_initial_overlap used: no overlap limit at step 0
    std::size_t series_columns_;        // columns of series.csv (an older run keeps its own)
    LineFile series_;
    LineFile faults_file_;              // faults.csv
    FaultParams fault_params_;
    StrainField strain_;                // over the interval ending at this output
    FaultCounts fault_counts_;          // active faults of this output
    double decoupling_x_ = 0.0;         // the belt's decoupling point over this output's interval [m]
    std::vector<FaultLine> fault_lines_;  // active faults of this output, drawn on its strain map [m]
    std::uint64_t steps_per_output_ = 1;
    std::uint64_t n_outputs_ = 1;
    std::uint64_t total_steps_ = 1;
    std::uint64_t first_step_ = 0;      // this piece's first step (a resume starts later)
    std::uint64_t rate_from_step_ = 0;  // the rate logged with an output is over the interval since the previous one
    double rate_from_secs_ = 0.0;       // [s]
    HealthLimits lim_;
    std::string last_good_;             // checkpoint bytes of the last output that passed the checks
    std::uint64_t last_good_step_ = 0;
    std::string last_good_snapshot_;
    std::chrono::steady_clock::time_point t0_;
    std::chrono::steady_clock::time_point last_checkpoint_time_;
    std::optional<HealthProblem> stop_for_;  // run.on_domain_exit = "stop": set by check(), carried out by output()
    ViewOptions view_;
    SurfaceErosion surface_;            // [surface]: erosion every surface.interval_steps (off: no-op)
    LineFile eroded_file_;              // eroded.csv, with [surface] only
    WedgeFlexure flexure_;              // [flexure]: the plate solved every flexure.interval_steps (off: no-op)
    LineFile flexure_file_;             // flexure.csv, with [flexure] only
    std::string extra_series_header() const;  // the ledger's and the plate's columns, after series_header()
    bool overlap_warned_ = false;       // stderr once; log.txt at every output
    bool wall_warned_ = false;
};

}  // namespace orodem
