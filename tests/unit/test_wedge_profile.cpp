// Wedge measurements (SPEC §3; analysis/wedge_profile) on hand-built states
// whose answers are known by construction:
//   - a flat layer of equal discs plus a triangular heap whose surface disc
//     centres lie exactly on lines of slope tan α (proside) and −tan β
//     (retroside): α, β, H, peak deviation and both toes;
//   - a flat lattice: H = 0 and D = 0;
//   - a rectangular block of known area on a flat layer: D = 100 A_w / (s h0);
//   - two straight lines meeting at a kink, alone and as a retroside with a
//     steep inner and a gentle outer slope: both slopes and the break.
// Every measure is taken, as in the implementation, on disc centres: the
// column surface is the highest centre and y_mean is a centre height.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "orodem/analysis/wedge_profile.hpp"

using namespace orodem;

namespace {

constexpr double kPi = std::numbers::pi;
double deg(double rad) { return rad * 180.0 / kPi; }
double rad(double deg) { return deg * kPi / 180.0; }

// Common geometry (metres). Discs of radius r; the heap surface is sampled
// every ds = r; columns are δx = 4 ds wide, so every column holds exactly four
// surface samples, at x_min + (k + 0.5) ds (never on a column boundary).
constexpr double kR = 0.01;
constexpr double kDs = kR;
constexpr double kColumn = 4 * kDs;
constexpr double kXMin = -8.0;
constexpr int kSamples = 1600;  // x_min .. x_min + 1600 ds = +8
constexpr double kXMax = kXMin + kSamples * kDs;
constexpr int kRows = 25;       // layer rows at y = r + 2 r j
constexpr double kYMean = kR + 2 * kR * (kRows - 1);  // top-row centre height = 0.49
constexpr double kH0 = kYMean + kR;                    // layer thickness 0.5

double sample_x(int k) { return kXMin + (k + 0.5) * kDs; }

/// Flat layer of equal discs on a square grid of spacing 2r, top centres at
/// exactly kYMean (the same double), from x_min to x_max.
void add_flat_layer(ParticleStore& p) {
    static_assert(kDs == kR);  // 2r spacing = every other sample slot
    for (int m = 0; m < kSamples / 2; ++m) {
        const double x = kXMin + (2 * m + 1) * kR;
        for (int j = 0; j < kRows - 1; ++j) p.add({x, kR + 2 * kR * j}, kR, 2500.0);
        p.add({x, kYMean}, kR, 2500.0);
    }
}

/// One surface disc at (x, kYMean + h) and, every other sample, a column of
/// fill discs (spacing 2r) strictly below it: the fill never changes a
/// column's maximum, it only makes the heap a heap.
void add_heap_column(ParticleStore& p, int k, double h) {
    const double x = sample_x(k);
    p.add({x, kYMean + h}, kR, 2500.0);
    if (k % 2 == 0)
        for (int j = 1; 2 * kR * j < h - kR; ++j) p.add({x, kYMean + 2 * kR * j}, kR, 2500.0);
}

/// The flat layer plus a heap of height h(x) (surface samples where h > 0),
/// after checking that both toes stay half a metre inside the domain.
template <class Height>
ParticleStore heap_on_layer(double x_toe_pro, double x_toe_retro, Height h) {
    EXPECT_GT(x_toe_pro, kXMin + 0.5);
    EXPECT_LT(x_toe_retro, kXMax - 0.5);
    ParticleStore p;
    add_flat_layer(p);
    for (int k = 0; k < kSamples; ++k) {
        const double hk = h(sample_x(k));
        if (hk > 0.0) add_heap_column(p, k, hk);
    }
    return p;
}

ProfileParams params(double toe_threshold) {
    ProfileParams pp;
    pp.x_min = kXMin;
    pp.x_max = kXMax;
    pp.column = kColumn;
    pp.y_mean = kYMean;
    pp.toe_threshold = toe_threshold;
    pp.h0 = kH0;
    pp.x_s = 0.0;
    pp.retro_side = true;
    return pp;
}

struct WedgeCase {
    double alpha_deg, beta_deg;
    int peak_sample;  // the peak sits on sample k (k mod 4 = 1: inside a column)
    double height;    // peak height above y_mean [m]
};

void check_triangular_wedge(const WedgeCase& wc) {
    const double ta = std::tan(rad(wc.alpha_deg)), tb = std::tan(rad(wc.beta_deg));
    const double x_peak = sample_x(wc.peak_sample);
    const double x_toe_pro = x_peak - wc.height / ta;    // where the α line meets y_mean
    const double x_toe_retro = x_peak + wc.height / tb;  // where the β line meets y_mean
    const ParticleStore p = heap_on_layer(
        x_toe_pro, x_toe_retro, [&](double x) { return std::min(ta * (x - x_toe_pro), tb * (x_toe_retro - x)); });

    // Toe threshold 0.15 m = 0.3 h0: the threshold line is crossed at least
    // 3 columns inside the geometric toe for both slopes (0.15 / tan 40° =
    // 0.179 m > 3 δx = 0.12 m), so the three-column smoothing there averages
    // three columns of one straight line and reproduces it exactly; the toe
    // column is then the one containing the crossing x, whose centre is
    // within one column width of it.
    const double thr = 0.15;
    const ProfileParams pp = params(thr);
    const WedgeMeasures m = measure_wedge(p, pp, /*shortening=*/2.0);  // s = 2 m

    // Taper tolerance 0.5°. Derivation of the discretisation error: each
    // column's surface is its highest sample, i.e. its upslope sample, so the
    // column heights on each flank lie exactly on a line of the true slope
    // (constant offset). Only the peak column deviates, by |e| ≤ tan·δx. A
    // least-squares slope over n equally spaced points moves by
    // 6 e / (δx n (n+1)) for an error e at one end, i.e. at most
    // 6 tan / (n (n+1)) in slope and cos² times that in angle.
    auto bound_deg = [&](double t, double flank_len) {
        const double n = flank_len / kColumn;  // columns from toe to peak (lower estimate)
        return deg(6.0 * t / (n * (n + 1.0)) / (1.0 + t * t));
    };
    const double bound_a = bound_deg(ta, (wc.height - thr) / ta);
    const double bound_b = bound_deg(tb, (wc.height - thr) / tb);
    ASSERT_LT(bound_a, 0.5);
    ASSERT_LT(bound_b, 0.5);
    std::printf("    alpha %.4f (ref %.1f, err bound %.3f)  beta %.4f (ref %.1f, err bound %.3f)\n", m.alpha_deg,
                wc.alpha_deg, bound_a, m.beta_deg, wc.beta_deg, bound_b);
    EXPECT_NEAR(m.alpha_deg, wc.alpha_deg, 0.5);
    EXPECT_NEAR(m.beta_deg, wc.beta_deg, 0.5);
    // A straight retroside in two pieces: every split fits both pieces
    // exactly, so both slopes are β (same tolerance), when the retroside is
    // wide enough for two segments of h0 each (plus a column between them).
    const double retro_span = (wc.height - thr) / tb;
    if (retro_span > 2.0 * kH0 + 2.0 * kColumn) {
        EXPECT_NEAR(m.beta_inner_deg, wc.beta_deg, 0.5);
        EXPECT_NEAR(m.beta_outer_deg, wc.beta_deg, 0.5);
    } else if (retro_span < 2.0 * kH0) {
        EXPECT_TRUE(std::isnan(m.beta_inner_deg) && std::isnan(m.beta_outer_deg) && std::isnan(m.retro_break_x));
    }

    // H: the peak disc centre sits at y_mean + height (both on centres), so
    // H is exact up to round-off; the tolerance r/2 is below one disc radius,
    // so it would also catch a mix of a disc-top height with a centre y_mean.
    std::printf("    H/h0 %.6f (ref %.6f)  peak dx/h0 %.6f (ref %.6f)\n", m.H_over_h0, wc.height / kH0,
                m.peak_dx_over_h0, x_peak / kH0);
    EXPECT_NEAR(m.H_over_h0 * kH0, wc.height, 0.5 * kR);
    // Peak deviation: x of the highest point, x_S = 0; one column width
    // (the resolution of a column-based surface).
    EXPECT_NEAR(m.peak_dx_over_h0 * kH0, x_peak, kColumn);

    // Toes: the outermost columns rising above y_mean by the threshold, i.e.
    // where each flank line crosses y_mean + thr; within one column.
    const double cross_pro = x_toe_pro + thr / ta, cross_retro = x_toe_retro - thr / tb;
    std::printf("    levels %.6f %.6f (y_mean %.6f)\n", m.level_pro, m.level_retro, kYMean);
    std::printf("    toe_pro %.4f (ref %.4f)  toe_retro %.4f (ref %.4f)\n", m.toe_pro_x, cross_pro,
                m.toe_retro_x, cross_retro);
    EXPECT_NEAR(m.toe_pro_x, cross_pro, kColumn);
    EXPECT_NEAR(m.toe_retro_x, cross_retro, kColumn);

    // Wedge area between the toes: the triangle above y_mean less the two
    // tails outside the toes (below the threshold line), ½ thr²/tan each.
    // Column error: each column counts δx · (its highest sample), which
    // differs from the integral of the surface over the column by at most
    // δx · (its oscillation); summed, δx · (total variation of the surface
    // between the toes) ≤ δx · 2 H. The toe columns reach at most δx past
    // the crossings, where the surface is below 2 thr: ≤ 2 · δx · 2 thr more.
    const double s = 2.0;
    const double area = 0.5 * wc.height * (x_toe_retro - x_toe_pro) - 0.5 * thr * thr / ta - 0.5 * thr * thr / tb;
    const double area_bound = kColumn * (2.0 * wc.height + 4.0 * thr);
    std::printf("    A_w %.5f (ref %.5f, bound %.3f)  D %.3f %% (ref %.3f)\n", m.wedge_area, area, area_bound,
                m.dilation_pct, 100.0 * area / (s * kH0));
    EXPECT_NEAR(m.wedge_area, area, area_bound);
    EXPECT_NEAR(m.dilation_pct, 100.0 * m.wedge_area / (s * kH0), 1e-12 * m.dilation_pct);
}

}  // namespace

