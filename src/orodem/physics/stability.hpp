// Timestep from the stiffest spring and the lightest disc (SPEC §1,
// RELIABILITY-CHECKLIST #3).
//
// dt = safety · sqrt(m_min / k_max), with k_max = max(k_n, 3 k_s): a disc's
// tangential-rotational mode is 1 + m R²/I = 3 times stiffer than k_s alone.
// The stability limit refused above: the explicit scheme is stable for
// ω dt < 2; a disc of mass m_min pressed by z_max = 6 neighbours of equal
// mass has ω² ≤ 2 z_max k_max / m_min (Gershgorin), so
// dt_crit = 2 sqrt(m_min / (12 k_max)) = 0.577 sqrt(m_min / k_max).
// The default safety 0.1 gives a margin of 5.8; the collision time of two
// lightest discs is t_c = π sqrt(m_min/(2 k_n)) ≈ 22 dt.
#pragma once

#include "orodem/physics/contact_law.hpp"

namespace orodem {

struct TimestepInfo {
    double dt = 0.0;        // the step used [s]
    double dt_crit = 0.0;   // stability limit [s]
    double t_collision = 0.0;  // undamped contact duration of two lightest discs [s]
    double margin() const { return dt_crit / dt; }
};

inline constexpr double kDefaultSafety = 0.1;   // dt / sqrt(m_min/k_max) [-]
inline constexpr double kMaxCoordination = 6.0; // z_max in the stability bound

double stiffest_spring(const LawParams& p);
double critical_timestep(double m_min, double k_max);

/// dt_requested = 0 means automatic: safety · sqrt(m_min/k_max). A requested
/// dt above dt_crit throws ConfigError naming both numbers.
TimestepInfo choose_timestep(double m_min, const LawParams& p, double dt_requested, double safety);

}  // namespace orodem
