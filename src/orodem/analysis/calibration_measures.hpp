// Measurements of the calibration experiments (setup/calibration.hpp): pure
// functions of a state or of a series, so each can be tested against hand
// calculations.
//
//   love_weber_stress   the average stress of the contact forces in a sample
//                       (Love-Weber), independent of the wall measurement;
//   mobilized_friction  sin φ = (σ1 − σ3)/(σ1 + σ3) of a biaxial test;
//   window_stats        mean and spread of y over x in [from, to]
//                       (the critical state);
//   heap_profile and fit_repose: the surface of a heap by columns and the
//                       least-squares slope of each flank.
#pragma once

#include <cstddef>
#include <vector>

#include "orodem/engine/simulation.hpp"

namespace orodem {

/// A 2D stress tensor [Pa], compression positive.
struct Stress2 {
    double xx = 0, xy = 0, yx = 0, yy = 0;
};

/// σ = (1/A) [Σ_pairs f_i ⊗ (x_i − x_j) + Σ_wall contacts f ⊗ (x_i − x_c)]:
/// every disc pair (bonds included) with f the force on i, every disc-wall
/// contact with f the force on the disc and x_c its contact point, over the
/// area A [m²]. In static equilibrium this equals the stress the walls'
/// forces give (Σ over wall contacts of F_on_wall ⊗ x_c / A); the two differ
/// by Σ_i F_i ⊗ x_i / A (net forces: inertia), see net_force_moment.
Stress2 love_weber_stress(const Simulation& sim, double area);

/// (1/A) Σ_i F_i ⊗ (x_i − x̄): the inertial term by which the Love-Weber
/// stress and the wall stress differ out of equilibrium [Pa] (F_i the net
/// force on disc i this step, x̄ the mean position).
Stress2 net_force_moment(const Simulation& sim, double area);

/// Mobilized friction angle [degrees] of principal stresses σ1 ≥ σ3 > 0:
/// asin((σ1 − σ3)/(σ1 + σ3)). NaN unless σ1 + σ3 > 0.
double mobilized_friction_deg(double sigma1, double sigma3);

struct WindowStats {
    double mean = 0.0;   // NaN with no point
    double sd = 0.0;     // sample standard deviation (n − 1); 0 for one point
    std::size_t n = 0;
};
/// Mean and spread of y[k] over the k with from <= x[k] <= to (NaN y skipped).
WindowStats window_stats(const std::vector<double>& x, const std::vector<double>& y, double from, double to);

struct LineFit {
    double slope = 0.0, intercept = 0.0;  // y = intercept + slope x
    double slope_se = 0.0;                // standard error of the slope
    std::size_t n = 0;
};
/// Least-squares line through (x[k], y[k]); n < 2 gives NaN slope.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

/// The surface of a heap: the top (y + R) of the highest free disc in each
/// column of width `column` [m] from x0, columns with no free disc left out.
struct HeapProfile {
    std::vector<double> x;     // column centres [m]
    std::vector<double> top;   // surface height [m]
    double base_y = 0.0;       // the floor level the heights are measured from [m]
    double height = 0.0;       // highest top − base_y [m]
    double x_peak = 0.0;       // centre of the highest column [m]
};
/// Fixed discs (the floor) are not part of the heap.
HeapProfile heap_profile(const ParticleStore& p, double base_y, double x0, double x1, double column);

struct ReposeFit {
    LineFit left, right;       // the two flanks (left rises to the peak, right falls from it)
    double angle_left_deg = 0.0, angle_right_deg = 0.0;  // atan|slope|
    double angle_deg = 0.0;    // mean of the two
};
/// Fits each flank's surface points whose height above base_y lies in
/// [from, to] × the heap height (excluding the toe and the top).
ReposeFit fit_repose(const HeapProfile& h, double from, double to);

}  // namespace orodem
