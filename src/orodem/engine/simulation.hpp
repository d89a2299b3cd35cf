// Simulation: the particle state, its contacts and walls, and the step loop
// (velocity Verlet; SPEC §1). It owns no I/O: apps and io/ read it through
// its public members and the diagnostics below.
//
// One step:
//   half kick (v += F/m dt/2, ω += T/I dt/2) and drift (x += v dt, θ += ω dt),
//     tracking the largest displacement since the last rebuild;
//   walls move; boundaries' after_drift;
//   rebuild pairs if needed (PairBuilder);
//   phase A: each disc pair evaluates the contact law into its own slots
//     (parallel over pairs, SIMD lanes, no shared writes; pair_kernel.hpp);
//   phase B: each disc sums gravity, its outgoing then incoming pairs, then
//     its wall contacts (evaluated there), in that fixed order (parallel
//     over discs);
//   boundaries' add_forces; second half kick; boundaries' after_step.
// With no boundaries the walls move first and the rest runs in one parallel
// region, each disc kicked right after its force is summed (the same
// operations, so the same results). With boundaries a step that needs no
// rebuild also runs in one parallel region, the boundaries' hooks on one
// thread between barriers, except the bases' forces, which each thread
// applies to its own discs (Boundary::ForceHook::by_disc_range). In these
// regions phases A and B hand out their pairs and discs in chunks, each
// thread its static share first, then what is left of the other's
// (core/stealing_split.hpp). No allocation happens in a step once the
// stores have reached their size.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "orodem/core/stealing_split.hpp"
#include "orodem/engine/boundary.hpp"
#include "orodem/engine/pair_kernel.hpp"
#include "orodem/engine/phase_clock.hpp"
#include "orodem/neighbor/pair_builder.hpp"
#include "orodem/physics/contact_law.hpp"
#include "orodem/physics/materials.hpp"
#include "orodem/state/contacts.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

/// Sleeping zones (engine/sleep.cpp): discs beyond the outermost disc that
/// departed from rigid motion, plus a buffer, move rigidly with the velocity
/// of their side and skip all force work between neighbour rebuilds.
struct SleepParams {
    bool enabled = false;
    double x_split = 0.0;          // the rigid velocity is u_left for x < x_split, u_right beyond [m]
    Vec2 u_left{}, u_right{};      // [m/s]
    bool left = false, right = false;  // which ends may sleep
    double tolerance = 0.0;        // a disc is active when |x - x_rebuild - u t| exceeds this between rebuilds [m]
    double buffer_left = 0.0;      // awake margin left of the leftmost active disc [m]
    double buffer_right = 0.0;     // awake margin right of the rightmost active disc [m]
};

struct SimParams {
    LawParams law;              // disc-disc and bond law
    double dt = 0.0;            // timestep [s]
    Vec2 gravity{0.0, -9.81};   // [m/s²]
    double skin = 0.0;          // Verlet skin [m]
    bool periodic_x = false;    // periodic in x with period period_x
    double period_x = 0.0;      // W [m]
    SleepParams sleep;          // off unless enabled
    double m_inertia_min = 0.0; // inertia floor: a free disc moves with max(m, this) (its weight stays m g;
                                // wedge.inertia_floor, docs/physics.md); 0 = off [kg]
};

struct EnergyReport {
    double kinetic_translational = 0;  // ½ Σ m v² [J]
    double kinetic_rotational = 0;     // ½ Σ I ω² [J]
    double gravitational = 0;          // Σ m (-g·x) [J], zero at the origin
    double elastic = 0;                // ½ k_n δ² + ½ k_s |ξ|² over pairs, bonds and walls [J]
    double total() const { return kinetic_translational + kinetic_rotational + gravitational + elastic; }
};

class Simulation {
public:
    ParticleStore particles;
    ContactStore contacts;
    WallContactStore wall_contacts;
    std::vector<Wall> walls;
    BondTopology bonds;
    SimParams params;
    std::vector<std::unique_ptr<Boundary>> boundaries;
    /// Several materials (physics/materials.hpp, engine/materials.cpp): empty
    /// in a one-material run (params.law for every pair). When set, together
    /// with ParticleStore::material, layer and damage, before initialize().
    MaterialTable materials;
    bool has_materials() const { return !materials.materials.empty(); }