TEST(WedgeProfile, TriangularWedgeAlpha8Beta30) {
    // Peak at x ≈ +0.495 m (sample 849, the second sample of its column).
    check_triangular_wedge({8.0, 30.0, 849, 1.0});
}

TEST(WedgeProfile, TriangularWedgeAlpha15Beta40) {
    // Peak at x ≈ −1.185 m, proside of the S point (sample 681).
    check_triangular_wedge({15.0, 40.0, 681, 1.0});
}

TEST(WedgeProfile, FlatLayerHasNoHeightNoDilation) {
    // Hexagonal lattice of equal discs: rows at y = r + j √3 r, odd rows
    // shifted by r; the top row (even) has centres every 2r, so every column
    // of width ≥ 2r holds one top-row disc and all column maxima are the same
    // double. Checked for δx = 2r (the default column width, 2 r_max) and an
    // incommensurate δx = 5r.
    const double r = 0.01, x0 = -1.0;
    const int cols = 100, rows = 25;  // top row: 100 discs over [x0, x0 + 200 r)
    ParticleStore p;
    double y_top = 0.0;
    for (int j = 0; j < rows; ++j) {
        const double y = r + j * std::sqrt(3.0) * r;
        y_top = y;
        for (int m = 0; m < cols; ++m) {
            const double x = x0 + r + 2 * r * m + ((j % 2) ? r : 0.0);
            if (x < x0 + 2 * r * cols) p.add({x, y}, r, 2500.0);
        }
    }
    ASSERT_EQ(rows % 2, 1);  // the top row is an even (unshifted) row
    const double h0 = y_top + r;
    for (double column : {2 * r, 5 * r}) {
        ProfileParams pp;
        pp.x_min = x0;
        pp.x_max = x0 + 2 * r * cols;
        pp.column = column;
        // y_mean as a run measures it: the mean of the column maxima.
        pp.y_mean = mean_surface(p, pp.x_min, pp.x_max, column);
        pp.toe_threshold = 0.1 * h0;
        pp.h0 = h0;
        const WedgeMeasures m = measure_wedge(p, pp, /*shortening=*/0.3);
        std::printf("    column %.3f: y_mean - y_top = %.3g, H/h0 = %.3g, D = %.3g %%\n", column, pp.y_mean - y_top,
                    m.H_over_h0, m.dilation_pct);
        // Round-off only: y_mean is a mean of identical doubles (error a few
        // ulp of 0.43 m, ~1e-16 m); 1e-12 leaves a wide margin yet is 10
        // orders below a disc radius.
        EXPECT_NEAR(pp.y_mean, y_top, 1e-12);
        EXPECT_NEAR(m.H_over_h0, 0.0, 1e-12);
        EXPECT_NEAR(m.dilation_pct, 0.0, 1e-9);  // = 100 · (≤ δx · 1e-16 m) / (0.3 · 0.44)
        EXPECT_TRUE(std::isnan(m.alpha_deg));    // no prowedge: no column above the toe level
        EXPECT_TRUE(std::isnan(m.beta_deg));
    }
}

