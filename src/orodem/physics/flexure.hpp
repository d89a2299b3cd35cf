// Flexural isostasy: a 1D thin elastic plate on an inviscid mantle
// (Turcotte & Schubert, Geodynamics, ch. 3), solved by finite differences.
// Only the plate: the wedge's loads come in per node, the deflection goes out
// per node or at any x. The design note with the discretisation, the boundary
// conditions and the resolution rule is at the top of flexure.cpp;
// docs/physics.md "Flexure: the plate solver" says the same for users.
//
//     D w'''' + Δρ g w = q(x),     D = E Te³ / (12 (1 − ν²)),
//     α = [4 D / (Δρ g)]^¼,        Δρ = ρ_mantle − ρ_infill,
//
// w the deflection [m], positive DOWN; q the load [Pa] (force per unit area,
// i.e. N/m per metre of x for a plate of unit out-of-plane width), positive
// down. Everything is per unit out-of-plane width: a line load V0 and a node
// force are in N/m, D in N·m. A continuous plate spans the model; a broken
// plate is two plates with free ends facing each other at x_break.
#pragma once

#include <cstddef>
#include <vector>

#include "orodem/core/angles.hpp"

namespace orodem {

/// The plate and the materials above and below it.
struct PlateParams {
    double E = 70e9;             ///< Young's modulus [Pa]
    double nu = 0.25;            ///< Poisson's ratio ν [-], in [0, 0.5)
    double Te = 20e3;            ///< elastic thickness [m]; ignored when D > 0
    double D = 0.0;              ///< flexural rigidity [N·m]; > 0 overrides E, ν, Te
    double rho_mantle = 3300.0;  ///< density of the mantle that the plate displaces [kg/m³]
    double rho_infill = 1000.0;  ///< density of what fills the deflection (water, sediment, air) [kg/m³]
    double g = 9.81;             ///< gravity [m/s²]
    bool broken = false;         ///< true: two plates, free ends facing each other at x_break
    double x_break = 0.0;        ///< position of the break [m] (broken only)

    /// D [N·m]: the given D, else E Te³ / (12 (1 − ν²)).
    double flexural_rigidity() const;
    /// Δρ g [Pa/m]: the restoring pressure per metre of deflection.
    double foundation_stiffness() const;
    /// α = [4 D / (Δρ g)]^¼ [m].
    double flexural_parameter() const;
};

/// Throws std::invalid_argument unless every parameter is finite, E > 0 (or
/// D > 0), 0 ≤ ν < 0.5, Te > 0 (or D > 0), ρ_mantle > ρ_infill ≥ 0, g > 0.
void check_plate_params(const PlateParams& p);

/// The resolution rule, the largest node spacing dx/α: at or below it the
/// deflection, the slope, the zero crossing and the forebulge's position and
/// height of both analytic line-load solutions come out within 0.1%
/// (measured thresholds in flexure.cpp; tests/physics/test_flexure.cpp
/// checks the rule and that α/2 breaks it).
inline constexpr double kFlexureMaxDxPerAlpha = 1.0 / 40.0;  // [-]
/// The default extension of the plate beyond each end of the model, in α:
/// 3π α, where a line load's deflection has decayed to e^(−3π) = 8e-5 of w0.
inline constexpr double kFlexureExtensionPerAlpha = 3.0 * kPi;  // [-]

/// The model region and the grid over it.
struct FlexureGridSpec {
    double x_min = 0.0;      ///< left end of the model [m]
    double x_max = 0.0;      ///< right end of the model [m], > x_min
    double dx = 0.0;         ///< node spacing [m]; 0: the resolution rule, kFlexureMaxDxPerAlpha α
    double extension = 0.0;  ///< plate beyond each model end [m]; 0: kFlexureExtensionPerAlpha α
};

/// One plate (or two, broken) on a uniform grid, its banded matrix factored
/// once at construction: solve() allocates nothing and changes nothing, so
/// it can run every N steps of a run (and from several threads at once).
///
/// Nodes k = 0 .. size()−1, sorted by x, spacing dx: x(k) = anchor + j dx with
/// the anchor x_min (continuous) or x_break (broken), covering
/// [x_min − extension, x_max + extension] at least. A broken plate has the
/// node at x_break twice: break_node() ends the left plate, break_node() + 1
/// starts the right one, and no stiffness couples them.
class FlexurePlate {
public:
    /// Throws std::invalid_argument for bad parameters (check_plate_params), a
    /// model range that is empty or not finite, dx or extension < 0, more than
    /// 50 million nodes, or a break that leaves a plate fewer than 3 nodes.
    FlexurePlate(const PlateParams& params, const FlexureGridSpec& grid);

