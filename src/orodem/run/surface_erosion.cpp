#include "orodem/run/surface_erosion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "orodem/analysis/wedge_profile.hpp"

namespace orodem {

std::string surface_series_header() {
    return "influx_area,eroded_area,stored_area,ledger_error,wedge_area,eroded_discs,erosion_asked,deposited_area,"
           "deposited_discs,deposit_asked";
}

std::string surface_series_line(const SurfaceLedger& l) {
    return fmt::format("{:.9g},{:.9g},{:.9g},{:.6g},{:.6g},{},{:.9g},{:.9g},{},{:.9g}", l.influx, l.eroded, l.stored,
                       l.error, l.wedge_area, l.removed_discs, l.asked, l.deposited, l.deposited_discs, l.deposit_asked);
}

std::string eroded_header() { return "id,x_over_h0,S,max_burial_depth_over_h0,initial_depth_over_h0,birth_S"; }

SurfaceLaw surface_law_of(const SurfaceConfig& s) {
    SurfaceLaw law;
    switch (s.law) {
        case SurfaceKind::none: law.kind = SurfaceLawKind::none; break;
        case SurfaceKind::elevation: law.kind = SurfaceLawKind::elevation; break;
        case SurfaceKind::slope: law.kind = SurfaceLawKind::slope; break;
        case SurfaceKind::uniform: law.kind = SurfaceLawKind::uniform; break;
        case SurfaceKind::cap: law.kind = SurfaceLawKind::cap; break;
        case SurfaceKind::diffusion: law.kind = SurfaceLawKind::diffusion; break;
    }
    law.k = s.k;
    law.K = s.slope_k;
    law.e_dot = s.rate;
    law.H_c = s.cap_height;
    law.kappa = s.kappa;
    law.ends = s.ends == "fixed" ? DiffusionEnds::fixed : DiffusionEnds::closed;
    law.h_left = s.h_left;
    law.h_right = s.h_right;
    return law;
}

SurfaceErosion::SurfaceErosion(const Config& c, const WedgeSetup& w)
    : on_(c.surface.present), law_(surface_law_of(c.surface)), rule_on_(c.surface.sedimenting()),
      interval_(static_cast<std::uint64_t>(std::max<std::int64_t>(1, c.surface.interval_steps))), h0_(c.packing.h0),
      r_max_(c.packing.r_max), r_min_(c.packing.r_min), w_(w) {
    if (!on_) return;
    column_ = c.surface.column_width * h0_;
    layer_length_ = c.packing.length / h0_;
    park_ = parking_grid(c, w);
    rule_.base_level = c.surface.base_level;
    rule_.at_once = c.surface.sediment_rate == 0.0;
    rule_.rate = c.surface.sediment_rate;
    fill_pro_ = c.surface.sediment == SedimentSide::pro || c.surface.sediment == SedimentSide::both;
    fill_retro_ = c.surface.sediment == SedimentSide::retro || c.surface.sediment == SedimentSide::both;
    if (c.layered()) {
        layer_pro_ = static_cast<std::uint8_t>(c.layers.size() - 1);
        layer_retro_ = static_cast<std::uint8_t>(c.retro_layers.empty() ? 0 : c.retro_layers.size() - 1);
    }
}

void SurfaceErosion::bind(const ParticleStore& p, std::uint64_t reserve_begin) {
    // Σ π R² over the layer's discs in id order (the same sum in a resumed
    // run, whatever the slots); the reserve's particles, in id order.
    const std::size_t n = p.size();
    std::vector<double> r_by_id(n, 0.0);
    for (std::size_t s = 0; s < n; ++s) r_by_id[p.id[s]] = p.radius[s];
    solid_total_ = 0.0;
    for (std::size_t id = 0; id < reserve_begin && id < n; ++id) solid_total_ += std::numbers::pi * r_by_id[id] * r_by_id[id];
    reserve_.clear();
    for (std::uint32_t id = static_cast<std::uint32_t>(reserve_begin); id < n;) {
        const std::int32_t cl = p.cluster[p.slot_of_id[id]];
        Reserve q;
        q.first = id;
        while (id < n && (q.count == 0 || (cl >= 0 && p.cluster[p.slot_of_id[id]] == cl))) {
            q.area += layer_length_ * (std::numbers::pi * r_by_id[id] * r_by_id[id]) / solid_total_;
            ++q.count;
            ++id;
        }
        reserve_.push_back(q);
    }
}

double SurfaceErosion::area_of(const ParticleStore& p, std::size_t slot) const {
    const double r = p.radius[slot];
    return layer_length_ * (std::numbers::pi * r * r) / solid_total_;
}

void SurfaceErosion::start(const ParticleStore& p, SurfaceState& st) {
    st = SurfaceState{};
    st.on = on_;
    if (!on_) return;
    const ProfileParams& pp = w_.profile;
    const int ncol = std::max(1, static_cast<int>(std::ceil((pp.x_max - pp.x_min) / column_)));
    st.remainder.assign(static_cast<std::size_t>(ncol), 0.0);
    st.max_burial.assign(p.size(), 0.0);
    for (std::size_t s = 0; s < p.size(); ++s) st.max_burial[p.id[s]] = p.initial_depth[s] / h0_;
    st.reserve_begin = std::min<std::uint64_t>(w_.reserve_begin, p.size());
    st.birth_S.assign(p.size(), 0.0);
    for (std::size_t id = st.reserve_begin; id < p.size(); ++id) st.birth_S[id] = std::numeric_limits<double>::quiet_NaN();
    st.erosion_S.assign(p.size(), std::numeric_limits<double>::quiet_NaN());
    if (rule_on_) st.sed_remainder.assign(static_cast<std::size_t>(ncol), 0.0);
    bind(p, st.reserve_begin);
}

void SurfaceErosion::resume(const ParticleStore& p, const SurfaceState& st) {
    if (on_) bind(p, st.reserve_begin);
}

void SurfaceErosion::apply(Simulation& sim, SurfaceState& st, double S, std::vector<Vec2>& x_then, LineFile& eroded) {
    ParticleStore& p = sim.particles;
    const std::size_t n = p.size();
    const double dS = std::max(0.0, S - st.last_S);
    st.last_S = S;

    // The profile above the incoming surface [h0], with the erosion's columns.
    ProfileParams pp = w_.profile;
    pp.column = column_;
    const std::vector<double> top = surface_profile(p, pp);
    const std::size_t ncol = top.size();
    h_.assign(ncol, 0.0);
    erode_.assign(ncol, 0.0);
    deposit_.assign(ncol, 0.0);
    if (st.remainder.size() != ncol) st.remainder.assign(ncol, 0.0);
    // Only the wedge, between the toes the measure finds: the incoming plate
    // and the retroside layer lie at the incoming surface, their disc-scale
    // roughness is not relief to erode.
    const WedgeMeasures m = measure_wedge(p, w_.profile, S * h0_);
    const double lo = m.toe_pro_x - 0.5 * w_.profile.column, hi = m.toe_retro_x + 0.5 * w_.profile.column;
    for (std::size_t c = 0; c < ncol; ++c) {
        const double xc = pp.x_min + (static_cast<double>(c) + 0.5) * column_;
        if (std::isfinite(top[c]) && xc >= lo && xc <= hi) h_[c] = (top[c] - pp.y_mean) / h0_;
    }

    // Burial: each present disc's depth below its column's surface now [h0].
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.flags[s] & kFlagRemoved) continue;
        const double fc = std::floor((p.x[s].x - pp.x_min) / column_);
        if (fc < 0.0 || fc >= static_cast<double>(ncol)) continue;
        const double t = top[static_cast<std::size_t>(fc)];
        if (std::isfinite(t)) st.max_burial[id] = std::max(st.max_burial[id], (t - p.x[s].y) / h0_);
    }

    bool moved = false;
    if (law_.kind != SurfaceLawKind::none) {
        st.requested_area += surface_request(law_, h_, column_ / h0_, dS, erode_, deposit_, ws_).eroded;
        erode(sim, st, S, top, x_then, eroded);
        moved = !take_.ids.empty();
    }
    if (rule_on_) {
        const std::uint64_t before = st.deposited;
        deposit(sim, st, S, dS, top, pp.x_s + m.peak_dx_over_h0 * h0_, x_then);
        moved = moved || st.deposited != before;
    }
    if (moved) sim.request_rebuild();
}

