// Boundary: a self-contained piece of the experiment's boundary conditions
// (conveyor base, fixed retroside, moving end wall, ...). The step loop calls
// each hook once per step for the whole system, never per particle, in the
// order the boundaries were added.
#pragma once

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
    /// After the second half kick (velocities at t+dt).
    virtual void after_step(Simulation&) {}
    /// Checkpoints (io/checkpoint.cpp): write / read back every member that a
    /// later step or output depends on, so a restored run continues bit for bit.
    /// A boundary with no state of its own keeps the empty defaults.
    virtual void save_state(ByteWriter&) const {}
    virtual void load_state(ByteReader&) {}
};

}  // namespace orodem
