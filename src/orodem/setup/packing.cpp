#include "orodem/setup/packing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "orodem/core/angles.hpp"
#include "orodem/core/error.hpp"

namespace orodem {

namespace {

struct ClusterShape {
    std::array<Vec2, 3> c;   // disc centres relative to the centre of mass [m]
    std::array<double, 3> r; // radii [m]
    double bound;            // radius of the enclosing circle about the centre of mass [m]
};

/// Three touching discs in a triangle: 0 at the origin, 1 on +x, 2 above.
ClusterShape make_cluster(Rng& rng, double r_min, double r_max) {
    ClusterShape s;
    for (double& r : s.r) r = rng.uniform(r_min, r_max);
    const double d01 = s.r[0] + s.r[1], d02 = s.r[0] + s.r[2], d12 = s.r[1] + s.r[2];
    const double x2 = (d02 * d02 - d12 * d12 + d01 * d01) / (2.0 * d01);
    const double y2 = std::sqrt(std::max(0.0, d02 * d02 - x2 * x2));
    std::array<Vec2, 3> p = {Vec2{0.0, 0.0}, Vec2{d01, 0.0}, Vec2{x2, y2}};
    // Centre of mass (area-weighted) at the origin, then a random rotation.
    double m = 0.0;
    Vec2 com{};
    for (int k = 0; k < 3; ++k) {
        const double mk = s.r[k] * s.r[k];
        com += mk * p[k];
        m += mk;
    }
    com = (1.0 / m) * com;
    const double a = rng.uniform(0.0, 2.0 * std::numbers::pi);
    const double ca = std::cos(a), sa = std::sin(a);
    s.bound = 0.0;
    for (int k = 0; k < 3; ++k) {
        const Vec2 q = p[k] - com;
        s.c[k] = {ca * q.x - sa * q.y, sa * q.x + ca * q.y};
        s.bound = std::max(s.bound, norm(q) + s.r[k]);
    }
    return s;
}

}  // namespace

ParticleStore generate_packing(const PackingConfig& pc, double density) {
    Rng rng(pc.seed);
    ParticleStore p;
    const double L = pc.length;
    const double target_area = 0.9 * L * (pc.h0 + 3.0 * pc.r_max);  // disc area to generate [m²]
    double area = 0.0;

    if (pc.kind == PackingKind::hexagonal) {
        const double R = pc.r_max;
        const double dy = std::sqrt(3.0) * R;
        const int per_row = static_cast<int>(std::floor(L / (2.0 * R)));
        for (int row = 0; area < target_area; ++row) {
            const double off = (row % 2) ? R : 0.0;
            const int n_row = per_row - ((row % 2) ? 1 : 0);
            for (int k = 0; k < n_row; ++k) {
                p.add({R + off + 2.0 * R * k, R + dy * row}, R, density);
                area += std::numbers::pi * R * R;
            }
        }
    } else if (pc.kind == PackingKind::discs) {
        const double spacing = 2.0 * pc.r_max * 1.05;
        const int ncol = std::max(1, static_cast<int>(std::floor(L / spacing)));
        const double jitter = 0.5 * (spacing - 2.0 * pc.r_max);
        for (int row = 0; area < target_area; ++row)
            for (int col = 0; col < ncol && area < target_area; ++col) {
                const double r = rng.uniform(pc.r_min, pc.r_max);
                const Vec2 c{spacing * (col + 0.5) + rng.uniform(-jitter, jitter),
                             spacing * (row + 0.5) + rng.uniform(-jitter, jitter)};
                p.add(c, r, density);
                area += std::numbers::pi * r * r;
            }
    } else {  // clusters
        std::vector<ClusterShape> shapes;
        double bound = 0.0;
        while (area < target_area) {
            shapes.push_back(make_cluster(rng, pc.r_min, pc.r_max));
            bound = std::max(bound, shapes.back().bound);
            for (double r : shapes.back().r) area += std::numbers::pi * r * r;
        }
        const double spacing = 2.0 * bound * 1.02;
        const int ncol = std::max(1, static_cast<int>(std::floor(L / spacing)));
        for (std::size_t k = 0; k < shapes.size(); ++k) {
            const int row = static_cast<int>(k / static_cast<std::size_t>(ncol));
            const int col = static_cast<int>(k % static_cast<std::size_t>(ncol));
            const Vec2 com{spacing * (col + 0.5), spacing * (row + 0.5)};
            for (int d = 0; d < 3; ++d)
                p.add(com + shapes[k].c[d], shapes[k].r[d], density, static_cast<std::int32_t>(k));
        }
    }
    return p;
}

SettleProgress settle(Simulation& sim, const PackingConfig& pc, double report_interval,
                      const std::function<void(const SettleProgress&)>& report) {
    const ParticleStore& p = sim.particles;
    double m_total = 0.0, y_top = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        m_total += p.mass[i];
        y_top = std::max(y_top, p.x[i].y);
    }
    const double g = norm(sim.params.gravity);
    const double e_ref = m_total * g * pc.h0;  // reference energy M g h0 [J]
    const double t_fall = g > 0.0 ? std::sqrt(2.0 * y_top / g) : 0.0;  // free fall from the top [s]
    const std::uint64_t chunk = std::max<std::uint64_t>(
        1, static_cast<std::uint64_t>(std::floor(report_interval / sim.params.dt)));
    SettleProgress s{};
    for (;;) {
        sim.advance(chunk);
        s.step = sim.step_count;
        s.time = sim.time;
        s.kinetic_energy = sim.kinetic_energy();
        s.ke_ratio = e_ref > 0.0 ? s.kinetic_energy / e_ref : 0.0;
        s.contacts = sim.touching_contacts();
        if (!std::isfinite(s.kinetic_energy))
            throw InstabilityError(fmt::format(
                "settling went unstable at step {} (kinetic energy {}); reduce numerics.safety or material.k_n",
                s.step, s.kinetic_energy));
        if (report) report(s);
        if (s.time > t_fall && s.ke_ratio < pc.settle_ke_ratio) return s;
        if (static_cast<std::int64_t>(s.step) >= pc.settle_max_steps)
            throw InstabilityError(fmt::format(
                "packing did not settle within packing.settle_max_steps = {} steps (E_kin/(M g h0) = {:.3g}, "
                "wanted < {:.3g}); raise packing.settle_max_steps or packing.settle_ke_ratio",
                pc.settle_max_steps, s.ke_ratio, pc.settle_ke_ratio));
    }
}

