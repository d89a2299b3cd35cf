// Critical-taper theory (analysis/critical_taper): the exact solution of
// Dahlen (1984) for a dry noncohesive Coulomb wedge, both branches.
//   - published values: ECCW, the exact-critical-Coulomb-wedge program of
//     B. C. L. Mary (github.com/bclmary/eccw, after Dahlen 1984 and Yuan et
//     al. 2015, JGR 120, doi:10.1002/2014JB011612), its test suite
//     tests/test_eccw_compute.py, test_compression: φ = 30°, φ_b = 10°,
//     β = 0 gives α = 3.4365° (compressive) and 23.9463° (extensional); and
//     α = 3.43653° is critical for β = 0 and β = 69.6780°; ECCW bounds the
//     taper by α + β < 90° − φ_b (the vertex (β, α) = (90°, −φ_b) here);
//   - an independent check sharing no code with the solution: the stress of
//     the critical wedge built from scratch (linear in depth, uniform along
//     the surface, traction-free surface, gravity), the wedge interior at
//     Mohr-Coulomb failure on its optimal planes and the base at sliding
//     τ_b = μ_b σ_n, to 1e-9;
//   - the small-angle limit of Davis, Suppe & Dahlen (1983) / Dahlen (1990),
//     derived below, agreeing to third order;
//   - limits and trends: the vertices of the envelope, a frictionless base,
//     α_min growing with φ_b, the refusal of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "orodem/analysis/critical_taper.hpp"

using namespace orodem;

namespace {

constexpr double kPi = std::numbers::pi;
double rad(double d) { return d * kPi / 180.0; }
double deg(double r) { return r * 180.0 / kPi; }

/// a − b as axes (mod 180°), in (−90°, 90°] [deg].
double axis_diff_deg(double a, double b) {
    double d = std::fmod(a - b, 180.0);
    if (d > 90.0) d -= 180.0;
    if (d <= -90.0) d += 180.0;
    return d;
}

/// Stress of an infinite critical slope per unit ρ g z (compression
/// positive), in the surface frame: x along the surface toward the toe
/// (downslope), z normal to it, down into the wedge. Equilibrium with gravity
/// (g_x = g sin α, g_z = g cos α) for a stress linear in z, independent of x
/// and free of traction at z = 0 gives S_zz = cos α, S_xz = sin α; S_xx is
/// left free by equilibrium and fixed here by Mohr-Coulomb failure
/// ((S_xx − S_zz)/2)² + S_xz² = sin²φ ((S_xx + S_zz)/2)², a quadratic in S_xx
/// with roots [cos α (1 + sin²φ) ± 2 √(sin²φ − sin²α)] / cos²φ: + is the
/// compressive (passive) state, − the extensional (active) one.
struct Stress {
    double xx = 0.0, xz = 0.0, zz = 0.0;
};

Stress critical_slope_stress(double phi, double alpha, bool compressive) {
    const double s2 = std::sin(phi) * std::sin(phi), c2 = std::cos(phi) * std::cos(phi);
    const double root = std::sqrt(std::max(0.0, s2 - std::sin(alpha) * std::sin(alpha)));
    Stress s;
    s.zz = std::cos(alpha);
    s.xz = std::sin(alpha);
    s.xx = (std::cos(alpha) * (1.0 + s2) + (compressive ? 2.0 : -2.0) * root) / c2;
    return s;
}

/// n·S·m for unit vectors n = (nx, nz), m = (mx, mz).
double form(const Stress& s, double nx, double nz, double mx, double mz) {
    return nx * (s.xx * mx + s.xz * mz) + nz * (s.xz * mx + s.zz * mz);
}

/// τ_b / σ_n on the base, the shear traction counted positive toward the
/// hinterland (resisting the wedge's motion toward the toe). The base makes
/// the angle θ = α + β with the surface and passes through the toe at the
/// origin; the wedge is x < 0, 0 < z < −x tan θ; outward normal of the base
/// n = (sin θ, cos θ), its direction toward the hinterland t = (−cos θ, sin θ).
/// The traction the substrate exerts on the wedge is −S n.
double base_ratio(const Stress& s, double taper) {
    const double nx = std::sin(taper), nz = std::cos(taper);
    const double tx = -std::cos(taper), tz = std::sin(taper);
    const double sigma_n = form(s, nx, nz, nx, nz);
    const double tau = -form(s, tx, tz, nx, nz);
    return tau / sigma_n;
}

/// max over plane orientations of τ − σ_n tan φ (per unit ρ g z), by a scan.
double worst_coulomb_excess(const Stress& s, double phi) {
    double worst = -1e300;
    for (int i = 0; i < 20000; ++i) {
        const double w = kPi * i / 20000.0;  // plane normal angle
        const double nx = std::cos(w), nz = std::sin(w);
        const double sigma = form(s, nx, nz, nx, nz);
        const double tau = std::abs(form(s, -nz, nx, nx, nz));
        worst = std::max(worst, tau - sigma * std::tan(phi));
    }
    return worst;
}

/// σ_1 direction from the surface (x toward z) [rad].
double sigma1_angle(const Stress& s) { return 0.5 * std::atan2(2.0 * s.xz, s.xx - s.zz); }

/// τ/σ_n on the optimal (Coulomb) planes: normals at ±(45° + φ/2) from σ_1.
double optimal_plane_ratio(const Stress& s, double phi, double sign) {
    const double w = sigma1_angle(s) + sign * (0.25 * kPi + 0.5 * phi);
    const double nx = std::cos(w), nz = std::sin(w);
    return std::abs(form(s, -nz, nx, nx, nz)) / form(s, nx, nz, nx, nz);
}

CriticalTaper solve(double phi, double phib, double beta) {
    const auto t = critical_taper(phi, phib, beta);
    EXPECT_TRUE(t.has_value()) << "phi " << phi << " phib " << phib << " beta " << beta;
    return t.value_or(CriticalTaper{});
}

}  // namespace

