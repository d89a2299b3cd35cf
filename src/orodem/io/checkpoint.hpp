// Checkpoints (SPEC §5): the whole state a run needs to continue bit for bit.
//
// File layout (ckpt-<step>.bin in RUN_DIR/checkpoint/), all values raw bytes
// as stored in memory (little-endian on every supported machine):
//   magic "ORODEMCK" | u32 format version | string program version |
//   u64 config hash | u64 step | u64 payload size | u64 payload checksum |
//   u64 header checksum (FNV-1a over every header byte before it) | payload
// The payload holds, in order: every ParticleStore column in current slot
// order (ParticleStore::for_each_column, so a new column is saved without
// touching this file), slot_of_id, the ContactStore and WallContactStore
// arrays, every wall (they move), step_count, time, the Simulation's private
// state (PairBuilder x_ref and rebuild count, wall_shift, max_disp2,
// force_rebuild, sleeping-zone ranges: Simulation::save_internals), each boundary's own state (by name,
// Boundary::save_state), and the run loop's state (RunLoopState).
//
// Loading checks magic, version, config hash, sizes and both checksums, and
// validates every index before anything of the Simulation is replaced: a
// refused file leaves the Simulation as it was.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "orodem/analysis/faults.hpp"
#include "orodem/analysis/strain.hpp"
#include "orodem/core/error.hpp"
#include "orodem/core/vec2.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/io/config.hpp"

