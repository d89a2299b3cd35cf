// Design note: a 1D thin elastic plate on an inviscid mantle (Turcotte &
// Schubert, Geodynamics, 2nd ed., §3-9 to §3-17),
//     D w'''' + Δρ g w = q,
// discretised as the minimum of its energy on a uniform grid (x_k, spacing h):
//     Π(w) = Σ_interior k  D/(2h³) (w_{k−1} − 2w_k + w_{k+1})²
//          + Σ_k  Δρg/2 c_k w_k²  −  Σ_k f_k w_k,
// c_k the node's cell width (h; h/2 at a free end), f_k the node force
// [N/m]. Its gradient K w = f is the usual five-point scheme: in the
// interior D/h⁴ (w_{k−2} − 4w_{k−1} + 6w_k − 4w_{k+1} + w_{k+2}) + Δρg w_k =
// f_k/h; at a free end the rows (1, −2, 1) and (−2, 5, −4, 1) (times D/h³),
// which are the ghost-node conditions w'' = 0, w''' = 0 with the end node's
// row halved, i.e. a half cell. K is symmetric positive definite (the
// foundation makes it so), so it is factored once as L D Lᵀ without pivoting
// and every solve is two sweeps in a fixed order: no threads, no reordering,
// the same bytes every time.
//
// Free ends everywhere. A break is two plates with free ends at the same x
// (the node at x_break appears twice, uncoupled). The far ends of the grid
// are free ends too, `extension` (3π α by default) beyond the model: a
// clamped end (w = w' = 0) would hold a reaction force; a free end is what a
// plate's end is, uses the same rows as the break, and keeps the discrete
// isostatic balance exact: the stiffness rows of K sum to zero (they
// annihilate constant and linear w), so Σ_k Δρg c_k w_k = Σ_k f_k, the
// trapezoid ∫w dx equals ∫q dx / (Δρg) to round-off. Either end's effect on
// the model decays as e^(−x/α) from the end and from the load: a load at
// the model's edge sees the far end at 3π α as a correction of about
// e^(−6π) = 7e-9 of w0 on the model's side (the test doubles the extension).
//
// Accuracy (second order in h/α, measured in tests/physics/test_flexure.cpp):
//  - interior: the five-point stencil is d⁴ + (h²/6) d⁶, i.e. a load error
//    −(Δρg h²/6) w'' spread over the whole deflection;
//  - a line load V on one node: the stencil sees the jump of D w''' at the
//    load spread as (1/6, 2/3, 1/6) V over three nodes (the cubic B-spline),
//    so one node carrying all of V differs by (−1/6, 1/3, −1/6) V: no net
//    force, no moment, a w error of (h²/6) |w''(0)| = (1/3)(h/α)² w0 at the
//    load; split linearly between two nodes, up to (1/4)(h/α)² w0 more;
//  - a free end with its half cell: the two end rows leave residual forces
//    −Δρg w h/12 and +Δρg w h/12 (end node, its neighbour): no net force, a
//    moment Δρg w h²/12, so the free-end solution (the broken plate with its
//    end load) converges at O(h²) too. A full cell at the end node would
//    leave a net force Δρg w h/2: first order.
// Measured on both analytic line-load solutions: deflection error
// 0.25 (h/α)² w0; zero crossing 0.08 (h/α)² of its position; forebulge
// height 0.64 (h/α)² of itself (broken plate, the worst of the deflection
// measures: 0.1% at h = α/25.3); slope 1.5 (h/α)² of the largest slope
// (continuous plate, in the cell next to the line load, where w''' jumps:
// 0.1% at h = α/38.3). The resolution rule kFlexureMaxDxPerAlpha, h ≤ α/40,
// keeps every one of them within 0.1%.
//
// Interpolation between nodes: cubic Hermite with node slopes from central
// differences (second-order one-sided at a plate's end), so deflection_at is
// exact at the nodes, C¹ within a plate, and third order between nodes;
// slope_at is its derivative.
#include "orodem/physics/flexure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace orodem {

namespace {

std::string flexure_num(double x) { return fmt::format("{:g}", x); }

constexpr double kFlexureMaxNodes = 5e7;  // refuse grids beyond this [-]

}  // namespace

double PlateParams::flexural_rigidity() const {
    if (D > 0.0) return D;
    return E * Te * Te * Te / (12.0 * (1.0 - nu * nu));
}