// ECCW test_compression (see the header comment): φ = 30°, φ_D = 10°, β = 0
// → α = 3.4365° and 23.9463° (assertAlmostEqual to 3 places).
TEST(CriticalTaper, MatchesPublishedEccwValues) {
    const CriticalTaper t = solve(30.0, 10.0, 0.0);
    EXPECT_NEAR(t.alpha_min_deg, 3.4365, 5e-4);
    EXPECT_NEAR(t.alpha_max_deg, 23.9463, 5e-4);
    // The same α = 3.43653° is critical on the upper branch for β = 69.6780°.
    const CriticalTaper steep = solve(30.0, 10.0, 69.6780);
    EXPECT_NEAR(steep.alpha_max_deg, 3.43653, 5e-4);
}

// The stability field is closed: both bounds meet at (β, α) = (−φ_b, φ_b)
// (a layer of uniform thickness on a slope at the basal friction angle) and
// at (90°, −φ_b) (ECCW's taper limit α + β = 90° − φ_b); outside, no solution.
TEST(CriticalTaper, EnvelopeVerticesAndRange) {
    for (double phib : {0.0, 5.0, 10.0, 20.0, 29.0}) {
        const CriticalTaper lo = solve(30.0, phib, -phib);
        EXPECT_NEAR(lo.alpha_min_deg, phib, 1e-9);
        EXPECT_NEAR(lo.alpha_max_deg, phib, 1e-9);
        const CriticalTaper hi = solve(30.0, phib, 90.0);
        EXPECT_NEAR(hi.alpha_min_deg, -phib, 1e-9);
        EXPECT_NEAR(hi.alpha_max_deg, -phib, 1e-9);
        EXPECT_FALSE(critical_taper(30.0, phib, -phib - 1e-6).has_value());
        EXPECT_FALSE(critical_taper(30.0, phib, 90.0 + 1e-6).has_value());
        const TaperBetaRange r = critical_taper_beta_range(30.0, phib);
        EXPECT_EQ(r.min_deg, -phib);
        EXPECT_EQ(r.max_deg, 90.0);
    }
}