namespace {

/// Flat layer plus a block of width w_samples·ds starting at x_a, whose
/// surface disc centres are hb above y_mean: extra area A_w = w hb exactly
/// (on centres).
ParticleStore layer_with_block(double x_a, int w_samples, double hb) {
    ParticleStore p;
    add_flat_layer(p);
    for (int k = 0; k < w_samples; ++k) {
        const double x = x_a + (k + 0.5) * kDs;
        p.add({x, kYMean + hb}, kR, 2500.0);
        if (k % 2 == 0)
            for (int j = 1; 2 * kR * j < hb - kR; ++j) p.add({x, kYMean + 2 * kR * j}, kR, 2500.0);
    }
    return p;
}

}  // namespace

TEST(WedgeProfile, DilationOfAKnownBlock) {
    const double hb = 0.2, s = 4.0;
    const int w_samples = 200;  // width 2.0 m = 50 columns
    const double A_w = w_samples * kDs * hb;
    const double D_true = 100.0 * A_w / (s * kH0);  // 20 %
    const ProfileParams pp = params(/*toe_threshold=*/0.1);

    // (1) Block edges on column boundaries: the 50 block columns measure
    // exactly hb each (the same doubles), every other column exactly 0, so
    // A_w is exact up to round-off (relative 1e-15; tolerance 1e-9 relative).
    {
        const ParticleStore p = layer_with_block(kXMin + 100 * kColumn, w_samples, hb);
        const WedgeMeasures m = measure_wedge(p, pp, s);
        std::printf("    aligned: D = %.9f %% (ref %.9f), A_w = %.9f (ref %.9f)\n", m.dilation_pct, D_true,
                    m.wedge_area, A_w);
        EXPECT_NEAR(m.wedge_area, A_w, 1e-9 * A_w);
        EXPECT_NEAR(m.dilation_pct, D_true, 1e-9 * D_true);
        EXPECT_NEAR(m.H_over_h0 * kH0, hb, 1e-12);
    }
    // (2) Block edges at 0.37 δx inside a column: a column counts in full
    // (δx · hb) as soon as it holds one block centre. The centres span
    // [x_a + ds/2, x_b − ds/2], so the counted columns cover that span and
    // reach at most δx beyond each end: counted width ∈ [w − ds, w − ds + 2δx],
    // |A_w,measured − A_w| ≤ 2 δx hb, hence |ΔD| ≤ 100 · 2 δx hb / (s h0) = 0.8 %.
    {
        const ParticleStore p = layer_with_block(kXMin + 100.37 * kColumn, w_samples, hb);
        const WedgeMeasures m = measure_wedge(p, pp, s);
        const double bound = 100.0 * 2.0 * kColumn * hb / (s * kH0);
        std::printf("    misaligned: D = %.6f %% (ref %.6f, bound %.3f)\n", m.dilation_pct, D_true, bound);
        EXPECT_NEAR(m.dilation_pct, D_true, bound);
    }
}

