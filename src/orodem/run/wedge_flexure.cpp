#include "orodem/run/wedge_flexure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "orodem/analysis/base_load.hpp"

namespace orodem {

std::string flexure_series_header() {
    return "moat_depth_over_h0,moat_x_over_h0,forebulge_pro_x_over_h0,forebulge_pro_height_over_h0,"
           "forebulge_retro_x_over_h0,forebulge_retro_height_over_h0,basin_pro_width_over_h0,"
           "basin_retro_width_over_h0,base_load_ratio";
}

std::string flexure_series_line(const FlexureMeasures& m) {
    return fmt::format("{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}", m.moat_depth, m.moat_x,
                       m.forebulge_pro_x, m.forebulge_pro_height, m.forebulge_retro_x, m.forebulge_retro_height,
                       m.basin_pro_width, m.basin_retro_width, m.load_ratio);
}

std::string flexure_profile_header() { return "S,node,x,load,w"; }

WedgeFlexure::WedgeFlexure(const Config& c, const WedgeSetup& w)
    : on_(c.flexure.present), interval_(static_cast<std::uint64_t>(std::max<std::int64_t>(1, c.flexure.interval_steps))),
      h0_(c.packing.h0) {
    if (!on_) return;
    const PlateParams pp = flexure_plate_params(c);
    const double alpha = pp.flexural_parameter();
    FlexureGridSpec g;
    g.x_min = -w.pro_length;
    g.x_max = w.retro_length;
    g.dx = c.flexure.dx * h0_;  // 0: α/40
    g.extension = c.flexure.extension * alpha;
    plate_ = std::make_unique<FlexurePlate>(pp, g);
    x_retro_end_ = w.retro_length;
    pro_length_ = w.pro_length;
    base_walls_ = {kWallProBase, kWallRetro};
    two_way_ = c.flexure.coupling == FlexureCoupling::two_way;
    // The undeformed layer's weight per unit length, in id order (the same
    // sum in a resumed run; removed discs keep their mass column).
    const ParticleStore& p = w.sim.particles;
    double m = 0.0;
    for (std::size_t id = 0; id < p.size(); ++id) m += p.mass[p.slot_of_id[id]];
    q_layer_ = c.numerics.gravity * m / (w.pro_length + w.retro_length);
    w_layer_ = q_layer_ / plate_->foundation_stiffness();
}

void WedgeFlexure::start(FlexureState& st) const {
    st = FlexureState{};
    st.on = on_;
    if (!on_) return;
    st.f.assign(plate_->size(), 0.0);
    st.w.assign(plate_->size(), 0.0);
}

void WedgeFlexure::make_profiles(const FlexureState& st, std::shared_ptr<const BaseProfile>& pro,
                                 std::shared_ptr<const BaseProfile>& retro) const {
    const FlexurePlate& pl = *plate_;
    const auto one = [&](std::size_t first, std::size_t last) {  // nodes [first, last] of one plate
        auto bp = std::make_shared<BaseProfile>();
        bp->x0 = pl.x(first);
        bp->dx = pl.dx();
        bp->inv_dx = 1.0 / pl.dx();
        bp->y.resize(last - first + 1);
        for (std::size_t k = first; k <= last; ++k) bp->y[k - first] = -(st.w[k] - w_layer_);
        return bp;
    };
    const std::size_t n = pl.size();
    if (pl.broken()) {
        pro = one(0, pl.break_node());
        retro = one(pl.break_node() + 1, n - 1);
    } else {
        pro = retro = one(0, n - 1);
    }
}

double WedgeFlexure::base_height(double x) const {
    const BaseProfile* bp = x < 0.0 ? pro_.get() : retro_.get();  // the S point at x = 0 (the break)
    return bp ? bp->height(x) : 0.0;
}

void WedgeFlexure::set_walls(Simulation& sim) const {
    sim.walls[kWallProBase].profile = pro_;
    sim.walls[kWallRetro].profile = retro_;
    // The end walls (vertical, from their foot up) reach 2 h0 below the base.
    for (const std::size_t e : {kWallProEnd, kWallRetroEnd}) {
        Wall& wall = sim.walls[e];
        wall.a.y = std::min(0.0, base_height(wall.a.x)) - 2.0 * h0_;
    }
}

void WedgeFlexure::resume(Simulation& sim, const FlexureState& st) {
    if (!on_ || !two_way_ || st.w.size() != plate_->size()) return;
    make_profiles(st, pro_, retro_);
    // Only the profiles: the end walls' feet are in the checkpoint as the
    // last solve set them (set again here from the trailing wall's x now,
    // they would differ by round-off).
    sim.walls[kWallProBase].profile = pro_;
    sim.walls[kWallRetro].profile = retro_;
}

void WedgeFlexure::measure_ratio(const Simulation& sim) {
    const double loads = base_load_by_id(sim, base_walls_, load_);
    const double weight = present_weight(sim);
    load_ratio_ = weight > 0.0 ? loads / weight : std::nan("");
}

void WedgeFlexure::node_forces(const Simulation& sim, bool weights, std::vector<double>& f) {
    const FlexurePlate& pl = *plate_;
    const std::size_t n = pl.size();
    f.assign(n, 0.0);
    const ParticleStore& p = sim.particles;
    if (weights) {
        const double g = -sim.params.gravity.y;  // [m/s²]
        load_.assign(p.size(), 0.0);
        for (std::size_t id = 0; id < p.size(); ++id) {
            const std::size_t s = p.slot_of_id[id];
            if (!(p.flags[s] & kFlagRemoved)) load_[id] = p.mass[s] * g;
        }
    } else {
        measure_ratio(sim);
    }
    const double x_lo = pl.x(0), x_hi = pl.x(n - 1);
    for (std::size_t id = 0; id < p.size(); ++id) {
        if (load_[id] == 0.0) continue;
        const double x = std::clamp(p.x[p.slot_of_id[id]].x, x_lo, x_hi);
        pl.add_line_load(x, load_[id], f.data());
    }
    // Beyond the model: the undeformed layer, left of the trailing wall and
    // right of the retroside end wall.
    const double x_pro_end = sim.walls[kWallProEnd].a.x;
    pl.add_pressure(x_lo - 1.0, x_pro_end, q_layer_, f.data());
    pl.add_pressure(x_retro_end_, x_hi + 1.0, q_layer_, f.data());
}

void WedgeFlexure::clear_clusters(const ParticleStore& p) {
    std::int32_t clusters = 0;
    for (std::size_t s = 0; s < p.size(); ++s) clusters = std::max(clusters, p.cluster[s] + 1);
    held_cluster_.assign(static_cast<std::size_t>(clusters), 0);
    held_step_.assign(static_cast<std::size_t>(clusters), 0.0);
}

void WedgeFlexure::start(Simulation& sim, FlexureState& st) {
    start(st);
    if (!on_ || !two_way_) return;
    // Two-way: the plate under the layer at rest (each disc's weight at its
    // x), and every disc onto the bent base (the base was flat).
    node_forces(sim, true, st.f);
    plate_->solve_forces(st.f.data(), st.w.data());
    st.solved_step = sim.step_count;
    make_profiles(st, pro_, retro_);
    // A cluster moves whole, by the height under its first disc (id order):
    // one across a broken plate's step at the S point stays whole.
    ParticleStore& p = sim.particles;
    clear_clusters(p);
    for (std::size_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.flags[s] & kFlagRemoved) continue;
        double dy = base_height(p.x[s].x);
        if (p.cluster[s] >= 0) {
            const auto c = static_cast<std::size_t>(p.cluster[s]);
            if (!held_cluster_[c]) {
                held_cluster_[c] = 1;
                held_step_[c] = dy;
            }
            dy = held_step_[c];
        }
        p.x[s].y += dy;
    }
    set_walls(sim);
    sim.request_rebuild();
}

