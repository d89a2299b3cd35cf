// Wedge experiments (SPEC §2; paper §3.2, §4, §5): the settled, cut layer is
// placed with the S point at x = 0 on the base y = 0 and given the walls and
// boundaries of the chosen experiment.
//
//   walls[0]  proside base, y = 0 from the far proside end to x = 0, open
//             ends, smooth; its law (wedge.base_law) carries discs at +v:
//             CoulombBase (default; spring-slider, friction μ_bp) or
//             ConveyorTraction (eq. 5 capped by μ_bp N).
//   walls[1]  retroside base, y = 0 from x = 0 on, open ends: smooth with
//             FixedRetroside (exp1, exp2); exp3's stationary Coulomb base with
//             μ_br = ratio · μ_bp (smooth with a CoulombBase at rest, or under
//             the traction law a rough wall); for critical-wedge it is the
//             rigid, vertical, smooth backstop at x = 0 instead.
//   walls[2]  far proside wall at the trailing end, moving with the base.
//   walls[3]  far retroside wall, fixed (not for critical-wedge).
//
// The layer spans x ∈ [−(s_max + pro_margin) h0, retro_length h0], so the
// incoming plate never runs out before S = s_max.
//
// The push-wall sandbox (run.experiment = "sandbox", issue #67) uses the
// critical wedge's walls on a base at rest: the layer spans
// x ∈ [−sandbox.length h0, 0], walls[0] is the base (CoulombBase or the
// traction law at v' = 0, friction μ_bp), walls[1] the fixed end wall at
// x = 0, walls[2] the wall that pushes the layer at +v. A wedge cut to
// sandbox.surface_slope_deg falls from h0 at the moving wall.
#pragma once

#include "orodem/analysis/wedge_profile.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/io/config.hpp"
#include "orodem/physics/stability.hpp"