double PlateParams::foundation_stiffness() const { return (rho_mantle - rho_infill) * g; }

double PlateParams::flexural_parameter() const {
    return std::sqrt(std::sqrt(4.0 * flexural_rigidity() / foundation_stiffness()));
}

void check_plate_params(const PlateParams& p) {
    const auto bad = [](const std::string& what) { throw std::invalid_argument("flexure: " + what); };
    if (!std::isfinite(p.D) || p.D < 0.0) bad("D must be >= 0 (0: from E, nu, Te), got " + flexure_num(p.D));
    if (p.D == 0.0) {
        if (!std::isfinite(p.E) || p.E <= 0.0) bad("E must be > 0 Pa, got " + flexure_num(p.E));
        if (!std::isfinite(p.nu) || p.nu < 0.0 || p.nu >= 0.5) bad("nu must be in [0, 0.5), got " + flexure_num(p.nu));
        if (!std::isfinite(p.Te) || p.Te <= 0.0) bad("Te must be > 0 m, got " + flexure_num(p.Te));
    }
    if (!std::isfinite(p.rho_infill) || p.rho_infill < 0.0)
        bad("rho_infill must be >= 0 kg/m3, got " + flexure_num(p.rho_infill));
    if (!std::isfinite(p.rho_mantle) || p.rho_mantle <= p.rho_infill)
        bad("rho_mantle must exceed rho_infill = " + flexure_num(p.rho_infill) + " kg/m3, got " +
            flexure_num(p.rho_mantle));
    if (!std::isfinite(p.g) || p.g <= 0.0) bad("g must be > 0 m/s2, got " + flexure_num(p.g));
    if (p.broken && !std::isfinite(p.x_break)) bad("x_break must be finite, got " + flexure_num(p.x_break));
}