namespace {

/// Keeps the discs (whole clusters, by centre of mass) whose centre lies
/// below top(x) and compacts the store.
template <class Top>
void packing_keep_below(ParticleStore& p, const Top& top) {
    const std::size_t n = p.size();
    // Centre of mass of every cluster (area-weighted), by cluster id.
    std::int32_t max_cluster = -1;
    for (std::size_t s = 0; s < n; ++s) max_cluster = std::max(max_cluster, p.cluster[s]);
    std::vector<double> cx(static_cast<std::size_t>(max_cluster + 1), 0.0), cy(cx.size(), 0.0), cm(cx.size(), 0.0);
    for (std::size_t s = 0; s < n; ++s)
        if (p.cluster[s] >= 0) {
            cx[static_cast<std::size_t>(p.cluster[s])] += p.mass[s] * p.x[s].x;
            cy[static_cast<std::size_t>(p.cluster[s])] += p.mass[s] * p.x[s].y;
            cm[static_cast<std::size_t>(p.cluster[s])] += p.mass[s];
        }
    std::vector<std::uint8_t> keep(n, 0);
    for (std::size_t s = 0; s < n; ++s) {
        const auto k = static_cast<std::size_t>(p.cluster[s]);
        const double x = p.cluster[s] >= 0 ? cx[k] / cm[k] : p.x[s].x;
        const double y = p.cluster[s] >= 0 ? cy[k] / cm[k] : p.x[s].y;
        keep[s] = y < top(x) ? 1 : 0;
    }
    p.compact(keep);
}

}  // namespace

void cut_layer_to_slope(ParticleStore& p, double h0, double x_wall, double slope_deg) {
    const double tan_slope = std::tan(slope_deg * kPi / 180.0);
    packing_keep_below(p, [&](double x) { return h0 - tan_slope * (x - x_wall); });
}

void cut_layer(ParticleStore& p, double h0) {
    packing_keep_below(p, [h0](double) { return h0; });
    for (std::size_t s = 0; s < p.size(); ++s) {
        p.v[s] = {};
        p.omega[s] = 0.0;
        p.force[s] = {};
        p.torque[s] = 0.0;
        p.initial_depth[s] = h0 - p.x[s].y;
    }
}

double mean_surface_height(const ParticleStore& p, double x0, double x1, double column) {
    const int ncol = std::max(1, static_cast<int>(std::floor((x1 - x0) / column)));
    std::vector<double> top(static_cast<std::size_t>(ncol), -1e300);
    for (std::size_t s = 0; s < p.size(); ++s) {
        const int c = static_cast<int>(std::floor((p.x[s].x - x0) / column));
        if (c < 0 || c >= ncol) continue;
        top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], p.x[s].y + p.radius[s]);
    }
    double sum = 0.0;
    int count = 0;
    for (double t : top)
        if (t > -1e299) { sum += t; ++count; }
    return count ? sum / count : 0.0;
}

}  // namespace orodem