// The independent check: for each solution, the stress built above from its
// α alone (the Mohr-Coulomb root whose σ_1 lies along the library's ψ_0, the
// two roots being the compressive and the extensional state) is at failure
// on its optimal planes, no plane exceeds Coulomb, and the base is exactly at
// sliding. On the ordinary part of the field the lower bound is the
// compressive state and the upper the extensional one, and the other root
// would not slide on the base.
TEST(CriticalTaper, StressStateIsAtFailureAndBaseAtSliding) {
    int checked = 0;
    for (double phi : {20.0, 30.0, 37.0, 45.0}) {
        for (double frac : {0.0, 0.1, 0.35, 0.7, 0.95}) {
            const double phib = frac * phi;
            const double mu_b = std::tan(rad(phib));
            for (double beta = -phib; beta <= 90.0; beta += 7.3) {
                const CriticalTaper t = solve(phi, phib, beta);
                bool lower_compressive = false, upper_compressive = false;
                for (bool lower : {true, false}) {
                    const double alpha = rad(lower ? t.alpha_min_deg : t.alpha_max_deg);
                    const double psi_0 = lower ? t.psi_0_min_deg : t.psi_0_max_deg;
                    const Stress plus = critical_slope_stress(rad(phi), alpha, true);
                    const Stress minus = critical_slope_stress(rad(phi), alpha, false);
                    const bool compressive = std::abs(axis_diff_deg(deg(sigma1_angle(plus)), psi_0)) <=
                                             std::abs(axis_diff_deg(deg(sigma1_angle(minus)), psi_0));
                    (lower ? lower_compressive : upper_compressive) = compressive;
                    const Stress& s = compressive ? plus : minus;
                    SCOPED_TRACE(::testing::Message() << "phi " << phi << " phib " << phib << " beta " << beta
                                                      << (lower ? " lower" : " upper") << " alpha " << deg(alpha));
                    // Interior: at failure on the optimal planes, nowhere beyond.
                    EXPECT_NEAR(optimal_plane_ratio(s, rad(phi), +1.0), std::tan(rad(phi)), 1e-9);
                    EXPECT_NEAR(optimal_plane_ratio(s, rad(phi), -1.0), std::tan(rad(phi)), 1e-9);
                    EXPECT_LE(worst_coulomb_excess(s, rad(phi)), 1e-12);
                    // Base: at sliding, shear resisting motion toward the toe.
                    EXPECT_NEAR(base_ratio(s, alpha + rad(beta)), mu_b, 1e-9);
                    // The library's ψ_0, ψ_b are this stress's σ_1 direction.
                    EXPECT_NEAR(axis_diff_deg(deg(sigma1_angle(s)), psi_0), 0.0, 1e-9);
                    const double psi_b = lower ? t.psi_b_min_deg : t.psi_b_max_deg;
                    EXPECT_NEAR(axis_diff_deg(psi_b - psi_0, deg(alpha) + beta), 0.0, 1e-9);
                    ++checked;
                }
                // Ordinary part: small basal dips (the lower bound leaves its
                // compressive piece only past β = 45° + φ/2 + ψ_b, the upper
                // its extensional piece past β ≈ 45° − φ/2 − φ_b (1 + 1/sin φ)/2,
                // above 5° for φ_b ≤ 0.1 φ here).
                if (beta < 45.0 && beta > -phib + 1.0) {
                    EXPECT_TRUE(lower_compressive);
                    const double a = rad(t.alpha_min_deg);
                    EXPECT_GT(std::abs(base_ratio(critical_slope_stress(rad(phi), a, false), a + rad(beta)) - mu_b),
                              1e-6);
                }
                if (frac > 0.0 && frac <= 0.1 && beta <= 5.0 && beta > -phib + 1.0) {
                    EXPECT_FALSE(upper_compressive);
                }
            }
        }
    }
    EXPECT_GT(checked, 500);
}

// Small angles. With K = 2 sin φ/(1 − sin φ): the compressive roots of
// sin(2ψ + x) = sin x / sin φ are ψ = x (1 − sin φ)/(2 sin φ) + O(x³) = x/K,
// so α + β = ψ_b − ψ_0 ≈ (μ_b − α)/K, i.e. α + β ≈ (β + μ_b)/(1 + K)
// (Davis et al. 1983; Dahlen 1990). The extensional roots are
// 90° − x (1 + K)/K + O(x³), giving α + β ≈ (1 + K)(β + μ_b) on the upper
// branch. Both ψ(x) are odd in x (and φ_b = atan μ_b odd in μ_b), so the
// error is third order: halving every angle divides it by 8.
TEST(CriticalTaper, SmallAngleLimitToThirdOrder) {
    for (double phi : {25.0, 30.0, 40.0}) {
        const double sp = std::sin(rad(phi)), K = 2.0 * sp / (1.0 - sp);
        for (double beta0 : {0.0, 0.5, -0.3}) {  // β = t β0, μ_b = t (radians)
            double prev_lo = 0.0, prev_hi = 0.0;
            for (double t : {0.02, 0.01, 0.005}) {
                const double beta = t * beta0, mu_b = t;
                const CriticalTaper c = solve(phi, deg(std::atan(mu_b)), deg(beta));
                const double err_lo = std::abs(rad(c.alpha_min_deg) + beta - (beta + mu_b) / (1.0 + K));
                const double err_hi = std::abs(rad(c.alpha_max_deg) + beta - (1.0 + K) * (beta + mu_b));
                SCOPED_TRACE(::testing::Message() << "phi " << phi << " beta0 " << beta0 << " t " << t);
                // Observed err/t³: 0.06-0.22 (lower), 14-175 (upper, larger tapers).
                EXPECT_LT(err_lo, 0.5 * t * t * t);
                EXPECT_LT(err_hi, 250.0 * t * t * t);
                if (prev_lo > 0.0) {
                    EXPECT_NEAR(prev_lo / err_lo, 8.0, 0.5);
                    EXPECT_NEAR(prev_hi / err_hi, 8.0, 0.5);
                }
                prev_lo = err_lo;
                prev_hi = err_hi;
            }
        }
    }
}

