#include "orodem/analysis/wedge_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "orodem/analysis/calibration_measures.hpp"  // fit_line

namespace orodem {

namespace {
constexpr double kEmpty = -std::numeric_limits<double>::infinity();

int column_count(const ProfileParams& pp) {
    return std::max(1, static_cast<int>(std::ceil((pp.x_max - pp.x_min) / pp.column)));
}
double column_centre(const ProfileParams& pp, int c) { return pp.x_min + (c + 0.5) * pp.column; }
}  // namespace

namespace {
/// Surface heights and the x of each column's surface particle.
std::vector<double> surface_with_x(const ParticleStore& p, const ProfileParams& pp, std::vector<double>& top_x) {
    const int n = column_count(pp);
    std::vector<double> top(static_cast<std::size_t>(n), kEmpty);
    top_x.assign(static_cast<std::size_t>(n), 0.0);
    for (std::size_t s = 0; s < p.size(); ++s) {
        if (p.flags[s] & kFlagRemoved) continue;  // eroded (run/surface_erosion.hpp)
        const double fc = std::floor((p.x[s].x - pp.x_min) / pp.column);
        if (fc < 0.0 || fc >= n) continue;
        const auto c = static_cast<std::size_t>(fc);
        // Ties (equal heights) go to the smaller x, whatever the slot order.
        if (p.x[s].y > top[c] || (p.x[s].y == top[c] && p.x[s].x < top_x[c])) {
            top[c] = p.x[s].y;
            top_x[c] = p.x[s].x;
        }
    }
    return top;
}
}  // namespace

std::vector<double> surface_profile(const ParticleStore& p, const ProfileParams& pp) {
    std::vector<double> top_x;
    return surface_with_x(p, pp, top_x);
}

double mean_surface(const ParticleStore& p, double x0, double x1, double column) {
    ProfileParams pp;
    pp.x_min = x0;
    pp.x_max = x1;
    pp.column = column;
    double sum = 0.0;
    int count = 0;
    for (double t : surface_profile(p, pp))
        if (t != kEmpty) { sum += t; ++count; }
    return count ? sum / count : 0.0;
}

double fit_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    if (n < 2) return std::numeric_limits<double>::quiet_NaN();
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < n; ++k) { mx += x[k]; my += y[k]; }
    mx /= static_cast<double>(n);
    my /= static_cast<double>(n);
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < n; ++k) {
        sxy += (x[k] - mx) * (y[k] - my);
        sxx += (x[k] - mx) * (x[k] - mx);
    }
    return sxx > 0 ? sxy / sxx : std::numeric_limits<double>::quiet_NaN();
}

namespace {
/// Running sums of one segment's points (x taken from an origin x0 so that
/// the centred sums keep their digits).
struct LineSums {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    void add(double x, double y) {
        n += 1; sx += x; sy += y; sxx += x * x; sxy += x * y; syy += y * y;
    }
    LineSums minus(const LineSums& o) const {
        return {n - o.n, sx - o.sx, sy - o.sy, sxx - o.sxx, sxy - o.sxy, syy - o.syy};
    }
    double cxx() const { return sxx - sx * sx / n; }
    double cxy() const { return sxy - sx * sy / n; }
    double slope() const { return cxy() / cxx(); }
    /// Sum of squared residuals about the least-squares line.
    double sse() const { return std::max(0.0, (syy - sy * sy / n) - cxy() * cxy() / cxx()); }
};
}  // namespace

TwoLineFit fit_two_lines(const std::vector<double>& x, const std::vector<double>& y, double min_width,
                         std::size_t min_points) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    TwoLineFit best{nan, nan, nan};
    const std::size_t n = x.size();
    min_points = std::max<std::size_t>(min_points, 2);
    if (n < 2 * min_points) return best;
    const double x0 = x.front();
    std::vector<LineSums> prefix(n + 1);  // prefix[k]: points [0, k)
    for (std::size_t k = 0; k < n; ++k) {
        prefix[k + 1] = prefix[k];
        prefix[k + 1].add(x[k] - x0, y[k]);
    }
    double best_sse = std::numeric_limits<double>::infinity();
    for (std::size_t k = min_points; k + min_points <= n; ++k) {
        if (x[k - 1] - x.front() < min_width || x.back() - x[k] < min_width) continue;
        const LineSums inner = prefix[k], outer = prefix[n].minus(prefix[k]);
        if (!(inner.cxx() > 0.0) || !(outer.cxx() > 0.0)) continue;
        const double sse = inner.sse() + outer.sse();
        if (sse < best_sse) {
            best_sse = sse;
            best = {inner.slope(), outer.slope(), x[k]};
        }
    }
    return best;
}