    std::uint64_t step_count = 0;  // steps taken
    double time = 0.0;             // simulated time [s]
    /// Awake discs from which a wedge step without a rebuild runs in one
    /// parallel region (step()): the intermediate wedge has 3,000-6,000
    /// awake, the demo wedges 500-1,700. Results do not depend on it (tests
    /// set it to compare the two paths).
    std::size_t one_region_min_awake = 2048;

    /// Builds the bond topology from cluster ids, the first pair list and the
    /// forces at t = 0. Call once after particles, walls and params are set.
    void initialize();
    /// Advances one timestep.
    void step();
    /// Advances n timesteps. Inside, the far sleeping discs drift lazily
    /// (engine/sleep.cpp); every position is current again on return.
    void advance(std::uint64_t n);

    /// Law parameters of wall w (its roughness and μ on top of params.law).
    LawParams wall_law(std::size_t w) const;

    // Diagnostics: deterministic (fixed-chunk) sums, safe at any thread count.
    double kinetic_energy() const;  // translational, ½ Σ m v² [J]
    EnergyReport energies() const;
    std::size_t touching_contacts() const;  // unbonded pairs + wall contacts with δ > 0
    double max_overlap_ratio() const;       // max over unbonded touching pairs of δ / min(R_i, R_j)
    double mean_overlap_ratio() const;      // mean over unbonded touching pairs of δ / min(R_i, R_j)
    double max_speed() const;               // max |v_i| [m/s]
    /// x_i - x_j of candidate pair k, j's periodic image included [m].
    Vec2 pair_branch(std::size_t k) const {
        return particles.x[contacts.i[k]] - (particles.x[contacts.j[k]] + Vec2{contacts.shift[k] * params.period_x, 0.0});
    }
    /// δ / min(R_i, R_j) of candidate pair k; negative when the discs are apart [-].
    double pair_overlap_ratio(std::size_t k) const {
        const double ri = particles.radius[contacts.i[k]], rj = particles.radius[contacts.j[k]];
        return (ri + rj - norm(pair_branch(k))) / std::min(ri, rj);
    }
    /// Total force exerted by discs on wall w [N] (opposite of the forces on the discs).
    Vec2 wall_force(std::size_t w) const;
    std::uint64_t rebuild_count() const { return builder_.rebuild_count(); }
    /// Slots of the discs with a candidate contact with wall w (ascending),
    /// valid until the next rebuild: boundaries loop over these, not all discs.
    const std::vector<std::uint32_t>& wall_discs(std::size_t w) const { return wall_discs_[w]; }
    /// Discs in the sleeping zones now (engine/sleep.cpp).
    std::size_t sleeping_count() const { return particles.size() - (awake_.disc_end - awake_.disc_begin); }
    /// Whether slot s lies in the awake range, whose forces every step
    /// computes; outside it (the sleeping zones' columns, their fixed discs
    /// included) force[s] is left from the last rebuild step or zero.
    bool in_awake_range(std::size_t s) const { return s >= awake_.disc_begin && s < awake_.disc_end; }
    /// The sleeping zones' last decision (at the last rebuild with sleeping on;
    /// a diagnostic, not saved in checkpoints): the x extent of the active
    /// discs and the bounds beyond which discs sleep [m]; ±inf where none.
    struct SleepDecision {
        double active_min = std::numeric_limits<double>::infinity();
        double active_max = -std::numeric_limits<double>::infinity();
        double x_lo = -std::numeric_limits<double>::infinity();
        double x_hi = std::numeric_limits<double>::infinity();
    };
    const SleepDecision& last_sleep_decision() const { return sleep_decision_; }
    /// Hash of the full dynamic state in id order (x, v, θ, ω, and ξ by key).
    std::uint64_t state_hash() const;

    /// Forces a pair rebuild at the next step (e.g. after particles were moved by hand).
    void request_rebuild() { force_rebuild_ = true; }
    /// Counts a displacement d [m] made outside the step (discs or a base
    /// moved by hand, e.g. the base following the plate: run/wedge_flexure)
    /// against the skin: the next rebuild comes d sooner, as if every disc
    /// had moved d more since the last one.
    void add_external_displacement(double d) {
        const double m = std::sqrt(max_disp2_) + d;
        max_disp2_ = m * m;
    }