    std::size_t size() const { return x_.size(); }            ///< number of nodes
    double x(std::size_t k) const { return x_[k]; }            ///< position of node k [m]
    /// Width of node k's cell [m]: dx, dx/2 at the free end of a plate.
    double cell_width(std::size_t k) const { return cell_[k]; }
    double dx() const { return dx_; }                          ///< node spacing [m]
    double rigidity() const { return D_; }                     ///< D [N·m]
    double foundation_stiffness() const { return k_; }         ///< Δρ g [Pa/m]
    double alpha() const { return alpha_; }                    ///< α [m]
    bool broken() const { return broken_; }
    /// The left plate's end node at x_break (the right plate starts at +1);
    /// size() when the plate is continuous.
    std::size_t break_node() const { return break_node_; }

    /// Deflection w [m] (size() values) under the pressure q [Pa] sampled at
    /// the nodes: node k carries q[k] cell_width(k) (the trapezoid rule).
    /// q and w may be the same array.
    void solve(const double* q, double* w) const;
    /// Deflection w [m] under node forces f [N/m]: the load on node k's cell,
    /// e.g. the weight of the material binned by node. f and w may alias.
    void solve_forces(const double* f, double* w) const;

    /// Adds a line load V [N/m] at x to the node forces f, split linearly
    /// between the two nodes around x (all of it on a node when x is one) of
    /// the plate that holds x: with a break, x < x_break is the left plate and
    /// x ≥ x_break the right one. Throws std::out_of_range outside the grid.
    void add_line_load(double x, double V, double* f) const;
    /// Adds a uniform pressure q [Pa] over [x0, x1] to the node forces f
    /// [N/m]: each node the integral of q times its hat function, the
    /// function add_line_load splits with (the parts outside the grid fall
    /// off; a range over the break loads both plates).
    void add_pressure(double x0, double x1, double q, double* f) const;

    /// w at any x of the grid [m], from the node values w by cubic Hermite
    /// interpolation with the nodes' finite-difference slopes (second order;
    /// one-sided at a plate's ends); slope_at is its derivative dw/dx [-],
    /// continuous in x within a plate. The plate that holds x as in
    /// add_line_load. Throw std::out_of_range outside [x(0), x(size()−1)].
    double deflection_at(const double* w, double x) const;
    double slope_at(const double* w, double x) const;

private:
    struct Span {
        std::size_t i;  // left node of the interval that holds x
        double t;       // (x − x_i) / dx, in [0, 1]
        std::size_t first, last;  // the plate's end nodes
    };
    /// The interval that holds x: its end values w0, w1 [m], their slopes
    /// times dx, m0, m1 [m], and t = (x − x_i)/dx.
    struct HermiteCell {
        double w0, m0, w1, m1, t;
    };
    Span locate(double x) const;
    HermiteCell hermite_cell(const double* w, double x) const;
    double node_slope(const double* w, std::size_t k, std::size_t first, std::size_t last) const;

    double D_ = 0.0;      // flexural rigidity [N·m]
    double k_ = 0.0;      // Δρ g [Pa/m]
    double alpha_ = 0.0;  // flexural parameter [m]
    double dx_ = 0.0;     // node spacing [m]
    bool broken_ = false;
    double x_break_ = 0.0;        // [m]
    std::size_t break_node_ = 0;  // left plate's end node; size() when continuous
    std::vector<double> x_;       // node positions [m]
    std::vector<double> cell_;    // node cell widths [m]
    // LDLᵀ factors of the symmetric pentadiagonal stiffness matrix K [N/m²]
    // (K w = f): d the diagonal of D, l1 and l2 the first and second
    // subdiagonals of the unit lower triangle L (l1[k] = L[k+1][k],
    // l2[k] = L[k+2][k]).
    std::vector<double> d_, l1_, l2_;
};

}  // namespace orodem
