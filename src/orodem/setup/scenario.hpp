// Scenario: turns a validated Config into engine objects (law parameters,
// timestep, simulations). The one place where config values become physics.
#pragma once

#include "orodem/engine/simulation.hpp"
#include "orodem/io/config.hpp"
#include "orodem/physics/stability.hpp"

namespace orodem {

/// Contact law from the material section: damping given as restitution e,
/// ratio ζ (γ = 2ζ sqrt(m_eff k)) or raw coefficient γ̃ (γ = m_eff γ̃).
LawParams make_law(const MaterialConfig& m);

/// Same law with both dashpots set to damping ratio zeta (settling).
LawParams with_damping_ratio(LawParams law, double zeta);

/// Mass of the lightest disc the packing can hold [kg].
/// The material that bounds the timestep: [material], or with several
/// materials (Config::materials) the least density and the largest k_n and
/// k_s / k_n of [material] and every material (each a bound on its own).
MaterialConfig governing_material(const Config& c);
double lightest_mass(const Config& c);

/// A wedge run's inertia floor, ρ π (wedge.inertia_floor r_min)² [kg]: free
/// discs move with at least this mass (SimParams::m_inertia_min); 0 when the
/// floor is off (inertia_floor = 1) and for every other experiment.
double inertia_floor_mass(const Config& c);

/// The layer's mean inertial mass over its mean own mass under the inertia
/// floor, E[max(R², F²)] / E[R²] for radii uniform in [r_min, r_max] (the
/// disc and cluster packings) and F = inertia_floor r_min [-]; 1 when the
/// floor is off or no disc is below it (hexagonal: all discs are r_max).
/// The mean inertial number grows by its square root (orodem check).
double inertia_floor_mean_mass_ratio(const Config& c);

/// The lightest mass a disc moves with: max(lightest_mass, inertia_floor_mass) [kg].
double lightest_inertial_mass(const Config& c);

/// dt and its stability margin from the lightest inertial mass; throws
/// ConfigError when numerics.dt is too large. with_floor = false: from the
/// lightest disc's own mass (the settling of the packing, which has no floor).
TimestepInfo timestep_for(const Config& c, bool with_floor = true);

/// A simulation of the packing of c settling in its box (not yet initialised
/// particles are generated from the packing seed).
Simulation make_settle_simulation(const Config& c);

/// Number of particles (discs) generation will create for c. Call
/// check_model_size first: it generates them.
std::size_t generated_particle_count(const Config& c);

/// The largest model orodem runs: 1e8 discs [-]; about 100 GB (docs/reliability.md, 6).
inline constexpr double kMaxDiscs = 1.0e8;
/// Memory a run needs per disc, about (particle columns, candidate pairs,
/// cell lists, checkpoint bytes) [bytes].
inline constexpr double kBytesPerDisc = 1024.0;
/// The discs generation will create for the packing, estimated from its
/// area (within a few per cent; no allocation) [-]; +inf when not finite.
double estimated_disc_count(const PackingConfig& pc);
/// Throws ConfigError, at once and before anything is allocated, when the
/// estimate exceeds kMaxDiscs or needs more memory than the machine has
/// (kBytesPerDisc per disc), naming the estimate and the keys to change.
void check_model_size(const Config& c);
/// The same for any sample (a calibration's block or column): `what` names
/// it, `keys` the keys that shrink it.
void check_disc_budget(const Config& c, const PackingConfig& sample, const std::string& what,
                       const std::string& keys);

}  // namespace orodem