    /// The private state that later steps depend on, for checkpoints
    /// (io/checkpoint.cpp): the pair builder's reference positions and
    /// rebuild count, the wall shifts and largest displacement since the last
    /// rebuild, a pending rebuild, and the sleeping-zone ranges. A new member
    /// that later steps depend on goes here and in the three functions below.
    struct Internals {
        std::vector<Vec2> x_ref;
        std::uint64_t rebuilds = 0;
        std::vector<Vec2> wall_shift;
        double max_disp2 = 0.0;
        bool force_rebuild = false;
        std::uint32_t awake_begin = 0, awake_end = 0, pairs_begin = 0, pairs_end = 0;  // engine/sleep.cpp
        std::uint64_t last_rebuild_step = 0;
    };
    void save_internals(ByteWriter& w) const;
    static Internals read_internals(ByteReader& r);
    /// The materials' state between rebuilds (engine/materials.cpp), saved
    /// in checkpoints of runs with materials only: each pair's plastic slip
    /// and separation since the last rebuild, the pairs whose cohesion is
    /// lost, and the time of the last damage update.
    struct MaterialState {
        std::vector<double> slip;                   // per pair [m]
        std::vector<std::uint8_t> broke;            // per pair
        std::vector<std::uint64_t> cohesion_lost;   // pair keys, ascending
        double damage_time = 0.0;                   // [s]
    };
    void save_material_state(ByteWriter& w) const;
    static MaterialState read_material_state(ByteReader& r);
    void restore_material_state(MaterialState&& m);
    /// A fresh material: every damage 0, no slip recorded, no cohesion lost
    /// (the biaxial test after its compaction).
    void reset_material_state();
    /// The pair keys whose cohesion is lost for good (ascending).
    const std::vector<std::uint64_t>& cohesion_lost() const { return material_state_.cohesion_lost; }
    /// After particles, contacts and walls are in place: the derived caches
    /// (bonds, wall laws, wall-disc lists, dashpots) and the saved internals.
    void restore_internals(Internals&& v);

    /// Per-phase wall time of step() so far (see PhaseTimes).
    const PhaseTimes& phase_times() const { return times_; }
    void reset_phase_times() { times_ = {}; }

private:
    // The paths of step() (engine/step.cpp): step() picks one; each runs the
    // phases below in the order the header comment gives. The clock times
    // them (PhaseTimes); nothing else differs between the paths' results.
    void step_without_hooks(PhaseClock& clock);      // no boundaries: walls first, the rest in one region
    void step_hooks_in_one_region(PhaseClock& clock);  // boundaries, from one_region_min_awake awake discs
    void step_hooks_by_phase(PhaseClock& clock, bool drifted);  // boundaries, phase by phase
    bool step_in_one_region(double wall_move, PhaseClock& clock);  // false: a rebuild is due (drift done)
    // With boundaries in one region: kick_drift, walls, after_drift, and (no
    // rebuild) A, B, add_forces, kick, after_step, the hooks on one thread
    // (the bases' add_forces per thread over its own discs when no boundary
    // needs a whole one: Boundary::ForceHook); false: a rebuild is due
    // (drift, walls and after_drift done).
    bool boundary_step_in_one_region(PhaseClock& clock);
    // Its parts, called by every thread of its region (one thread runs the hooks).
    bool hooks_after_drift(bool lazy, double max_d2, bool by_range, PhaseClock& clock);  // true: rebuild due
    void gather_bases_kick(const GatherData& gd, const KickData& kk, std::size_t disc0, PhaseClock& clock);
    void gather_hooks_kick(const GatherData& gd, const KickData& kk, std::size_t disc0, PhaseClock& clock);
    void hooks_after_step(bool by_range, PhaseClock& clock);

    // The phases. bench/bench_kernels.cpp times them one by one through KernelBench.
    friend struct KernelBench;
    void kick_drift();       // v += F/m dt/2, ω += T/I dt/2, x += v dt, θ += ω dt; max displacement
    bool drift_range(long long& b, long long& e) const;  // slots this step drifts; true: lazy (advance())
    void end_drift(bool lazy, double max_d2);  // max_disp2_ from the drift's max (plus the lazy discs' bound)
    bool needs_rebuild(double wall_move) const;
    void rebuild_pairs();
    // Sleeping zones (engine/sleep.cpp): the bounds from the motion since the
    // last rebuild (before it), then flags, inverse masses and the awake
    // slot and pair ranges (after it, in the new slot order).
    void sleep_bounds(SleepDecision& d) const;
    void apply_sleep(double x_lo, double x_hi);
    template <bool kUpdateHistory>
    void pair_forces(bool all = true);    // phase A; all = false: the awake pairs only
    template <bool kUpdateHistory, bool kKick>
    void gather_forces(bool all = true);  // phase B; kKick: also the second half kick
    void kick();             // second half kick
    void pair_forces_gather_kick(PhaseClock& clock);  // phases A, B and kick() in one parallel region
    double move_walls();     // walls move by dt; returns the largest wall shift since the rebuild [m]
    PairKernelData pair_kernel_data(bool update_history);
    GatherData gather_data(bool update_history, bool kick);
    KickData kick_data();
    template <bool kUpdateHistory>
    void compute_forces();   // phases A and B, no kick
    PairBuilder::Settings builder_settings() const;
    // Phases A and B's chunks in the one-region steps (core/stealing_split.hpp).
    void reset_splits(std::size_t npairs, std::size_t ndiscs, std::size_t threads);  // before each such step

