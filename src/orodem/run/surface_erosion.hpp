// Erosion in the running wedge ([surface], docs/physics.md "Erosion in the
// running wedge"): every surface.interval_steps steps, between two calls of
// Simulation::advance (the belt does not pause), the surface profile above
// the incoming surface is measured per column, the law of
// analysis/surface_laws.hpp asks for an area per column over the shortening
// since the last application, and whole particles (a cluster's discs
// together, lone discs alone) are taken by take_whole_particles, each
// column keeping its remainder.
//
// A removed particle keeps its slot and its id (the outputs are by id): its
// discs are flagged kFlagRemoved and fixed (kFlagFixed: inverse mass 0), and
// the cluster is moved rigidly (its bonds keep their length) to its own
// parking place, a grid of places 2 h0 and more below the base, far enough
// apart that no two parked particles, and no parked particle and wall, are
// ever contact candidates. The wedge measures skip them (surface_profile,
// the health check); the pictures' frame ends above them; the strain sees
// them only among themselves (their positions at the last output are moved
// with them).
//
// The ledger (series.csv, only with [surface]) is in layer area: a disc
// counts for the area it had in the incoming layer, π R² / φ0 with φ0 the
// layer's solid fraction (all discs' area over packing.length × h0), so all
// discs together make exactly the layer's length in h0².
//
// Everything here runs on one thread, in id and column order: deterministic
// at any thread count. What later applications depend on is SurfaceState
// (io/checkpoint.hpp), saved in checkpoints.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "orodem/analysis/surface_laws.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/setup/wedge.hpp"

namespace orodem {

/// The ledger at one output [h0²].
struct SurfaceLedger {
    double influx = 0.0;      // layer carried in by the trailing wall: S h0² [h0²]
    double eroded = 0.0;      // layer area of the removed particles [h0²]
    double stored = 0.0;      // layer area of the particles present beyond an undeformed layer
                              // of the domain's present length (L0 − S) [h0²]
    double error = 0.0;       // influx − eroded − stored [h0²]
    double wedge_area = 0.0;  // the wedge's area above the incoming surface from the profile
                              // (WedgeMeasures::wedge_area / h0²) [h0²]
    std::uint64_t removed_discs = 0;  // discs removed so far [-]
    double asked = 0.0;       // Σ of the areas the law asked for (the taken ones differ by the
                              // columns' remainders, within half a particle each) [h0²]
};

/// series.csv's columns of the ledger (appended after series_header()).
std::string surface_series_header();
std::string surface_series_line(const SurfaceLedger& l);
/// eroded.csv's header.
std::string eroded_header();

SurfaceLaw surface_law_of(const SurfaceConfig& s);

class SurfaceErosion {
public:
    SurfaceErosion(const Config& c, const WedgeSetup& w);  // reads w.profile (y_mean) at each application
    bool on() const { return on_; }
    bool active() const { return on_ && law_.kind != SurfaceLawKind::none; }
    /// The next step after `step` at which erosion applies.
    std::uint64_t next_step(std::uint64_t step) const { return (step / interval_ + 1) * interval_; }
    bool due(std::uint64_t step) const { return active() && step % interval_ == 0; }
    /// A run from step 0: the remainders at 0, the burial depths the initial ones.
    void start(const ParticleStore& p, SurfaceState& st) const;
    /// One application at shortening S: updates the burial record, removes
    /// the particles taken (x_then by id follows them to their parking
    /// place), one eroded.csv line per disc removed.
    void apply(Simulation& sim, SurfaceState& st, double S, std::vector<Vec2>& x_then, LineFile& eroded);
    SurfaceLedger ledger(const ParticleStore& p, const SurfaceState& st, double S, double wedge_area_m2) const;

private:
    bool on_ = false;
    SurfaceLaw law_;
    std::uint64_t interval_ = 100;
    double h0_ = 1.0;               // [m]
    const WedgeSetup& w_;           // its profile (y_mean, the measure's columns and toes)
    double column_ = 0.0;           // the erosion's column width [m]
    double layer_length_ = 0.0;     // L0 [h0]
    double park_x0_ = 0.0, park_y0_ = 0.0, park_pitch_ = 0.0;  // parking grid [m]
    std::uint64_t park_per_row_ = 1;
    // Scratch, reused.
    std::vector<double> h_, erode_, deposit_;
    SurfaceWorkspace ws_;
    WholeTake take_;
    std::vector<WholeCandidate> cands_;
    std::vector<std::size_t> column_begin_;
    double area_of(const ParticleStore& p, std::size_t slot) const;  // layer area of a disc [h0²]
    double solid_total_ = -1.0;     // Σ π R² over all discs [m²] (removed included: constant)
};

}  // namespace orodem