void SurfaceErosion::erode(Simulation& sim, SurfaceState& st, double S, const std::vector<double>& top,
                           std::vector<Vec2>& x_then, LineFile& eroded) {
    ParticleStore& p = sim.particles;
    const std::size_t n = p.size();
    const std::size_t ncol = top.size();
    const ProfileParams& pp = w_.profile;
    // Candidates: lone discs and whole clusters (centroid, summed area),
    // above the incoming surface, by the column of their centroid.
    cx_.assign(n, 0.0);
    cy_.assign(n, 0.0);
    carea_.assign(n, 0.0);
    ccount_.assign(n, 0);
    cfirst_.assign(n, 0);
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.flags[s] & kFlagRemoved) continue;
        const std::size_t k = p.cluster[s] >= 0 ? static_cast<std::size_t>(p.cluster[s]) : n;
        if (k == n) continue;
        if (ccount_[k]++ == 0) cfirst_[k] = id;
        cx_[k] += p.x[s].x;
        cy_[k] += p.x[s].y;
        carea_[k] += area_of(p, s);
    }
    cands_.clear();
    col_of_.clear();
    auto consider = [&](std::uint32_t id, double x, double y, double a) {
        const double fc = std::floor((x - pp.x_min) / column_);
        if (fc < 0.0 || fc >= static_cast<double>(ncol) || !(y > pp.y_mean)) return;
        cands_.push_back({id, a, (y - pp.y_mean) / h0_});
        col_of_.push_back(static_cast<std::size_t>(fc));
    };
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        if ((p.flags[s] & kFlagRemoved) || p.cluster[s] >= 0) continue;
        consider(id, p.x[s].x, p.x[s].y, area_of(p, s));
    }
    for (std::size_t k = 0; k < n; ++k)
        if (ccount_[k] > 0) {
            const double cnt = static_cast<double>(ccount_[k]);
            consider(cfirst_[k], cx_[k] / cnt, cy_[k] / cnt, carea_[k]);
        }
    // Grouped by column (a stable counting sort).
    column_begin_.assign(ncol + 1, 0);
    for (const std::size_t c : col_of_) ++column_begin_[c + 1];
    for (std::size_t c = 0; c < ncol; ++c) column_begin_[c + 1] += column_begin_[c];
    sorted_.resize(cands_.size());
    fill_.assign(column_begin_.begin(), column_begin_.end() - 1);
    for (std::size_t k = 0; k < cands_.size(); ++k) sorted_[fill_[col_of_[k]]++] = cands_[k];
    take_whole_particles(st.remainder, erode_, column_begin_, sorted_, take_);

    // Removal: each taken particle's discs, parked together.
    for (const std::uint64_t taken : take_.ids) {
        const std::size_t s0 = p.slot_of_id[taken];
        members_.clear();
        if (p.cluster[s0] < 0) {
            members_.push_back(static_cast<std::uint32_t>(taken));
        } else {
            const std::int32_t cl = p.cluster[s0];
            for (std::uint32_t id = static_cast<std::uint32_t>(taken);
                 id < n && members_.size() < ccount_[static_cast<std::size_t>(cl)]; ++id)
                if (p.cluster[p.slot_of_id[id]] == cl) members_.push_back(id);
        }
        Vec2 centre{0.0, 0.0};
        for (const std::uint32_t id : members_) centre = centre + p.x[p.slot_of_id[id]];
        centre = centre * (1.0 / static_cast<double>(members_.size()));
        const Vec2 place = park_.place(reserve_.size() + st.removed);
        ++st.removed;
        for (const std::uint32_t id : members_) {
            const std::size_t s = p.slot_of_id[id];
            eroded.line(fmt::format("{},{:.6g},{:.6f},{:.6g},{:.6g},{:.6f}", id, (p.x[s].x - pp.x_s) / h0_, S,
                                    st.max_burial[id], p.initial_depth[s] / h0_, st.birth_S[id]));
            st.eroded_area += area_of(p, s);
            st.erosion_S[id] = S;
            p.fix(s);
            p.flags[s] = static_cast<std::uint8_t>((p.flags[s] | kFlagRemoved) & ~kFlagAsleep);
            p.x[s] = place + (p.x[s] - centre);
            p.force[s] = {};
            p.torque[s] = 0.0;
            if (id < x_then.size()) x_then[id] = p.x[s];
        }
    }
}

