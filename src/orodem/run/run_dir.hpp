// The run directory (SPEC "Run directory"): choosing a new one, checking that
// a path is one, where the run in it stands (run_state: what orodem status,
// the sweeps and orodem resume of a sweep read), and whether its disk can
// take the rest of a run. Nothing here writes: files are written through io/.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "orodem/io/config.hpp"
#include "orodem/run/run_log.hpp"

namespace orodem {

/// A new run directory: `out` if given (must be absent or empty, else
/// ConfigError), else runs/<config stem>, runs/<stem>-2, ... whichever is free first.
std::string choose_run_dir(const std::string& out, const std::string& config_path);

/// The files of a run directory and what each holds, in one table (docs/reference.md "Run directory" is made
/// from it; tests/unit/test_docs_reference.cpp checks), the headers of events.csv and faults.csv from the code
/// that writes them.
struct RunDirFile {
    std::string file;      // as markdown, e.g. `series.csv`
    std::string contents;  // as markdown
};
std::vector<RunDirFile> run_dir_files();
/// Throws ConfigError unless dir exists and holds a config.toml.
void require_run_dir(const std::string& dir);

/// Where a run stands by its own files.
enum class RunState {
    not_started,  // nothing to continue: no log.txt yet (a settled layer: no packing.bin; its settling starts again)
    no_end_line,  // started, and its last piece has no end line: still running, or killed
    interrupted,  // its last piece ended with a checkpoint to continue from (a signal, the wall-time limit, a full disk)
    finished,
    failed        // unstable, or stopped by run.on_domain_exit: resuming would repeat it
};

/// What run_state reads from a run directory. For a settled layer (not a
/// wedge experiment) only state and config are filled.
struct RunStatus {
    RunState state = RunState::not_started;
    Config config;                    // its config.toml
    std::optional<EventRecord> last;  // the last event that starts or ends a piece
    double dt = std::nan("");         // timestep of the last start event [s]
    double S = std::nan("");          // at the last output [-]
    double last_step = std::nan("");  // the step of series.csv's last row (exact; S in the log is rounded)
    double total_steps = std::nan("");  // about s_max h0 / (v dt): the run's steps
    /// steps/s: the median of the last three outputs' rates (of two, the
    /// higher): a run paused or shared with other work shows one low rate.
    double rate = std::nan("");
    int rate_outputs = 0;   // how many outputs the rate is taken from
    double wall_s = 0.0;    // the wall time of the pieces whose end line gives it [s]
    int pieces = 0;         // pieces started (start and resume events)
    int pieces_timed = 0;   // pieces whose end line gives their wall time
    std::optional<std::pair<std::uint64_t, std::string>> newest_checkpoint;  // its step and path
    double log_age_s = std::nan("");  // since log.txt was last written [s]
};

/// Where the run in dir stands, read once from its files: config.toml,
/// events.csv (or the log.txt of a run made before events.csv), the last row
/// of series.csv and checkpoint/. Throws ConfigError unless dir is a run
/// directory (require_run_dir). Writes nothing.
RunStatus run_state(const std::string& dir);

/// Data rows of a series.csv (lines after the header); 0 when it is absent.
std::size_t series_rows(const std::string& path);
/// Free bytes for an unprivileged user on the file system holding path.
std::uint64_t free_bytes(const std::string& path);
/// Refuses (IoError, exit 4) when the disk holding dir cannot take what the
/// rest of the run writes: per remaining output one snapshot and its two
/// pictures (sized like the last ones written), two checkpoints plus the one
/// being written, and 2 MB for series, log and the final plots.
void check_free_space(const std::string& dir, const std::string& last_snapshot, std::uint64_t outputs_left,
                      std::uint64_t checkpoint_size);

}  // namespace orodem