namespace orodem {

class BasalBoundary;
class CoulombBase;
class FixedRetroside;

inline constexpr std::size_t kWallProBase = 0;
inline constexpr std::size_t kWallRetro = 1;      // retroside base, or the backstop
inline constexpr std::size_t kWallProEnd = 2;
inline constexpr std::size_t kWallRetroEnd = 3;

struct WedgeSetup {
    Simulation sim;
    ProfileParams profile;       // measurement parameters, y_mean measured on the layer
    double pro_length = 0.0;     // incoming plate length [m]
    double retro_length = 0.0;   // retroside layer length [m]
    BasalBoundary* base = nullptr;           // the proside base law, owned by sim.boundaries
    CoulombBase* retro_base = nullptr;       // exp3 under the Coulomb law: the retroside base
    FixedRetroside* fixed_retro = nullptr;   // exp1, exp2 only
    std::uint32_t reserve_begin = 0;         // with sedimentation: the first id of the sediment reserve
                                             // (add_sediment_reserve); the layer's discs are the ids below
};

/// The parking places of particles out of the model ([surface]): eroded ones
/// and the sediment reserve. A cluster lies within 3 r_max of its centroid
/// (three touching discs in a row at most), so places 6 r_max + 2 skins apart
/// are never contact candidates (a pair is one within the sum of its radii
/// plus the skin); the first row 2 h0 below the base, far from every wall
/// (the bases are y = 0), rows along the whole layer's length. The reserve
/// takes the first places, eroded particles the places after it.
struct ParkingGrid {
    double x0 = 0.0, y0 = 0.0, pitch = 0.0;  // place 0 and the spacing [m]
    std::uint64_t per_row = 1;                // places in a row [-]
    Vec2 place(std::uint64_t k) const {
        return {x0 + static_cast<double>(k % per_row) * pitch, y0 - static_cast<double>(k / per_row) * pitch};
    }
};
ParkingGrid parking_grid(const Config& c, const WedgeSetup& w);

/// Sedimentation's reserve ([surface] sediment, docs/physics.md
/// "Sedimentation in the running wedge"): copies of the layer's particles
/// (clusters and lone discs, in id order, repeated) with the ids after the
/// layer's, in the sediment material, until their layer area reaches
/// surface.sediment_reserve h0²; each is fixed, flagged kFlagRemoved |
/// kFlagReserve and parked at its place of parking_grid (reserve particle j
/// at place j), out of every contact and measure until it is deposited.
/// Sets w.reserve_begin. Returns the number of reserve particles.
std::size_t add_sediment_reserve(const Config& c, WedgeSetup& w);

struct RunNumbers;

/// Builds the experiment from the settled layer (discs in [0, L], cut to h0)
/// with the numbers derived from c (derive_run_numbers, which throws
/// ConfigError if eq. 6 (v' < m g / (k_n dt)) is violated under the traction
/// law, or the Coulomb base's dashpot would be unstable).
WedgeSetup make_wedge(const Config& c, const ParticleStore& layer, const RunNumbers& n);
/// The same, deriving the numbers first.
WedgeSetup make_wedge(const Config& c, const ParticleStore& layer);

/// The measurement parameters of the experiment (SPEC §3) from the config
/// alone; y_mean is left 0 (undeformed_surface measures it).
ProfileParams wedge_profile_params(const Config& c);
/// y_mean: the mean surface-centre height of the incoming layer at the start,
/// from h0 inside its trailing end to h0 before the S point [m].
double undeformed_surface(const ParticleStore& p, const ProfileParams& pp);
/// The same for the experiment of c: the push-wall sandbox measures a flat
/// layer's far half, and takes the base (0) under a wedge cut to a slope.
double undeformed_surface(const ParticleStore& p, const ProfileParams& pp, const Config& c);

/// Eq. 6 bound on the belt speed for the lightest disc: m_min g / (k_n dt) [m/s]
/// (dt [s] the run's timestep; without it, timestep_for(c)).
double belt_speed_limit(const Config& c, double dt);
double belt_speed_limit(const Config& c);
/// Throws ConfigError naming wedge.v and the numbers when v' >= belt_speed_limit.
void check_belt_speed(const Config& c, double dt);
void check_belt_speed(const Config& c);
/// The checks of the config's base law: check_belt_speed for the traction
/// law, check_base_dashpot for the Coulomb base.
void check_wedge_base(const Config& c, double dt);
void check_wedge_base(const Config& c);
/// The inertial number of the convergence, I = γ̇ d sqrt(ρ/P) [-], with the
/// bulk shear rate γ̇ = v'/h0, d = r_min + r_max and P = ρ g h0, the
/// lithostatic pressure at the base of the incoming layer (the décollement);
/// quasi-static below about 1e-3 (docs/experiments.md "Belt speed").
double inertial_number(const Config& c);
/// How far the prowedge's deformation front reaches by wedge.s_max, from
/// critical-taper theory, to size the incoming plate (docs/experiments.md
/// "Plate length"). The wedge grows at its critical slope α_c (Dahlen's α_min
/// for β = 0, the bulk friction φ of the material and φ_b = atan μ_bp, capped
/// 0.5° below φ); all the accreted area S h0² is put in one triangle above the
/// undeformed surface, ½ L² tan α_c (no retrowedge: an upper bound), so the
/// front lies L = h0 sqrt(2 S / tan α_c) from the S point, and the plate
/// beyond s_max h0 must be at least L/h0 + 2 (the trailing wall is h0 from a
/// toe that the run reports, plus h0 of compacting plate ahead of the toe).
struct PlateEstimate {
    double phi_deg = 0.0;         // bulk friction angle used (the calibrated φ_cs of the packing kind at μ_i) [deg]
    double phi_b_deg = 0.0;       // basal friction angle used [deg]
    double alpha_deg = 0.0;       // critical slope α_c [deg]
    double front_h0 = 0.0;        // L / h0 at s_max [-]
    double pro_margin_min = 0.0;  // the shortest wedge.pro_margin for it [h0]
};
PlateEstimate plate_estimate(const Config& c);
/// Bulk (critical-state) friction angle of a packing kind with contact
/// friction μ_i, from the biaxial calibration (docs/validation.md
/// "Calibration"), interpolated linearly in μ_i [deg]. Hexagonal packings
/// use the discs' row.
double bulk_friction_deg(PackingKind kind, double mu_i);
/// Throws ConfigError when dt [s] is too long for the Coulomb base's dashpot
/// (wedge or calibrate base_law = "coulomb"; nothing for the traction law).
void check_base_dashpot(const Config& c, double dt);
void check_base_dashpot(const Config& c);

/// The numbers a run derives from its config, computed once by
/// derive_run_numbers and handed on (orodem check prints them; the run and
/// make_wedge use them) instead of being derived again by each caller.
struct RunNumbers {
    TimestepInfo timestep;          // dt, its stability limit, the collision time
    double belt_speed_limit = 0.0;  // eq. 6 bound m_min g / (k_n dt) [m/s] (the traction law's)
    double inertial_number = 0.0;   // of the convergence [-] (wedge experiments)
    PlateEstimate plate;            // the plate the deformation front needs (wedge experiments)
};
/// With the checks of a runnable config: ConfigError for a dt above the
/// stability limit (timestep_for) and, for a wedge, a base law's bound
/// (check_wedge_base).
RunNumbers derive_run_numbers(const Config& c);

}  // namespace orodem
