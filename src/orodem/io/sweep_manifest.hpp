// The record a sweep keeps of itself (DIR/sweep.toml): the config it was
// started from, the key it varies with its values in order (and, for a
// product grid of several --vary keys, the further keys in [[grid]]), and
// the --set overrides. Each member's resolved config is written to DIR/<key>=<value>/
// config.toml before the first member runs, so `orodem resume DIR` can finish
// an interrupted sweep from this record and those configs alone, even if the
// original config file has changed or is gone since.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace orodem {

/// One varied key and its values, in run order (TOML syntax, as given).
struct SweepAxis {
    std::string key;
    std::vector<std::string> values;
};

struct SweepManifest {
    std::string config;               // the config file the sweep was started from (as given)
    std::string key;                  // the (first) varied key, e.g. "wedge.mu_bp"
    std::vector<std::string> values;  // its values, in run order (TOML syntax, as given)
    std::vector<std::string> sets;    // the sweep's --set overrides, "key=value"
    std::vector<SweepAxis> more;      // further --vary keys: the members are the product grid; none for one key
};

/// One member of a sweep: its (key, value) for each varied key, in --vary order.
using SweepMember = std::vector<std::pair<std::string, std::string>>;

/// The members of m in run order: every combination of the values, the first key varying slowest.
std::vector<SweepMember> sweep_members(const SweepManifest& m);

/// Whether one of m's varied keys is a seed (run.seed, packing.seed): the plots then draw each group of members
/// that differ only in their seeds as its mean over a band.
bool varies_seed(const SweepManifest& m);

/// "wedge.mu_bp = 3 values" or "wedge.mu_bp = 3 values x run.seed = 2 values".
std::string sweep_axes_text(const SweepManifest& m);

/// The manifest's file in a sweep folder.
std::string sweep_manifest_path(const std::string& sweep_dir);

/// The folder of one member run: <sweep_dir>/<key>=<value>, for a grid
/// <sweep_dir>/<key1>=<value1>,<key2>=<value2>...
std::string sweep_member_dir(const std::string& sweep_dir, const SweepMember& member);

/// The manifest as TOML text (strings escaped by toml++).
std::string to_toml(const SweepManifest& m);

/// Reads DIR/sweep.toml; throws ConfigError naming the file and what is wrong
/// (missing, not TOML, a key missing or of the wrong type, no values).
SweepManifest read_sweep_manifest(const std::string& sweep_dir);

}  // namespace orodem