WedgeMeasures measure_wedge(const ParticleStore& p, const ProfileParams& pp, double shortening) {
    WedgeMeasures m;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> top_x;
    const std::vector<double> top = surface_with_x(p, pp, top_x);
    const int n = static_cast<int>(top.size());
    int highest = -1;
    for (int c = 0; c < n; ++c)
        if (top[static_cast<std::size_t>(c)] != kEmpty &&
            (highest < 0 || top[static_cast<std::size_t>(c)] > top[static_cast<std::size_t>(highest)]))
            highest = c;
    if (highest < 0) return m;
    // H: the highest surface particle.
    m.H_over_h0 = std::max(0.0, top[static_cast<std::size_t>(highest)] - pp.y_mean) / pp.h0;

    // Smoothed surface (three-column mean of the non-empty columns).
    std::vector<double> smooth(static_cast<std::size_t>(n), kEmpty);
    for (int c = 0; c < n; ++c) {
        double s = 0;
        int k = 0;
        for (int d = -1; d <= 1; ++d) {
            const int cc = c + d;
            if (cc >= 0 && cc < n && top[static_cast<std::size_t>(cc)] != kEmpty) {
                s += top[static_cast<std::size_t>(cc)];
                ++k;
            }
        }
        if (k) smooth[static_cast<std::size_t>(c)] = s / k;
    }
    // The peak: the highest column. (Its smoothed surface's highest column
    // was tried: on six intermediate exp1 runs it moved the split between the
    // flanks across flat tops and doubled β's largest change between
    // outputs, 3.2° to 6.2°; docs/physics.md "Wedge measures".)
    const int peak = highest;
    m.peak_dx_over_h0 = (top_x[static_cast<std::size_t>(peak)] - pp.x_s) / pp.h0;

    // The plate's surface on each side: the most common height of the
    // smoothed surface between the domain's end and the peak (bins of
    // toe_threshold / 2; the median of the modal bin and its neighbours). The
    // incoming plate is the largest flat stretch; a flank spreads over all
    // heights. Unlike y_mean it follows a plate thickened or thinned as a
    // whole, and the long low tail of a gentle flank does not lift it.
    auto plate_level = [&](int from, int to) {
        std::vector<double> hs;
        for (int c = std::min(from, to); c <= std::max(from, to); ++c)
            if (smooth[static_cast<std::size_t>(c)] != kEmpty) hs.push_back(smooth[static_cast<std::size_t>(c)]);
        const double window = std::max(0.5 * pp.toe_threshold, 1e-9 * pp.h0);
        if (hs.size() < 3) return pp.y_mean;
        std::sort(hs.begin(), hs.end());
        std::size_t best_count = 0;
        double best_lo = hs.front();
        for (std::size_t i = 0, j = 0; i < hs.size(); ++i) {  // window [hs[i], hs[i] + window)
            while (j < hs.size() && hs[j] < hs[i] + window) ++j;
            if (j - i > best_count) best_count = j - i, best_lo = hs[i];
        }
        std::vector<double> modal;
        for (double h : hs)
            if (h >= best_lo && h < best_lo + window) modal.push_back(h);
        return modal[modal.size() / 2];
    };
    m.level_pro = plate_level(0, peak);
    m.level_retro = plate_level(peak, n - 1);
    // Toes: walking out from the peak while the smoothed surface stays above
    // the plate's surface + toe_threshold.
    auto walk = [&](double level, int dir) {
        int c = peak;
        auto above = [&](int k) { return smooth[static_cast<std::size_t>(k)] != kEmpty && smooth[static_cast<std::size_t>(k)] > level; };
        while (c + dir >= 0 && c + dir < n && above(c + dir)) c += dir;
        return c;
    };
    const int toe_pro = walk(m.level_pro + pp.toe_threshold, -1), toe_retro = walk(m.level_retro + pp.toe_threshold, +1);
    m.toe_pro_x = column_centre(pp, toe_pro);
    m.toe_retro_x = column_centre(pp, toe_retro);

    auto surface_points = [&](int a, int b, std::vector<double>& xs, std::vector<double>& ys) {
        for (int c = a; c <= b; ++c)
            if (top[static_cast<std::size_t>(c)] != kEmpty) {
                xs.push_back(top_x[static_cast<std::size_t>(c)]);
                ys.push_back(top[static_cast<std::size_t>(c)]);
            }
    };
    // A flank's taper: the line through its surface points between 20% and
    // 80% of its relief above the plate ahead of its toe (the rounded top
    // and the toe, where pop-ups and slumps sit, left out), or through all
    // of them when fewer than three lie there; with the slope's standard
    // error, in degrees.
    const double top_y = top[static_cast<std::size_t>(peak)];
    auto taper = [&](int a, int b, double level, double* se_deg) {
        std::vector<double> xs, ys, fx, fy;
        surface_points(a, b, xs, ys);
        *se_deg = nan;
        if (xs.size() < 3) return nan;
        const double lo = level + 0.2 * (top_y - level), hi = level + 0.8 * (top_y - level);
        for (std::size_t k = 0; k < xs.size(); ++k)
            if (ys[k] >= lo && ys[k] <= hi) fx.push_back(xs[k]), fy.push_back(ys[k]);
        const LineFit f = fx.size() >= 3 ? fit_line(fx, fy) : fit_line(xs, ys);
        *se_deg = f.slope_se / (1.0 + f.slope * f.slope) * 180.0 / std::numbers::pi;
        return std::atan(f.slope) * 180.0 / std::numbers::pi;
    };
    int alpha_end = peak;
    if (!pp.retro_side)
        while (alpha_end > toe_pro && column_centre(pp, alpha_end) > pp.x_max - pp.backstop_margin) --alpha_end;
    m.alpha_deg = m.alpha_se_deg = m.beta_se_deg = nan;
    if (toe_pro < alpha_end) m.alpha_deg = taper(toe_pro, alpha_end, m.level_pro, &m.alpha_se_deg);
    m.beta_deg = (pp.retro_side && toe_retro > peak) ? -taper(peak, toe_retro, m.level_retro, &m.beta_se_deg) : nan;
    if (std::isnan(m.beta_deg)) m.beta_deg = nan;  // never "-nan" in series.csv
    m.beta_inner_deg = m.beta_outer_deg = m.retro_break_x = nan;
    if (pp.retro_side && toe_retro > peak) {
        // The surface points ascend in x (each lies inside its own column),
        // as fit_two_lines needs.
        std::vector<double> xs, ys;
        surface_points(peak, toe_retro, xs, ys);
        const TwoLineFit f = fit_two_lines(xs, ys, pp.h0, 3);
        if (!std::isnan(f.break_x)) {
            m.beta_inner_deg = -std::atan(f.slope_inner) * 180.0 / std::numbers::pi;
            m.beta_outer_deg = -std::atan(f.slope_outer) * 180.0 / std::numbers::pi;
            m.retro_break_x = f.break_x;
        }
    }

    double area = 0.0;
    for (int c = toe_pro; c <= toe_retro; ++c)
        if (top[static_cast<std::size_t>(c)] != kEmpty) area += pp.column * (top[static_cast<std::size_t>(c)] - pp.y_mean);
    m.wedge_area = area;
    m.dilation_pct = shortening > 0.0 ? 100.0 * area / (shortening * pp.h0) : nan;
    return m;
}

bool plate_at_trailing_wall(const WedgeMeasures& m, double wall_x, double h0, double shortening) {
    return shortening > 0.0 && m.toe_pro_x - wall_x < h0;
}

}  // namespace orodem
