// ConveyorTraction: the paper's eq. 5 base ([43]; wedge.base_law = "traction"). Every disc that
// touches the base wall (a wall contact with a positive normal force N) gets
// the traction F = γ_b (v' − v_i·û) û along the base direction û, capped at
// μ_b N, so the disc is dragged toward the belt speed v' but can still slide
// on the base. γ_b = g_b m_i / dt with the gain g_b ∈ (0, 1.5]: with g_b = 1
// a free disc reaches the belt speed in one step (the velocity change per
// step is g_b (v' − v_i); stable for g_b < 2). This is the reading of eq. 5
// under which the paper's eq. 6 follows: the displacement the traction
// induces in one step is v' dt, which must stay below the overlap m g / k_n.
// It is also what makes the base Coulomb-like rather than viscous: a disc
// that transmits the full μ_b N lags the belt by μ_b N dt / (g_b m_i), which
// is a small fraction of v' only when v' is near the eq. 6 bound
// (docs/experiments.md). The traction acts at the disc centre (no torque),
// as eq. 5 is written.
//
// With v' = 0 the same boundary is a viscous-Coulomb stationary base.
//
// Optional uncapped drag (wedge.drag_gain g_d, default 0): a second reading
// of [43], where eq. 5 is "one term added to the force summation" beside the
// Coulomb base rather than the Coulomb base itself. Each disc on the base
// then also gets F_d = γ_d (v' − v_i·û) û with γ_d = g_d m_i / dt, not capped
// by μ_b N. A disc held still transmits μ_b N + g_d m_i v'/dt: the drag adds
// the most where N is small (a thin plate), the Coulomb cap where it is large
// (under a thick wedge). Uncapped, the velocity change per step is
// (g_b + g_d)(v' − v_i), so g_b + g_d < 2 keeps it stable (config checks).
// Per-disc work in a loop over the discs with a candidate contact with the base (Simulation::wall_discs, listed at each rebuild); each iteration writes only its
// own disc's force, so the result is independent of the thread count.
#pragma once

#include <cstddef>

#include "orodem/boundary/basal_boundary.hpp"

namespace orodem {

class ConveyorTraction : public BasalBoundary {
public:
    /// wall: index of the base wall in Simulation::walls; v_belt: v' [m/s];
    /// mu_b: basal Coulomb coefficient [-]; gain: g_b in γ_b = g_b m_i / dt [-];
    /// drag_gain: g_d in the uncapped drag γ_d = g_d m_i / dt [-] (0: none).
    ConveyorTraction(std::size_t wall, double v_belt, double mu_b, double gain, double drag_gain = 0.0)
        : BasalBoundary(wall, v_belt, mu_b), gain_(gain), drag_gain_(drag_gain) {}

    std::string_view name() const override { return "conveyor-traction"; }

protected:
    /// Writes the traction into ParticleStore::force; total_traction() is the
    /// capped part and the drag together, discs_sliding() those at the cap.
    void apply_law(Simulation& sim, std::size_t c0, std::size_t c1, bool parallel) override;

private:
    double gain_;       // g_b [-]
    double drag_gain_;  // g_d [-]
};

}  // namespace orodem