void WedgeFlexure::solve(Simulation& sim, FlexureState& st) {
    const std::uint64_t previous_step = st.solved_step;
    const FlexurePlate& pl = *plate_;
    const std::size_t n = pl.size();
    if (two_way_) {
        // The discs' weights at their x: the measured base forces answer
        // the base's own motion through the contacts' stiffness, a feedback
        // that a solve every N steps does not keep stable (docs/physics.md);
        // they are still measured for base_load_ratio.
        measure_ratio(sim);
        node_forces(sim, true, st.f);
    } else {
        node_forces(sim, false, st.f);  // the load of this step
    }
    st.w.assign(n, 0.0);
    pl.solve_forces(st.f.data(), st.w.data());
    st.solved_step = sim.step_count;
    if (!two_way_) return;

    // The bases follow: the new profiles, the discs that do not move on
    // their own carried with them (id order; serial).
    std::shared_ptr<const BaseProfile> pro, retro;
    make_profiles(st, pro, retro);
    const auto height = [](const BaseProfile* bp, double x) { return bp ? bp->height(x) : 0.0; };
    const double dt_since = static_cast<double>(sim.step_count - std::min(previous_step, sim.step_count)) * sim.params.dt;
    ParticleStore& pp = sim.particles;
    double moved = 0.0;  // the largest change of the base or of a carried disc's height [m]
    // A cluster with a fixed disc hangs on it by its bonds: all of it rides
    // with the base, rigidly, by its first fixed disc's step (carrying the
    // fixed disc alone jerked its partners at every solve, and the largest
    // overlap grew above the flat base's: docs/physics.md; one step for the
    // whole cluster keeps a cluster across a broken plate's step whole).
    const auto step_at = [&](const Vec2 x, const Vec2 v) {  // the base's step under a disc moving at v [m]
        const Vec2 x_then = x - dt_since * v;                 // where it was at the previous solve [m]
        return height(x.x < 0.0 ? pro.get() : retro.get(), x.x) -
               height(x_then.x < 0.0 ? pro_.get() : retro_.get(), x_then.x);
    };
    clear_clusters(pp);
    for (std::size_t id = 0; id < pp.size(); ++id) {
        const std::size_t s = pp.slot_of_id[id];
        if (!(pp.flags[s] & kFlagFixed) || pp.cluster[s] < 0 || (pp.flags[s] & kFlagRemoved)) continue;
        const auto c = static_cast<std::size_t>(pp.cluster[s]);
        if (held_cluster_[c]) continue;
        held_cluster_[c] = 1;
        held_step_[c] = step_at(pp.x[s], pp.v[s]);
    }
    for (std::size_t id = 0; id < pp.size(); ++id) {
        const std::size_t s = pp.slot_of_id[id];
        const bool held = pp.cluster[s] >= 0 && held_cluster_[static_cast<std::size_t>(pp.cluster[s])] != 0;
        if ((pp.inv_mass[s] != 0.0 && !held) || (pp.flags[s] & kFlagRemoved)) continue;
        const double dy = held ? held_step_[static_cast<std::size_t>(pp.cluster[s])] : step_at(pp.x[s], pp.v[s]);
        pp.x[s].y += dy;
        moved = std::max(moved, std::fabs(dy));
    }
    for (std::size_t k = 0; k < n; ++k) {
        const double x = pl.x(k);
        if (x < -pro_length_ - 2.0 * h0_ || x > x_retro_end_ + 2.0 * h0_) continue;  // the bases' reach
        const bool pro_side = pl.broken() ? k <= pl.break_node() : x < 0.0;
        const BaseProfile* now = pro_side ? pro.get() : retro.get();
        const BaseProfile* then = pro_side ? pro_.get() : retro_.get();
        moved = std::max(moved, std::fabs(height(now, x) - height(then, x)));
    }
    pro_ = std::move(pro);
    retro_ = std::move(retro);
    set_walls(sim);
    sim.add_external_displacement(moved);
}