// Singly vergent wedge against a backstop at x_max: a straight prowedge of
// slope tan 10° up to the backstop, where the last 0.4 m is dragged up by a
// further 0.15 m (the backstop's own drag zone). With backstop_margin = 0.5 m
// the fit leaves that zone out and returns 10° within 0.5° (same bound as the
// doubly vergent cases: the fitted points lie on the line). Without the
// margin the fit over the flank's 20-80% relief band leaves it out as well
// (the drag zone is the top 20% of the relief), so the result is the same.
TEST(WedgeProfile, CriticalWedgeAlphaMeasuredAwayFromTheBackstop) {
    const double alpha = rad(10.0);
    const double x_back = 0.0;  // backstop [m]
    ParticleStore p;
    add_flat_layer(p);
    const int k_back = static_cast<int>((x_back - kXMin) / kDs);  // first sample at the backstop
    const double height = 0.8;                                      // at the backstop [m]
    const int k_toe = k_back - static_cast<int>(height / std::tan(alpha) / kDs);
    for (int k = k_toe; k < k_back; ++k) {
        double h = height - (x_back - sample_x(k)) * std::tan(alpha);
        if (x_back - sample_x(k) < 0.4) h += 0.15;
        if (h > 2 * kR) add_heap_column(p, k, h);
    }
    ProfileParams pp = params(0.05);
    pp.x_max = x_back;
    pp.retro_side = false;
    pp.backstop_margin = 0.5;
    const WedgeMeasures with = measure_wedge(p, pp, 1.0);
    EXPECT_NEAR(with.alpha_deg, 10.0, 0.5);
    EXPECT_TRUE(std::isnan(with.beta_deg));
    pp.backstop_margin = 0.0;
    const WedgeMeasures without = measure_wedge(p, pp, 1.0);
    EXPECT_NEAR(without.alpha_deg, 10.0, 0.5);
}