void SurfaceErosion::deposit(Simulation& sim, SurfaceState& st, double S, double dS, const std::vector<double>& top,
                             double crest_x, std::vector<Vec2>& x_then) {
    ParticleStore& p = sim.particles;
    const std::size_t n = p.size();
    const std::size_t ncol = top.size();
    const ProfileParams& pp = w_.profile;
    const double dx = column_ / h0_;  // [h0]
    // The forelands' columns as the erosion leaves them [h0]; every other
    // column (the other side of the crest, an empty column, one within a
    // particle's reach of an end wall) at the base level: nothing to fill.
    const double reach = 3.0 * r_max_;  // a particle's extent from its centroid [m]
    const double x_lo = sim.walls[kWallProEnd].a.x + reach;
    const double x_hi = sim.walls.size() > kWallRetroEnd ? sim.walls[kWallRetroEnd].a.x - reach : pp.x_max;
    hd_.assign(ncol, rule_.base_level);
    for (std::size_t c = 0; c < ncol; ++c) {
        const double x0 = pp.x_min + static_cast<double>(c) * column_, x1 = x0 + column_;
        const double xc = 0.5 * (x0 + x1);
        const bool side = xc < crest_x ? fill_pro_ : fill_retro_;
        if (side && std::isfinite(top[c]) && x0 >= x_lo && x1 <= x_hi)
            hd_[c] = (top[c] - pp.y_mean) / h0_ - erode_[c] / dx;
    }
    st.deposit_requested += sedimentation_request(rule_, hd_, dx, dS, deposit_);
    if (st.sed_remainder.size() != ncol) st.sed_remainder.assign(ncol, 0.0);
    // At once, the deficit itself is the state: nothing carried over.
    if (rule_.at_once) std::fill(st.sed_remainder.begin(), st.sed_remainder.end(), 0.0);

    // The present discs by column (linked lists by id), for the drop heights.
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    head_.assign(ncol, kNone);
    next_.assign(n, kNone);
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.flags[s] & kFlagRemoved) continue;
        const double fc = std::floor((p.x[s].x - pp.x_min) / column_);
        if (fc < 0.0 || fc >= static_cast<double>(ncol)) continue;
        next_[id] = head_[static_cast<std::size_t>(fc)];
        head_[static_cast<std::size_t>(fc)] = id;
    }
    // One row a pass: from left to right, each particle clear of the one
    // placed before it in this application (x_free), so that it rests on
    // the surface as it was, never on a particle still to land; a column
    // blocked keeps its request for the next application.
    double x_free = -std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < ncol; ++c) {
        double& r = st.sed_remainder[c];
        r += deposit_[c];
        // Whole particles, rounding the running request to the nearest one.
        while (st.deposited < reserve_.size() && r >= 0.5 * reserve_[st.deposited].area) {
            const Reserve& q = reserve_[st.deposited];
            if (!place(p, st, q, c, S, sim.params.m_inertia_min, x_free, x_then)) break;
            r -= q.area;
            ++st.deposited;
        }
    }
}

