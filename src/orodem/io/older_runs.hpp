// Older run directories: every rule by which this orodem reads, resumes and
// draws a run directory an older orodem wrote, listed in one table
// (kOlderRunRules) with where it is applied. The rules about the config and
// its hash (what an older config.toml means, which of its keys the
// checkpoint hash leaves out) are the code in this file; the others are
// applied where the file they concern is read, and the table names the
// function. Adding or dropping support for an old format starts here.
#pragma once

#include <string>

#include <toml++/toml.h>

#include "orodem/io/config.hpp"

namespace orodem {

struct OlderRunRule {
    const char* what;   // the older run directory's difference
    const char* rule;   // what this orodem does with it
    const char* where;  // the function that applies it
};
inline constexpr OlderRunRule kOlderRunRules[] = {
    {"config.toml without base_law (written before the Coulomb base)",
     "read as base_law = \"traction\", the law that run used; its defaults text and hash as that orodem made them",
     "older_base_law_default, older_config_defaults (io/older_runs.cpp)"},
    {"config.toml without wedge.sleep_buffer_pro", "the key equal to sleep_buffer is left out of the hash",
     "drop_keys_older_runs_lacked (io/older_runs.cpp)"},
    {"a checkpoint hashed with packing.cache_dir (before kResultNeutralKeys)", "accepted as well as the current hash",
     "accepted_config_hashes (io/checkpoint.cpp)"},
    {"series.csv with fewer columns", "a resumed run keeps the columns it started with",
     "WedgeRun's constructor (run/wedge_run.cpp), csv_leading_columns (io/series_reader.cpp)"},
    {"no events.csv", "the events are read from log.txt's lines", "read_events (run/run_log.cpp)"},
    {"snapshots without rel_disp_abs", "the displacement picture on a per-frame scale", "read_frame (render/run_figures.cpp)"},
    {"snapshots without strain arrays", "no strain map (a strain figure is refused, exit 2)",
     "has_colour_data (render/run_figures.cpp)"},
    {"series.csv without the two-slope or decoupling columns", "measured again from the snapshots",
     "scripts/validate-findings (LATE_COLUMNS)"},
};

/// The base law of a config without a base_law key: in a run directory's
/// resolved config.toml (resolved_file) an older orodem wrote it, whose base
/// was the eq. 5 traction (legacy set); else the current default, Coulomb.
BaseLaw older_base_law_default(bool resolved_file, bool has_key, bool& legacy);

/// The all-defaults config text that c's resolved keys are compared with
/// (to_toml_without_defaults): its experiment, and for a legacy config the
/// defaults of the orodem that wrote it.
std::string older_config_defaults(const Config& c);

/// Leaves out of `resolved` the keys an older orodem did not write where
/// their value is what that orodem implied (wedge.sleep_buffer_pro equal to
/// wedge.sleep_buffer), so that an older run's hash stays what it was.
void drop_keys_older_runs_lacked(toml::table& resolved);

}  // namespace orodem