TEST(WedgeProfile, PlateAtTheTrailingWallOnlyOnceTheWedgeHasGrown) {
    // A flat layer 20 m long with one bump by its trailing end (x = -9.5 m,
    // wall at -10 m): at shortening 0 the bump is the "peak" and its toe lies
    // within h0 of the wall, which is no wedge at the wall; once shortened,
    // a toe within h0 of the wall is one, and a toe farther away is not.
    ParticleStore p;
    for (int k = 0; k < 40; ++k) p.add({-10.0 + 0.25 + 0.5 * k, 0.25}, 0.25, 2500.0);
    p.add({-9.5, 0.75}, 0.25, 2500.0);
    ProfileParams pp;
    pp.column = 0.5;
    pp.x_min = -10.0;
    pp.x_max = 10.0;
    pp.x_s = 0.0;
    pp.h0 = 2.0;
    pp.y_mean = 0.25;
    pp.toe_threshold = 0.1;
    const WedgeMeasures m = measure_wedge(p, pp, 0.0);
    ASSERT_LT(m.toe_pro_x - (-10.0), pp.h0) << m.toe_pro_x;  // the bump's toe, by the wall
    EXPECT_FALSE(plate_at_trailing_wall(m, -10.0, pp.h0, 0.0));
    EXPECT_TRUE(plate_at_trailing_wall(m, -10.0, pp.h0, 0.5));
    WedgeMeasures far = m;
    far.toe_pro_x = -7.0;
    EXPECT_FALSE(plate_at_trailing_wall(far, -10.0, pp.h0, 0.5));
}


