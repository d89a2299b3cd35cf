// Wedge measurements from the surface profile (SPEC §3, [39], [44]).
// Read-only over the particle state.
//
// Surface: the domain [x_min, x_max) is cut into columns of width δx; a
// column's surface particle is its highest disc centre (y_i). y_mean is the
// undeformed surface height, measured once on the incoming layer.
// Peak: the column with the highest surface. Toes: walking outward from the
// peak, the last column of the contiguous run whose smoothed surface stays
// above a level + toe_threshold: first y_mean, then the plate's own surface
// between h0/2 and 2 h0 beyond that toe (a thickened or tilted plate is not
// taken for wedge). α (prowedge, x < peak) and β (retrowedge, x > peak):
// least-squares lines through the surface centroids (x_i, y_i of each
// column's surface particle) between toe and peak that lie between 20% and
// 80% of the flank's relief above its plate (all of them when fewer than
// three do), in degrees (α = atan slope, β = −atan slope), with the slope's
// standard error. H = (highest surface centre − y_mean) / h0, peak
// deviation = (x of the peak column's surface particle − x_S) / h0. Dilation D = 100 A_w / A_s with
// A_w = δx Σ (y_surface − y_mean) between the toes and A_s = shortening · h0.
// Retroside in two pieces (Experiment 3's second, shallower retrowedge, [52]):
// the same retroside surface points, peak to toe, split into an inner and an
// outer straight segment at the break that minimises the summed squared
// residuals of the two least-squares lines (each segment at least h0 wide
// and three columns); β_inner and β_outer are their slopes, the break the x
// of the first outer point. A single straight retrowedge gives β_inner ≈
// β_outer; a steep retrowedge in front of a long gentle one, β_inner > β_outer.
#pragma once

#include <vector>

#include "orodem/state/particles.hpp"

namespace orodem {

struct ProfileParams {
    double x_min = 0.0;          // left end of the measured range [m]
    double x_max = 0.0;          // right end [m]
    double column = 1.0;         // δx [m]
    double y_mean = 0.0;         // undeformed surface (surface-centre height) [m]
    double toe_threshold = 0.0;  // rise above y_mean that marks the wedge [m]
    double h0 = 1.0;             // [m]
    double x_s = 0.0;            // S point [m]
    bool retro_side = true;      // false: singly vergent (backstop), β not measured
    double backstop_margin = 0.0;  // singly vergent: columns this close to x_max are left
                                   // out of the α fit, which is measured away from the backstop [m]
};

struct WedgeMeasures {
    double H_over_h0 = 0.0;        // wedge height above y_mean / h0
    double alpha_deg = 0.0;        // prowedge taper α [deg] (NaN if no prowedge)
    double beta_deg = 0.0;         // retrowedge taper β [deg] (NaN if none)
    double peak_dx_over_h0 = 0.0;  // (x_peak − x_S) / h0
    double dilation_pct = 0.0;     // 100 A_w / A_s (NaN when A_s = 0)
    double toe_pro_x = 0.0;        // x of the prowedge toe [m]
    double toe_retro_x = 0.0;      // x of the retrowedge toe [m]
    double wedge_area = 0.0;       // A_w [m²]
    double beta_inner_deg = 0.0;   // retroside slope, peak to the break [deg] (NaN if too short)
    double beta_outer_deg = 0.0;   // retroside slope, break to the toe [deg] (NaN if too short)
    double retro_break_x = 0.0;    // x of the break [m] (NaN if too short)
    double alpha_se_deg = 0.0;     // standard error of α's fit [deg] (NaN with fewer than 3 points)
    double beta_se_deg = 0.0;      // standard error of β's fit [deg]
    double level_pro = 0.0;        // surface of the plate ahead of the prowedge toe [m]
    double level_retro = 0.0;      // surface of the plate ahead of the retrowedge toe [m]
};

/// Per-column surface heights (highest disc centre; -inf for an empty column).
std::vector<double> surface_profile(const ParticleStore& p, const ProfileParams& pp);

/// Mean of the non-empty columns' surface heights over [x0, x1).
double mean_surface(const ParticleStore& p, double x0, double x1, double column);

/// shortening: the convergence v t so far [m].
WedgeMeasures measure_wedge(const ParticleStore& p, const ProfileParams& pp, double shortening);

/// Whether the raised surface has run back to within h0 of the trailing wall
/// at x = wall_x (the incoming plate is then too short for the run: the wall
/// pushes the deformed plate). Never at shortening 0, where no wedge has
/// grown and the toes are those of the flat layer's highest roughness bump,
/// which may lie anywhere, by the trailing wall too.
bool plate_at_trailing_wall(const WedgeMeasures& m, double wall_x, double h0, double shortening);

/// Least-squares slope of y on x.
double fit_slope(const std::vector<double>& x, const std::vector<double>& y);

/// Two least-squares lines through the points (x sorted ascending): the
/// split k (inner = points [0, k), outer = [k, n)) with the smallest summed
/// squared residuals, among the splits that leave each side at least
/// min_points points spanning at least min_width in x. The first such split
/// wins a tie. NaN slopes and break when no split qualifies.
struct TwoLineFit {
    double slope_inner = 0.0;  // dy/dx of the inner line [-]
    double slope_outer = 0.0;  // dy/dx of the outer line [-]
    double break_x = 0.0;      // x of the first outer point [m]
};
TwoLineFit fit_two_lines(const std::vector<double>& x, const std::vector<double>& y, double min_width,
                         std::size_t min_points);

}  // namespace orodem