namespace orodem {

inline constexpr std::uint32_t kCheckpointVersion = 4;  // 2: sleeping-zone ranges; 3: strain and faults; 4: stage
inline constexpr std::uint32_t kOldestCheckpointVersion = 2;  // still read (no strain or fault state)

/// A checkpoint that cannot be used: corrupt, truncated, another format
/// version, not a checkpoint. what() says which. (An I/O problem: exit 4.)
class CheckpointError : public IoError {
public:
    using IoError::IoError;
};

/// Erosion's state between applications (run/surface_erosion.hpp); saved
/// in the checkpoint's "surface" section, present only when `on` ([surface]
/// in the config), so every other run's checkpoint keeps its bytes.
struct SurfaceState {
    bool on = false;                     // [surface] present (not saved: the section is)
    double last_S = 0.0;                 // S of the last application [-]
    std::vector<double> remainder;       // per surface column: area asked for and not yet taken [h0²]
    std::vector<double> max_burial;      // by id: largest depth below the surface seen at an application [h0]
    double eroded_area = 0.0;            // Σ layer area of the removed particles [h0²]
    double requested_area = 0.0;         // Σ of the areas the law asked for [h0²]
    std::uint64_t removed = 0;           // particles (clusters, lone discs) removed: the next parking place [-]
    std::uint64_t eroded_bytes = 0;      // eroded.csv length [bytes]
    // The particles' paths and sedimentation ("surface_paths" section).
    std::uint64_t reserve_begin = 0;     // the first id of the sediment reserve; the layer's discs are below [-]
    std::vector<double> birth_S;         // by id: S when deposited, 0 for the layer, NaN for the reserve [-]
    std::vector<double> erosion_S;       // by id: S when eroded, NaN while present [-]
    std::vector<double> sed_remainder;   // per surface column: deposit asked for and not yet placed [h0²]
    double deposited_area = 0.0;         // Σ layer area of the deposited particles [h0²]
    double deposit_requested = 0.0;      // Σ of the areas sedimentation asked for [h0²]
    std::uint64_t deposited = 0;         // reserve particles deposited: the next one to place [-]
    std::uint64_t deposited_discs = 0;   // their discs [-]
};

/// The plate under the wedge (run/wedge_flexure.hpp); saved in the
/// checkpoint's "flexure" section, present only when `on` ([flexure] in the
/// config), so every other run's checkpoint keeps its bytes.
struct FlexureState {
    bool on = false;                     // [flexure] present (not saved: the section is)
    std::uint64_t solved_step = 0;       // step of the last solve [-]
    std::vector<double> f;               // node forces of the last solve [N/m]
    std::vector<double> w;               // deflection of the last solve, positive down [m]
    std::uint64_t profile_bytes = 0;     // flexure.csv length [bytes]
};

/// The run loop's own state (run/wedge_run.hpp) at the checkpoint.
struct RunLoopState {
    std::uint64_t outputs = 0;                          // output rows written so far
    std::vector<Vec2> x_then;                           // positions by id at the last output
    std::vector<std::pair<double, std::string>> pvd;    // run.pvd entries (S, file)
    std::uint64_t series_bytes = 0;                     // series.csv length [bytes]
    std::uint64_t log_bytes = 0;                        // log.txt length [bytes]
    double surface_y_mean = 0.0;                        // undeformed surface (measured on the layer) [m]
    // Structures (analysis/strain.hpp, analysis/faults.hpp); empty from a
    // version-2 checkpoint: the finite strain then counts from the resume.
    std::vector<Mat2> F_total;                          // finite deformation gradient by id [-]
    std::vector<Fault> faults;                          // every fault found so far (FaultTracker::known)
    std::int64_t next_fault_id = 1;                     // FaultTracker::next_id
    std::uint64_t faults_bytes = 0;                     // faults.csv length [bytes]
    std::int32_t stage = 0;                             // the stage reached (stage_reached)
    std::int32_t stage_last_output = 0;                 // classify_stage of the last output
    SurfaceState surface;                               // erosion ([surface]); off: not saved
    FlexureState flexure;                               // the plate ([flexure]); off: not saved
};

/// FNV-1a 64 of the resolved config without the keys at their defaults
/// (to_toml_without_defaults) and without the result-neutral keys
/// (kResultNeutralKeys, io/config.hpp): a run may resume with other values of
/// those; and a newer orodem that adds keys still resumes the run.
std::uint64_t config_hash(const Config& c);

/// The config hashes a checkpoint of c may carry: config_hash(c), and the hash
/// an orodem before the result-neutral table gave it (packing.cache_dir was
/// hashed then; the two differ only for a non-default cache_dir). Converts
/// from one hash (tests, and callers that know the exact one).
struct AcceptedHashes {
    AcceptedHashes(std::uint64_t h) : current(h), earlier(h) {}  // NOLINT: implicit on purpose
    AcceptedHashes(std::uint64_t now, std::uint64_t before) : current(now), earlier(before) {}
    bool accepts(std::uint64_t h) const { return h == current || h == earlier; }
    std::uint64_t current, earlier;
};
AcceptedHashes accepted_config_hashes(const Config& c);

/// The checkpoint file bytes of sim and run.
std::string encode_checkpoint(const Simulation& sim, const RunLoopState& run, std::uint64_t config_hash);

/// Header facts, readable without restoring (for messages and listings).
struct CheckpointInfo {
    std::uint32_t version = 0;
    std::string program_version;
    std::uint64_t config_hash = 0;
    std::uint64_t step = 0;
};

/// Checks the header and checksums; throws CheckpointError naming the problem,
/// or ConfigError when the config hash differs from expected_config_hash.
CheckpointInfo verify_checkpoint(std::string_view bytes, AcceptedHashes expected_config_hash);

/// Restores a verified checkpoint into sim, which must have been built by the
/// same scenario code as the saved one (same walls and boundaries; particles
/// and contacts are replaced). Does not call sim.initialize(). Throws as
/// verify_checkpoint, or CheckpointError when the contents do not fit sim;
/// on any throw sim and run are unchanged.
void decode_checkpoint(std::string_view bytes, AcceptedHashes expected_config_hash, Simulation& sim,
                       RunLoopState& run);

/// Writes bytes to DIR/ckpt-<step>.bin atomically and reads them back, then
/// deletes the checkpoints older than the newest `keep` intact ones
/// (checkpoint_file_intact; only after the new one is in place and verified,
/// and a damaged file never counts as kept). Returns the path (keep <= 0:
/// delete none). Throws IoError; a failed write leaves older checkpoints intact.
std::string write_checkpoint(const std::string& dir, std::uint64_t step, std::string_view bytes, int keep = 2);

/// True when the file is an intact checkpoint of this format: magic,
/// version, sizes and both checksums (the config hash is not looked at).
bool checkpoint_file_intact(const std::string& path);

/// Checkpoint files in dir (ckpt-<step>.bin), newest (highest step) first.
std::vector<std::pair<std::uint64_t, std::string>> list_checkpoints(const std::string& dir);

/// Restores the newest checkpoint of dir that passes every check, falling
/// back to older ones; `notes` gets one line per file skipped and why.
/// Returns the path used. Throws CheckpointError when none is usable, and
/// ConfigError (not falling back) when a checkpoint was made from another config.
/// `fits` (when given) is asked of each decoded checkpoint: a non-empty answer (why the files on disk do not
/// match it, e.g. a series.csv shorter than it recorded after a power loss) skips it like a damaged one.
std::string restore_newest_checkpoint(const std::string& dir, AcceptedHashes expected_config_hash, Simulation& sim,
                                      RunLoopState& run, std::vector<std::string>* notes = nullptr,
                                      const std::function<std::string(const RunLoopState&)>& fits = {});

}  // namespace orodem