// A frictionless base (φ_b = 0) carries no shear, so σ_1 lies along it
// (ψ_b = 0) and α + β = −ψ_0(α). On a flat base the only critical wedge is the
// flat layer: α_min = α_max = 0. On a dipping base the critical surface is
// NOT parallel to the base (α = −β would need τ = ρ g H sin α = 0 on a base
// parallel to the surface): to first order α = −β K/(1 + K), a positive
// taper (β + μ_b)/(1 + K) = β/(1 + K).
TEST(CriticalTaper, FrictionlessBase) {
    const CriticalTaper flat = solve(30.0, 0.0, 0.0);
    EXPECT_NEAR(flat.alpha_min_deg, 0.0, 1e-12);
    EXPECT_NEAR(flat.alpha_max_deg, 0.0, 1e-12);
    EXPECT_NEAR(flat.psi_b_min_deg, 0.0, 1e-12);
    const double K = 2.0 * 0.5 / (1.0 - 0.5);  // φ = 30°
    for (double beta : {0.5, 2.0, 5.0}) {
        const CriticalTaper t = solve(30.0, 0.0, beta);
        EXPECT_NEAR(t.psi_b_min_deg, 0.0, 1e-12);
        EXPECT_NEAR(axis_diff_deg(t.alpha_min_deg + beta, -t.psi_0_min_deg), 0.0, 1e-9);
        EXPECT_GT(t.alpha_min_deg + beta, 0.0);
        EXPECT_NEAR(t.alpha_min_deg, -beta * K / (1.0 + K), 2e-3 * beta * beta);
    }
}

TEST(CriticalTaper, AlphaMinGrowsWithBasalFriction) {
    for (double beta : {-2.0, 0.0, 3.0, 10.0, 30.0}) {
        double prev = -1e300;
        for (double phib = std::max(0.0, -beta); phib < 30.0; phib += 1.0) {
            const CriticalTaper t = solve(30.0, phib, beta);
            EXPECT_GT(t.alpha_min_deg, prev) << "beta " << beta << " phib " << phib;
            EXPECT_GE(t.alpha_max_deg, t.alpha_min_deg - 1e-12);
            prev = t.alpha_min_deg;
        }
    }
    // And with the basal dip the critical surface flattens: α_min falls as β grows.
    double prev = 1e300;
    for (double beta = -10.0; beta <= 60.0; beta += 5.0) {
        const double a = solve(30.0, 10.0, beta).alpha_min_deg;
        EXPECT_LT(a, prev);
        prev = a;
    }
}

// The envelope is point-symmetric about (β, α) = (45° − φ_b/2, 0):
// α_min(β) = −α_max(90° − φ_b − β). From (1)-(3): ψ_0 (compressive) is odd in
// α and ψ_b (extensional) = 90° − φ_b − ψ_b (compressive), so the lower
// piece L1 maps onto the upper piece U2 (and L2 onto U1).
TEST(CriticalTaper, EnvelopeIsPointSymmetric) {
    for (double phi : {20.0, 30.0, 45.0}) {
        for (double frac : {0.0, 0.3, 0.9}) {
            const double phib = frac * phi;
            for (double beta = -phib; beta <= 90.0; beta += 0.7) {
                const auto mirror = critical_taper(phi, phib, 90.0 - phib - beta);
                if (!mirror) continue;  // rounding at the far vertex
                EXPECT_NEAR(solve(phi, phib, beta).alpha_min_deg, -mirror->alpha_max_deg, 1e-9)
                    << "phi " << phi << " phib " << phib << " beta " << beta;
            }
        }
    }
}

