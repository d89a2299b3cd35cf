// BasalBoundary: what the two proside base laws share (SPEC §2;
// docs/physics.md "The proside base"). A base is a wall of the Simulation on
// which discs are carried at the belt speed v' along the wall direction û,
// with friction μ_b; the law that does it is the subclass:
//   CoulombBase       (wedge.base_law = "coulomb", the default): a spring-slider
//                     per disc against the belt, static and kinetic friction μ_b;
//   ConveyorTraction  ("traction"): the paper's eq. 5 traction capped by μ_b N.
// Both loop once per step over the discs with a candidate contact with the
// base (Simulation::wall_discs), write one slot per disc, and tally the
// step's total traction and counts here, in slot order, so the outputs are
// the same at any thread count. Those tallies are the boundary's checkpointed
// state (the per-slot buffers are rewritten by every step).
//
// A disc's law reads and writes only that disc's state, so a base is a
// ForceHook::by_disc_range boundary: in the step's parallel region each
// thread applies the law to the base discs among its own gathered discs and
// kicks them with no barrier between, and the tally follows the kick's
// barrier (engine/boundary.hpp). The slots start each step cleared
// (begin_forces), so those the ranges skip (the sleeping discs') read 0, as
// when the law itself clears them.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "orodem/core/parallel.hpp"
#include "orodem/engine/boundary.hpp"
#include "orodem/engine/simulation.hpp"

namespace orodem {

class BasalBoundary : public Boundary {
public:
    /// wall: index of the base wall in Simulation::walls; v_belt: v' [m/s]
    /// (0: a stationary base); mu_b: basal Coulomb coefficient [-].
    BasalBoundary(std::size_t wall, double v_belt, double mu_b) : wall_(wall), v_belt_(v_belt), mu_b_(mu_b) {}

    /// Sum of the base's tangential forces on the discs this step, along û [N].
    double total_traction() const { return total_traction_; }
    /// Discs with a positive normal force from the base this step, and those
    /// among them whose tangential force is at the Coulomb limit μ_b N.
    std::size_t discs_on_base() const { return on_base_; }
    std::size_t discs_sliding() const { return sliding_; }
    std::size_t wall() const { return wall_; }
    double v_belt() const { return v_belt_; }
    double mu_b() const { return mu_b_; }

    void save_state(ByteWriter& w) const override;
    void load_state(ByteReader& r) override;

    ForceHook force_hook() const override { return ForceHook::by_disc_range; }
    /// Sizes the slots for this step's base discs and clears them.
    void begin_forces(Simulation& sim) override {
        size_slots(sim.wall_discs(wall_).size());
        std::fill(traction_.begin(), traction_.end(), 0.0);
        std::fill(touching_.begin(), touching_.end(), static_cast<unsigned char>(0));
        std::fill(sliding_slot_.begin(), sliding_slot_.end(), static_cast<unsigned char>(0));
    }
    /// The law for the base discs in disc slots [begin, end), on this thread.
    void add_forces_range(Simulation& sim, std::size_t begin, std::size_t end) override {
        const std::vector<std::uint32_t>& discs = sim.wall_discs(wall_);  // ascending
        const auto c0 = std::lower_bound(discs.begin(), discs.end(), begin);
        const auto c1 = std::lower_bound(c0, discs.end(), end);
        apply_law(sim, static_cast<std::size_t>(c0 - discs.begin()), static_cast<std::size_t>(c1 - discs.begin()),
                  false);
    }
    void end_forces(Simulation&) override { tally(); }
    /// The whole step: the slots cleared, the law for every base disc (in
    /// parallel when there are many), the totals.
    void add_forces(Simulation& sim) override {
        begin_forces(sim);
        apply_law(sim, 0, sim.wall_discs(wall_).size(), true);
        tally();
    }

protected:
    /// The law over wall-disc slots [c0, c1) (for_each_base_contact);
    /// parallel: split them among threads when there are many.
    virtual void apply_law(Simulation& sim, std::size_t c0, std::size_t c1, bool parallel) = 0;

    /// Sizes the per-slot buffers for n discs (no allocation once sized).
    void size_slots(std::size_t n);
    /// One disc slot's result this step (slot c of wall_discs, not the disc slot).
    void set_slot(std::size_t c, double traction, bool touching, bool sliding) {
        traction_[c] = traction;
        touching_[c] = touching ? 1 : 0;
        sliding_slot_[c] = sliding ? 1 : 0;
    }
    /// The step's totals from the slots, in slot order.
    void tally();
    /// The per-step loop both laws share, over the discs with a candidate
    /// contact with the base (a few per cent of them; Simulation::wall_discs)
    /// in slots [c0, c1) (cleared by begin_forces), in parallel when asked and
    /// there are many: for every disc with a finite mass, law(c, i, k, N, û)
    /// for its contact k with the base, N the (smooth) base's normal force on
    /// it [N], which the law records with set_slot when N > 0, û the base's
    /// unit direction there (the wall's; a base following the plate, its
    /// segment under the disc: wall_tangent).
    template <class Law>
    void for_each_base_contact(Simulation& sim, std::size_t c0, std::size_t c1, bool parallel, Law&& law) {
        const ParticleStore& p = sim.particles;
        const WallContactStore& ws = sim.wall_contacts;
        const Wall& w = sim.walls[wall_];
        const Vec2 u_wall = (1.0 / norm(w.b - w.a)) * (w.b - w.a);
        const bool profiled = w.profile != nullptr;
        const std::vector<std::uint32_t>& discs = sim.wall_discs(wall_);
        const auto one = [&](std::size_t c) {
            const std::size_t i = discs[c];
            if (p.inv_mass[i] == 0.0) return;  // fixed and sleeping discs are left as they are
            const Vec2 u = profiled ? wall_tangent(w, p.x[i]) : u_wall;
            for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k)
                if (ws.wall[k] == wall_) law(c, i, k, ws.f[k].x * -u.y + ws.f[k].y * u.x, u);
        };
        const long long cb = static_cast<long long>(c0), ce = static_cast<long long>(c1);
        if (!parallel || ce - cb < kParallelMin) {
            // No parallel construct at all: an inactive one still costs a
            // team start, paid per disc chunk by add_forces_range.
            for (std::size_t c = c0; c < c1; ++c) one(c);
            return;
        }
#pragma omp parallel for schedule(static)
        for (long long ii = cb; ii < ce; ++ii) one(static_cast<std::size_t>(ii));
    }

    std::size_t wall_;
    double v_belt_;  // v' [m/s]
    double mu_b_;    // μ_b [-]

private:
    std::vector<double> traction_;             // per wall-disc slot, this step [N]
    std::vector<unsigned char> touching_;      // 1: a positive normal force from the base this step
    std::vector<unsigned char> sliding_slot_;  // 1: at the Coulomb limit this step
    double total_traction_ = 0.0;
    std::size_t on_base_ = 0, sliding_ = 0;
};

}  // namespace orodem
