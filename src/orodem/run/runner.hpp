// Starting and continuing runs in a run directory (SPEC "Run directory"):
// what `orodem run`, `orodem run --resume`, `orodem resume` and the members of
// `orodem sweep` do once the config is loaded and the directory chosen. A new
// run writes config.toml, log.txt and events.csv, settles its layer (or takes
// it from the packing cache) and, for a wedge experiment, hands over to
// WedgeRun; a resume checks the config against the run's, restores the newest
// usable checkpoint, cuts series.csv and log.txt back to it and continues.
#pragma once

#include <string>
#include <vector>

#include "orodem/io/config.hpp"
#include "orodem/run/observer.hpp"
#include "orodem/setup/wedge.hpp"

namespace orodem {

/// Throws ConfigError unless c can run: a model size within the limits, a
/// stable timestep, and the base law's checks (check_wedge_base). Returns the
/// numbers derived on the way, for the run to use.
RunNumbers check_runnable(const Config& c);
/// A wedge run's cost from its config alone (orodem check prints it; run and
/// sweep print it and refuse a run above kLongRunHours without --force).
struct RunTimeEstimate {
    double steps = 0.0;      // to wedge.s_max [-]
    double work = 0.0;       // (awake) disc-steps [-]
    double seconds_1 = 0.0;  // on 1 thread at the development host's rate [s]
    double seconds_2 = 0.0;  // on 2 threads [s]
};
/// A run estimated above this many hours on 2 threads needs --force: a
/// week, far beyond a paper-size run (minutes), where a mistyped speed or
/// output interval (wedge.v = 1e-9: 668,000 h) lands.
inline constexpr double kLongRunHours = 168.0;
/// The estimate for c with `discs` discs generated (before the cut to h0), dt [s].
RunTimeEstimate estimate_run_time(const Config& c, double discs, double dt);
/// Prints the estimate (one line) before a run or sweep starts, and throws
/// ConfigError (exit 2) if it is above kLongRunHours unless force; nothing
/// has been written when it throws. `what`: "the run", "each run".
void check_run_time(const Config& c, const RunNumbers& n, bool force, const std::string& what);
/// A one-line warning when the wedge's incoming plate is shorter than the
/// estimate (plate_estimate) says the deformation front needs; "" otherwise.
std::string short_plate_warning(const Config& c, const PlateEstimate& pe);
/// Runs c from the beginning in dir (which exists: empty, or holding only its
/// config.toml); n from check_runnable(c). Returns the exit status (0;
/// 128 + signal or ExitCode::time_limit when a wedge run stopped early with a
/// checkpoint).
int start_run_in(const Config& c, const RunNumbers& n, const std::string& dir, RunObserver& obs);
/// Continues the wedge run in dir from its newest usable checkpoint (from the
/// beginning when it was stopped before its first); c must be its config.
int resume_run(const Config& c, const RunNumbers& n, const std::string& dir, RunObserver& obs);
/// The --set overrides that extend a wedge run with config `saved` to
/// s_max = S on the same incoming plate (orodem resume DIR --s-max S):
/// wedge.s_max = S and wedge.pro_margin = saved's s_max + pro_margin − S, so
/// that s_max + pro_margin, packing.length and every disc stay as they are
/// and the run continues as one made with them from the start. Throws
/// ConfigError (one line naming the plate length) when S is not beyond the
/// run's s_max by one output interval at least, or when the plate left ahead
/// of the trailing wall at S would be shorter than plate_estimate's
/// pro_margin_min (docs/experiments.md "Plate length").
std::vector<Override> extension_overrides(const Config& saved, double S, const std::string& dir);
/// Continues the wedge run in dir (its config.toml is `saved`) as the run of
/// c, saved with extension_overrides applied: the newest checkpoint
/// restored (made with saved's config or c's), written again with c's
/// config hash, c written as config.toml, the pictures of the outputs so far
/// drawn again from their snapshots in c's frame, then resumed as
/// resume_run. Nothing is changed when it throws before the first write.
int extend_run(const Config& saved, const Config& c, const RunNumbers& n, const std::string& dir, RunObserver& obs);
/// Settles c's layer into its packing cache unless it is there already; the
/// log lines go to dir/log.txt (and dir/events.csv).
void ensure_packing_cached(const Config& c, const std::string& dir, RunObserver& obs);

}  // namespace orodem
