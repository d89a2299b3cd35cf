// Design note: the exact critical taper of a dry, noncohesive, subaerial
// Coulomb wedge (Dahlen 1984, JGR 89, 10125-10133; Lehner 1986, JGR 91,
// 793-796), as used for the "critical wedge" of Naylor et al. (2005) §2.1.
//
// Geometry: surface slope α (dips toward the toe), basal dip β (dips toward
// the hinterland), taper α + β. Material: internal friction φ (μ = tan φ),
// basal friction φ_b (μ_b = tan φ_b), no cohesion, no pore fluid
// (λ = λ_b = 0, so α' = α and φ'_b = φ_b in Dahlen's notation).
//
// In a critical wedge the stress is linear in depth and σ_1 has the same
// direction everywhere: ψ_0 from the surface, ψ_b from the base, and since
// the base is the surface turned by the taper,
//     α + β = ψ_b − ψ_0                                   (mod 180°).   (1)
// Every plane in the wedge carries τ/σ_n ≤ tan φ, with equality on the
// optimal planes (Mohr circle of centre p and radius p sin φ). A plane at
// angle ψ from σ_1 carries σ_n = p (1 − sin φ cos 2ψ), τ = p sin φ sin 2ψ.
// Traction-free surface + gravity: planes parallel to the surface carry
// τ/σ_n = tan α; the base is at sliding: τ_b/σ_b = μ_b = tan φ_b. Both give
//     sin(2ψ_0 + α)   = sin α   / sin φ,                               (2)
//     sin(2ψ_b + φ_b) = sin φ_b / sin φ,                               (3)
// with two solutions each (the two branches of arcsin):
//     ψ_0 = ½ arcsin(sin α/sin φ) − ½ α        (σ_1 near the surface: compressive)
//     ψ_0 = 90° − ½ arcsin(sin α/sin φ) − ½ α  (σ_1 near its normal: extensional)
//     ψ_b = ½ arcsin(sin φ_b/sin φ) − ½ φ_b    (compressive)
//     ψ_b = 90° − ½ arcsin(sin φ_b/sin φ) − ½ φ_b  (extensional)
//
// The whole stability envelope in the (β, α) plane is one closed curve of
// four pieces, each monotone in α on [−φ, φ]; A(α) = arcsin(sin α/sin φ),
// ψ_b^c and ψ_b^e the compressive and extensional basal angles:
//   L1  β = ψ_b^c − ½A − ½α          (ψ_0 compressive)       decreasing in α
//   L2  β = ψ_b^c + 90° + ½A − ½α    (ψ_0 extensional −180°) increasing
//   U1  β = ψ_b^e − 90° + ½A − ½α    (ψ_0 extensional)       increasing
//   U2  β = ψ_b^e − ½A − ½α          (ψ_0 compressive)       decreasing
// L1 and U1 meet at (β, α) = (−φ_b, φ_b) (a layer of uniform thickness on a
// slope at its basal friction angle); L2 and U2 at (90°, −φ_b) (taper
// 90° − φ_b). L1 meets L2 at α = −φ, U1 meets U2 at α = +φ (the surface at
// the angle of repose, where the two ψ_0 roots coincide). So for
// −φ_b ≤ β ≤ 90° the lower bound α_min (compressively critical: Dahlen's
// critical taper) lies on L1, or on L2 beyond β = ψ_b^c + 45° + φ/2, and the
// upper bound α_max (extensionally critical) on U1, or on U2 beyond
// β = ψ_b^e − 45° − φ/2; outside [−φ_b, 90°] no wedge is stable.
//
// Each bound is found by bisection on α over [−φ, φ] of its monotone piece:
// bracketed, so it cannot diverge, and run to the last representable bit.
// The arcsin argument is clamped to [−1, 1] against rounding at α = ±φ.
//
// Small angles (Davis, Suppe & Dahlen 1983; Dahlen 1990): with
// K = 2 sin φ/(1 − sin φ), the compressive roots of (2) and (3) are
// ψ_0 ≈ α/K and ψ_b ≈ μ_b/K up to third-order terms, so on L1
// α + β ≈ (β + μ_b)/(1 + K); the extensional roots are 90° − α(1 + K)/K and
// 90° − μ_b(1 + K)/K, so on U1 α + β ≈ (1 + K)(β + μ_b) (the tests check both).
#include "orodem/analysis/critical_taper.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "orodem/core/angles.hpp"