TEST(WedgeProfile, TwoLinesFitRecoversBothSlopesAndTheBreak) {
    // y = 10 - 0.5 x up to the kink at x = 12, then 4 - 0.1 (x - 12): the
    // kink point lies on both lines, so the splits before and after it both
    // fit exactly (zero residual); the break is x = 12 or 13.
    std::vector<double> x, y;
    for (int k = 0; k < 30; ++k) {
        x.push_back(k);
        y.push_back(k <= 12 ? 10.0 - 0.5 * k : 4.0 - 0.1 * (k - 12));
    }
    const TwoLineFit f = fit_two_lines(x, y, 3.0, 3);
    EXPECT_NEAR(f.slope_inner, -0.5, 1e-9);
    EXPECT_NEAR(f.slope_outer, -0.1, 1e-9);
    EXPECT_GE(f.break_x, 12.0);
    EXPECT_LE(f.break_x, 13.0);

    // Bounded noise ±e (alternating): a least-squares slope over n equally
    // spaced points moves by at most e Σ|x_i − x̄| / Σ(x_i − x̄)² ≈ 3 e / n;
    // the shorter segment has n = 12 (or 13), so 3 e / 12 bounds both.
    const double e = 0.05;
    std::vector<double> noisy = y;
    for (std::size_t k = 0; k < noisy.size(); ++k) noisy[k] += (k % 2 ? e : -e);
    const TwoLineFit g = fit_two_lines(x, noisy, 3.0, 3);
    EXPECT_NEAR(g.slope_inner, -0.5, 3.0 * e / 12.0);
    EXPECT_NEAR(g.slope_outer, -0.1, 3.0 * e / 12.0);
    EXPECT_NEAR(g.break_x, 12.5, 1.5);

    // Too short for two segments of the minimum width: no fit.
    const TwoLineFit none = fit_two_lines(x, y, 15.0, 3);
    EXPECT_TRUE(std::isnan(none.slope_inner) && std::isnan(none.slope_outer) && std::isnan(none.break_x));
    EXPECT_TRUE(std::isnan(fit_two_lines({0.0, 1.0, 2.0, 3.0, 4.0}, {0, 1, 2, 3, 4}, 0.0, 3).break_x));
}

TEST(WedgeProfile, RetrosideWithASteepInnerAndAGentleOuterSlope) {
    // Experiment 3's shape: from the peak a 25° retrowedge over 1.0 m (2 h0),
    // then a 6° slope down to the undeformed surface (about 5 m, 10 h0). As in
    // the triangular wedges, every column's surface point lies exactly on one
    // of the two lines (the kink column's on both), so the split at the kink
    // fits exactly: both slopes within the triangular cases' 0.5° and the
    // break within one column of the kink. The single-line β lies between.
    const double ta = std::tan(rad(15.0)), t1 = std::tan(rad(25.0)), t2 = std::tan(rad(6.0));
    const int peak_sample = 449;  // x ≈ −3.505 m
    const double x_peak = sample_x(peak_sample), height = 1.0, inner = 1.0;
    const double x_kink = x_peak + inner, h_kink = height - t1 * inner;
    const double x_toe_pro = x_peak - height / ta, x_toe_retro = x_kink + h_kink / t2;
    const ParticleStore p = heap_on_layer(x_toe_pro, x_toe_retro, [&](double x) {
        const double retro = x <= x_kink ? height - t1 * (x - x_peak) : h_kink - t2 * (x - x_kink);
        return std::min(ta * (x - x_toe_pro), retro);
    });
    const WedgeMeasures m = measure_wedge(p, params(0.15), 2.0);
    std::printf("    beta %.3f  inner %.3f (ref 25)  outer %.3f (ref 6)  break %.4f (ref %.4f)\n", m.beta_deg,
                m.beta_inner_deg, m.beta_outer_deg, m.retro_break_x, x_kink);
    EXPECT_NEAR(m.beta_inner_deg, 25.0, 0.5);
    EXPECT_NEAR(m.beta_outer_deg, 6.0, 0.5);
    EXPECT_NEAR(m.retro_break_x, x_kink, kColumn);
    EXPECT_GT(m.beta_deg, 6.5);
    EXPECT_LT(m.beta_deg, 24.5);
}

// The robust measures (issue: re-validation): a noisy surface gives its
// slopes within a few standard errors and a standard error that is not
// zero; a plate thickened as a whole is not taken for wedge; a pop-up ahead
// of the toe does not move the toe or α.
namespace {
constexpr double kAlpha = 12.0, kBeta = 35.0, kHeight = 0.6;  // [deg], [deg], [m]
const double kPeakX = sample_x(801);
double wedge_h(double x) {
    const double ta = std::tan(rad(kAlpha)), tb = std::tan(rad(kBeta));
    return std::min(ta * (x - (kPeakX - kHeight / ta)), tb * ((kPeakX + kHeight / tb) - x));
}
}  // namespace

