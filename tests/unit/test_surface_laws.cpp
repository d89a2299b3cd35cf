// Erosion and sedimentation laws (analysis/surface_laws) against their
// analytic answers, in Naylor units (lengths h0, time S, areas h0²):
//   - diffusion of a unit step against ½ erfc(x / (2√(κt))), and the steady
//     state of uplift U between fixed ends at ±L, U (L² − x²) / (2κ); the
//     step conserves area (erosion = deposition) and is stable at any dS;
//   - the whole-particle remainder rule: random requests and particle areas
//     over 10,000 applications stay within half a particle (the rule's
//     bound; the requirement is one particle), a constant request gives
//     exactly the rounded running total, candidates in a fixed order;
//   - the elevation law on a growing triangular wedge: A → D/k with
//     e-folding length 1/k in S;
//   - slope law: eroded flux 2KH for one crest, whatever the tapers;
//     uniform law: ė W; cap: exactly the area above H_c; sedimentation:
//     exactly the deficit below the base level.
// The triangles put toes, crest and cap lines on column centres, where the
// column sum Σ h_c Δx of a piecewise-linear profile is its exact integral,
// so those comparisons are to round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "orodem/analysis/surface_laws.hpp"

using namespace orodem;

namespace {

/// A small deterministic generator (splitmix64), the same on every platform.
struct SurfaceTestRng {
    std::uint64_t s;
    std::uint64_t next() {
        std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

/// Triangle with its crest H at x = 0, flanks of slope s_left (x < 0) and
/// s_right (x > 0), zero beyond the toes, sampled at x_c = x0 + c dx [h0].
std::vector<double> triangle(double H, double s_left, double s_right, double x0, double dx, std::size_t n) {
    std::vector<double> h(n);
    for (std::size_t c = 0; c < n; ++c) {
        const double x = x0 + static_cast<double>(c) * dx;
        h[c] = std::max(0.0, x < 0.0 ? H + s_left * x : H - s_right * x);
    }
    return h;
}

double area_above_zero(const std::vector<double>& h, double dx) {
    double a = 0.0;
    for (double v : h) a += std::max(v, 0.0) * dx;
    return a;
}

/// One application of a law followed by apply_areas; returns the totals.
SurfaceTotals apply_law(const SurfaceLaw& law, std::vector<double>& h, double dx, double dS, SurfaceWorkspace& ws) {
    std::vector<double> e(h.size()), d(h.size());
    const SurfaceTotals t = surface_request(law, h, dx, dS, e, d, ws);
    apply_areas(h, e, d, dx);
    return t;
}

}  // namespace

TEST(SurfaceDiffusion, StepRelaxesAsErfc) {
    // A unit step (h = 1 for x < 0) diffused with κ = 1 to t = 1 S on
    // |x| < 10 (5 diffusion lengths 2√(κt) from the step, closed ends: the
    // erfc tail there is 1.5e-12). Errors expected: O(Δx²) = 0.0025² from
    // space and O(dS) from backward Euler, a few 1e-4 here; the requirement,
    // 0.01 in max |h − ½ erfc|, leaves room for both and still fails a
    // wrong r = κ dS/Δx² (factor 2 in κ moves h by > 0.05 near x = ±1).
    const double kappa = 1.0, t_end = 1.0, L = 10.0, dx = 0.05, dS = 0.002;
    const auto n = static_cast<std::size_t>(std::lround(2.0 * L / dx));
    std::vector<double> h(n), x(n);
    for (std::size_t c = 0; c < n; ++c) {
        x[c] = -L + (static_cast<double>(c) + 0.5) * dx;
        h[c] = x[c] < 0.0 ? 1.0 : 0.0;
    }
    SurfaceLaw law;
    law.kind = SurfaceLawKind::diffusion;
    law.kappa = kappa;
    SurfaceWorkspace ws;
    const double area0 = sum(h) * dx;
    const int steps = static_cast<int>(std::lround(t_end / dS));
    for (int i = 0; i < steps; ++i) {
        const SurfaceTotals tot = apply_law(law, h, dx, dS, ws);
        // Closed ends: what one column loses another gains; round-off of
        // n = 400 sums of terms ≤ 1 Δx is below 1e-13.
        EXPECT_NEAR(tot.eroded, tot.deposited, 1e-13);
        EXPECT_GT(tot.eroded, 0.0);
    }
    EXPECT_NEAR(sum(h) * dx, area0, 1e-12);  // area conserved (round-off over 500 steps)
    double err = 0.0;
    for (std::size_t c = 0; c < n; ++c)
        err = std::max(err, std::abs(h[c] - 0.5 * std::erfc(x[c] / (2.0 * std::sqrt(kappa * t_end)))));
    std::printf("diffusion step vs erfc: max |error| = %.3g (tolerance 0.01)\n", err);
    EXPECT_LE(err, 0.01);
}

TEST(SurfaceDiffusion, UpliftSteadyStateBetweenFixedEnds) {
    // h += U dS then a diffusion step, repeated to S = 20 L²/κ (the slowest
    // mode decays as exp(−π² κ S / (4 L²)), 1e-21 by then). The ghost
    // columns sit at x = ±L, so the three-point Laplacian, exact for a
    // parabola, has h = U (L² − x²)/(2κ) as its steady state: the error is
    // round-off. The requirement is 1% of the crest U L²/(2κ); a ghost at
    // the column face instead (x = ±(L − Δx/2)) would be 5% off here.
    const double U = 1.0, kappa = 0.5, L = 1.0, dS = 0.02;
    const std::size_t N = 40;  // intervals: columns at x_i = −L + i Δx, i = 1..N−1
    const double dx = 2.0 * L / static_cast<double>(N);
    std::vector<double> h(N - 1, 0.0), x(N - 1);
    for (std::size_t i = 0; i < N - 1; ++i) x[i] = -L + static_cast<double>(i + 1) * dx;
    SurfaceLaw law;
    law.kind = SurfaceLawKind::diffusion;
    law.kappa = kappa;
    law.ends = DiffusionEnds::fixed;
    SurfaceWorkspace ws;
    const int steps = static_cast<int>(std::lround(20.0 * L * L / kappa / dS));
    for (int s = 0; s < steps; ++s) {
        for (double& v : h) v += U * dS;
        apply_law(law, h, dx, dS, ws);
    }
    const double crest = U * L * L / (2.0 * kappa);
    double err = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i)
        err = std::max(err, std::abs(h[i] - U * (L * L - x[i] * x[i]) / (2.0 * kappa)));
    std::printf("uplift + diffusion steady state: max |error| / crest = %.3g (tolerance 0.01)\n", err / crest);
    EXPECT_LE(err, 0.01 * crest);
}

TEST(SurfaceDiffusion, StableAndMonotoneAtAnyStep) {
    // One step of dS = 1e8 (r = κ dS/Δx² = 1e10): closed ends flatten the
    // profile to its mean, fixed ends to the ghosts' level; nothing leaves
    // the old range. Tolerances: the solve's round-off grows with r as
    // r ε ≈ 1e-6, hence 1e-5 for the flat levels.
    SurfaceTestRng rng{7};
    std::vector<double> h(60);
    for (double& v : h) v = 3.0 * rng.uniform() - 1.0;
    const double lo = *std::min_element(h.begin(), h.end()), hi = *std::max_element(h.begin(), h.end());
    const double mean = sum(h) / static_cast<double>(h.size());
    SurfaceLaw law;
    law.kind = SurfaceLawKind::diffusion;
    law.kappa = 1.0;
    SurfaceWorkspace ws;
    std::vector<double> closed = h;
    const SurfaceTotals t = apply_law(law, closed, 0.1, 1e8, ws);
    EXPECT_NEAR(t.eroded, t.deposited, 1e-12);
    for (double v : closed) {
        EXPECT_NEAR(v, mean, 1e-5);
        EXPECT_GE(v, lo);
        EXPECT_LE(v, hi);
    }
    // A modest step stays within the old range too (the monotone scheme).
    std::vector<double> small = h;
    apply_law(law, small, 0.1, 0.05, ws);
    for (double v : small) {
        EXPECT_GE(v, lo - 1e-15);
        EXPECT_LE(v, hi + 1e-15);
    }
    law.ends = DiffusionEnds::fixed;
    law.h_left = law.h_right = 0.25;
    std::vector<double> fixed = h;
    apply_law(law, fixed, 0.1, 1e8, ws);
    for (double v : fixed) EXPECT_NEAR(v, 0.25, 1e-5);
}

TEST(SurfaceWhole, RandomRequestsStayWithinHalfAParticle) {
    // Four columns, 10,000 applications; each asks for 0 to 3 A_ref per
    // column (one in four asks nothing) from twelve fresh candidates of area
    // 0.5 to 1.5 A_ref at random heights (some tied). The requirement:
    // |removed − requested| ≤ the largest particle area at every
    // application; the rule promises half of it, tested here. Twelve
    // candidates of ≥ 0.5 cover the largest debt, 3 + 0.75, so none starves.
    SurfaceTestRng rng{12345};
    const std::size_t n_col = 4, per_col = 12;
    const double a_max = 1.5;
    std::vector<double> remainder(n_col, 0.0), request(n_col), asked(n_col, 0.0), removed(n_col, 0.0);
    std::vector<std::size_t> begin(n_col + 1);
    for (std::size_t c = 0; c <= n_col; ++c) begin[c] = c * per_col;
    std::vector<WholeCandidate> cand(n_col * per_col);
    WholeTake taken;
    double worst = 0.0;
    std::uint64_t next_id = 1;
    for (int app = 0; app < 10000; ++app) {
        for (std::size_t c = 0; c < n_col; ++c) request[c] = rng.uniform() < 0.25 ? 0.0 : 3.0 * rng.uniform();
        for (WholeCandidate& w : cand) {
            w.id = next_id++;
            w.area = 0.5 + rng.uniform();
            w.height = std::floor(8.0 * rng.uniform()) / 8.0;  // coarse heights: ties
        }
        take_whole_particles(remainder, request, begin, cand, taken);
        ASSERT_EQ(taken.starved, 0u);
        ASSERT_EQ(taken.column_begin.size(), n_col + 1);
        for (std::size_t c = 0; c < n_col; ++c) {
            asked[c] += request[c];
            // The taken ids of this column: the first ones of its sorted
            // candidates, in order.
            const std::size_t k = taken.column_begin[c + 1] - taken.column_begin[c];
            for (std::size_t j = 0; j < k; ++j) {
                const WholeCandidate& w = cand[begin[c] + j];
                ASSERT_EQ(taken.ids[taken.column_begin[c] + j], w.id);
                removed[c] += w.area;
            }
            for (std::size_t j = begin[c] + 1; j < begin[c + 1]; ++j)
                ASSERT_TRUE(cand[j - 1].height > cand[j].height ||
                            (cand[j - 1].height == cand[j].height && cand[j - 1].id < cand[j].id));
            const double gap = std::abs(removed[c] - asked[c]);
            worst = std::max(worst, gap);
            // Round-off of 10,000 sums of O(1) terms: below 1e-9.
            ASSERT_LE(gap, 0.5 * a_max + 1e-9) << "application " << app << " column " << c;
            ASSERT_NEAR(remainder[c], asked[c] - removed[c], 1e-9);
        }
    }
    std::printf("remainder rule: max |removed - requested| = %.4f (bound A_max/2 = %.2f, requirement %.2f)\n", worst,
                0.5 * a_max, a_max);
}

TEST(SurfaceWhole, ConstantRequestGivesTheExactRate) {
    // 3/8 of a unit particle per application (exact in binary): after n
    // applications exactly floor(3n/8 + 1/2) particles are gone (the running
    // request rounded to the nearest whole, halves up), so the long-run rate
    // is 3/8 with an error ≤ 1/(2n).
    std::vector<double> remainder(1, 0.0);
    const std::vector<double> request(1, 0.375);
    const std::vector<std::size_t> begin = {0, 3};
    std::vector<WholeCandidate> cand(3);
    WholeTake taken;
    std::size_t count = 0;
    const int n_app = 10000;
    for (int n = 1; n <= n_app; ++n) {
        for (std::size_t j = 0; j < cand.size(); ++j) cand[j] = {static_cast<std::uint64_t>(j), 1.0, 0.0};
        take_whole_particles(remainder, request, begin, cand, taken);
        count += taken.ids.size();
        ASSERT_EQ(count, static_cast<std::size_t>(std::floor(3.0 * n / 8.0 + 0.5))) << "application " << n;
    }
    EXPECT_NEAR(static_cast<double>(count) / n_app, 0.375, 0.5 / n_app);
}

TEST(SurfaceWhole, OrderIsByHeightThenIdAndStarvedColumnsKeepTheirDebt) {
    // Two columns; the candidates come in a scrambled order. Column 0 asks
    // 2.6: the two highest (tie at 2.0 broken by id 3 < 9) go, r = 0.6 stays
    // below half the next (area 1.5). Column 1 asks 5 of its only two
    // particles: both go and the debt 3 stays, counted as starved.
    std::vector<double> remainder = {0.0, 0.0};
    const std::vector<double> request = {2.6, 5.0};
    const std::vector<std::size_t> begin = {0, 4, 6};
    std::vector<WholeCandidate> cand = {{9, 1.0, 2.0}, {5, 1.5, 1.0}, {3, 1.0, 2.0}, {4, 1.0, 0.5},
                                        {20, 1.0, 0.0}, {21, 1.0, 0.3}};
    WholeTake taken;
    take_whole_particles(remainder, request, begin, cand, taken);
    const std::vector<std::uint64_t> want = {3, 9, 21, 20};
    EXPECT_EQ(taken.ids, want);
    EXPECT_EQ(taken.column_begin, (std::vector<std::size_t>{0, 2, 4}));
    EXPECT_NEAR(remainder[0], 0.6, 1e-15);
    EXPECT_NEAR(remainder[1], 3.0, 1e-15);
    EXPECT_EQ(taken.starved, 1u);
    EXPECT_DOUBLE_EQ(taken.area, 4.0);
    // Bad input is refused.
    const std::vector<double> negative = {-1.0, 0.0};
    EXPECT_THROW(take_whole_particles(remainder, negative, begin, cand, taken), std::invalid_argument);
    const std::vector<std::size_t> short_begin = {0, 4};
    EXPECT_THROW(take_whole_particles(remainder, request, short_begin, cand, taken), std::invalid_argument);
    cand[0].area = 0.0;
    EXPECT_THROW(take_whole_particles(remainder, request, begin, cand, taken), std::invalid_argument);
}

TEST(SurfaceElevation, GrowingWedgeConvergesToDOverK) {
    // A wedge ODE: each step the influx D dS is added by rebuilding the
    // profile as a triangle of fixed flank slopes (a critical-taper wedge
    // grows self-similarly) holding the area A + D dS, then the elevation
    // law erodes it. dA/dS = D − k A, so A → A_ss = D/k with e-folding
    // length 1/k. The splitting (influx, then the exact decay over dS)
    // biases A_ss by k dS/2 = 5e-4 and the e-folding length by less; the
    // requirement is 1% on both. Each step's flux is also checked against
    // A (1 − e^(−k dS)) to round-off (1e-12 relative).
    const double D = 0.95, k = 0.1, dS = 0.01, A0 = 0.2, S_end = 80.0;
    const double s_pro = 0.2, s_retro = 0.5, dx = 0.1;
    const std::size_t n = 400;
    const double x0 = -28.0;
    const double A_ss = D / k;
    SurfaceLaw law;
    law.kind = SurfaceLawKind::elevation;
    law.k = k;
    SurfaceWorkspace ws;
    std::vector<double> h(n), e(n), d(n);
    auto rebuild = [&](double A) {
        const double H = std::sqrt(2.0 * A / (1.0 / s_pro + 1.0 / s_retro));
        h = triangle(H, s_pro, s_retro, x0, dx, n);
        const double scale = A / area_above_zero(h, dx);  // the columns' area exactly A
        for (double& v : h) v *= scale;
    };
    rebuild(A0);
    double A = A0, S = 0.0, S_efold = -1.0;
    const double target = A_ss - (A_ss - A0) / std::exp(1.0);
    while (S < S_end - 0.5 * dS) {
        rebuild(A + D * dS);
        const double before = area_above_zero(h, dx);
        const SurfaceTotals t = surface_request(law, h, dx, dS, e, d, ws);
        // The law's flux is k A for any shape: exactly A (1 − e^(−k dS)).
        ASSERT_NEAR(t.eroded, before * -std::expm1(-k * dS), 1e-12 * before);
        apply_areas(h, e, d, dx);
        const double A_next = area_above_zero(h, dx);
        S += dS;
        if (S_efold < 0.0 && A_next >= target) S_efold = S - dS * (A_next - target) / (A_next - A);
        A = A_next;
    }
    std::printf("elevation law: A(S=%g) / (D/k) = %.5f, e-folding length k S_e = %.5f (tolerance 1%%)\n", S, A / A_ss,
                k * S_efold);
    EXPECT_NEAR(A, A_ss, 0.01 * A_ss);
    EXPECT_NEAR(S_efold, 1.0 / k, 0.01 / k);
    // The crest stays inside the domain (the triangle was not clipped).
    EXPECT_EQ(h.front(), 0.0);
    EXPECT_EQ(h.back(), 0.0);
}

TEST(SurfaceSlope, OneCrestErodesAtTwoKH) {
    // Crest H = 1.5 at a column centre, toes on column centres (H/s a whole
    // number of columns, all values exact in binary): Σ e_c / dS = K × total
    // relief = 2KH, for a symmetric and an asymmetric triangle; the
    // relative tolerance 1e-12 is round-off. Inside the flanks every column
    // lowers by K s dS (the continuum's uniform lowering of a straight
    // flank), the crest by the mean of its two flanks' rates.
    const double H = 1.5, K = 0.2, dS = 1e-3, dx = 0.125;
    SurfaceLaw law;
    law.kind = SurfaceLawKind::slope;
    law.K = K;
    SurfaceWorkspace ws;
    for (const double s_right : {0.25, 0.5}) {
        const double s_left = 0.25;
        const std::vector<double> h = triangle(H, s_left, s_right, -8.0, dx, 129);  // x from −8 to 8
        std::vector<double> e(h.size()), d(h.size());
        const SurfaceTotals t = surface_request(law, h, dx, dS, e, d, ws);
        std::printf("slope law (tapers %.2f, %.2f): flux / 2KH = %.15f\n", s_left, s_right, t.eroded / dS / (2 * K * H));
        EXPECT_NEAR(t.eroded / dS, 2.0 * K * H, 1e-12 * 2.0 * K * H);
        EXPECT_EQ(t.deposited, 0.0);
        // x = −3 (column 40) on the left flank, x = 0.5 (column 68) on the right.
        EXPECT_NEAR(e[40], K * s_left * dS * dx, 1e-15);
        EXPECT_NEAR(e[68], K * s_right * dS * dx, 1e-15);
        EXPECT_NEAR(e[64], K * 0.5 * (s_left + s_right) * dS * dx, 1e-15);  // the crest
        for (std::size_t c = 0; c < h.size(); ++c)
            if (h[c] <= 0.0) {
                EXPECT_EQ(e[c], 0.0);  // only the subaerial part erodes
            }
    }
}

TEST(SurfaceUniform, FluxIsRateTimesSubaerialWidth) {
    // Triangle H = 1.5, slopes 0.25: the columns with h > 0 span
    // W = 95 Δx = 11.875 (the continuum's 2H/s = 12 less the two half
    // columns at the toes); Σ e_c / dS = ė W to round-off (1e-12).
    const double H = 1.5, e_dot = 0.3, dS = 1e-3, dx = 0.125;
    std::vector<double> h = triangle(H, 0.25, 0.25, -8.0, dx, 129);
    SurfaceLaw law;
    law.kind = SurfaceLawKind::uniform;
    law.e_dot = e_dot;
    SurfaceWorkspace ws;
    std::vector<double> e(h.size()), d(h.size());
    const SurfaceTotals t = surface_request(law, h, dx, dS, e, d, ws);
    const auto wet = std::count_if(h.begin(), h.end(), [](double v) { return v > 0.0; });
    EXPECT_EQ(wet, 95);
    EXPECT_NEAR(t.eroded / dS, e_dot * 11.875, 1e-12);
    EXPECT_NEAR(t.eroded / dS, e_dot * 2.0 * H / 0.25, e_dot * dx);  // continuum, within a column
    // A step far longer than h/ė takes each column down to the surface, no further.
    const SurfaceTotals all = apply_law(law, h, dx, 100.0, ws);
    EXPECT_NEAR(all.eroded, H * H / 0.25, 1e-12);
    for (double v : h) EXPECT_EQ(v, 0.0);
}

TEST(SurfaceCap, RemovesExactlyTheAreaAboveHc) {
    // Triangle H = 1.5, slopes 0.25, cap at H_c = 1: the cap line meets the
    // flanks at x = ±2, on column centres, so the column sum is the exact
    // area (H − H_c)² / s = 1 (round-off tolerance 1e-12). After the cut
    // nothing stands above H_c and nothing below it moved.
    const double H = 1.5, s = 0.25, H_c = 1.0, dx = 0.125;
    std::vector<double> h = triangle(H, s, s, -8.0, dx, 129);
    const std::vector<double> old = h;
    SurfaceLaw law;
    law.kind = SurfaceLawKind::cap;
    law.H_c = H_c;
    SurfaceWorkspace ws;
    const SurfaceTotals t = apply_law(law, h, dx, 0.0, ws);
    EXPECT_NEAR(t.eroded, (H - H_c) * (H - H_c) / s, 1e-12);
    for (std::size_t c = 0; c < h.size(); ++c) {
        EXPECT_LE(h[c], H_c + 1e-15);
        if (old[c] <= H_c) {
            EXPECT_EQ(h[c], old[c]);
        }
    }
    // A second cut finds nothing left above H_c.
    EXPECT_NEAR(apply_law(law, h, dx, 0.0, ws).eroded, 0.0, 1e-15);
}

TEST(SurfaceSediment, FillsExactlyTheDeficitBelowTheBaseLevel) {
    // A V-shaped basin 0.5 deep with slopes 0.25 (its rims on column centres
    // at x = ±2) beside a wedge, base level b = 0: the deficit area is
    // 0.5 × 4 / 2 = 1, filled exactly (round-off tolerance 1e-12), leaving
    // the basin flat at b and the wedge as it was. At a rate ḃ the fill is
    // min(ḃ dS, b − h) per column.
    const double dx = 0.125;
    const std::size_t n = 97;  // x from −6 to 6
    std::vector<double> h(n);
    for (std::size_t c = 0; c < n; ++c) {
        const double x = -6.0 + static_cast<double>(c) * dx;
        h[c] = x < 3.0 ? std::min(0.0, -0.5 + 0.25 * std::abs(x)) : 0.5 * (x - 3.0);
    }
    const std::vector<double> old = h;
    SedimentRule rule;  // b = 0, at once
    std::vector<double> dep(n), none(n, 0.0);
    EXPECT_NEAR(sedimentation_request(rule, h, dx, 1.0, dep), 1.0, 1e-12);
    apply_areas(h, none, dep, dx);
    for (std::size_t c = 0; c < n; ++c) EXPECT_NEAR(h[c], std::max(old[c], 0.0), 1e-15);

    rule.at_once = false;
    rule.rate = 0.1;  // 0.1 h0 per S for dS = 1: the basin's columns deeper than 0.1 get 0.1
    double want = 0.0;
    for (double v : old) want += std::min(0.1, std::max(-v, 0.0)) * dx;
    EXPECT_NEAR(sedimentation_request(rule, old, dx, 1.0, dep), want, 1e-12);
    // The basin's floor (x = 0, 0.5 deep) gets 0.1; its rim (x = ±1.75) its deficit 0.0625.
    EXPECT_NEAR(dep[48], 0.1 * dx, 1e-15);
    EXPECT_NEAR(dep[34], 0.0625 * dx, 1e-15);
}

TEST(SurfaceLaws, RefuseBadInput) {
    SurfaceLaw law;
    law.kind = SurfaceLawKind::elevation;
    law.k = -1.0;
    EXPECT_THROW(check_surface_law(law), std::invalid_argument);
    law.kind = SurfaceLawKind::diffusion;
    law.kappa = std::nan("");
    EXPECT_THROW(check_surface_law(law), std::invalid_argument);
    law.kappa = 1.0;
    EXPECT_NO_THROW(check_surface_law(law));
    SedimentRule rule;
    rule.at_once = false;
    rule.rate = -0.1;
    EXPECT_THROW(check_sediment_rule(rule), std::invalid_argument);
    std::vector<double> h(5, 1.0), e(5), d(4);
    SurfaceWorkspace ws;
    EXPECT_THROW(surface_request(law, h, 0.1, 0.1, e, d, ws), std::invalid_argument);
    d.resize(5);
    EXPECT_THROW(surface_request(law, h, 0.0, 0.1, e, d, ws), std::invalid_argument);
    EXPECT_THROW(surface_request(law, h, 0.1, -0.1, e, d, ws), std::invalid_argument);
}
