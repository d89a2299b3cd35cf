// Calibration experiments (issue #7; docs/validation.md "Calibration"): a DEM
// has no input friction angle, so the bulk strength of the material is
// measured on it, for the material of a config ([material], [packing]) and
// the tests' parameters in [calibrate]:
//
// biaxial         A gravity-free sample in a box of four smooth walls
//                 (infinite lines; bottom 0, top 1, left 2, right 3). The
//                 loose packing is compacted isotropically to σ_3 by the
//                 servo-controlled top and right walls (damping ratio
//                 packing.settle_damping_ratio) until both stresses are within
//                 calibrate.servo_tolerance of σ_3 and the r.m.s. speed is
//                 below ε̇ d. Then, with the material's damping, the top wall
//                 moves down at ε̇ H0 (bottom fixed) while both side walls are
//                 servo-controlled to σ_3. Every calibrate.output_strain a row:
//                 σ1 = mean of top and bottom stress, σ3 = mean of left and
//                 right (interval means of every step), the mobilized friction
//                 sin φ = (σ1 − σ3)/(σ1 + σ3), axial strain ε_a = (H0 − H)/H0
//                 and volumetric strain ε_v = (A − A0)/A0 (dilation positive).
//                 φ_peak = max over the rows; φ_cs = mean over ε_a in
//                 [critical_from, max_strain] with its standard deviation.
// basal-friction  A block (block_length × block_height, settled under gravity
//                 in a box and cut) on the proside base: a smooth base wall
//                 y = 0 with the ConveyorTraction (eq. 5) at belt_speed toward
//                 a fixed smooth wall that holds the block at its right end (a
//                 fixed smooth wall at its left end keeps the free face from
//                 slumping, as the settling box did). The effective basal
//                 friction μ_eff is the base's horizontal force (the total
//                 traction) over its normal force, interval means averaged
//                 over t in [measure_from · duration, duration]; the walls'
//                 net horizontal force over the normal force is the same
//                 number measured independently (equal once the block's
//                 momentum is steady). A rigid block on a Coulomb base gives
//                 μ_bp exactly; where the base drags discs along at the belt
//                 speed (the material above them shears instead: the
//                 décollement moves into the material) it gives less.
// repose          A column (column_width × column_height, settled in a box) on
//                 a floor of touching fixed discs of radius r_max (a rough
//                 floor: a disc cannot roll away over it), between two walls
//                 that rise at lift_speed and release it. When the heap is at
//                 rest (E_kin < packing.settle_ke_ratio · M g H), the surface
//                 (highest disc top per column of width 2 r_max) is fitted by
//                 least squares on each flank between fit_from and fit_to of
//                 the heap height: the angle of repose is atan |slope|.
//
// Each run_* function runs one test (one packing kind, one value of the swept
// coefficient) and returns its measurements; orodem calibrate (apps/orodem/
// cmd_calibrate.cpp) sweeps them and writes the report. Measurements are
// taken every N steps between calls of Simulation::advance, never inside the
// step loop (ServoWalls only sums what the step gathered).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "orodem/analysis/calibration_measures.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/io/config.hpp"

