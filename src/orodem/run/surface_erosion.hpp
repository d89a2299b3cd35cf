// Erosion and sedimentation in the running wedge ([surface], docs/physics.md
// "Erosion in the running wedge", "Sedimentation in the running wedge"):
// every surface.interval_steps steps, between two calls of
// Simulation::advance (the belt does not pause), the surface profile above
// the incoming surface is measured per column, the law of
// analysis/surface_laws.hpp asks for an area per column over the shortening
// since the last application, and whole particles (a cluster's discs
// together, lone discs alone) are taken by take_whole_particles, each
// column keeping its remainder. Sedimentation then fills the chosen
// forelands' columns toward the base level (sedimentation_request on the
// profile the erosion leaves) with particles of the reserve
// (setup/wedge.hpp add_sediment_reserve), each dropped at the lowest height
// where it touches nothing.
//
// A removed particle keeps its slot and its id (the outputs are by id): its
// discs are flagged kFlagRemoved and fixed (kFlagFixed: inverse mass 0), and
// the cluster is moved rigidly (its bonds keep their length) to its own
// parking place (setup/wedge.hpp ParkingGrid, after the reserve's places),
// 2 h0 and more below the base, far enough apart that no two parked
// particles, and no parked particle and wall, are ever contact candidates.
// The wedge measures skip them (surface_profile, the health check); the
// pictures' frame ends above them; the strain sees them only among
// themselves (their positions at the last output are moved with them).
// A deposited particle leaves its parking place the same way, in reverse.
//
// The ledger (series.csv, only with [surface]) is in layer area: a disc
// counts for the area it had in the incoming layer, π R² / φ0 with φ0 the
// layer's solid fraction (the layer's discs' area over packing.length × h0),
// so the layer's discs together make exactly the layer's length in h0².
//
// Everything here runs on one thread, in id and column order: deterministic
// at any thread count. What later applications depend on is SurfaceState
// (io/checkpoint.hpp), saved in checkpoints. An application allocates only
// when a column or candidate count grows (the buffers here are reused).
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
    double deposited = 0.0;   // layer area of the deposited particles [h0²]
    double stored = 0.0;      // layer area of the particles present beyond an undeformed layer
                              // of the domain's present length (L0 − S) [h0²]
    double error = 0.0;       // influx − eroded + deposited − stored [h0²]
    double wedge_area = 0.0;  // the wedge's area above the incoming surface from the profile
                              // (WedgeMeasures::wedge_area / h0²) [h0²]
    std::uint64_t removed_discs = 0;  // discs removed so far [-]
    double asked = 0.0;       // Σ of the areas the law asked for (the taken ones differ by the
                              // columns' remainders, within half a particle each) [h0²]
    std::uint64_t deposited_discs = 0;  // discs deposited so far [-]
    double deposit_asked = 0.0;  // Σ of the areas sedimentation asked for [h0²]
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
    bool sedimenting() const { return on_ && rule_on_; }
    bool active() const { return on_ && (law_.kind != SurfaceLawKind::none || rule_on_); }
    /// The next step after `step` at which erosion applies.
    std::uint64_t next_step(std::uint64_t step) const { return (step / interval_ + 1) * interval_; }
    bool due(std::uint64_t step) const { return active() && step % interval_ == 0; }
    /// A run from step 0: the remainders at 0, the burial depths the initial
    /// ones, birth S 0 for the layer (NaN for the reserve), no erosion S.
    void start(const ParticleStore& p, SurfaceState& st);
    /// A resumed run: the state st from its checkpoint.
    void resume(const ParticleStore& p, const SurfaceState& st);
    /// One application at shortening S: updates the burial record, removes
    /// the particles taken (x_then by id follows them to their parking
    /// place), one eroded.csv line per disc removed, then deposits.
    void apply(Simulation& sim, SurfaceState& st, double S, std::vector<Vec2>& x_then, LineFile& eroded);
    SurfaceLedger ledger(const ParticleStore& p, const SurfaceState& st, double S, double wedge_area_m2) const;

private:
    bool on_ = false;
    SurfaceLaw law_;
    bool rule_on_ = false;          // sedimentation
    SedimentRule rule_;
    bool fill_pro_ = false, fill_retro_ = false;  // the forelands filled (left, right of the crest)
    std::uint8_t layer_pro_ = 0, layer_retro_ = 0;  // layered runs: the layer id of a deposit (each side's top)
    std::uint64_t interval_ = 100;
    double h0_ = 1.0;               // [m]
    double r_max_ = 0.0, r_min_ = 0.0;  // [m]
    const WedgeSetup& w_;           // its profile (y_mean, the measure's columns and toes)
    double column_ = 0.0;           // the erosion's column width [m]
    double layer_length_ = 0.0;     // L0 [h0]
    ParkingGrid park_;              // eroded particle k at place reserve_.size() + k
    /// One particle of the reserve: discs [first, first + count) by id.
    struct Reserve {
        std::uint32_t first = 0, count = 0;
        double area = 0.0;          // layer area [h0²]
    };
    std::vector<Reserve> reserve_;  // in id order: deposited in this order
    // Scratch, reused.
    std::vector<double> h_, erode_, deposit_, hd_;
    SurfaceWorkspace ws_;
    WholeTake take_;
    std::vector<WholeCandidate> cands_, sorted_;
    std::vector<std::size_t> column_begin_, col_of_, fill_;
    std::vector<double> cx_, cy_, carea_;
    std::vector<std::uint32_t> ccount_, cfirst_, members_;
    std::vector<std::uint32_t> head_, next_;   // present discs by column (drop heights)
    std::vector<Vec2> offsets_;
    void bind(const ParticleStore& p, std::uint64_t reserve_begin);
    double area_of(const ParticleStore& p, std::size_t slot) const;  // layer area of a disc [h0²]
    double solid_total_ = -1.0;     // Σ π R² over the layer's discs [m²] (constant)
    void erode(Simulation& sim, SurfaceState& st, double S, const std::vector<double>& top,
               std::vector<Vec2>& x_then, LineFile& eroded);
    void deposit(Simulation& sim, SurfaceState& st, double S, double dS, const std::vector<double>& top,
                 double crest_x, std::vector<Vec2>& x_then);
    /// Places q in `column`, clear of the particle before it in this pass
    /// (x_free: its right edge, then q's); false when the column is blocked.
    bool place(ParticleStore& p, SurfaceState& st, const Reserve& q, std::size_t column, double S,
               double m_inertia_min, double& x_free, std::vector<Vec2>& x_then);
};

}  // namespace orodem