namespace orodem {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

double rad(double deg) { return deg * kPi / 180.0; }
double deg(double rad) { return rad * 180.0 / kPi; }

/// The wedge's friction in radians and its two basal angles ψ_b.
struct Friction {
    double phi = 0.0;      // φ [rad]
    double phi_b = 0.0;    // φ_b [rad]
    double psi_b_c = 0.0;  // compressive ψ_b [rad]
    double psi_b_e = 0.0;  // extensional ψ_b [rad]
};

Friction friction(double phi_deg, double phi_b_deg) {
    Friction f;
    f.phi = rad(phi_deg);
    f.phi_b = rad(phi_b_deg);
    const double a_b = std::asin(std::clamp(std::sin(f.phi_b) / std::sin(f.phi), -1.0, 1.0));
    f.psi_b_c = 0.5 * a_b - 0.5 * f.phi_b;
    f.psi_b_e = kHalfPi - 0.5 * a_b - 0.5 * f.phi_b;
    return f;
}

/// A(α) = arcsin(sin α / sin φ) [rad].
double aux_angle(double alpha, double phi) {
    return std::asin(std::clamp(std::sin(alpha) / std::sin(phi), -1.0, 1.0));
}

enum class Piece { L1, L2, U1, U2 };

/// ψ_0(α) of a piece, before wrapping [rad].
double psi_0(Piece p, double alpha, double phi) {
    const double a = aux_angle(alpha, phi);
    switch (p) {
        case Piece::L1:
        case Piece::U2: return 0.5 * a - 0.5 * alpha;                  // compressive root of (2)
        case Piece::U1: return kHalfPi - 0.5 * a - 0.5 * alpha;        // extensional root of (2)
        case Piece::L2: return kHalfPi - 0.5 * a - 0.5 * alpha - kPi;  // extensional root, −180°
    }
    return 0.0;
}

double psi_b(Piece p, const Friction& f) { return (p == Piece::L1 || p == Piece::L2) ? f.psi_b_c : f.psi_b_e; }

/// β(α) on a piece, from (1): β = ψ_b − ψ_0 − α [rad].
double beta_on(Piece p, const Friction& f, double alpha) { return psi_b(p, f) - psi_0(p, alpha, f.phi) - alpha; }

/// The α in [−φ, φ] with beta_on(p, α) = β, by bisection (each piece is
/// monotone; the caller has checked that β lies in its range) [rad].
double solve_alpha(Piece p, const Friction& f, double beta) {
    double lo = -f.phi, hi = f.phi;
    double g_lo = beta_on(p, f, lo) - beta;
    const double g_hi = beta_on(p, f, hi) - beta;
    if (g_lo == 0.0) return lo;
    if (g_hi == 0.0) return hi;
    if ((g_lo > 0.0) == (g_hi > 0.0)) return std::abs(g_lo) < std::abs(g_hi) ? lo : hi;  // only by rounding
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;  // the bracket is two adjacent doubles
        const double g_mid = beta_on(p, f, mid) - beta;
        if (g_mid == 0.0) return mid;
        if ((g_mid > 0.0) == (g_lo > 0.0)) {
            lo = mid;
            g_lo = g_mid;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

/// An axis direction (mod 180°) in (−90°, 90°] [rad].
double wrap_axis(double a) {
    while (a > kHalfPi) a -= kPi;
    while (a <= -kHalfPi) a += kPi;
    return a;
}

std::string num(double x) { return fmt::format("{:g}", x); }

}  // namespace

void check_taper_friction(double phi_deg, double phi_b_deg) {
    if (!std::isfinite(phi_deg) || phi_deg <= 0.0 || phi_deg >= 90.0)
        throw std::invalid_argument("phi must be an angle in (0, 90) degrees, got " + num(phi_deg));
    if (!std::isfinite(phi_b_deg) || phi_b_deg < 0.0 || phi_b_deg >= phi_deg)
        throw std::invalid_argument("phi_b must be in [0, phi) = [0, " + num(phi_deg) +
                                    ") degrees (a base weaker than the wedge), got " + num(phi_b_deg));
}

TaperBetaRange critical_taper_beta_range(double phi_deg, double phi_b_deg) {
    check_taper_friction(phi_deg, phi_b_deg);
    return {-phi_b_deg, 90.0};
}

std::optional<CriticalTaper> critical_taper(double phi_deg, double phi_b_deg, double beta_deg) {
    const TaperBetaRange range = critical_taper_beta_range(phi_deg, phi_b_deg);
    if (!std::isfinite(beta_deg)) throw std::invalid_argument("beta must be a finite angle, got " + num(beta_deg));
    if (beta_deg < range.min_deg || beta_deg > range.max_deg) return std::nullopt;

    const Friction f = friction(phi_deg, phi_b_deg);
    const double beta = rad(beta_deg);
    // The knees where a bound leaves its first piece: α = −φ (lower), α = +φ (upper).
    const Piece lower = beta <= beta_on(Piece::L1, f, -f.phi) ? Piece::L1 : Piece::L2;
    const Piece upper = beta <= beta_on(Piece::U1, f, f.phi) ? Piece::U1 : Piece::U2;
    const double a_min = solve_alpha(lower, f, beta);
    const double a_max = solve_alpha(upper, f, beta);

    CriticalTaper t;
    t.alpha_min_deg = deg(a_min);
    t.alpha_max_deg = deg(a_max);
    t.psi_0_min_deg = deg(wrap_axis(psi_0(lower, a_min, f.phi)));
    t.psi_b_min_deg = deg(wrap_axis(psi_b(lower, f)));
    t.psi_0_max_deg = deg(wrap_axis(psi_0(upper, a_max, f.phi)));
    t.psi_b_max_deg = deg(wrap_axis(psi_b(upper, f)));
    return t;
}

std::vector<CriticalTaperPoint> critical_taper_envelope(double phi_deg, double phi_b_deg, std::size_t points) {
    const TaperBetaRange range = critical_taper_beta_range(phi_deg, phi_b_deg);
    if (points < 2) throw std::invalid_argument("the envelope needs at least 2 points, got " + std::to_string(points));
    std::vector<CriticalTaperPoint> out;
    out.reserve(points);
    const double step = (range.max_deg - range.min_deg) / static_cast<double>(points - 1);
    for (std::size_t i = 0; i < points; ++i) {
        const double beta = i + 1 == points ? range.max_deg : range.min_deg + step * static_cast<double>(i);
        const auto t = critical_taper(phi_deg, phi_b_deg, beta);
        out.push_back({beta, t->alpha_min_deg, t->alpha_max_deg});  // β is in range by construction
    }
    return out;
}

}  // namespace orodem
