#include "orodem/analysis/calibration_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "orodem/core/angles.hpp"

namespace orodem {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void add_outer(Stress2& s, Vec2 f, Vec2 arm) {
    s.xx += f.x * arm.x;
    s.xy += f.x * arm.y;
    s.yx += f.y * arm.x;
    s.yy += f.y * arm.y;
}
}  // namespace

Stress2 love_weber_stress(const Simulation& sim, double area) {
    const ParticleStore& p = sim.particles;
    const ContactStore& cs = sim.contacts;
    Stress2 s;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        add_outer(s, cs.f[k], sim.pair_branch(k));
    }
    const WallContactStore& ws = sim.wall_contacts;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k) {
            if (ws.f[k].x == 0.0 && ws.f[k].y == 0.0) continue;
            Vec2 cp;
            if (!wall_contact_point(sim.walls[ws.wall[k]], p.x[i], cp)) continue;
            add_outer(s, ws.f[k], p.x[i] - cp);
        }
    const double inv = 1.0 / area;
    return {s.xx * inv, s.xy * inv, s.yx * inv, s.yy * inv};
}

Stress2 net_force_moment(const Simulation& sim, double area) {
    const ParticleStore& p = sim.particles;
    Vec2 mean{};
    for (const Vec2& x : p.x) mean += x;
    if (!p.x.empty()) mean = (1.0 / static_cast<double>(p.size())) * mean;
    Stress2 s;
    for (std::size_t i = 0; i < p.size(); ++i) add_outer(s, p.force[i], p.x[i] - mean);
    const double inv = 1.0 / area;
    return {s.xx * inv, s.xy * inv, s.yx * inv, s.yy * inv};
}

double mobilized_friction_deg(double sigma1, double sigma3) {
    const double sum = sigma1 + sigma3;
    if (!(sum > 0.0)) return kNaN;
    return std::asin(std::clamp((sigma1 - sigma3) / sum, -1.0, 1.0)) * kDeg;
}

WindowStats window_stats(const std::vector<double>& x, const std::vector<double>& y, double from, double to) {
    WindowStats w;
    double sum = 0.0;
    const std::size_t n = std::min(x.size(), y.size());
    for (std::size_t k = 0; k < n; ++k)
        if (x[k] >= from && x[k] <= to && std::isfinite(y[k])) {
            sum += y[k];
            ++w.n;
        }
    if (w.n == 0) {
        w.mean = w.sd = kNaN;
        return w;
    }
    w.mean = sum / static_cast<double>(w.n);
    double ss = 0.0;
    for (std::size_t k = 0; k < n; ++k)
        if (x[k] >= from && x[k] <= to && std::isfinite(y[k])) ss += (y[k] - w.mean) * (y[k] - w.mean);
    w.sd = w.n > 1 ? std::sqrt(ss / static_cast<double>(w.n - 1)) : 0.0;
    return w;
}

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
    LineFit f;
    f.n = std::min(x.size(), y.size());
    if (f.n < 2) {
        f.slope = f.intercept = f.slope_se = kNaN;
        return f;
    }
    const double n = static_cast<double>(f.n);
    double mx = 0.0, my = 0.0;
    for (std::size_t k = 0; k < f.n; ++k) mx += x[k], my += y[k];
    mx /= n;
    my /= n;
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t k = 0; k < f.n; ++k) {
        sxx += (x[k] - mx) * (x[k] - mx);
        sxy += (x[k] - mx) * (y[k] - my);
    }
    if (!(sxx > 0.0)) {
        f.slope = f.intercept = f.slope_se = kNaN;
        return f;
    }
    f.slope = sxy / sxx;
    f.intercept = my - f.slope * mx;
    double ssr = 0.0;
    for (std::size_t k = 0; k < f.n; ++k) {
        const double r = y[k] - (f.intercept + f.slope * x[k]);
        ssr += r * r;
    }
    f.slope_se = f.n > 2 ? std::sqrt(ssr / (n - 2.0) / sxx) : 0.0;
    return f;
}

HeapProfile heap_profile(const ParticleStore& p, double base_y, double x0, double x1, double column) {
    HeapProfile h;
    h.base_y = base_y;
    const int ncol = std::max(1, static_cast<int>(std::ceil((x1 - x0) / column)));
    std::vector<double> top(static_cast<std::size_t>(ncol), -std::numeric_limits<double>::infinity());
    for (std::size_t s = 0; s < p.size(); ++s) {
        if (p.flags[s] & kFlagFixed) continue;
        const int c = static_cast<int>(std::floor((p.x[s].x - x0) / column));
        if (c < 0 || c >= ncol) continue;
        top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], p.x[s].y + p.radius[s]);
    }
    double best = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < ncol; ++c) {
        const double t = top[static_cast<std::size_t>(c)];
        if (!std::isfinite(t)) continue;
        const double xc = x0 + (c + 0.5) * column;
        h.x.push_back(xc);
        h.top.push_back(t);
        if (t > best) {
            best = t;
            h.x_peak = xc;
        }
    }
    h.height = std::isfinite(best) ? best - base_y : 0.0;
    return h;
}

ReposeFit fit_repose(const HeapProfile& h, double from, double to) {
    ReposeFit r;
    const double lo = h.base_y + from * h.height, hi = h.base_y + to * h.height;
    std::vector<double> lx, ly, rx, ry;
    for (std::size_t k = 0; k < h.x.size(); ++k) {
        if (h.top[k] < lo || h.top[k] > hi) continue;
        if (h.x[k] < h.x_peak) {
            lx.push_back(h.x[k]);
            ly.push_back(h.top[k]);
        } else if (h.x[k] > h.x_peak) {
            rx.push_back(h.x[k]);
            ry.push_back(h.top[k]);
        }
    }
    r.left = fit_line(lx, ly);
    r.right = fit_line(rx, ry);
    r.angle_left_deg = std::atan(std::fabs(r.left.slope)) * kDeg;
    r.angle_right_deg = std::atan(std::fabs(r.right.slope)) * kDeg;
    r.angle_deg = 0.5 * (r.angle_left_deg + r.angle_right_deg);
    return r;
}

}  // namespace orodem
