// Erosion and sedimentation laws on a 1D surface profile (docs/physics.md
// "Erosion and sedimentation laws"; /work/shared/ANCHORS.md). Pure functions
// on values: no particles, no state but the caller's, so each law can be
// tested against its analytic flux. The model wiring turns the profile of a
// run into h, calls these every N steps, and removes or places whole
// clusters through take_whole_particles.
//
// Units (Naylor units, the same law at every model size): lengths in h0, the
// incoming layer thickness; "time" is the shortening S in h0; rates in h0 per
// unit S; areas in h0². The profile is n columns of width Δx [h0], column c
// at height h_c [h0] above the incoming surface (h ≤ 0: at or below it).
//
// A law asks, for one application over a shortening increment dS, for an
// area per column to erode (e_c ≥ 0) and to deposit (d_c ≥ 0) [h0²];
// apply_areas then moves the profile by (d_c − e_c)/Δx.
//   elevation  E = k h on h > 0, applied exactly over dS: e_c = h_c (1 − e^(−k dS)) Δx,
//              so the eroded flux is k A (A the subaerial area) to O(k dS).
//   slope      E = K |dh/dx| on the subaerial profile h⁺ = max(h, 0): each
//              interface between columns carries |Δh⁺|/Δx, split half to each
//              side, all of it to the subaerial side where the other is at or
//              below 0, so Σ e_c = K dS × (total variation of h⁺): 2KH dS for
//              one crest of height H, whatever the tapers. Profile ends carry
//              no interface (nothing beyond is counted).
//   uniform    e_c = ė dS Δx on h > 0: flux ė W, W = Δx × (columns with h > 0).
//   cap        e_c = (h_c − H_c)⁺ Δx at once (dS is not used).
//   The three rate laws never ask for more than the column's h⁺ Δx (erosion
//   stops at the incoming surface); in the steady regimes they are meant
//   for, this clip does not bind (E dS ≪ h).
//   diffusion  ∂h/∂t = κ ∂²h/∂x², one backward-Euler step over dS solved by
//              the tridiagonal (Thomas) algorithm: unconditionally stable, first
//              order in dS, monotone (the new profile has no new extremum, so
//              erosion never digs below and deposition never builds above the
//              old range). Ends: closed (zero flux; Σ h is conserved and
//              Σ e_c = Σ d_c up to round-off) or fixed (a ghost column beyond
//              each end held at h_left / h_right; the balance then differs
//              by the flux through the ends). The change per column is split
//              into erosion (h decreases) and deposition (h increases).
//
// Sedimentation fills the columns below a base level b [h0] (relative to the
// incoming surface): at once, d_c = (b − h_c)⁺ Δx, or at a rate ḃ [h0/S],
// d_c = min(ḃ dS, (b − h_c)⁺) Δx.
//
// Whole particles (take_whole_particles): particles (clusters) are removed
// or placed whole. Each column keeps a remainder r_c [h0²], the area asked
// for and not yet taken: r_c += a_c, then, the column's candidates taken
// topmost first, the next candidate (area A) is taken while r_c ≥ A/2, and
// r_c −= A (r_c may go negative). This rounds the running request to the
// nearest whole particle: after each application −A_max/2 ≤ r_c < A_max/2
// while candidates last, and since taken = asked − r_c the taken area stays
// within half the largest particle's area of the asked area at every
// application, with no drift. Taking at r_c ≥ A (rounding down) lags by up
// to one particle and at r_c > 0 (rounding up) overshoots by up to one.
// A column whose candidates run out keeps its unmet remainder (counted in
// WholeTake::starved); the caller may clear it.
//
// Determinism: no threads; every loop runs over the columns in order; a
// column's candidates are ordered by height (highest first) and then by id
// (smaller first), whatever order the caller gave. Allocation: the functions
// that take a SurfaceWorkspace or WholeTake reuse its buffers and allocate
// only when the column or candidate count grows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace orodem {

enum class SurfaceLawKind { none, elevation, slope, uniform, cap, diffusion };

enum class DiffusionEnds {
    closed,  // zero flux through both ends: area conserved
    fixed,   // a ghost column beyond each end held at h_left, h_right
};

