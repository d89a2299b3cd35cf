// Wedge experiments (SPEC §2; paper §3.2, §4, §5): the settled, cut layer is
// placed with the S point at x = 0 on the base y = 0 and given the walls and
// boundaries of the chosen experiment.
//
//   walls[0]  proside base, y = 0 from the far proside end to x = 0, open
//             ends, smooth; ConveyorTraction drags discs on it at +v (eq. 5)
//             capped by μ_bp N.
//   walls[1]  retroside base, y = 0 from x = 0 on, open ends: smooth with
//             FixedRetroside (exp1, exp2), or rough with μ_br = ratio · μ_bp
//             (exp3, the stationary Coulomb base); for critical-wedge it is
//             the rigid, vertical, smooth backstop at x = 0 instead.
//   walls[2]  far proside wall at the trailing end, moving with the base.
//   walls[3]  far retroside wall, fixed (not for critical-wedge).
//
// The layer spans x ∈ [−(s_max + pro_margin) h0, retro_length h0], so the
// incoming plate never runs out before S = s_max.
#pragma once

#include "orodem/analysis/wedge_profile.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/io/config.hpp"

namespace orodem {

class ConveyorTraction;
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
    ConveyorTraction* base = nullptr;        // owned by sim.boundaries
    FixedRetroside* fixed_retro = nullptr;   // exp1, exp2 only
};

/// Builds the experiment from the settled layer (discs in [0, L], cut to h0).
/// Throws ConfigError if eq. 6 (v' < m g / (k_n dt)) is violated.
WedgeSetup make_wedge(const Config& c, const ParticleStore& layer);

/// The measurement parameters of the experiment (SPEC §3) from the config
/// alone; y_mean is left 0 (undeformed_surface measures it).
ProfileParams wedge_profile_params(const Config& c);
/// y_mean: the mean surface-centre height of the incoming layer at the start,
/// from h0 inside its trailing end to h0 before the S point [m].
double undeformed_surface(const ParticleStore& p, const ProfileParams& pp);

/// Eq. 6 bound on the belt speed for the lightest disc: m_min g / (k_n dt) [m/s].
double belt_speed_limit(const Config& c);
/// Throws ConfigError naming wedge.v and the numbers when v' >= belt_speed_limit.
void check_belt_speed(const Config& c);

}  // namespace orodem
