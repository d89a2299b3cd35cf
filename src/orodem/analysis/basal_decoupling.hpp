// The belt's decoupling point of an output interval (issue "structures"; docs/
// physics.md "Decoupling point"): where, going from the S point upstream, the
// discs on the proside base first move on average at half the belt's speed or
// more over the interval. Downstream of it the plate no longer rides the belt:
// the wedge stands on a base that slides beneath it, and the basal velocity
// discontinuity that roots the retro-vergent shear zone ([45]-[47]) sits
// there, not at x = 0, wherever the base cannot drag the layer all the way
// to the S point.
//
// The base layer: the discs whose lowest point lies within 5% of their radius
// of the base (y − R ≤ 0.05 R, the base at y = 0) at the start of the interval
// and whose centre is on the proside (x < 0, the S point at x = 0). Their
// speed over the interval, in units of the belt's, is u = Δx / d with d the
// belt's displacement over the interval. Bins of width w from x = 0 upstream
// ([−w, 0), [−2w, −w), ...): the first bin (from the S point) whose mean u is
// ≥ ½ gives x_d, interpolated linearly between its centre and the centre of
// the nearest non-empty bin downstream (whose mean is < ½). x_d = 0 when the
// non-empty bin nearest the S point moves at ≥ ½ (the belt carries the layer
// up to S); NaN when no bin does (d ≤ 0, or nothing rides the belt). Pure
// function of its inputs, sequential in id order.
#pragma once

#include <vector>

#include "orodem/core/vec2.hpp"

namespace orodem {

/// The bin width the runs and `orodem faults` use, in h0 [-].
constexpr double kDecouplingBinOverH0 = 0.5;

/// x_d [m] (x relative to the S point) from the positions at the start and end
/// of an interval and the radii [m], all by disc id (a NaN position: a disc
/// that one of the two lacks, skipped), the belt's displacement d [m] over the
/// interval and the bin width w [m].
double basal_decoupling_x(const std::vector<Vec2>& x_then, const std::vector<Vec2>& x_now,
                          const std::vector<double>& radius, double belt_displacement, double bin_width);

}  // namespace orodem