FlexurePlate::FlexurePlate(const PlateParams& params, const FlexureGridSpec& grid) {
    check_plate_params(params);
    const auto bad = [](const std::string& what) { throw std::invalid_argument("flexure: " + what); };
    if (!std::isfinite(grid.x_min) || !std::isfinite(grid.x_max) || !(grid.x_max > grid.x_min))
        bad("the model range needs finite x_min < x_max, got [" + flexure_num(grid.x_min) + ", " +
            flexure_num(grid.x_max) + "] m");
    if (!std::isfinite(grid.dx) || grid.dx < 0.0) bad("dx must be >= 0 m (0: alpha/40), got " + flexure_num(grid.dx));
    if (!std::isfinite(grid.extension) || grid.extension < 0.0)
        bad("extension must be >= 0 m (0: 3 pi alpha), got " + flexure_num(grid.extension));

    D_ = params.flexural_rigidity();
    k_ = params.foundation_stiffness();
    alpha_ = params.flexural_parameter();
    dx_ = grid.dx > 0.0 ? grid.dx : kFlexureMaxDxPerAlpha * alpha_;
    const double extension = grid.extension > 0.0 ? grid.extension : kFlexureExtensionPerAlpha * alpha_;
    broken_ = params.broken;
    x_break_ = params.x_break;

    // Node j (integer) sits at anchor + j dx; the model's ends are rounded
    // outward to nodes (to a billionth of a cell, so that a range of whole
    // cells gets exactly its nodes), then the extension, in whole cells.
    const double anchor = broken_ ? x_break_ : grid.x_min;
    const double slack = 1e-9;
    const double n_ext = std::ceil(extension / dx_ - slack);
    const double j_lo = std::floor((grid.x_min - anchor) / dx_ + slack) - n_ext;
    const double j_hi = std::ceil((grid.x_max - anchor) / dx_ - slack) + n_ext;
    if (!(j_hi - j_lo + 2.0 <= kFlexureMaxNodes))
        bad("the grid would have more than " + flexure_num(kFlexureMaxNodes) + " nodes (dx " + flexure_num(dx_) +
            " m over [" + flexure_num(grid.x_min) + ", " + flexure_num(grid.x_max) + "] m and " +
            flexure_num(extension) + " m each side)");
    const auto lo = static_cast<long long>(j_lo);
    const auto hi = static_cast<long long>(j_hi);
    if (broken_ && (lo > -2 || hi < 2))
        bad("the break at x = " + flexure_num(x_break_) + " m leaves a plate fewer than 3 nodes of the grid [" +
            flexure_num(anchor + j_lo * dx_) + ", " + flexure_num(anchor + j_hi * dx_) + "] m");

    // Nodes, and each plate's first and last node.
    for (long long j = lo; j <= hi; ++j) {
        x_.push_back(anchor + static_cast<double>(j) * dx_);
        if (broken_ && j == 0) x_.push_back(anchor);  // the right plate's end at the break
    }
    const std::size_t n = x_.size();
    break_node_ = broken_ ? static_cast<std::size_t>(-lo) : n;
    const std::size_t plates = broken_ ? 2 : 1;
    const std::size_t first[2] = {0, break_node_ + 1};
    const std::size_t last[2] = {broken_ ? break_node_ : n - 1, n - 1};

    // Stiffness K: integer stencil coefficients per plate (exact), times
    // D/h³, plus the foundation Δρg c_k on the diagonal. a0, a1, a2: the
    // diagonal, first and second superdiagonals (K[k][k+1], K[k][k+2]).
    std::vector<double> a0(n, 0.0), a1(n, 0.0), a2(n, 0.0);
    cell_.assign(n, dx_);
    for (std::size_t p = 0; p < plates; ++p) {
        // One curvature term (w_{j−1} − 2w_j + w_{j+1})² per interior node j.
        for (std::size_t j = first[p] + 1; j < last[p]; ++j) {
            a0[j - 1] += 1.0;
            a0[j] += 4.0;
            a0[j + 1] += 1.0;
            a1[j - 1] += -2.0;
            a1[j] += -2.0;
            a2[j - 1] += 1.0;
        }
        cell_[first[p]] = 0.5 * dx_;
        cell_[last[p]] = 0.5 * dx_;
    }
    const double c = D_ / (dx_ * dx_ * dx_);  // [N/m²]
    for (std::size_t k = 0; k < n; ++k) {
        a0[k] = c * a0[k] + k_ * cell_[k];
        a1[k] = c * a1[k];
        a2[k] = c * a2[k];
    }

    // L D Lᵀ, row by row: A[k][k] = d_k + l1_{k−1}² d_{k−1} + l2_{k−2}² d_{k−2},
    // A[k+1][k] = l1_k d_k + l2_{k−1} d_{k−1} l1_{k−1}, A[k+2][k] = l2_k d_k.
    d_.assign(n, 0.0);
    l1_.assign(n, 0.0);
    l2_.assign(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
        double dk = a0[k];
        double ak1 = a1[k];
        if (k >= 1) {
            dk -= l1_[k - 1] * l1_[k - 1] * d_[k - 1];
            ak1 -= l2_[k - 1] * d_[k - 1] * l1_[k - 1];
        }
        if (k >= 2) dk -= l2_[k - 2] * l2_[k - 2] * d_[k - 2];
        if (!(dk > 0.0)) bad("the plate's matrix is not positive definite (pivot " + flexure_num(dk) + " at node " +
                             std::to_string(k) + "): dx is too small for double precision");
        d_[k] = dk;
        l1_[k] = ak1 / dk;
        l2_[k] = a2[k] / dk;
    }
}

void FlexurePlate::solve(const double* q, double* w) const {
    const std::size_t n = size();
    for (std::size_t k = 0; k < n; ++k) w[k] = q[k] * cell_[k];
    solve_forces(w, w);
}

void FlexurePlate::solve_forces(const double* f, double* w) const {
    const std::size_t n = size();
    // L y = f, then y /= d, then Lᵀ w = y, in place in w.
    for (std::size_t k = 0; k < n; ++k) {
        double y = f[k];
        if (k >= 1) y -= l1_[k - 1] * w[k - 1];
        if (k >= 2) y -= l2_[k - 2] * w[k - 2];
        w[k] = y;
    }
    for (std::size_t k = 0; k < n; ++k) w[k] /= d_[k];
    for (std::size_t k = n; k-- > 0;) {
        double v = w[k];
        if (k + 1 < n) v -= l1_[k] * w[k + 1];
        if (k + 2 < n) v -= l2_[k] * w[k + 2];
        w[k] = v;
    }
}

