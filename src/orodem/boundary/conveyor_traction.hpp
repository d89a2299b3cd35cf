// ConveyorTraction: the paper's Coulomb base (eq. 5, [43]). Every disc that
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
#include <vector>

#include "orodem/engine/boundary.hpp"

namespace orodem {

class ConveyorTraction : public Boundary {
public:
    /// wall: index of the base wall in Simulation::walls; v_belt: v' [m/s];
    /// mu_b: basal Coulomb coefficient [-]; gain: g_b in γ_b = g_b m_i / dt [-];
    /// drag_gain: g_d in the uncapped drag γ_d = g_d m_i / dt [-] (0: none).
    ConveyorTraction(std::size_t wall, double v_belt, double mu_b, double gain, double drag_gain = 0.0)
        : wall_(wall), v_belt_(v_belt), mu_b_(mu_b), gain_(gain), drag_gain_(drag_gain) {}

    std::string_view name() const override { return "conveyor-traction"; }
    void add_forces(Simulation& sim) override;
    /// The last step's outputs (total traction, counts); the per-slot buffers
    /// are rewritten by every add_forces and need no saving.
    void save_state(ByteWriter& w) const override;
    void load_state(ByteReader& r) override;

    /// Sum of the tractions applied this step [N] (x along û; capped part and
    /// drag together), and the number of discs on the base and of those whose
    /// capped part is at the Coulomb cap.
    double total_traction() const { return total_traction_; }
    std::size_t discs_on_base() const { return on_base_; }
    std::size_t discs_sliding() const { return sliding_; }
    double v_belt() const { return v_belt_; }
    double mu_b() const { return mu_b_; }

private:
    std::size_t wall_;
    double v_belt_;   // v' [m/s]
    double mu_b_;     // μ_b [-]
    double gain_;     // g_b [-]
    double drag_gain_;  // g_d [-]
    std::vector<double> traction_;  // per disc slot, this step [N]
    std::vector<unsigned char> capped_;
    std::vector<unsigned char> touching_;  // 1: a positive normal force from the base this step
    double total_traction_ = 0.0;
    std::size_t on_base_ = 0, sliding_ = 0;
};

}  // namespace orodem