TEST(WedgeProfile, NoisySlopesComeWithTheirStandardErrors) {
    // Each surface disc moved up or down by up to 0.8 r (a fixed pseudo-random sequence).
    const ParticleStore p = heap_on_layer(kPeakX - kHeight / std::tan(rad(kAlpha)) - 0.1, kPeakX + kHeight / std::tan(rad(kBeta)) + 0.1,
                                          [](double x) {
                                              const double h = wedge_h(x);
                                              return h > 0.0 ? h + 0.8 * kR * std::sin(1e3 * x * x) : h;
                                          });
    const WedgeMeasures m = measure_wedge(p, params(0.05), 2.0);
    std::printf("    alpha %.3f ± %.3f (ref %.1f)  beta %.3f ± %.3f (ref %.1f)\n", m.alpha_deg, m.alpha_se_deg, kAlpha,
                m.beta_deg, m.beta_se_deg, kBeta);
    EXPECT_GT(m.alpha_se_deg, 0.0);
    EXPECT_GT(m.beta_se_deg, 0.0);
    EXPECT_LT(std::fabs(m.alpha_deg - kAlpha), 4.0 * m.alpha_se_deg + 0.05);
    EXPECT_LT(std::fabs(m.beta_deg - kBeta), 4.0 * m.beta_se_deg + 0.05);
    EXPECT_LT(m.alpha_se_deg, 0.5);  // a noise of 0.8 r on a 2.8 m flank: a small error
}

TEST(WedgeProfile, APlateThickenedAsAWholeIsNotTakenForWedge) {
    // The incoming plate and the retroside 0.2 h0 above y_mean; the wedge on it.
    const double lift = 0.2 * kH0;
    const ParticleStore p = heap_on_layer(-7.4, 7.4, [&](double x) { return std::max(lift, wedge_h(x)); });
    const WedgeMeasures m = measure_wedge(p, params(0.05), 2.0);
    EXPECT_NEAR(m.level_pro, kYMean + lift, 1e-12);
    EXPECT_NEAR(m.level_retro, kYMean + lift, 1e-12);
    // The toes where the flanks cross the plate's surface + the threshold, within one column.
    const double ta = std::tan(rad(kAlpha)), tb = std::tan(rad(kBeta));
    EXPECT_NEAR(m.toe_pro_x, kPeakX - (kHeight - lift - 0.05) / ta, kColumn);
    EXPECT_NEAR(m.toe_retro_x, kPeakX + (kHeight - lift - 0.05) / tb, kColumn);
    EXPECT_NEAR(m.alpha_deg, kAlpha, 0.5);
    EXPECT_NEAR(m.beta_deg, kBeta, 0.5);
}

TEST(WedgeProfile, APopUpAheadOfTheToeMovesNeitherTheToeNorAlpha) {
    // A pop-up 0.3 m high and 0.4 m wide, 0.5 m ahead of the prowedge toe.
    const double ta = std::tan(rad(kAlpha));
    const double toe = kPeakX - kHeight / ta;
    auto popup = [&](double x) { return std::max(0.0, 0.3 - std::fabs(x - (toe - 0.7)) * 1.5); };
    const ParticleStore clean = heap_on_layer(toe - 1.0, 7.4, [&](double x) { return wedge_h(x); });
    const ParticleStore with = heap_on_layer(toe - 1.0, 7.4, [&](double x) { return std::max(wedge_h(x), popup(x)); });
    const WedgeMeasures a = measure_wedge(clean, params(0.05), 2.0), b = measure_wedge(with, params(0.05), 2.0);
    EXPECT_EQ(a.toe_pro_x, b.toe_pro_x);
    EXPECT_EQ(a.alpha_deg, b.alpha_deg);
    EXPECT_NEAR(b.alpha_deg, kAlpha, 0.5);
}
