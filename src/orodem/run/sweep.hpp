// A sweep (orodem sweep, and orodem resume of a sweep's folder): one run per
// value of a config key, DIR/<key>=<value>/. The paper's sweeps take hours
// per member, so a sweep survives what a single run survives: before the
// first member runs, DIR/sweep.toml records it (io/sweep_manifest.hpp) and
// every member's resolved config.toml is written; continuing it goes through
// the members in order by their state (run_state): a finished one is kept,
// one that failed (unstable, stopped) is skipped, an interrupted one resumed
// from its checkpoint (bit for bit as if never stopped), one not started yet
// is started. A member that goes unstable does not stop the others: it is
// reported and the sweep exits with 3.
//
// This module holds the sweep's policy on this machine: the members' states,
// the packings settled first (members about to start that share a packing
// not cached yet would each settle it at the same time), and the scheduler:
// the members in order in this process, or `jobs` at a time, each in a child
// process (`orodem sweep-member DIR`, output in DIR/console.txt, the cores
// shared among them) watched with waitpid. The Slurm side is
// run/sweep_slurm.hpp. Nothing here prints: the lines go to a SweepObserver,
// the runs' progress to its RunObserver.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "orodem/io/config.hpp"
#include "orodem/io/sweep_manifest.hpp"
#include "orodem/run/observer.hpp"
#include "orodem/run/run_dir.hpp"

namespace orodem {

/// How a sweep reaches the person who started it (apps/orodem prints the
/// lines; tests keep them).
class SweepObserver {
public:
    virtual ~SweepObserver() = default;
    /// A line for standard output ("sweep: ...").
    virtual void say(const std::string& line) = 0;
    /// A line for standard error (the terminal puts "orodem: " before it).
    virtual void trouble(const std::string& line) = 0;
    /// The observer of the runs and settlings done in this process; its stop
    /// requests also stop a parallel sweep.
    virtual RunObserver& runs() = 0;
};

/// Splits "key=v1,v2,..." (--vary) into the key and its values; ConfigError
/// when it is not of that form or lists a value twice.
std::pair<std::string, std::vector<std::string>> parse_vary(const std::string& text);

/// A sweep's folder and its members' folders.
struct Sweep {
    std::string root;               // the folder, as given
    SweepManifest manifest;
    std::vector<std::string> dirs;  // member k's folder: root/<key>=<value>, in the manifest's order
    std::vector<SweepMember> members;  // member k's (key, value) pairs (sweep_members)
    std::size_t size() const { return dirs.size(); }
    /// "key = value" of member k ("key1 = value1, key2 = value2" in a grid).
    std::string label(std::size_t k) const;
};
/// The sweep of manifest m in root.
Sweep sweep_in(const std::string& root, const SweepManifest& m);
/// The sweep in root, from its sweep.toml (ConfigError when there is none or it is broken).
Sweep open_sweep(const std::string& root);
/// The folders orodem status reads in dir: its sweep's members in order
/// (manifest set), or without sweep.toml every sub-folder holding a
/// config.toml, by name.
std::vector<std::string> sweep_folders(const std::string& dir, bool& manifest);

/// The folder of a new sweep: out_arg when given (ConfigError unless it is
/// absent or empty, naming orodem resume when it holds a sweep), else a free
/// runs/<config stem>-sweep.
std::string new_sweep_dir(const std::string& out_arg, const std::string& config_path);
/// ConfigError unless a sweep can run c (not a calibration; check_runnable).
void check_sweep_member(const Config& c);
/// Writes the sweep's folder: each member's resolved config.toml (configs in
/// the order of m.values), then sweep.toml.
Sweep create_sweep(const std::string& root, const SweepManifest& m, const std::vector<Config>& configs);

/// The config of the member in dir of the sweep in root, from its
/// config.toml (threads >= 0 overrides run.threads), checked runnable.
Config member_config(const std::string& root, const std::string& dir, int threads);
/// Every member's.
std::vector<Config> member_configs(const Sweep& s, int threads);

/// What a member needs.
enum class MemberState { start, resume, finished, failed };
MemberState member_state(RunState s);
/// member_state(run_state(dir).state).
MemberState member_state(const std::string& dir);

/// The members whose packing is settled before the members run, one per
/// packing: wedge members still to be started whose packing is not cached
/// yet; only_shared: only the packings that two or more of them use (a
/// packing of its own a member settles itself).
std::vector<std::size_t> packings_to_settle(const std::vector<Config>& configs, const std::vector<std::string>& dirs,
                                            bool only_shared);
/// Settles the packings of the members `which` into their caches (log in root/log.txt).
void settle_packings(const Sweep& s, const std::vector<Config>& configs, const std::vector<std::size_t>& which,
                     SweepObserver& obs);
/// The hidden `orodem sweep-settle DIR`: the packings that several members of
/// the sweep in root share, settled once (the Slurm job its array waits for).
int settle_shared_packings(const std::string& root, int threads, SweepObserver& obs);

/// The member in dir kept, continued or started (the hidden `orodem
/// sweep-member DIR`, in a parallel sweep's child or a Slurm array task):
/// its exit status (0 when kept, 3 when it failed before).
int run_sweep_member(const std::string& dir, int threads, SweepObserver& obs);

/// How a sweep's members run on this machine.
struct LocalJobs {
    int threads = -1;  // each member's threads; < 0: its run.threads (with jobs > 1: the cores shared among the jobs)
    int jobs = 1;      // members at once; > 1: each in a child process
    std::string exe;   // what a child runs: `exe sweep-member DIR [--threads T]`; empty: this executable
};

/// The members of s on this machine, then the overlay plots. The exit
/// status: 0; 3 when some went unstable; a member's stop status (128 +
/// signal, ExitCode::time_limit) when the sweep stopped, to be continued.
int run_sweep(const Sweep& s, const LocalJobs& j, SweepObserver& obs);

/// The end of a sweep: the overlay plots of the members that finished
/// (finished_dirs; when every member is a wedge run) into root/plots.png,
/// and the exit status (3 when some went unstable, naming them).
int finish_sweep(const std::string& root, const SweepManifest& m, const std::vector<std::string>& finished_dirs,
                 const std::vector<std::string>& failed_labels, bool all_wedges, SweepObserver& obs);

/// Says that a member needs no run (finished or failed); its exit status (0 kept, 3 failed before).
int report_done(MemberState st, const std::string& dir, const std::string& label, SweepObserver& obs);

/// This executable (/proc/self/exe), which the sweep's children and batch scripts run.
std::string this_executable();

}  // namespace orodem
