// Relative displacement of neighbours ([41]; SPEC §3): for every disc, the
// largest |Δx_i − Δx_j| over its neighbours j (the candidate pairs of the
// contact store, bonds included) between two outputs, Δx = x(now) − x(then),
// in metres, and divided by the largest value over all discs in the interval,
// so it lies in [0, 1] and picks out the active shear zones. Read-only over
// the state.
#pragma once

#include <vector>

#include "orodem/engine/simulation.hpp"

namespace orodem {

/// x_then: positions by particle id at the previous output. Returns per
/// slot the largest |Δx_i − Δx_j| over the disc's neighbours [m] (no
/// normalisation: the pictures scale it by the convergence ΔS h0 of the
/// interval, the same for every frame; the VTU's rel_disp_abs).
std::vector<double> relative_displacement_m(const Simulation& sim, const std::vector<Vec2>& x_then);

/// The same divided by its largest value over all discs, in [0, 1] (the
/// VTU's rel_disp; 0 everywhere when nothing moved).
std::vector<double> normalised(std::vector<double> v);

/// normalised(relative_displacement_m(sim, x_then)).
std::vector<double> relative_displacement(const Simulation& sim, const std::vector<Vec2>& x_then);

/// Positions by particle id (to pass as x_then at the next output).
std::vector<Vec2> positions_by_id(const ParticleStore& p);

}  // namespace orodem
