// Boundary: a self-contained piece of the experiment's boundary conditions
// (conveyor base, fixed retroside, moving end wall, ...). The step loop calls
// each hook once per step for the whole system, never per particle, in the
// order the boundaries were added.
#pragma once

#include <cstddef>
#include <string_view>

namespace orodem {

class Simulation;
class ByteWriter;
class ByteReader;

class Boundary {
public:
    virtual ~Boundary() = default;
    virtual std::string_view name() const = 0;
    /// After the drift (positions at t+dt, velocities at t+dt/2), before forces.
    virtual void after_drift(Simulation&) {}
    /// After contact, bond and wall forces are gathered into ParticleStore::force.
    virtual void add_forces(Simulation&) {}
    /// How add_forces may run in the step's parallel region
    /// (Simulation::boundary_step_in_one_region):
    ///   whole (the default): add_forces on one thread, between phase B and
    ///     the kick, behind barriers;
    ///   none: add_forces does nothing;
    ///   by_disc_range: add_forces equals begin_forces, add_forces_range over
    ///     consecutive disc slot ranges covering [0, n) in any split, then
    ///     end_forces; each disc's work reads and writes only that disc's
    ///     state (its force, velocity, mass and wall contacts), so every
    ///     thread applies it to its own discs right after their gather and
    ///     kicks them with no barrier between. Discs outside the awake range
    ///     (sleeping, inverse mass 0) may be skipped by the ranges.
    enum class ForceHook { whole, none, by_disc_range };
    virtual ForceHook force_hook() const { return ForceHook::whole; }
    /// by_disc_range only. One thread, before any add_forces_range of the step.
    virtual void begin_forces(Simulation&) {}
    /// by_disc_range only. The discs of slots [begin, end); called by several
    /// threads at once on disjoint ranges.
    virtual void add_forces_range(Simulation&, std::size_t /*begin*/, std::size_t /*end*/) {}
    /// by_disc_range only. One thread, after every add_forces_range of the
    /// step (totals over the discs).
    virtual void end_forces(Simulation&) {}
    /// After the second half kick (velocities at t+dt).
    virtual void after_step(Simulation&) {}
    /// Checkpoints (io/checkpoint.cpp): write / read back every member that a
    /// later step or output depends on, so a restored run continues bit for bit.
    /// A boundary with no state of its own keeps the empty defaults.
    virtual void save_state(ByteWriter&) const {}
    virtual void load_state(ByteReader&) {}
};

}  // namespace orodem