FlexurePlate::Span FlexurePlate::locate(double x) const {
    const std::size_t n = size();
    if (!(x >= x_[0] && x <= x_[n - 1]))
        throw std::out_of_range("flexure: x = " + flexure_num(x) + " m lies outside the plate's grid [" +
                                flexure_num(x_[0]) + ", " + flexure_num(x_[n - 1]) + "] m");
    Span s{};
    s.first = 0;
    s.last = n - 1;
    if (broken_) {
        if (x < x_break_) {
            s.last = break_node_;
        } else {
            s.first = break_node_ + 1;
        }
    }
    const double u = (x - x_[s.first]) / dx_;
    double cellf = std::floor(u);
    const double cells = static_cast<double>(s.last - s.first);
    if (cellf < 0.0) cellf = 0.0;
    if (cellf > cells - 1.0) cellf = cells - 1.0;
    s.i = s.first + static_cast<std::size_t>(cellf);
    s.t = (x - x_[s.i]) / dx_;
    if (s.t < 0.0) s.t = 0.0;
    if (s.t > 1.0) s.t = 1.0;
    return s;
}

double FlexurePlate::node_slope(const double* w, std::size_t k, std::size_t first, std::size_t last) const {
    if (k == first) return (-3.0 * w[k] + 4.0 * w[k + 1] - w[k + 2]) / (2.0 * dx_);
    if (k == last) return (3.0 * w[k] - 4.0 * w[k - 1] + w[k - 2]) / (2.0 * dx_);
    return (w[k + 1] - w[k - 1]) / (2.0 * dx_);
}

void FlexurePlate::add_line_load(double x, double V, double* f) const {
    const Span s = locate(x);
    if (s.t == 0.0) {
        f[s.i] += V;
    } else if (s.t == 1.0) {
        f[s.i + 1] += V;
    } else {
        f[s.i] += (1.0 - s.t) * V;
        f[s.i + 1] += s.t * V;
    }
}

void FlexurePlate::add_pressure(double x0, double x1, double q, double* f) const {
    const std::size_t n = size();
    const double h = dx_;
    for (std::size_t k = 0; k < n; ++k) {
        const bool first = k == 0 || (broken_ && k == break_node_ + 1);
        const bool last = k + 1 == n || (broken_ && k == break_node_);
        double a = 0.0;  // ∫ of the hat over [x0, x1] [m]
        if (!first) {    // left half: (x − x_l)/h on [x_l, x_k]
            const double xl = x_[k] - h, lo = std::max(x0, xl), hi = std::min(x1, x_[k]);
            if (hi > lo) a += ((hi - xl) * (hi - xl) - (lo - xl) * (lo - xl)) / (2.0 * h);
        }
        if (!last) {     // right half: (x_r − x)/h on [x_k, x_r]
            const double xr = x_[k] + h, lo = std::max(x0, x_[k]), hi = std::min(x1, xr);
            if (hi > lo) a += ((xr - lo) * (xr - lo) - (xr - hi) * (xr - hi)) / (2.0 * h);
        }
        f[k] += q * a;
    }
}

FlexurePlate::HermiteCell FlexurePlate::hermite_cell(const double* w, double x) const {
    const Span s = locate(x);
    return HermiteCell{w[s.i], node_slope(w, s.i, s.first, s.last) * dx_, w[s.i + 1],
                       node_slope(w, s.i + 1, s.first, s.last) * dx_, s.t};
}

double FlexurePlate::deflection_at(const double* w, double x) const {
    const HermiteCell c = hermite_cell(w, x);
    // Hermite basis: h00 = 2t³ − 3t² + 1, h10 = t³ − 2t² + t, h01 = −2t³ + 3t², h11 = t³ − t².
    const double t2 = c.t * c.t;
    const double t3 = t2 * c.t;
    return (2.0 * t3 - 3.0 * t2 + 1.0) * c.w0 + (t3 - 2.0 * t2 + c.t) * c.m0 + (3.0 * t2 - 2.0 * t3) * c.w1 +
           (t3 - t2) * c.m1;
}

double FlexurePlate::slope_at(const double* w, double x) const {
    const HermiteCell c = hermite_cell(w, x);
    const double t2 = c.t * c.t;
    const double dwdt = (6.0 * t2 - 6.0 * c.t) * c.w0 + (3.0 * t2 - 4.0 * c.t + 1.0) * c.m0 +
                        (6.0 * c.t - 6.0 * t2) * c.w1 + (3.0 * t2 - 2.0 * c.t) * c.m1;
    return dwdt / dx_;
}

}  // namespace orodem
