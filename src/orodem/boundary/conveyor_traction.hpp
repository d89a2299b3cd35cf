// ConveyorTraction: the paper's Coulomb base (eq. 5, [43]). Every disc that
// touches the base wall (a wall contact with a positive normal force N) gets
// the traction F = γ_b (v' − v_i·û) û along the base direction û, capped at
// μ_b N, so the disc is dragged toward the belt speed v' but can still slide
// on the base. γ_b = 2 ζ_b sqrt(m_i k_n): the disc relaxes to the belt speed
// on the contact time scale, critically damped for ζ_b = 1, and the explicit
// update stays stable (γ_b dt / m_i = 2 ζ_b dt sqrt(k_n/m_i) ≪ 2).
// The traction acts at the disc centre (no torque), as eq. 5 is written.
//
// With v' = 0 the same boundary is a viscous-Coulomb stationary base.
// Per-disc work in a parallel loop over discs; each iteration writes only its
// own disc's force, so the result is independent of the thread count.
#pragma once

#include <cstddef>
#include <vector>

#include "orodem/engine/boundary.hpp"

namespace orodem {

class ConveyorTraction : public Boundary {
public:
    /// wall: index of the base wall in Simulation::walls; v_belt: v' [m/s];
    /// mu_b: basal Coulomb coefficient [-]; zeta_b: traction damping ratio [-].
    ConveyorTraction(std::size_t wall, double v_belt, double mu_b, double zeta_b)
        : wall_(wall), v_belt_(v_belt), mu_b_(mu_b), zeta_b_(zeta_b) {}

    std::string_view name() const override { return "conveyor-traction"; }
    void add_forces(Simulation& sim) override;

    /// Sum of the tractions applied this step [N] (x along û), and the number
    /// of discs on the base and of those at the Coulomb cap.
    double total_traction() const { return total_traction_; }
    std::size_t discs_on_base() const { return on_base_; }
    std::size_t discs_sliding() const { return sliding_; }
    double v_belt() const { return v_belt_; }
    double mu_b() const { return mu_b_; }

private:
    std::size_t wall_;
    double v_belt_;   // v' [m/s]
    double mu_b_;     // μ_b [-]
    double zeta_b_;   // ζ_b [-]
    std::vector<double> traction_;  // per disc slot, this step [N]
    std::vector<unsigned char> capped_;
    double total_traction_ = 0.0;
    std::size_t on_base_ = 0, sliding_ = 0;
};

}  // namespace orodem
