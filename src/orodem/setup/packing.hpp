// Packings ([33]-[37], Figure 6): generation of a loose granular layer, its
// settling under gravity in a box, and the cut to mean thickness h0.
//
// Generation places discs or 3-disc clusters on a loose square lattice (no
// initial overlap), enough disc area to fill L × (h0 + 3 r_max) at packing
// fraction 0.9, so the settled layer is always thicker than h0.
// Settling runs the engine in a box (rough floor y = 0, smooth side walls
// x = 0 and x = L) with damping ratio settle_damping_ratio, and stops when
// (a) a free fall from the top of the loose pack has had time to finish and
// (b) the kinetic energy per unit weight is below settle_ke_ratio · h0, i.e.
// E_kin < settle_ke_ratio · M g h0. The cut keeps a disc (a whole cluster)
// whose centre (centre of mass) lies below y = h0, and records each disc's
// initial depth h0 - y.
#pragma once

#include <cstdint>
#include <functional>

#include "orodem/core/rng.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/io/config.hpp"

namespace orodem {

/// Loose, overlap-free particles in x ∈ [0, L], y > 0, at rest.
ParticleStore generate_packing(const PackingConfig& pc, double density);

struct SettleProgress {
    std::uint64_t step;
    double time;               // [s]
    double kinetic_energy;     // [J]
    double ke_ratio;           // E_kin / (M g h0) [-]
    std::size_t contacts;
};

/// Runs sim until settled (see the file note). `report` is called every
/// `report_interval` of simulated time [s]. Throws InstabilityError if
/// settle_max_steps pass first.
SettleProgress settle(Simulation& sim, const PackingConfig& pc, double report_interval,
                      const std::function<void(const SettleProgress&)>& report);

/// Removes discs (clusters, by centre of mass) above y = h0, zeroes velocities
/// and sets initial_depth = h0 - y. Ids are renumbered densely.
void cut_layer(ParticleStore& p, double h0);

/// The push-wall sandbox's wedge (sandbox.surface_slope_deg): removes the
/// discs (clusters, by centre of mass) above the surface y = h0 - tan(slope)
/// (x - x_wall), which falls from h0 at the wall at x_wall; keeps every other
/// column as it is (initial_depth included).
void cut_layer_to_slope(ParticleStore& p, double h0, double x_wall, double slope_deg);

/// Height of the top of the layer's surface, averaged over columns of width
/// 2 r_max: the mean of the highest disc top y + R in each column [m].
double mean_surface_height(const ParticleStore& p, double x0, double x1, double column);

}  // namespace orodem