struct SurfaceLaw {
    SurfaceLawKind kind = SurfaceLawKind::none;
    double k = 0.0;        // elevation law E = k h [1/S] (per unit shortening in h0)
    double K = 0.0;        // slope law E = K |dh/dx| [h0/S]
    double e_dot = 0.0;    // uniform rate ė [h0/S]
    double H_c = 0.0;      // cap height above the incoming surface [h0]
    double kappa = 0.0;    // diffusivity κ [h0²/S]
    DiffusionEnds ends = DiffusionEnds::closed;
    double h_left = 0.0;   // fixed ends: height held beyond column 0 [h0]
    double h_right = 0.0;  // fixed ends: height held beyond column n−1 [h0]
};

/// Throws std::invalid_argument unless the law's own parameter is finite and
/// ≥ 0 (k, K, ė, κ; H_c finite, any sign) and fixed ends' heights are finite.
void check_surface_law(const SurfaceLaw& law);

struct SedimentRule {
    double base_level = 0.0;  // b: fill up to this height above the incoming surface [h0]
    bool at_once = true;      // true: fill the whole deficit at each application
    double rate = 0.0;        // ḃ: otherwise, fill at most ḃ dS per application [h0/S]
};

/// Throws std::invalid_argument unless b is finite and (at once or ḃ finite and ≥ 0).
void check_sediment_rule(const SedimentRule& rule);

/// Buffers of surface_request (the diffusion solve).
struct SurfaceWorkspace {
    std::vector<double> h_new;    // the diffused profile [h0]
    std::vector<double> c_prime;  // Thomas sweep: modified super-diagonal [-]
};

/// Summed areas of one application [h0²].
struct SurfaceTotals {
    double eroded = 0.0;     // Σ e_c [h0²]
    double deposited = 0.0;  // Σ d_c [h0²]
};

/// The areas law asks to erode (erode[c]) and deposit (deposit[c]) over a
/// shortening increment dS ≥ 0 [S] on the profile h [h0] with columns dx > 0
/// wide [h0]. erode and deposit must have h's size; they are overwritten.
/// Only diffusion deposits. Throws std::invalid_argument on mismatched sizes,
/// dx ≤ 0 or dS < 0.
SurfaceTotals surface_request(const SurfaceLaw& law, std::span<const double> h, double dx, double dS,
                              std::span<double> erode, std::span<double> deposit, SurfaceWorkspace& ws);

/// Per-column area to deposit [h0²] filling toward the base level over dS
/// [S]; returns the total [h0²]. deposit has h's size and is overwritten.
double sedimentation_request(const SedimentRule& rule, std::span<const double> h, double dx, double dS,
                             std::span<double> deposit);

/// h[c] += (deposit[c] − erode[c]) / dx: the profile the areas leave [h0].
void apply_areas(std::span<double> h, std::span<const double> erode, std::span<const double> deposit,
                 double dx);

/// One particle (cluster) that may be taken from, or placed in, a column.
struct WholeCandidate {
    std::uint64_t id = 0;  // the particle's (cluster's) id, unique
    double area = 0.0;     // its area A > 0 [h0²]
    double height = 0.0;   // its order key: removal takes the highest first [h0]
};

/// What one application took; its buffers are reused by the next.
struct WholeTake {
    std::vector<std::uint64_t> ids;        // taken, column by column, highest first within a column
    std::vector<std::size_t> column_begin;  // ids of column c: [column_begin[c], column_begin[c+1])
    double area = 0.0;                     // Σ A of the taken [h0²]
    std::size_t starved = 0;               // columns left with r_c ≥ A/2 of their last
                                           // candidate, or r_c > 0 with no candidate at all
};

/// The whole-particle rule (see the note above): for each column c,
/// r_c += request[c], then take its candidates
/// candidates[column_begin[c] .. column_begin[c+1]) in order of height
/// (highest first; ties: smaller id first) while r_c ≥ A/2 of the next one,
/// subtracting A. Sorts each column's candidates in place. remainder and
/// request have one entry per column [h0²]; column_begin has one more, starts
/// at 0, never decreases and ends at candidates.size(). Throws
/// std::invalid_argument on mismatched sizes, a negative or non-finite
/// request, a candidate area that is not finite and > 0 or a height that is
/// not finite. For placing
/// (sedimentation), the candidates are the particles ready to be placed in
/// the column, their height the order in which to place them.
void take_whole_particles(std::span<double> remainder, std::span<const double> request,
                          std::span<const std::size_t> column_begin, std::span<WholeCandidate> candidates,
                          WholeTake& taken);

}  // namespace orodem