FlexureMeasures WedgeFlexure::measures(const FlexureState& st) const {
    FlexureMeasures m;
    const FlexurePlate& pl = *plate_;
    const std::size_t n = st.w.size();
    const double nan = std::nan("");
    m.load_ratio = load_ratio_;
    if (n == 0) {
        m = FlexureMeasures{nan, nan, nan, nan, nan, nan, nan, nan, load_ratio_};
        return m;
    }
    const auto d = [&](std::size_t k) { return st.w[k] - w_layer_; };  // [m], positive down
    std::size_t kmax = 0;
    for (std::size_t k = 1; k < n; ++k)
        if (d(k) > d(kmax)) kmax = k;
    m.moat_depth = d(kmax) / h0_;
    m.moat_x = pl.x(kmax) / h0_;
    std::size_t kp = 0, kr = kmax;
    for (std::size_t k = 0; k < kmax; ++k)
        if (d(k) < d(kp)) kp = k;
    for (std::size_t k = kmax; k < n; ++k)
        if (d(k) < d(kr)) kr = k;
    m.forebulge_pro_x = kmax > 0 && d(kp) < 0.0 ? pl.x(kp) / h0_ : nan;
    m.forebulge_pro_height = kmax > 0 && d(kp) < 0.0 ? -d(kp) / h0_ : nan;
    m.forebulge_retro_x = d(kr) < 0.0 ? pl.x(kr) / h0_ : nan;
    m.forebulge_retro_height = d(kr) < 0.0 ? -d(kr) / h0_ : nan;
    // The basin: the nodes around the moat with w > w_layer, its ends where
    // w − w_layer crosses 0 (linear between nodes; a plate's end otherwise).
    if (!(d(kmax) > 0.0)) {
        m.basin_pro_width = m.basin_retro_width = 0.0;
        return m;
    }
    std::size_t a = kmax, b = kmax;
    while (a > 0 && d(a - 1) > 0.0) --a;
    while (b + 1 < n && d(b + 1) > 0.0) ++b;
    const auto cross = [&](std::size_t in, std::size_t out) {  // zero of d between an inside and an outside node
        const double xi = pl.x(in), xo = pl.x(out);
        if (xi == xo) return xi;  // the break's two nodes
        return xi + (xo - xi) * d(in) / (d(in) - d(out));
    };
    const double x_a = a > 0 ? cross(a, a - 1) : pl.x(0);
    const double x_b = b + 1 < n ? cross(b, b + 1) : pl.x(n - 1);
    m.basin_pro_width = std::max(0.0, std::min(0.0, x_b) - x_a) / h0_;
    m.basin_retro_width = std::max(0.0, x_b - std::max(0.0, x_a)) / h0_;
    return m;
}

void WedgeFlexure::write_profile(const FlexureState& st, double S, LineFile& out) const {
    const FlexurePlate& pl = *plate_;
    for (std::size_t k = 0; k < st.w.size(); ++k)
        out.line(fmt::format("{:.6f},{},{:.9g},{:.17g},{:.17g}", S, k, pl.x(k), st.f[k], st.w[k]));
}

}  // namespace orodem
