// The record a sweep keeps of itself (DIR/sweep.toml): the config it was
// started from, the key it varies with its values in order, and the --set
// overrides. Each member's resolved config is written to DIR/<key>=<value>/
// config.toml before the first member runs, so `orodem resume DIR` can finish
// an interrupted sweep from this record and those configs alone, even if the
// original config file has changed or is gone since.
#pragma once

#include <string>
#include <vector>

namespace orodem {

struct SweepManifest {
    std::string config;               // the config file the sweep was started from (as given)
    std::string key;                  // the varied key, e.g. "wedge.mu_bp"
    std::vector<std::string> values;  // its values, in run order (TOML syntax, as given)
    std::vector<std::string> sets;    // the sweep's --set overrides, "key=value"
};

/// The manifest's file in a sweep folder.
std::string sweep_manifest_path(const std::string& sweep_dir);

/// The folder of one member run: <sweep_dir>/<key>=<value>.
std::string sweep_member_dir(const std::string& sweep_dir, const SweepManifest& m, const std::string& value);

/// The manifest as TOML text (strings escaped by toml++).
std::string to_toml(const SweepManifest& m);

/// Reads DIR/sweep.toml; throws ConfigError naming the file and what is wrong
/// (missing, not TOML, a key missing or of the wrong type, no values).
SweepManifest read_sweep_manifest(const std::string& sweep_dir);

}  // namespace orodem
