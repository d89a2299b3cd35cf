// ServoWalls: the sides of an axis-aligned box of walls, each measured every
// step (the normal stress the discs exert on it) and, when asked, moved to
// hold a target normal stress (a servo-controlled wall, as in the biaxial
// test of the calibration, setup/calibration.hpp).
//
// A side's stress is σ = F·n / L: F the total force of the discs on the wall
// (the forces the engine gathered this step, WallContactStore::f, summed as
// Simulation::wall_force does), n the side's outward unit normal, L the
// side's length, the distance between the two perpendicular sides ("span"
// walls) measured along the side. Compression is positive.
//
// Servo (after the second half kick, so for the next step's wall move), on
// the elastic stress σ_e = Σ k_n δ (n̂·n) / L of the wall's contacts (the
// spring part of the wall force: the dashpot part responds to the wall's own
// velocity within the step and would feed the servo's output straight back
// into its input, which makes a stiff servo ring at the step frequency):
//   v = clamp(G (σ_e − σ_target) + I, −v_max, v_max) along n,
//   G = α L / (k_n N_c dt),  I += G (σ_e − σ_target) / N_i when not clamped,
// with N_c ≥ 1 the number of discs touching the wall. With the discs held
// still, one step of the proportional part changes the wall's spring force
// by k_n N_c v dt = α (σ_e − σ_target) L: it corrects the fraction α of the
// error per step (the PFC servo, Itasca 2008); the integral part I (time
// constant N_i steps) supplies the steady speed a moving target needs
// (a dilating sample) without a steady stress error. In the stiff limit the
// error obeys e' = (1 − α) e − j, j' = j + α e / N_i: stable for 0 < α ≤ 1
// and N_i ≥ 4.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "orodem/core/vec2.hpp"
#include "orodem/engine/boundary.hpp"

namespace orodem {

struct BoxSide {
    std::size_t wall;     // index in Simulation::walls
    Vec2 outward;         // unit normal pointing out of the sample [-]
    std::size_t span_a = kNoSpan;  // the two walls whose distance along the side is its length;
    std::size_t span_b = kNoSpan;  // kNoSpan: length 1 m (σ is then the force per unit depth) [-]
    static constexpr std::size_t kNoSpan = std::numeric_limits<std::size_t>::max();
};

class ServoWalls : public Boundary {
public:
    /// sides: the measured walls; alpha: the servo's α (0 < α ≤ 1) [-];
    /// integral_steps: N_i, the integral time constant in steps [-].
    ServoWalls(std::vector<BoxSide> sides, double alpha, double integral_steps = 100.0);

    std::string_view name() const override { return "servo-walls"; }
    ForceHook force_hook() const override { return ForceHook::none; }
    void after_step(Simulation& sim) override;
    void save_state(ByteWriter& w) const override;
    void load_state(ByteReader& r) override;

    /// Servo side s to the normal stress target [Pa] at speeds up to v_max [m/s].
    void set_servo(std::size_t s, double target, double v_max);
    /// Stops servoing side s (its wall keeps the velocity the caller gives it).
    void clear_servo(std::size_t s) {
        servo_[s] = 0;
        integral_[s] = 0.0;
    }
    void set_alpha(double alpha) { alpha_ = alpha; }

    std::size_t sides() const { return sides_.size(); }
    const BoxSide& side(std::size_t s) const { return sides_[s]; }
    /// Length of side s now [m].
    double length(const Simulation& sim, std::size_t s) const;

    // This step's values (after the last after_step).
    double stress(std::size_t s) const { return stress_[s]; }     // [Pa]
    double elastic_stress(std::size_t s) const { return elastic_[s]; }  // σ_e [Pa]
    std::size_t contacts(std::size_t s) const { return n_[s]; }   // discs pushing on the wall
    Vec2 force(std::size_t s) const { return force_[s]; }         // on the wall [N]

    // Means since the last reset_means().
    std::uint64_t samples() const { return samples_; }
    double mean_stress(std::size_t s) const;   // [Pa]
    void reset_means();

private:
    std::vector<BoxSide> sides_;
    double alpha_;
    double integral_steps_;
    std::vector<std::int32_t> side_of_wall_;  // wall index -> side, -1 unmeasured
    std::vector<unsigned char> servo_;
    std::vector<double> target_, v_max_, integral_;
    std::vector<Vec2> force_;
    std::vector<std::size_t> n_;
    std::vector<double> stress_, elastic_, sum_stress_;
    std::uint64_t samples_ = 0;
};

}  // namespace orodem
