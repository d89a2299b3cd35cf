// The elastic plate under a running wedge ([flexure], issue #68;
// docs/physics.md "Flexure under the wedge"): every flexure.interval_steps
// steps and at every output, between two calls of Simulation::advance (the
// belt does not pause), the base load is measured (analysis/base_load.hpp)
// and the plate (physics/flexure.hpp) is solved under it. Quasi-static: the
// plate takes at once the deflection of the load of that step.
//
// The plate spans the model, x ∈ [−pro_length, retro_length] (the layer's
// initial extent; the S point at x = 0), and flexure.extension α (3π α by
// default) beyond each end; a broken plate breaks at the S point. Its load,
// as node forces [N/m]:
//   - each disc's measured base load as a line load at its x, split between
//     the two nodes around it (FlexurePlate::add_line_load);
//   - beyond the model's ends, what the model stands for there: the
//     undeformed layer, an infinite slab h0 thick. Its weight per unit
//     length, q_layer = g Σ m / L0 [Pa] (all discs over the layer's initial
//     length L0), as a uniform pressure left of the trailing wall (which
//     moves in with the belt) and right of the retroside end wall.
// So before any deformation the plate sinks uniformly by w_layer =
// q_layer / (Δρ g), and the measures are taken against that level.
//
// Two-way coupling (flexure.coupling = "two-way", the default): after each
// solve the proside and retroside bases take the deflected shape, height
// y_base(x) = −(w(x) − w_layer) [m] (the deflection against that of the
// undeformed layer, so the incoming plate far from the wedge stays at
// y = 0, where the layer was made; a uniform offset would move the whole
// model rigidly and change nothing in it): a BaseProfile (state/contacts.hpp)
// on the plate's nodes, piecewise linear, set at once at the solve (the
// step between two solves is what the load's change over N steps makes of
// w: small against the contacts' overlaps; FlexureRun tests bound the
// kinetic energy after solves). A broken plate gives each base its own
// plate's profile (a step at the S point). The discs that do not move on
// their own, the sleeping and the fixed ones (inverse mass 0), and every
// disc of a cluster with a fixed disc (it hangs on it by its bonds; the
// whole cluster by its first fixed disc's step), move with their base:
// y += y_new(x) − y_old(x − v Δt), v their velocity, Δt the time since the
// previous solve. The end walls reach 2 h0 below the
// base at their x. The largest change of the base counts against the skin
// (Simulation::add_external_displacement). One-way: the base stays flat
// (y = 0); the deflection is computed and written only.
//
// Everything here runs on one thread, in id and node order: deterministic
// at any thread count. The state (the last solve) is FlexureState
// (io/checkpoint.hpp), saved in checkpoints.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/physics/flexure.hpp"
#include "orodem/setup/wedge.hpp"

namespace orodem {

/// The measures of one deflection [h0] (NaN where there is none). Heights
/// and depths against w_layer, the deflection under the undeformed layer.
struct FlexureMeasures {
    double moat_depth = 0.0;          // largest w − w_layer, positive down [h0]
    double moat_x = 0.0;              // its x [h0]
    double forebulge_pro_x = 0.0;     // x of the least w − w_layer proside of the moat [h0]
    double forebulge_pro_height = 0.0;    // −(w − w_layer) there, positive up [h0]
    double forebulge_retro_x = 0.0;   // the same retroside of the moat [h0]
    double forebulge_retro_height = 0.0;  // [h0]
    double basin_pro_width = 0.0;     // from the proside end of the moat's basin (w > w_layer) to the S point [h0]
    double basin_retro_width = 0.0;   // from the S point to the retroside end of the basin [h0]
    double load_ratio = 0.0;          // Σ measured disc loads / Σ weight of the discs present [-]
};

/// series.csv's columns of the plate (appended after the others).
std::string flexure_series_header();
std::string flexure_series_line(const FlexureMeasures& m);
/// flexure.csv's header: one line per plate node per output.
std::string flexure_profile_header();

class WedgeFlexure {
public:
    WedgeFlexure(const Config& c, const WedgeSetup& w);
    bool on() const { return on_; }
    /// The next step after `step` at which the plate is solved.
    std::uint64_t next_step(std::uint64_t step) const { return (step / interval_ + 1) * interval_; }
    bool due(std::uint64_t step) const { return on_ && step % interval_ == 0; }
    /// A run from step 0: the state sized, no solve yet.
    void start(FlexureState& st) const;
    /// The same; two-way, the plate solved under the discs' weights and
    /// every disc moved onto the bent base (y += y_base(x)).
    void start(Simulation& sim, FlexureState& st);
    /// A resumed run (two-way): the bases take st's deflection again (the
    /// walls' profiles are not in the checkpoint); nothing moves.
    void resume(Simulation& sim, const FlexureState& st);
    /// Measures the base load now and solves the plate under it into st;
    /// two-way, the bases and the discs resting on them follow.
    void solve(Simulation& sim, FlexureState& st);
    /// The base's height under x [m] now (0 when flat: one-way, or no solve yet).
    double base_height(double x) const;
    bool two_way() const { return two_way_; }
    /// The measures of st's deflection (solve first).
    FlexureMeasures measures(const FlexureState& st) const;
    /// flexure.csv's lines of st at S: S, node, x [m], load [N/m], w [m].
    void write_profile(const FlexureState& st, double S, LineFile& out) const;
    const FlexurePlate& plate() const { return *plate_; }
    double w_layer() const { return w_layer_; }  // [m]

private:
    bool on_ = false;
    std::uint64_t interval_ = 100;
    double h0_ = 1.0;                  // [m]
    double x_retro_end_ = 0.0;         // the retroside end wall [m]
    double pro_length_ = 0.0;          // the trailing wall's start is at −pro_length [m]
    double q_layer_ = 0.0;             // weight of the undeformed layer per unit length [Pa]
    double w_layer_ = 0.0;             // q_layer / (Δρ g) [m]
    double load_ratio_ = 0.0;          // of the last solve [-]
    std::unique_ptr<FlexurePlate> plate_;
    std::vector<std::size_t> base_walls_;
    std::vector<double> load_;         // by id, scratch [N]
    bool two_way_ = false;             // flexure.coupling = "two-way"
    /// base_load_ratio now: Σ measured base loads / Σ weights (load_ by id).
    void measure_ratio(const Simulation& sim);
    /// The node forces [N/m] of the measured base load (weights: of each
    /// disc's weight instead), with the undeformed layer beyond the model.
    void node_forces(const Simulation& sim, bool weights, std::vector<double>& f);
    // The bases' shapes now (two-way, after a solve; null: flat): the
    // proside's, and the retroside's (the same one on a continuous plate).
    std::shared_ptr<const BaseProfile> pro_, retro_;
    std::vector<unsigned char> held_cluster_;  // two-way: 1 for a cluster with a fixed disc, scratch
    std::vector<double> held_step_;            // two-way: its first fixed disc's step this solve, scratch [m]
    /// held_cluster_ and held_step_ sized to p's clusters and cleared.
    void clear_clusters(const ParticleStore& p);
    /// The profiles of st's deflection (y = −(w − w_layer)).
    void make_profiles(const FlexureState& st, std::shared_ptr<const BaseProfile>& pro,
                       std::shared_ptr<const BaseProfile>& retro) const;
    /// Puts pro_ and retro_ on the base walls and the end walls' feet below them.
    void set_walls(Simulation& sim) const;
};

}  // namespace orodem