bool SurfaceErosion::place(ParticleStore& p, SurfaceState& st, const Reserve& q, std::size_t column, double S,
                           double m_inertia_min, double& x_free, std::vector<Vec2>& x_then) {
    const ProfileParams& pp = w_.profile;
    const std::size_t ncol = head_.size();
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    // Across the column by the golden-ratio sequence of the deposit count:
    // successive particles of a column spread over it.
    const double frac = std::fmod(0.5 + 0.6180339887498949 * static_cast<double>(st.deposited), 1.0);
    // The discs' offsets from their centroid (as parked: rigid), and the
    // particle's extent in x about its centroid.
    Vec2 centre{0.0, 0.0};
    for (std::uint32_t k = 0; k < q.count; ++k) centre = centre + p.x[p.slot_of_id[q.first + k]];
    centre = centre * (1.0 / static_cast<double>(q.count));
    offsets_.clear();
    double left = 0.0, right = 0.0;
    for (std::uint32_t k = 0; k < q.count; ++k) {
        const std::size_t s = p.slot_of_id[q.first + k];
        offsets_.push_back(p.x[s] - centre);
        left = std::min(left, offsets_.back().x - p.radius[s]);
        right = std::max(right, offsets_.back().x + p.radius[s]);
    }
    // Clear of the particle placed before it in this pass, within its column.
    const double gap = 0.05 * r_min_;
    const double x0 = pp.x_min + static_cast<double>(column) * column_;
    const double x_lo = std::max(x0, x_free + gap - left), x_hi = x0 + column_;
    if (!(x_lo < x_hi)) return false;
    // The lowest centroid height at x at which no disc comes within `gap` of
    // a present disc or of the base (y = 0): dropped from there, it lands
    // without an overlap.
    const auto span = static_cast<std::size_t>(std::ceil((3.0 * r_max_ + 2.0 * r_max_ + gap) / column_));
    const std::size_t c0 = column > span ? column - span : 0, c1 = std::min(ncol - 1, column + span);
    auto drop_height = [&](double x) {
        double y = 0.0;
        for (std::uint32_t k = 0; k < q.count; ++k) {
            const double rk = p.radius[p.slot_of_id[q.first + k]];
            const Vec2 o = offsets_[k];
            y = std::max(y, rk + gap - o.y);
            for (std::size_t c = c0; c <= c1; ++c)
                for (std::uint32_t j = head_[c]; j != kNone; j = next_[j]) {
                    const std::size_t sj = p.slot_of_id[j];
                    const double d = rk + p.radius[sj] + gap;
                    const double ddx = p.x[sj].x - (x + o.x);
                    if (std::abs(ddx) < d) y = std::max(y, p.x[sj].y + std::sqrt(d * d - ddx * ddx) - o.y);
                }
        }
        return y;
    };
    // Of kPlaceTries places across what is left of the column (offset by
    // frac), the lowest: a particle set in a hollow of the surface, not on a
    // crest from which it would tumble.
    constexpr int kPlaceTries = 8;
    double x = 0.0, y = std::numeric_limits<double>::infinity();
    for (int t = 0; t < kPlaceTries; ++t) {
        const double xt = x_lo + (static_cast<double>(t) + frac) / kPlaceTries * (x_hi - x_lo);
        const double yt = drop_height(xt);
        if (yt < y) x = xt, y = yt;
    }
    x_free = x + right;
    // Placed at (x, y), moving with its side's rigid motion (the belt's
    // left of the S point, rest right of it), in the reverse of a removal.
    const SleepParams& sp = w_.sim.params.sleep;
    const Vec2 at{x, y};
    for (std::uint32_t k = 0; k < q.count; ++k) {
        const std::uint32_t id = q.first + k;
        const std::size_t s = p.slot_of_id[id];
        p.x[s] = at + offsets_[k];
        p.flags[s] = static_cast<std::uint8_t>(p.flags[s] & ~(kFlagFixed | kFlagRemoved | kFlagReserve));
        p.set_free_inertia(s, m_inertia_min);
        p.v[s] = p.x[s].x < sp.x_split ? sp.u_left : sp.u_right;
        p.omega[s] = 0.0;
        p.force[s] = {};
        p.torque[s] = 0.0;
        p.side[s] = p.x[s].x > 0.0 ? 1 : 0;
        if (p.has_materials()) p.layer[s] = p.side[s] ? layer_retro_ : layer_pro_;
        st.birth_S[id] = S;
        st.max_burial[id] = 0.0;
        st.deposited_area += area_of(p, s);
        ++st.deposited_discs;
        if (id < x_then.size()) x_then[id] = p.x[s];
        const double fc = std::floor((p.x[s].x - pp.x_min) / column_);
        if (fc >= 0.0 && fc < static_cast<double>(ncol)) {
            next_[id] = head_[static_cast<std::size_t>(fc)];
            head_[static_cast<std::size_t>(fc)] = id;
        }
    }
    return true;
}

SurfaceLedger SurfaceErosion::ledger(const ParticleStore& p, const SurfaceState& st, double S,
                                     double wedge_area_m2) const {
    SurfaceLedger l;
    double present = 0.0;
    for (std::uint32_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (!(p.flags[s] & kFlagRemoved)) present += area_of(p, s);
        else if (!(p.flags[s] & kFlagReserve)) ++l.removed_discs;
    }
    l.influx = S;
    l.eroded = st.eroded_area;
    l.deposited = st.deposited_area;
    l.asked = st.requested_area;
    l.deposit_asked = st.deposit_requested;
    l.deposited_discs = st.deposited_discs;
    l.stored = present - (layer_length_ - S);
    l.error = l.influx - l.eroded + l.deposited - l.stored;
    l.wedge_area = wedge_area_m2 / (h0_ * h0_);
    return l;
}

}  // namespace orodem
