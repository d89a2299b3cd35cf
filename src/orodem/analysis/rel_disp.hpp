// Relative displacement of neighbours ([41]; SPEC §3): for every disc, the
// largest |Δx_i − Δx_j| over its neighbours j (the candidate pairs of the
// contact store, bonds included) between two outputs, Δx = x(now) − x(then),
// divided by the largest value over all discs in the interval, so it lies in
// [0, 1] and picks out the active shear zones. Read-only over the state.
#pragma once

#include <vector>

#include "orodem/engine/simulation.hpp"

namespace orodem {

/// x_then: positions by particle id at the previous output. Returns per slot.
std::vector<double> relative_displacement(const Simulation& sim, const std::vector<Vec2>& x_then);

/// Positions by particle id (to pass as x_then at the next output).
std::vector<Vec2> positions_by_id(const ParticleStore& p);

}  // namespace orodem
