// ParticleStore: every disc as structure-of-arrays columns, in slot order.
// Slots are re-sorted by cell at each neighbour rebuild; `id` is permanent and
// `slot_of_id` maps back. Fixed (kinematic) discs have inv_mass = inv_inertia
// = 0, so the integrator needs no branch for them.
//
// Hot columns (read for every contact): x, v, omega, radius, mass.
// Integrator columns: inv_mass, inv_inertia, theta, force, torque.
// Identity: id, cluster, flags. Cold (analysis/output): initial_depth, side.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "orodem/core/vec2.hpp"

namespace orodem {

/// Per-disc flag bits.
enum ParticleFlag : std::uint8_t {
    kFlagFixed = 1u << 0,  ///< held fixed in space (inv_mass = inv_inertia = 0)
    kFlagAsleep = 1u << 1, ///< in a sleeping zone: moves rigidly, inv_mass = inv_inertia = 0 (engine/sleep.cpp)
    kFlagRemoved = 1u << 2, ///< eroded: fixed (kFlagFixed too) and parked below the base, out of every contact
                            ///< and measure; its slot and id stay (run/surface_erosion.hpp)
    kFlagReserve = 1u << 3, ///< sediment not yet deposited: parked like an eroded disc (kFlagRemoved and
                            ///< kFlagFixed too) until sedimentation places it (setup/wedge.hpp add_sediment_reserve)
};

struct ParticleStore {
    std::vector<Vec2> x;               // centre [m]
    std::vector<Vec2> v;               // velocity [m/s]
    std::vector<double> theta;         // rotation angle [rad]
    std::vector<double> omega;         // spin [rad/s], counter-clockwise positive
    std::vector<double> radius;        // R_i [m]
    std::vector<double> mass;          // m_i = ρ π R_i² (per unit depth): the weight's mass [kg]
    std::vector<double> inv_mass;      // 1/m_i (1/max(m_i, m_inertia_min)), 0 when fixed or asleep [1/kg]
    std::vector<double> inv_inertia;   // 1/I_i, I_i = m_i R_i²/2, 0 when fixed [1/(kg m²)]
    std::vector<Vec2> force;           // total force of the current step [N]
    std::vector<double> torque;        // total torque of the current step [N m]
    std::vector<std::uint32_t> id;     // permanent particle id, 0..N-1
    std::vector<std::int32_t> cluster; // cluster id, -1 for a lone disc
    std::vector<std::uint8_t> flags;   // ParticleFlag bits
    std::vector<double> initial_depth; // depth below the layer top when the layer was cut [m]
    std::vector<std::uint8_t> side;    // 0 proside, 1 retroside (SPEC §4)
    // Materials (physics/materials.hpp): empty unless the run has layers
    // (Simulation::materials), so a one-material run's state, checkpoints and
    // outputs hold none of them.
    std::vector<std::uint8_t> material; // material id (MaterialTable::materials)
    std::vector<std::uint8_t> layer;    // layer id: the index in its side's stack of layers, 0 at the base
    std::vector<double> damage;         // D: sliding distance of the particle's contacts [mean disc diameters]

    std::vector<std::uint32_t> slot_of_id;  // id -> current slot

    std::size_t size() const { return x.size(); }

    /// Appends one disc at rest; returns its slot. density ρ [kg/m³].
    std::size_t add(Vec2 pos, double r, double density, std::int32_t cluster_id = -1);

    /// Applies fn(column) to every per-slot column (not slot_of_id). One list of
    /// fields, so a new column cannot be forgotten by permute/resize/checkpoint.
    template <class F>
    void for_each_column(F&& fn) {
        fn(x); fn(v); fn(theta); fn(omega); fn(radius); fn(mass); fn(inv_mass);
        fn(inv_inertia); fn(force); fn(torque); fn(id); fn(cluster); fn(flags);
        fn(initial_depth); fn(side);
    }
    /// The material columns (empty in a one-material run): permuted and
    /// compacted with the others, saved in their own checkpoint section.
    template <class F>
    void for_each_material_column(F&& fn) {
        fn(material); fn(layer); fn(damage);
    }
    template <class F>
    void for_each_material_column(F&& fn) const {
        fn(material); fn(layer); fn(damage);
    }
    bool has_materials() const { return !material.empty(); }
    template <class F>
    void for_each_column(F&& fn) const {
        const_cast<ParticleStore*>(this)->for_each_column(
            [&](auto& col) { fn(static_cast<const std::remove_reference_t<decltype(col)>&>(col)); });
    }

    /// Counts the changes of an inverse mass after add() (fix, set_free_inertia,
    /// sleeping): the engine's per-pair dashpots (m_eff) are refreshed when it moves.
    std::uint64_t inertia_epoch = 0;

    /// Holds disc `slot` fixed in space from now on (zero velocity, infinite mass).
    void fix(std::size_t slot) {
        ++inertia_epoch;
        flags[slot] |= kFlagFixed;
        inv_mass[slot] = 0.0;
        inv_inertia[slot] = 0.0;
        v[slot] = {};
        omega[slot] = 0.0;
    }

    /// The mass a disc moves with: its own, or m_inertia_min when lighter (the
    /// inertia floor, SimParams::m_inertia_min; max(m, 0) is m, bit for bit) [kg].
    double inertial_mass(std::size_t slot, double m_inertia_min) const { return std::max(mass[slot], m_inertia_min); }

    /// The integrator's inverse mass and inertia of a free disc (as add() sets
    /// them when m_inertia_min is 0): I = m R²/2 with the inertial mass m.
    void set_free_inertia(std::size_t slot, double m_inertia_min = 0.0) {
        ++inertia_epoch;
        const double m = inertial_mass(slot, m_inertia_min);
        inv_mass[slot] = 1.0 / m;
        inv_inertia[slot] = 2.0 / (m * radius[slot] * radius[slot]);
    }

    /// Rebuilds slot_of_id from id.
    void rebuild_slot_map();

    /// Keeps only slots with keep[slot] != 0 and renumbers ids 0..n-1 in slot
    /// order; cluster ids are renumbered densely too. Used when cutting a layer.
    void compact(const std::vector<std::uint8_t>& keep);
};

}  // namespace orodem