// Each bound leaves its first piece at a knee (α = ∓φ, where the two roots
// for ψ_0 meet): the bounds are continuous there, and |α| ≤ φ everywhere.
TEST(CriticalTaper, ContinuousAcrossTheKnees) {
    const double phi = 30.0, phib = 10.0;
    double prev_lo = 0.0, prev_hi = 0.0;
    const double step = 1e-3;
    for (double beta = -phib; beta <= 90.0; beta += step) {
        const CriticalTaper t = solve(phi, phib, beta);
        EXPECT_GE(t.alpha_min_deg, -phi - 1e-9);
        EXPECT_LE(t.alpha_max_deg, phi + 1e-9);
        if (beta > -phib) {
            // dα/dβ is finite except at the two vertices, where α − φ_b
            // grows like √(β + φ_b): 1 deg per 1e-3 deg bounds any step.
            EXPECT_LT(std::abs(t.alpha_min_deg - prev_lo), 1.0) << beta;
            EXPECT_LT(std::abs(t.alpha_max_deg - prev_hi), 1.0) << beta;
        }
        prev_lo = t.alpha_min_deg;
        prev_hi = t.alpha_max_deg;
    }
}

TEST(CriticalTaper, EnvelopeForPlots) {
    const auto env = critical_taper_envelope(30.0, 10.0, 201);
    ASSERT_EQ(env.size(), 201u);
    EXPECT_EQ(env.front().beta_deg, -10.0);
    EXPECT_EQ(env.back().beta_deg, 90.0);
    EXPECT_NEAR(env.front().alpha_min_deg, env.front().alpha_max_deg, 1e-9);  // closed at both ends
    EXPECT_NEAR(env.back().alpha_min_deg, env.back().alpha_max_deg, 1e-9);
    for (std::size_t i = 0; i < env.size(); ++i) {
        if (i > 0) {
            EXPECT_GT(env[i].beta_deg, env[i - 1].beta_deg);
        }
        EXPECT_LE(env[i].alpha_min_deg, env[i].alpha_max_deg + 1e-12);
        const CriticalTaper t = solve(30.0, 10.0, env[i].beta_deg);
        EXPECT_EQ(env[i].alpha_min_deg, t.alpha_min_deg);
        EXPECT_EQ(env[i].alpha_max_deg, t.alpha_max_deg);
        EXPECT_TRUE(std::isfinite(env[i].alpha_min_deg) && std::isfinite(env[i].alpha_max_deg));
    }
    EXPECT_THROW(critical_taper_envelope(30.0, 10.0, 1), std::invalid_argument);
}

TEST(CriticalTaper, RefusesBadInput) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(critical_taper(0.0, 0.0, 0.0), std::invalid_argument);    // φ ≤ 0
    EXPECT_THROW(critical_taper(-5.0, 0.0, 0.0), std::invalid_argument);
    EXPECT_THROW(critical_taper(90.0, 10.0, 0.0), std::invalid_argument);  // φ ≥ 90
    EXPECT_THROW(critical_taper(120.0, 10.0, 0.0), std::invalid_argument);
    EXPECT_THROW(critical_taper(30.0, 30.0, 0.0), std::invalid_argument);  // φ_b ≥ φ
    EXPECT_THROW(critical_taper(30.0, 35.0, 0.0), std::invalid_argument);
    EXPECT_THROW(critical_taper(30.0, -1.0, 0.0), std::invalid_argument);  // φ_b < 0
    EXPECT_THROW(critical_taper(nan, 10.0, 0.0), std::invalid_argument);
    EXPECT_THROW(critical_taper(30.0, nan, 0.0), std::invalid_argument);
    EXPECT_THROW(critical_taper(30.0, 10.0, nan), std::invalid_argument);
    EXPECT_THROW(critical_taper(30.0, 10.0, std::numeric_limits<double>::infinity()), std::invalid_argument);
    EXPECT_THROW(critical_taper_beta_range(30.0, 31.0), std::invalid_argument);
    try {
        critical_taper(30.0, 35.0, 0.0);
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("phi_b"), std::string::npos) << e.what();
    }
    // Extreme but valid friction: finite answers.
    for (double phi : {0.5, 89.5}) {
        const CriticalTaper t = solve(phi, 0.5 * phi, 0.0);
        EXPECT_TRUE(std::isfinite(t.alpha_min_deg) && std::isfinite(t.alpha_max_deg));
        EXPECT_LT(t.alpha_min_deg, t.alpha_max_deg);
    }
}
