#include "orodem/analysis/faults.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "orodem/analysis/neighbour_grid.hpp"
#include "orodem/core/angles.hpp"

namespace orodem {

namespace {

/// Principal axis of a set of points: centre, unit direction of the larger
/// spread, and the standard deviations along and across it [m].
struct Axis {
    Vec2 centre;
    Vec2 dir{1.0, 0.0};
    double sd_along = 0.0;
    double sd_across = 0.0;
};

/// Weighted by w (the discs' raw γ: the fit follows the ridge of the strain,
/// not the smoothed zone around it); equal weights when w sums to zero.
Axis principal_axis(const std::vector<Vec2>& x, const std::vector<std::uint32_t>& idx, const std::vector<double>& w) {
    Axis a;
    if (idx.empty()) return a;
    double n = 0.0;
    for (std::uint32_t i : idx) n += w[i];
    const bool equal = !(n > 0.0);
    if (equal) n = static_cast<double>(idx.size());
    for (std::uint32_t i : idx) a.centre += (equal ? 1.0 : w[i]) * x[i];
    a.centre = (1.0 / n) * a.centre;
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (std::uint32_t i : idx) {
        const Vec2 d = x[i] - a.centre;
        const double wi = equal ? 1.0 : w[i];
        sxx += wi * d.x * d.x;
        sxy += wi * d.x * d.y;
        syy += wi * d.y * d.y;
    }
    sxx /= n;
    sxy /= n;
    syy /= n;
    // Eigenvalues of the symmetric 2x2 covariance.
    const double mid = 0.5 * (sxx + syy), r = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
    const double l1 = mid + r, l2 = std::max(mid - r, 0.0);
    const double th = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // direction of l1
    a.dir = {std::cos(th), std::sin(th)};
    a.sd_along = std::sqrt(l1);
    a.sd_across = std::sqrt(l2);
    return a;
}

double perpendicular_distance(const Axis& a, Vec2 p) { return std::fabs(cross(a.dir, p - a.centre)); }

bool elongated(const Axis& a, const FaultParams& p) {
    return 4.0 * a.sd_along >= p.min_length && a.sd_along >= p.min_elongation * a.sd_across;
}

/// Splits a zone in two lines when two fit it at more than split_angle_deg
/// (two-line clustering from the halves along its axis); recursion depth <= 2.
void split_lines(const std::vector<Vec2>& x, const std::vector<double>& w, std::vector<std::uint32_t> idx,
                 const FaultParams& p, int depth,
                 std::vector<std::vector<std::uint32_t>>& out) {
    if (depth >= 2 || idx.size() < 2 * p.min_discs + 10) {
        out.push_back(std::move(idx));
        return;
    }
    const Axis whole = principal_axis(x, idx, w);
    std::vector<char> side(idx.size());
    for (std::size_t k = 0; k < idx.size(); ++k) side[k] = dot(x[idx[k]] - whole.centre, whole.dir) > 0.0;
    std::vector<std::uint32_t> part[2];
    Axis fit[2];
    for (int iter = 0; iter < 20; ++iter) {
        part[0].clear();
        part[1].clear();
        for (std::size_t k = 0; k < idx.size(); ++k) part[static_cast<int>(side[k])].push_back(idx[k]);
        if (part[0].size() < 3 || part[1].size() < 3) {
            out.push_back(std::move(idx));
            return;
        }
        fit[0] = principal_axis(x, part[0], w);
        fit[1] = principal_axis(x, part[1], w);
        bool changed = false;
        for (std::size_t k = 0; k < idx.size(); ++k) {
            const char s = perpendicular_distance(fit[1], x[idx[k]]) < perpendicular_distance(fit[0], x[idx[k]]);
            changed = changed || s != side[k];
            side[k] = s;
        }
        if (!changed) break;
    }
    const double angle = std::acos(std::min(1.0, std::fabs(dot(fit[0].dir, fit[1].dir)))) * 180.0 / kPi;
    if (!(angle > p.split_angle_deg && std::min(part[0].size(), part[1].size()) >= p.min_discs &&
          elongated(fit[0], p) && elongated(fit[1], p))) {
        out.push_back(std::move(idx));
        return;
    }
    split_lines(x, w, std::move(part[0]), p, depth + 1, out);
    split_lines(x, w, std::move(part[1]), p, depth + 1, out);
}

/// The mean position of the discs with the n_end lowest (top = false) or
/// highest y, ties by index.
Vec2 end_of(const std::vector<Vec2>& x, std::vector<std::uint32_t> idx, bool top) {
    const std::size_t n_end = std::max<std::size_t>(3, idx.size() / 10);
    std::sort(idx.begin(), idx.end(), [&](std::uint32_t a, std::uint32_t b) {
        return top ? (x[a].y > x[b].y || (x[a].y == x[b].y && a < b)) : (x[a].y < x[b].y || (x[a].y == x[b].y && a < b));
    });
    Vec2 m;
    const std::size_t k = std::min(n_end, idx.size());
    for (std::size_t i = 0; i < k; ++i) m += x[idx[i]];
    return (1.0 / static_cast<double>(k)) * m;
}

/// The point of the zone's line at the height of `end` (the mean of its
/// deepest or highest discs); for a line within 10° of the horizontal,
/// whose height does not fix a point, the line's own end (two standard
/// deviations from its centre) on the side of `end`.
Vec2 on_line(const Axis& a, Vec2 end, bool upper) {
    if (std::fabs(a.dir.y) < std::sin(10.0 * kPi / 180.0)) {
        const Vec2 e1 = a.centre + 2.0 * a.sd_along * a.dir, e2 = a.centre - 2.0 * a.sd_along * a.dir;
        return (e1.y > e2.y) == upper ? e1 : e2;
    }
    return {a.centre.x + (end.y - a.centre.y) * a.dir.x / a.dir.y, end.y};
}

}  // namespace

FaultParams fault_params(double d_mean, double h0) {
    FaultParams p;
    p.smooth_radius = 2.0 * d_mean;
    p.link_radius = 1.5 * d_mean;
    p.min_length = 0.5 * h0;
    return p;
}

FaultScan detect_faults(const std::vector<Vec2>& x, const std::vector<double>& shear, const FaultParams& p) {
    const std::size_t n = std::min(x.size(), shear.size());
    FaultScan scan;
    scan.zone.assign(n, -1);
    std::vector<char> defined(x.size(), 0);
    std::size_t n_def = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (std::isfinite(shear[i]) && std::isfinite(x[i].x) && std::isfinite(x[i].y)) defined[i] = 1, ++n_def;
    if (n_def < p.min_discs) return scan;

    // 1. Smoothing.
    const NeighbourGrid smooth_grid(x, p.smooth_radius, &defined);
    std::vector<double> g(n, std::numeric_limits<double>::quiet_NaN());
    std::vector<std::uint32_t> nb;
    for (std::size_t i = 0; i < n; ++i) {
        if (!defined[i]) continue;
        smooth_grid.within(x[i], i, nb);
        double sum = shear[i];
        for (std::uint32_t j : nb) sum += shear[j];
        g[i] = sum / static_cast<double>(nb.size() + 1);
    }
    // 2. Threshold.
    std::vector<double> vals;
    vals.reserve(n_def);
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        if (defined[i]) vals.push_back(g[i]), sum += g[i];
    std::nth_element(vals.begin(), vals.begin() + static_cast<std::ptrdiff_t>(vals.size() / 2), vals.end());
    const double median = vals[vals.size() / 2];
    scan.threshold = std::max(p.k_median * median, p.k_mean * sum / static_cast<double>(n_def));
    std::vector<char> hot(x.size(), 0);
    for (std::size_t i = 0; i < n; ++i) hot[i] = defined[i] && g[i] > scan.threshold;

    // 3. Zones (connected components, discovered in index order).
    const NeighbourGrid link_grid(x, p.link_radius, &hot);
    std::vector<std::int32_t> comp(n, -1);
    std::vector<std::vector<std::uint32_t>> zones;
    std::vector<std::uint32_t> stack;
    for (std::size_t i = 0; i < n; ++i) {
        if (!hot[i] || comp[i] >= 0) continue;
        const auto c = static_cast<std::int32_t>(zones.size());
        zones.emplace_back();
        comp[i] = c;
        stack.assign(1, static_cast<std::uint32_t>(i));
        while (!stack.empty()) {
            const std::uint32_t j = stack.back();
            stack.pop_back();
            zones.back().push_back(j);
            link_grid.within(x[j], j, nb);
            for (std::uint32_t k : nb)
                if (comp[k] < 0) comp[k] = c, stack.push_back(k);
        }
        std::sort(zones.back().begin(), zones.back().end());
    }

    // 4-5. Lines and faults, fitted with the raw γ as weights.
    std::vector<double> w(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        if (defined[i]) w[i] = std::max(shear[i], 0.0);
    for (auto& z : zones) {
        if (z.size() < p.min_discs) continue;
        std::vector<std::vector<std::uint32_t>> lines;
        split_lines(x, w, std::move(z), p, 0, lines);
        for (auto& idx : lines) {
            std::sort(idx.begin(), idx.end());
            const Axis a = principal_axis(x, idx, w);
            if (idx.size() < p.min_discs || !elongated(a, p)) continue;
            Fault f;
            f.discs = static_cast<std::uint32_t>(idx.size());
            f.length = 4.0 * a.sd_along;
            f.width = 4.0 * a.sd_across;
            f.root = on_line(a, end_of(x, idx, false), false);
            f.tip = on_line(a, end_of(x, idx, true), true);
            f.vergence = f.tip.x < f.root.x ? +1 : -1;
            // Dip at mid-depth: the axis of the middle half of the zone along
            // its own axis (a cut by depth would bias a wide zone toward the
            // horizontal).
            std::vector<double> t;
            for (std::uint32_t i : idx) t.push_back(dot(x[i] - a.centre, a.dir));
            std::vector<double> ts = t;
            std::sort(ts.begin(), ts.end());
            const double t_lo = ts[ts.size() / 4], t_hi = ts[(3 * ts.size()) / 4];
            std::vector<std::uint32_t> mid;
            for (std::size_t k = 0; k < idx.size(); ++k)
                if (t[k] >= t_lo && t[k] <= t_hi) mid.push_back(idx[k]);
            // Only where that half is itself a line (four times longer than
            // wide: a long, listric fault); else the whole zone's line.
            const Axis half = mid.size() >= 5 ? principal_axis(x, mid, w) : a;
            const Axis& am = half.sd_along >= 4.0 * half.sd_across ? half : a;
            f.dip_deg = std::atan2(std::fabs(am.dir.y), std::fabs(am.dir.x)) * 180.0 / kPi;
            double gs = 0.0;
            for (std::uint32_t i : idx) gs += shear[i];
            f.slip = 2.0 * gs / static_cast<double>(idx.size()) * f.width;
            const auto k = static_cast<std::int32_t>(scan.faults.size());
            for (std::uint32_t i : idx) scan.zone[i] = k;
            scan.faults.push_back(f);
        }
    }
    return scan;
}

std::vector<Fault> FaultTracker::update(std::vector<Fault> found, double S, double h0) {
    struct Candidate {
        double cost;
        std::size_t f, k;
    };
    std::vector<Candidate> cand;
    for (std::size_t f = 0; f < found.size(); ++f)
        for (std::size_t k = 0; k < known.size(); ++k) {
            const Fault& a = found[f];
            const Fault& b = known[k];
            const double dr = norm(a.root - b.root) / h0, dtip = norm(a.tip - b.tip) / h0;
            const double ddip = std::fabs(a.dip_deg - b.dip_deg);
            if (a.vergence != b.vergence || dr > 1.0 || dtip > 1.0 || ddip > 25.0) continue;
            cand.push_back({dr + dtip + ddip / 25.0, f, k});
        }
    std::stable_sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
    std::vector<char> f_done(found.size(), 0), k_done(known.size(), 0);
    for (const Candidate& c : cand) {
        if (f_done[c.f] || k_done[c.k]) continue;
        f_done[c.f] = k_done[c.k] = 1;
        found[c.f].id = known[c.k].id;
        found[c.f].first_S = known[c.k].first_S;
    }
    for (Fault& k : known) k.active = false, k.slip = 0.0;
    for (std::size_t f = 0; f < found.size(); ++f) {
        Fault& a = found[f];
        a.active = true;
        a.last_S = S;
        if (!f_done[f]) {
            a.id = next_id++;
            a.first_S = S;
            known.push_back(a);
        } else {
            for (Fault& k : known)
                if (k.id == a.id) k = a;
        }
    }
    std::vector<Fault> all = known;
    std::sort(all.begin(), all.end(), [](const Fault& a, const Fault& b) { return a.id < b.id; });
    return all;
}

int classify_stage(const std::vector<Fault>& faults, double h0) {
    bool any = false, pro_out = false, retro_out = false;
    for (const Fault& f : faults) {
        if (!f.active) continue;
        any = true;
        const bool on_base = f.root.y <= 0.25 * h0;
        if (on_base && f.vergence < 0 && f.root.x > h0) retro_out = true;
        if (on_base && f.vergence > 0 && f.root.x < -h0) pro_out = true;
    }
    if (!any) return 0;
    if (retro_out) return 3;
    if (pro_out) return 2;
    return 1;
}

int stage_reached(int reached, int last, int now) { return std::max(reached, std::min(now, last)); }

FaultCounts count_faults(const std::vector<Fault>& faults) {
    FaultCounts c;
    c.front_x = std::numeric_limits<double>::quiet_NaN();
    for (const Fault& f : faults) {
        if (!f.active) continue;
        if (f.vergence > 0) {
            ++c.pro;
            if (!(f.root.x >= c.front_x)) c.front_x = f.root.x;
        } else {
            ++c.retro;
        }
    }
    return c;
}

}  // namespace orodem
