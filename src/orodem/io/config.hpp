// Config: the typed, validated form of a TOML config file. Parsing happens
// only here (io/config.cpp); everything downstream receives these structs.
//
// Every default lives in the member initialisers below, with its unit. The
// loader fills `resolved` with every key actually used, defaults included,
// which is what a run directory's config.toml holds (SPEC §4).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "orodem/core/named.hpp"

namespace orodem {

/// The proside (and exp3 retroside) base law (boundary/basal_boundary.hpp).
enum class BaseLaw { coulomb, traction };
inline constexpr Named<BaseLaw> kBaseLaws[] = {{BaseLaw::coulomb, "coulomb"}, {BaseLaw::traction, "traction"}};
constexpr const char* name_of(BaseLaw v) { return name_in(kBaseLaws, v); }

/// How material.damping_normal and damping_tangential are read (setup/scenario.cpp make_law).
enum class DampingKind { restitution, ratio, coefficient };
inline constexpr Named<DampingKind> kDampingKinds[] = {
    {DampingKind::restitution, "restitution"}, {DampingKind::ratio, "ratio"}, {DampingKind::coefficient, "coefficient"}};
constexpr const char* name_of(DampingKind v) { return name_in(kDampingKinds, v); }

/// The particles of a packing ([33]-[37]): equal discs on a lattice, random discs, random 3-disc clusters.
enum class PackingKind { hexagonal, discs, clusters };
inline constexpr Named<PackingKind> kPackingKinds[] = {
    {PackingKind::hexagonal, "hexagonal"}, {PackingKind::discs, "discs"}, {PackingKind::clusters, "clusters"}};
constexpr const char* name_of(PackingKind v) { return name_in(kPackingKinds, v); }

struct RunConfig {
    std::string experiment = "settle";  // required: settle | critical-wedge | exp1 | exp2 | exp3 | sandbox
                                        // | biaxial | basal-friction | repose (orodem calibrate)
    std::uint64_t seed = 1;             // master seed; packing.seed defaults to it [-]
    int threads = 0;                    // OpenMP threads, 0 = all cores [-]
    double output_interval = 0.05;      // settle: simulated time between series rows [s]
    int checkpoint_every_outputs = 1;   // wedge: a checkpoint every this many outputs [-]
    double checkpoint_minutes = 10.0;   // wedge: and after this much wall time, checked every 100 steps; 0 = off [min]
    double max_wall_minutes = 0.0;      // wedge: stop with a checkpoint (exit 5) after this much wall time in one
                                        // invocation, as a batch job's time limit asks; 0 = no limit [min]
    double max_overlap_ratio = 0.5;     // wedge: stop (exit 3) when an overlap exceeds this fraction of the smaller radius [-]
    double warn_overlap_ratio = 0.1;    // wedge: log a warning when the largest overlap exceeds this fraction [-] (demo runs peak near 0.07)
    bool allow_initial_overlap = false; // wedge: start even when the initial layer has an overlap above max_overlap_ratio
    double domain_height = 0.0;         // wedge: discs above this height leave the domain [h0]; 0 = all the
                                        // material stacked in one column h0 wide (docs/reliability.md)
    std::string on_domain_exit = "error";  // wedge: a disc leaving the domain: error (exit 3, last good state kept)
                                           // | stop (outputs and checkpoint of the current state, exit 3)
};

/// The wedge experiments (SPEC §2). Lengths in units of h0 where noted.
struct WedgeConfig {
    double v = 0.1;                   // convergence (belt) speed v' [m/s]
    double s_max = 3.0;               // stop at normalised convergence S = v t / h0 [-]
    double output_ds = 0.25;          // ΔS between outputs (series rows) [-]
    double mu_bp = 0.3;               // proside basal friction μ_bp [-]
    double mu_br_over_mu_bp = 2.0;    // exp3: retroside basal friction μ_br / μ_bp [-]
    BaseLaw base_law = BaseLaw::coulomb;  // proside base: coulomb (spring-slider, static friction μ_bp) | traction
                                      // (eq. 5 capped by μ_bp N); boundary/basal_boundary.hpp
    double traction_gain = 1.0;       // traction only: g_b in the eq. 5 traction γ_b = g_b m_i / dt [-]
    double drag_gain = 0.0;           // g_d in an uncapped drag γ_d = g_d m_i / dt added to it [-]; 0: none
    double pro_margin = 10.0;         // incoming plate beyond s_max·h0 [h0]
    double retro_length = 8.0;        // retroside layer length [h0] (not for critical-wedge)
    double toe_threshold = 0.1;       // rise above the undeformed surface marking a toe [h0]
    double column_width = 0.0;        // surface column width δx [m]; 0 = 2 r_max
    bool sleep = false;               // sleeping zones: rigidly moving material skips force work (engine/sleep.cpp)
    double sleep_tolerance = 0.01;    // departure from rigid motion between rebuilds that keeps a disc awake [r_min]
    double sleep_buffer = 2.0;        // awake margin beyond the outermost deforming disc [h0]
    double sleep_buffer_pro = 2.0;    // the same margin on the proside (the incoming plate, left of the S point)
                                      // [h0]; when the key is absent, sleep_buffer
    double inertia_floor = 1.0;       // discs smaller than inertia_floor·r_min move with the mass and moment of
                                      // inertia of a disc of that radius (their weight stays ρ π R² g), and the
                                      // automatic dt follows the lightest inertia; 1 = off (docs/physics.md) [-]
};

/// [sandbox]: the push-wall sandbox (run.experiment = "sandbox"; docs/experiments.md
/// "The push-wall sandbox"): a layer between a wall that moves right at wedge.v
/// and a fixed wall, on a base at rest with friction wedge.mu_bp.
struct SandboxConfig {
    double length = 10.0;             // layer length from the moving wall to the fixed end wall [h0]
    double surface_slope_deg = 0.0;   // 0: a flat layer h0 thick; > 0: its top cut to a surface falling at this
                                      // angle from h0 at the moving wall (GeoMod 2008 Exp. 1: 20) [deg]
};

struct MaterialConfig {
    double density = 2500.0;          // ρ, disc mass m = ρ π R² per unit depth [kg/m³]
    double k_n = 1.0e8;               // normal spring stiffness [N/m]
    double k_s_over_k_n = 1.0 / 3.0;  // k_s / k_n [-]; 1/3 keeps the tangential-rotational mode (3 k_s) no stiffer than k_n
    double mu = 0.3;                  // μ_i = tan φ_i, disc-disc Coulomb coefficient [-]
    double cohesion = 0.0;            // C in F_max = μ F_n + C [N]
    DampingKind damping_kind = DampingKind::restitution;  // restitution | ratio | coefficient
    double damping_normal = 0.5;      // e (restitution), ζ_n (ratio) or γ̃_n [1/s] (coefficient, F = m_eff γ̃ v)
    double damping_tangential = 0.0;  // ζ_s (restitution, ratio) or γ̃_s [1/s] (coefficient)
    bool clamp_normal = true;         // unbonded contacts never attract (F_n >= 0)
};

/// A named material of a layered wedge ([materials.NAME]; physics/materials.hpp):
/// the keys it does not give take [material]'s values; the damping is
/// [material]'s for every material.
struct NamedMaterial {
    std::string name;                 // the NAME of [materials.NAME]
    MaterialConfig m;                 // density, k_n, k_s_over_k_n, mu (the peak μ), cohesion
    double mu_residual = 0.0;         // μ_res after weakening [-]; default: mu (no weakening)
    double weakening_distance = 1.0;  // sliding distance over which μ falls from mu to mu_residual [mean disc diameters]
    double healing = 0.0;             // damage healed per unit of S [mean disc diameters]
    bool cohesion_loss = false;       // a contact's cohesion is lost for good once it slides or separates
};

/// One layer of a layered wedge ([[layers]] from the base up, [[retro_layers]]).
struct LayerConfig {
    std::string material;             // a NAME of [materials.NAME]
    double thickness = 0.0;           // [h0]; the layers add up to 1
};

/// The friction of a pair of materials named explicitly ([[friction_pairs]]);
/// otherwise the smaller of the two materials' values.
struct FrictionPair {
    std::string a, b;                 // material names
    double mu = 0.0;                  // peak μ of a contact between them [-]
    double mu_residual = 0.0;         // residual μ [-]; default mu
};

/// [surface]: erosion and sedimentation applied while the belt runs
/// (docs/physics.md "Erosion and sedimentation laws", "Erosion in the running
/// wedge", "Sedimentation in the running wedge"); wedge
/// experiments only. Absent: nothing is resolved and the run is as before.
/// Rates in h0 per unit S, lengths in h0 (analysis/surface_laws.hpp).
enum class SurfaceKind { none, elevation, slope, uniform, cap, diffusion };
inline constexpr Named<SurfaceKind> kSurfaceKinds[] = {
    {SurfaceKind::none, "none"},       {SurfaceKind::elevation, "elevation"}, {SurfaceKind::slope, "slope"},
    {SurfaceKind::uniform, "uniform"}, {SurfaceKind::cap, "cap"},             {SurfaceKind::diffusion, "diffusion"}};
constexpr const char* name_of(SurfaceKind v) { return name_in(kSurfaceKinds, v); }
enum class SedimentSide { none, pro, retro, both };
inline constexpr Named<SedimentSide> kSedimentSides[] = {
    {SedimentSide::none, "none"}, {SedimentSide::pro, "pro"}, {SedimentSide::retro, "retro"}, {SedimentSide::both, "both"}};
constexpr const char* name_of(SedimentSide v) { return name_in(kSedimentSides, v); }
struct SurfaceConfig {
    bool present = false;             // (not a key) the config has a [surface] table
    SurfaceKind law = SurfaceKind::none;  // none | elevation | slope | uniform | cap | diffusion
    double k = 0.0;                   // elevation: E = k h [1/S]
    double slope_k = 0.0;             // slope: E = K |dh/dx| [h0/S]
    double rate = 0.0;                // uniform: rate ė over the columns above the incoming surface [h0/S]
    double cap_height = 0.0;          // cap: everything above this height is removed [h0]
    double kappa = 0.0;               // diffusion: ∂h/∂S = κ ∂²h/∂x² [h0²/S]
    std::string ends = "closed";      // diffusion: closed (no flux) | fixed (the heights h_left, h_right beyond the wedge)
    double h_left = 0.0;              // diffusion, fixed ends: height held beyond the pro toe [h0]
    double h_right = 0.0;             // diffusion, fixed ends: height held beyond the retro toe [h0]
    std::int64_t interval_steps = 100;  // apply every this many steps (100: the run loop's chunk) [-]
    double column_width = 0.0;        // surface column width [h0]; 0 = wedge.column_width
    SedimentSide sediment = SedimentSide::none;  // none | pro | retro | both: the forelands to fill below base_level
    double base_level = 0.0;          // sedimentation: fill up to this height above the incoming surface [h0]
    double sediment_rate = 0.0;       // sedimentation: raise each column at most this fast; 0 = the whole deficit at each application [h0/S]
    std::string sediment_material;    // sedimentation: a NAME of [materials.NAME] (layered configs only; default: the top layer's); without [materials] the sediment is [material]
    double sediment_reserve = 0.0;    // sedimentation: layer area of new particles made ready at the start; 0 = 1.5 base_level (incoming plate + retroside + s_max) [h0²]
    bool sedimenting() const { return sediment != SedimentSide::none; }
};

/// [flexure]: the 1D elastic plate under the wedge (docs/physics.md "Flexure
/// under the wedge"; physics/flexure.hpp); exp1, exp2 and exp3 only. Absent:
/// nothing is resolved and the run is as before. The plate is quasi-static:
/// solved every interval_steps steps under the base load measured then.
enum class PlateKind { continuous, broken };
inline constexpr Named<PlateKind> kPlateKinds[] = {{PlateKind::continuous, "continuous"}, {PlateKind::broken, "broken"}};
constexpr const char* name_of(PlateKind v) { return name_in(kPlateKinds, v); }
enum class FlexureCoupling { one_way, two_way };
inline constexpr Named<FlexureCoupling> kFlexureCouplings[] = {{FlexureCoupling::one_way, "one-way"},
                                                               {FlexureCoupling::two_way, "two-way"}};
constexpr const char* name_of(FlexureCoupling v) { return name_in(kFlexureCouplings, v); }
struct FlexureConfig {
    bool present = false;             // (not a key) the config has a [flexure] table
    PlateKind plate = PlateKind::continuous;  // continuous | broken (two plates, free ends at the S point)
    FlexureCoupling coupling = FlexureCoupling::two_way;  // two-way: the base follows the plate; one-way: it stays flat
    double Te = 0.0;                  // elastic thickness T_e [m]; give Te or D
    double D = 0.0;                   // flexural rigidity D [N m] (per unit width); give D or Te
    double E = 70.0e9;                // Young's modulus E [Pa] (with Te)
    double nu = 0.25;                 // Poisson's ratio ν [-] (with Te)
    double rho_mantle = 3300.0;       // density of the mantle under the plate [kg/m³]
    double rho_infill = 0.0;          // density of what fills the deflection outside the model [kg/m³]; 0: air
    std::int64_t interval_steps = 100;  // solve the plate every this many steps (and at each output) [-]
    double dx = 0.0;                  // plate node spacing [h0]; 0 = α/40 (at most α/40)
    double extension = 9.42477796076938;  // plate beyond each end of the model [α]; default 3π
};

struct PackingConfig {
    PackingKind kind = PackingKind::clusters;  // hexagonal | discs | clusters ([33]-[37])
    double r_min = 0.5;               // smallest disc radius [m]
    double r_max = 1.0;               // largest disc radius [m] (hexagonal uses r_max)
    double length = 100.0;            // layer length L [m] (settle only; wedge experiments derive it)
    double h0 = 10.0;                 // mean layer thickness after the cut [m]
    std::uint64_t seed = 0;           // packing seed; 0 = run.seed [-]
    double settle_ke_ratio = 1.0e-6;  // settled when E_kin < ratio · m_total g h0 [-]
    double settle_damping_ratio = 0.5;  // ζ_n and ζ_s used while settling [-]
    std::int64_t settle_max_steps = 2000000;  // give up (error) after this many steps [-]
    double wall_mu = 0.3;             // μ of the settling box's floor (rough) [-]
    std::string cache_dir = "";       // settled packings are reused from here; "" = $XDG_CACHE_HOME/orodem or ~/.cache/orodem
};

/// The calibration experiments (orodem calibrate; docs/validation.md): each
/// runs once per packing kind and per value of its swept coefficient.
struct CalibrateConfig {
    std::vector<PackingKind> kinds;        // packing kinds to test; default {packing.kind}
    std::vector<double> mu_values;         // biaxial, repose: μ_i values [-]; default {material.mu}
    std::vector<double> mu_bp_values;      // basal-friction: μ_bp values [-]; default {0.3}
    std::string material;                  // biaxial: a NAME of [materials.NAME] to test (its μ, weakening and
                                           // cohesion) instead of [material] with mu_values; "" = [material]
    double compaction_mu = -1.0;           // biaxial: μ_i while compacting (0 gives the densest sample); -1 = the
                                           // tested μ [-]
    // biaxial: gravity-free sample in a box of four smooth walls
    double width = 30.0;                   // sample width after compaction, about [m]
    double height = 60.0;                  // sample height after compaction, about [m]
    double confining_stress = 2.0e5;       // σ_3 held by the side walls (and the compaction stress) [Pa]
    double strain_rate = 0.0;              // axial strain rate ε̇ [1/s]; 0 = the rate giving max_inertial_number
    double max_inertial_number = 1.0e-3;   // largest I = ε̇ d sqrt(ρ/σ_3) allowed (d = r_min + r_max) [-]
    double max_strain = 0.2;               // axial strain at the end of the test [-]
    double critical_from = 0.15;           // critical state: mean over axial strain in [critical_from, max_strain] [-]
    double output_strain = 0.0025;         // axial strain between rows of the series [-]
    double servo_gain = 0.5;               // α: fraction of a wall's stress error corrected per step [-]
    double servo_tolerance = 0.01;         // compaction ends when both servo stresses are within this relative error [-]
    // basal-friction: a block held by a fixed wall on the conveyor base
    double block_length = 20.0;            // block length along the base [m]
    double block_height = 10.0;            // block thickness [m]
    double belt_speed = 0.1;               // belt speed v' [m/s] (eq. 6 checked for the traction law)
    BaseLaw base_law = BaseLaw::coulomb;   // coulomb | traction, as wedge.base_law
    double traction_gain = 1.0;            // traction only: g_b in the eq. 5 traction γ_b = g_b m_i / dt [-]
    double belt_travel = 8.0;              // belt displacement of the run [m] (duration = belt_travel / belt_speed)
    double min_duration = 80.0;            // ... but at least this long [s]
    double duration = 0.0;                 // belt running time [s]; 0: max(belt_travel / belt_speed, min_duration)
    double measure_from = 0.5;             // the measurement averages over t in [measure_from · duration, duration] [-]
    // repose: a column released by lifting its side walls onto a floor of fixed discs
    double column_width = 20.0;            // column width [m]
    double column_height = 60.0;           // column height [m]
    double lift_speed = 2.0;               // side walls rise at this speed [m/s]
    double fit_from = 0.15;                // flanks fitted between these fractions of the heap height [-]
    double fit_to = 0.85;                  // (excludes the toe and the top) [-]
};

struct NumericsConfig {
    double dt = 0.0;                  // timestep [s]; 0 = safety · sqrt(m_min / k_max)
    double safety = 0.1;              // dt / sqrt(m_min / k_max) when automatic [-]
    double skin = 0.0;                // Verlet skin [m]; 0 = 0.4 r_min
    double gravity = 9.81;            // g, along -y [m/s²]
};

struct Config {
    std::string path;                 // file it came from
    RunConfig run;
    WedgeConfig wedge;
    SandboxConfig sandbox;            // the push-wall sandbox only
    MaterialConfig material;
    PackingConfig packing;
    NumericsConfig numerics;
    CalibrateConfig calibrate;        // calibration experiments only
    // Layered wedges (docs/physics.md "Materials, layers and weakening"):
    // empty in a one-material run, which [material] alone describes.
    std::vector<NamedMaterial> materials;      // [materials.NAME], in name order (material ids)
    std::vector<LayerConfig> layers;           // [[layers]]: the incoming plate from the base up
    std::vector<LayerConfig> retro_layers;     // [[retro_layers]]: the retroside; default the same as layers
    std::vector<FrictionPair> friction_pairs;  // [[friction_pairs]]
    SurfaceConfig surface;                     // [surface]: erosion while the belt runs (absent: off)
    FlexureConfig flexure;                     // [flexure]: the elastic plate under the wedge (absent: off)
    bool layered() const { return !layers.empty(); }
    toml::table resolved;             // every key with its final value
    // A run directory's config.toml written before base_law existed (orodem
    // 0.x up to the Coulomb base) has no base_law key: it is read as
    // base_law = "traction", the law that run used, and hashed as that
    // orodem hashed it (io/checkpoint.cpp config_hash), so it still resumes.
    bool legacy_base_law = false;
};

struct PlateParams;
/// The plate of [flexure] (io/config_flexure.cpp): g = numerics.gravity, a
/// break at the S point (x = 0) on a broken plate.
PlateParams flexure_plate_params(const Config& c);

/// The experiments (run.experiment), in one table: what each one is and
/// which boundaries it has (SPEC §2; setup/wedge.cpp builds them).
enum class ExperimentClass { settle, wedge, calibration };
enum class Retroside { none, fixed, coulomb };  // the retroside base of a wedge experiment
struct Experiment {
    const char* name;
    ExperimentClass kind;
    Retroside retroside;  // wedge experiments with a retroside
    bool backstop;        // the singly vergent critical wedge's rigid backstop at x = 0 (the sandbox: its fixed end wall)
    bool push_wall = false;  // the sandbox: a base at rest, the trailing wall pushes the layer toward the fixed end wall
};
inline constexpr Experiment kExperiments[] = {
    {"settle", ExperimentClass::settle, Retroside::none, false},
    {"critical-wedge", ExperimentClass::wedge, Retroside::none, true},
    {"exp1", ExperimentClass::wedge, Retroside::fixed, false},
    {"exp2", ExperimentClass::wedge, Retroside::fixed, false},
    {"exp3", ExperimentClass::wedge, Retroside::coulomb, false},
    // The push-wall sandbox (GeoMod 2008, issue #67): the set-up of analogue
    // laboratories, a layer pushed by a wall over a fixed base.
    {"sandbox", ExperimentClass::wedge, Retroside::none, true, true},
    {"biaxial", ExperimentClass::calibration, Retroside::none, false},
    {"basal-friction", ExperimentClass::calibration, Retroside::none, false},
    {"repose", ExperimentClass::calibration, Retroside::none, false},
};
/// The table's row of a name; a name the table does not have (which the
/// config loader refuses) is taken as settle.
inline const Experiment& experiment_of(const std::string& name) {
    for (const Experiment& e : kExperiments)
        if (name == e.name) return e;
    return kExperiments[0];
}
inline const Experiment& experiment_of(const Config& c) { return experiment_of(c.run.experiment); }
/// True for the calibration experiments (orodem calibrate): biaxial, basal-friction, repose.
inline bool is_calibration(const Config& c) { return experiment_of(c).kind == ExperimentClass::calibration; }
/// True for the wedge experiments (critical-wedge, exp1, exp2, exp3, sandbox).
inline bool is_wedge(const Config& c) { return experiment_of(c).kind == ExperimentClass::wedge; }

/// The keys that do not change a run's results, in one table: a run may be
/// resumed with other values (config_hash leaves them out), `orodem run
/// --resume` does not name them as a difference, and `orodem plot` does not
/// label runs by them. A key belongs here only if every output is
/// byte-identical whatever its value.
struct ResultNeutralKey {
    const char* section;
    const char* key;
    const char* why;
};
inline constexpr ResultNeutralKey kResultNeutralKeys[] = {
    {"run", "threads", "the results are identical at any thread count"},
    {"run", "checkpoint_minutes", "when checkpoints are written, not what is computed"},
    {"run", "max_wall_minutes", "where a piece of the run stops; the resumed run is identical"},
    {"packing", "cache_dir", "where settled packings are kept; a packing is found by what settles it"},
};
/// True for "run.threads" and the other keys of kResultNeutralKeys.
bool is_result_neutral(const std::string& dotted_key);
/// The first line where the resolved configs differ, leaving out the
/// result-neutral keys: "the run has '[s] k = a', this config has '[s] k = b'"; "" if none.
std::string first_config_difference(const Config& a, const Config& b);
/// run.experiment of a config file's text, read leniently (a config of another
/// orodem version, or with errors, still gives its name); "" when absent or not TOML.
std::string experiment_in(const std::string& config_text);
/// What the pictures of a run need of its config (`orodem render` and
/// `orodem movie` read it from config.toml leniently, as experiment_in; the
/// run loop takes it from its Config): the experiment, h0 and the model box
/// that fixes the frame of every picture of the run (render/particle_view.hpp
/// run_view). Keys absent from an older config.toml take their defaults.
struct ConfigBasics {
    std::string experiment;  // "run" when absent
    double h0 = 0.0;         // [m]
    double s_max = WedgeConfig{}.s_max;                // [-]
    double output_ds = WedgeConfig{}.output_ds;        // [-]
    double pro_margin = WedgeConfig{}.pro_margin;      // [h0]
    double retro_length = WedgeConfig{}.retro_length;  // [h0]
    std::size_t layers = 0;                            // a layered wedge's [[layers]]; 0: one material
};
/// IoError when the file is not TOML, ConfigError without a positive packing.h0.
ConfigBasics read_config_basics(const std::string& path);
/// The same from a loaded config.
ConfigBasics config_basics(const Config& c);

/// One `--set key=value` override; value is TOML syntax (1.5, true, "clusters").
using Override = std::pair<std::string, std::string>;

/// Whether two --set/--vary values (TOML syntax) are the same value: 0.3 and 0.30, 1e3 and 1000.0; values that
/// are not TOML are compared as text.
bool same_toml_value(const std::string& a, const std::string& b);

/// Parses "key=value"; throws ConfigError when there is no '='.
Override parse_override(const std::string& text);

/// Loads and validates. Throws ConfigError with a one-line message
/// "FILE:LINE:COL: key 'a.b' = VALUE: what is allowed" on any problem.
Config load_config(const std::string& path, const std::vector<Override>& overrides = {});
/// Same from a string (tests); `name` stands in for the file name.
Config parse_config(const std::string& text, const std::string& name,
                    const std::vector<Override>& overrides = {});

/// The first line of every resolved config.toml (to_toml): a file that starts
/// with it is read as a run directory's resolved config.
inline constexpr const char* kResolvedHeader =
    "# orodem resolved config: every key with its final value (defaults written out)\n";

/// The resolved config as TOML text.
std::string to_toml(const Config& c);

/// The resolved config without the keys whose value is this version's default
/// for the experiment (a config made only of `[run] experiment = ...`). Keys a
/// later version adds, with their defaults, leave this text unchanged; a
/// changed default or any value the user set changes it.
std::string to_toml_without_defaults(const Config& c);

}  // namespace orodem
