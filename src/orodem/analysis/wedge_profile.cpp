#include "orodem/analysis/wedge_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

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
    int peak = -1;
    for (int c = 0; c < n; ++c)
        if (top[static_cast<std::size_t>(c)] != kEmpty &&
            (peak < 0 || top[static_cast<std::size_t>(c)] > top[static_cast<std::size_t>(peak)]))
            peak = c;
    if (peak < 0) return m;
    // The highest point is the surface particle of the peak column.
    const double peak_x = top_x[static_cast<std::size_t>(peak)];
    m.H_over_h0 = std::max(0.0, top[static_cast<std::size_t>(peak)] - pp.y_mean) / pp.h0;
    m.peak_dx_over_h0 = (peak_x - pp.x_s) / pp.h0;

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
    const double level = pp.y_mean + pp.toe_threshold;
    auto above = [&](int c) { return smooth[static_cast<std::size_t>(c)] != kEmpty && smooth[static_cast<std::size_t>(c)] > level; };
    int toe_pro = peak, toe_retro = peak;
    while (toe_pro - 1 >= 0 && above(toe_pro - 1)) --toe_pro;
    while (toe_retro + 1 < n && above(toe_retro + 1)) ++toe_retro;
    m.toe_pro_x = column_centre(pp, toe_pro);
    m.toe_retro_x = column_centre(pp, toe_retro);

    auto surface_points = [&](int a, int b, std::vector<double>& xs, std::vector<double>& ys) {
        for (int c = a; c <= b; ++c)
            if (top[static_cast<std::size_t>(c)] != kEmpty) {
                xs.push_back(top_x[static_cast<std::size_t>(c)]);
                ys.push_back(top[static_cast<std::size_t>(c)]);
            }
    };
    auto taper = [&](int a, int b) {
        std::vector<double> xs, ys;
        surface_points(a, b, xs, ys);
        if (xs.size() < 3) return nan;
        return std::atan(fit_slope(xs, ys)) * 180.0 / std::numbers::pi;
    };
    int alpha_end = peak;
    if (!pp.retro_side)
        while (alpha_end > toe_pro && column_centre(pp, alpha_end) > pp.x_max - pp.backstop_margin) --alpha_end;
    m.alpha_deg = toe_pro < alpha_end ? taper(toe_pro, alpha_end) : nan;
    m.beta_deg = (pp.retro_side && toe_retro > peak) ? -taper(peak, toe_retro) : nan;
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