namespace orodem {

class ServoWalls;

/// Progress lines (log.txt and the terminal); may be empty.
using CalibrationLog = std::function<void(const std::string&)>;

/// Mean disc diameter r_min + r_max [m] (the d of the inertial number).
double mean_disc_diameter(const Config& c);

// ------------------------------------------------------------------ biaxial

inline constexpr std::size_t kBoxBottom = 0, kBoxTop = 1, kBoxLeft = 2, kBoxRight = 3;  // wall and side indices

struct BiaxialSample {
    Simulation sim;
    ServoWalls* servo = nullptr;  // owned by sim.boundaries
    double mu = 0.0;              // the tested μ_i (the compaction may use another: calibrate.compaction_mu) [-]
    double width() const;         // right − left wall [m]
    double height() const;        // top − bottom wall [m]
    double solid_fraction() const;  // disc area / box area [-]
};

/// The loose packing of `kind` in its box with μ_i = mu, not yet compacted
/// (initialised; compaction damping).
BiaxialSample make_biaxial_sample(const Config& c, PackingKind kind, double mu);

struct CompactionResult {
    std::uint64_t steps = 0;
    double sigma_top = 0, sigma_right = 0;  // interval means at the end [Pa]
    double v_rms = 0;                        // r.m.s. disc speed at the end [m/s]
};
/// Isotropic compaction to calibrate.confining_stress (see the file note).
/// Throws InstabilityError after packing.settle_max_steps steps.
CompactionResult compact_biaxial(BiaxialSample& s, const Config& c, const CalibrationLog& log);

struct BiaxialRow {
    double axial_strain = 0;       // ε_a = (H0 − H)/H0 [-]
    double volumetric_strain = 0;  // ε_v = (A − A0)/A0, dilation positive [-]
    double sigma1 = 0, sigma3 = 0; // [Pa], interval means
    double sigma3_left = 0, sigma3_right = 0, sigma1_top = 0, sigma1_bottom = 0;  // [Pa]
    double stress_ratio = 0;       // (σ1 − σ3)/(σ1 + σ3) = sin φ [-]
    double phi_deg = 0;            // mobilized friction angle [°]
    double width = 0, height = 0;  // [m]
    double kinetic_energy = 0;     // [J]
    std::size_t contacts = 0;      // touching contacts
};

struct BiaxialResult {
    PackingKind kind = PackingKind::clusters;
    double mu = 0;
    std::size_t discs = 0;
    double strain_rate = 0;          // ε̇ [1/s]
    double inertial_number = 0;      // ε̇ d sqrt(ρ/σ_3) [-]
    double width0 = 0, height0 = 0;  // after compaction [m]
    double solid_fraction0 = 0;      // after compaction [-]
    std::uint64_t compaction_steps = 0, shear_steps = 0;
    double phi_peak_deg = 0, strain_at_peak = 0;
    WindowStats phi_cs;              // [°]
    double sigma3_mean_error = 0;    // mean |σ3/σ_target − 1| over the rows [-]
    double sigma3_max_error = 0;     // max of the same [-]
    double volumetric_strain_end = 0;
    std::vector<BiaxialRow> rows;
};

/// Shears a compacted sample (rows as in the file note).
BiaxialResult shear_biaxial(BiaxialSample& s, const Config& c, const CalibrationLog& log);
/// make_biaxial_sample, compact_biaxial, shear_biaxial.
BiaxialResult run_biaxial(const Config& c, PackingKind kind, double mu, const CalibrationLog& log);

// ----------------------------------------------------------- basal friction

struct BasalRow {
    double time = 0;            // since the belt started [s]
    double base_normal = 0;     // normal force on the base, interval mean [N]
    double traction = 0;        // sum of the base tractions, interval mean [N]
    double holding_force = 0;   // horizontal force on the holding (right) wall, interval mean [N]
    double back_force = 0;      // horizontal force on the left wall, interval mean [N]
    double mu_eff = 0;          // traction / base_normal [-]
    double mu_walls = 0;        // (holding_force − back_force) / base_normal [-]
    std::size_t on_base = 0, sliding = 0;  // discs on the base, at the Coulomb cap
};

struct BasalResult {
    PackingKind kind = PackingKind::clusters;
    double mu = 0, mu_bp = 0;
    std::size_t discs = 0;
    double block_length = 0, block_height = 0;  // the block as placed [m]
    double weight = 0;                          // M g [N]
    WindowStats mu_eff;                         // over the measurement window
    WindowStats mu_walls;                       // the walls' measure over the same window
    double phi_eff_deg = 0;                     // atan(mean μ_eff) [°]
    double sliding_fraction = 0;                // mean sliding / on_base over the window
    double traction_limit_ratio = 0;            // γ_b v' / (μ_bp N) of the most loaded base disc at the end
    std::vector<BasalRow> rows;
};

/// The test on a given block (discs resting on y = 0; the walls go at the
/// block's ends): a hand-built block in the tests, the settled one in
/// run_basal_friction.
BasalResult run_basal_block(const Config& c, ParticleStore block, double mu, double mu_bp,
                            const CalibrationLog& log);
BasalResult run_basal_friction(const Config& c, PackingKind kind, double mu_bp, const CalibrationLog& log);

// ------------------------------------------------------------------- repose

struct ReposeResult {
    PackingKind kind = PackingKind::clusters;
    double mu = 0;
    std::size_t discs = 0;       // free discs
    double time = 0;             // simulated time to rest [s]
    std::uint64_t steps = 0;
    HeapProfile profile;
    ReposeFit fit;
};

ReposeResult run_repose(const Config& c, PackingKind kind, double mu, const CalibrationLog& log);

/// A layer of `kind` with μ_i = mu settled under gravity in a box of the
/// given length and cut to height (setup/packing.hpp), discs in x ∈ [0, length].
ParticleStore settled_block(const Config& c, PackingKind kind, double mu, double length, double height,
                            const CalibrationLog& log);

/// Refuses (ConfigError, before anything is generated) a calibration whose
/// samples are too large to run (check_disc_budget, setup/scenario.hpp).
void check_calibration_size(const Config& c);
/// The packing of one calibration sample: c's packing with this kind, length
/// and height [m], refused (ConfigError) when it is too large to run.
PackingConfig calibration_sample(const Config& c, PackingKind kind, double length, double height);

}  // namespace orodem
