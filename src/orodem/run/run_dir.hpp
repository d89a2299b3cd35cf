// The run directory (SPEC "Run directory"): choosing a new one, checking that
// a path is one, and whether its disk can take the rest of a run. Nothing here
// writes: files are written through io/.
#pragma once

#include <cstdint>
#include <string>

namespace orodem {

/// A new run directory: `out` if given (must be absent or empty, else
/// ConfigError), else runs/<config stem>, runs/<stem>-2, ... whichever is free first.
std::string choose_run_dir(const std::string& out, const std::string& config_path);
/// Throws ConfigError unless dir exists and holds a config.toml.
void require_run_dir(const std::string& dir);
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
