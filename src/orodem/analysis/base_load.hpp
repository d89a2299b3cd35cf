// The load the layer puts on the base (issue #68; docs/physics.md "Flexure
// under the wedge"): per disc, the downward force [N/m per unit out-of-plane
// width, i.e. N in the 2D model] that the base carries under it, measured
// from the contact forces of the last step:
//   - a disc resting on a base wall (any free, awake disc): the normal force
//     of its contacts with the base walls (Σ f_y of those wall contacts);
//   - a fixed disc (Experiments 1, 2: the retroside discs glued to their
//     base): what holds it, the opposite of the force on it from everything
//     but the base walls, −(F − F_base)_y;
//   - a disc in a sleeping zone (asleep, or fixed in a sleeping column:
//     outside Simulation::in_awake_range): its weight m g (a sleeping zone
//     moves rigidly on the base, its forces are not evaluated; each of its
//     columns rests on the base with its own weight; a fixed disc's force
//     there is that of the last rebuild step, which would count the column
//     above it a second time);
//   - a removed (eroded) disc: nothing.
// In a quasi-static layer the loads add up to the layer's weight; their sum
// over the discs against the discs' weight is reported (base_load_ratio).
// Reads the engine's state only; serial, in id order: deterministic.
#pragma once

#include <cstddef>
#include <vector>

#include "orodem/engine/simulation.hpp"

namespace orodem {

/// The base load of each disc by id [N] into load (resized to the disc
/// count); base_walls: the indices of the walls that are the base (y up).
/// Returns Σ load [N].
double base_load_by_id(const Simulation& sim, const std::vector<std::size_t>& base_walls, std::vector<double>& load);

/// Σ m g over the discs present (not removed), in id order [N].
double present_weight(const Simulation& sim);

}  // namespace orodem
