// CoulombBase: the Coulomb base of SPEC §2 and [42] (wedge.base_law =
// "coulomb", the default): a base moving at v' along its direction û with
// static and kinetic friction μ_b, whatever the load, belt speed or timestep.
//
// Each disc touching the base wall (a positive normal force N from it) has a
// tangential spring-slider against the belt surface (physics/contact_law.hpp,
// eval_base_spring): its history ξ (along û) is loaded each step with the
// disc centre's displacement relative to the belt, (v_i·û − v') dt, and
// F = −k_s ξ − γ_s (v_i·û − v') is limited by μ_b N, beyond which the disc
// slides with friction μ_b N. A disc that sticks moves with the belt at
// exactly v' (its force is elastic, not a drag that needs a velocity lag). k_s
// is the material's tangential stiffness; the dashpot is critically damped on
// the disc's mass, γ_s = 2 sqrt(k_s m_i), so a stuck disc does not ring
// against the belt (ω dt = sqrt(k_s/m_i) dt ≤ 0.06 with the automatic dt, so
// the explicit dashpot is far inside its stability limit γ_s dt / m_i < 2). The force acts
// at the disc centre with no torque: the belt grips each disc as eq. 5 does,
// so a base disc cannot roll on the belt, and the basal friction of a layer is
// μ_b, not that of discs rolling on it (docs/physics.md "The proside base").
//
// The base wall itself is smooth (the engine gives only its normal force);
// ξ lives in the wall contact's history slot (WallContactStore::xi, keyed by
// disc id and wall), so it survives neighbour rebuilds and re-sorting, is
// saved in checkpoints and reset by the engine when the disc leaves the base.
// A sleeping or fixed disc (inverse mass 0) is skipped and keeps its ξ: a
// sleeping disc rides rigidly at the belt speed, where ξ would not change.
// The tangential force is added to the wall contact's force too, so
// Simulation::wall_force(wall) is the base's whole force on the layer.
//
// With v' = 0 it is the stationary Coulomb retroside base of Experiment 3
// (μ_b = μ_br).
//
// Per disc in a loop over Simulation::wall_discs; each iteration writes only
// its own disc's force, history and slot, so the result is independent of
// the thread count.
#pragma once

#include <cstddef>

#include "orodem/boundary/basal_boundary.hpp"

namespace orodem {

class CoulombBase : public BasalBoundary {
public:
    /// The base wall must be smooth (this boundary is its tangential law).
    CoulombBase(std::size_t wall, double v_belt, double mu_b) : BasalBoundary(wall, v_belt, mu_b) {}

    std::string_view name() const override { return "coulomb-base"; }

protected:
    void apply_law(Simulation& sim, std::size_t c0, std::size_t c1, bool parallel) override;
};

/// Damping ratio of the base spring (critical) [-].
inline constexpr double kBaseDampingRatio = 1.0;

}  // namespace orodem