    PairBuilder builder_;
    std::vector<Vec2> wall_shift_;    // wall displacement since the last rebuild [m]
    std::vector<LawParams> wall_law_; // cached per wall
    std::vector<std::vector<std::uint32_t>> wall_discs_;  // per wall: slots with a candidate contact
    void index_wall_discs();  // wall_discs_ from wall_contacts (after a rebuild or a restore)
    double max_disp2_ = 0.0;          // largest |x - x_ref|² since the last rebuild [m²]
    bool force_rebuild_ = false;
    PhaseTimes times_;
    StealingSplit pair_split_, disc_split_;

    /// The slots and pairs a step works on (engine/sleep.cpp). Slots
    /// [disc_begin, disc_end) are stepped and pairs [pair_begin, pair_end)
    /// evaluated between rebuilds (all of them at a rebuild step and when
    /// sleeping is off). Inside advance() only slots [drift_begin,
    /// drift_end) (the awake discs and every disc of an awake pair) drift
    /// each step; the others, sleeping or fixed discs at a constant
    /// velocity, fall drift_lag steps behind and catch up at once, before a
    /// rebuild and when advance() returns.
    struct AwakeRanges {
        std::uint32_t disc_begin = 0, disc_end = 0;
        std::uint32_t pair_begin = 0, pair_end = 0;
        std::uint64_t last_rebuild_step = 0;  // the step of the last rebuild
        std::uint32_t drift_begin = 0, drift_end = 0;
        std::uint64_t drift_lag = 0;          // steps the discs outside the drift range are behind
        bool defer_drift = false;             // set by advance() while it steps
    } awake_;
    SleepDecision sleep_decision_;  // the last one (diagnostic)
    void set_drift_range();           // from the awake and pair ranges
    void catch_up_drift();            // x += lag dt v, θ += lag dt ω outside the drift range

    /// What changes only with the pair list or the masses, kept per pair (and
    /// per disc) instead of computed every step; valid for the pair list of
    /// the last rebuild, refreshed by pair_kernel_data() and gather_data()
    /// when stale (a rebuild or a restore) or the inverse masses changed.
    struct PairColumns {
        std::vector<double> gamma_n, gamma_s;  // per-pair dashpots γ_n, γ_s [N s/m] (pair_dashpots)
        std::vector<double> r_i, r_j;          // radii R_i, R_j [m] (pair_radii)
        bool stale = true;
        std::uint64_t epoch = 0;               // the inertia_epoch of the inverse masses they used
        std::vector<std::uint32_t> in_slots;   // phase B's four-slot table of incoming pairs (incoming_slots)
        bool in_slots_stale = true;
    } columns_;
    void refresh_dashpots();

    // Several materials (engine/materials.cpp).
    MaterialState material_state_;
    struct MaterialColumns {
        std::vector<double> k_n, k_s, mu, cohesion;  // per pair: the pair's law (PairKernelData::k_n_pair ...)
        std::vector<double> add, cluster_add;        // scratch of absorb_slip, per slot and per cluster [mean diameters]
        std::vector<std::uint64_t> lost_now;         // scratch: keys newly lost at this rebuild
    } material_columns_;
    /// Before a rebuild (pairs still in the old order): each pair's slip into
    /// its particles' damage, the broken pairs' cohesion lost, healing; the
    /// slip and separation columns zeroed.
    void absorb_slip();
    /// The per-pair law columns and dashpots of the current pair list from
    /// the materials, the damage and the lost cohesion (in refresh_dashpots).
    void refresh_material_columns();
};

/// Builds the bond topology (all pairs inside each cluster) from cluster ids.
BondTopology build_bond_topology(const ParticleStore& p);

}  // namespace orodem
