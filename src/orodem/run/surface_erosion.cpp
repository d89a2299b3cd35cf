#include "orodem/run/surface_erosion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "orodem/analysis/wedge_profile.hpp"

namespace orodem {

std::string surface_series_header() {
    return "influx_area,eroded_area,stored_area,ledger_error,wedge_area,eroded_discs,erosion_asked";
}

std::string surface_series_line(const SurfaceLedger& l) {
    return fmt::format("{:.9g},{:.9g},{:.9g},{:.6g},{:.6g},{},{:.9g}", l.influx, l.eroded, l.stored, l.error,
                       l.wedge_area, l.removed_discs, l.asked);
}

std::string eroded_header() { return "id,x_over_h0,S,max_burial_depth_over_h0,initial_depth_over_h0"; }

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
    : on_(c.surface.present), law_(surface_law_of(c.surface)),
      interval_(static_cast<std::uint64_t>(std::max<std::int64_t>(1, c.surface.interval_steps))), h0_(c.packing.h0),
      w_(w) {
    if (!on_) return;
    column_ = c.surface.column_width * h0_;
    layer_length_ = c.packing.length / h0_;
    // Parking: a cluster lies within 3 r_max of its centroid (three touching
    // discs in a row at most), so places 6 r_max + 2 skins apart are never
    // contact candidates (a pair is one within the sum of its radii plus
    // the skin); the first row 2 h0 below the base, far from every wall
    // (the bases are y = 0), rows along the whole layer's length.
    const double skin = w.sim.params.skin;
    park_pitch_ = 6.0 * c.packing.r_max + 2.0 * skin;
    park_x0_ = -w.pro_length + 0.5 * park_pitch_;
    park_y0_ = -2.0 * h0_;
    park_per_row_ = std::max<std::uint64_t>(
        1, static_cast<std::uint64_t>(std::floor((w.pro_length + w.retro_length) / park_pitch_)) - 1);
    // Σ π R² in id order (the same sum in a resumed run, whatever the slots).
    const ParticleStore& p = w.sim.particles;
    std::vector<double> r_by_id(p.size(), 0.0);
    for (std::size_t s = 0; s < p.size(); ++s) r_by_id[p.id[s]] = p.radius[s];
    solid_total_ = 0.0;
    for (const double r : r_by_id) solid_total_ += std::numbers::pi * r * r;
}

double SurfaceErosion::area_of(const ParticleStore& p, std::size_t slot) const {
    const double r = p.radius[slot];
    return layer_length_ * (std::numbers::pi * r * r) / solid_total_;
}

void SurfaceErosion::start(const ParticleStore& p, SurfaceState& st) const {
    st = SurfaceState{};
    st.on = on_;
    if (!on_) return;
    const ProfileParams& pp = w_.profile;
    const int ncol = std::max(1, static_cast<int>(std::ceil((pp.x_max - pp.x_min) / column_)));
    st.remainder.assign(static_cast<std::size_t>(ncol), 0.0);
    st.max_burial.assign(p.size(), 0.0);
    for (std::size_t s = 0; s < p.size(); ++s) st.max_burial[p.id[s]] = p.initial_depth[s] / h0_;
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

    st.requested_area += surface_request(law_, h_, column_ / h0_, dS, erode_, deposit_, ws_).eroded;

    // Candidates: lone discs and whole clusters (centroid, summed area),
    // above the incoming surface, by the column of their centroid.
    std::vector<double> cx(n, 0.0), cy(n, 0.0), carea(n, 0.0);
    std::vector<std::uint32_t> ccount(n, 0), cfirst(n, 0);
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.flags[s] & kFlagRemoved) continue;
        const std::size_t k = p.cluster[s] >= 0 ? static_cast<std::size_t>(p.cluster[s]) : n;
        if (k == n) continue;
        if (ccount[k]++ == 0) cfirst[k] = id;
        cx[k] += p.x[s].x;
        cy[k] += p.x[s].y;
        carea[k] += area_of(p, s);
    }
    cands_.clear();
    std::vector<std::size_t> col_of;
    auto consider = [&](std::uint32_t id, double x, double y, double a) {
        const double fc = std::floor((x - pp.x_min) / column_);
        if (fc < 0.0 || fc >= static_cast<double>(ncol) || !(y > pp.y_mean)) return;
        cands_.push_back({id, a, (y - pp.y_mean) / h0_});
        col_of.push_back(static_cast<std::size_t>(fc));
    };
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        if ((p.flags[s] & kFlagRemoved) || p.cluster[s] >= 0) continue;
        consider(id, p.x[s].x, p.x[s].y, area_of(p, s));
    }
    for (std::size_t k = 0; k < n; ++k)
        if (ccount[k] > 0) {
            const double cnt = static_cast<double>(ccount[k]);
            consider(cfirst[k], cx[k] / cnt, cy[k] / cnt, carea[k]);
        }
    // Grouped by column (a stable counting sort).
    column_begin_.assign(ncol + 1, 0);
    for (const std::size_t c : col_of) ++column_begin_[c + 1];
    for (std::size_t c = 0; c < ncol; ++c) column_begin_[c + 1] += column_begin_[c];
    std::vector<WholeCandidate> sorted(cands_.size());
    {
        std::vector<std::size_t> fill(column_begin_.begin(), column_begin_.end() - 1);
        for (std::size_t k = 0; k < cands_.size(); ++k) sorted[fill[col_of[k]]++] = cands_[k];
    }
    take_whole_particles(st.remainder, erode_, column_begin_, sorted, take_);
    if (take_.ids.empty()) return;

    // Removal: each taken particle's discs, parked together.
    std::vector<std::uint32_t> members;
    for (const std::uint64_t taken : take_.ids) {
        const std::size_t s0 = p.slot_of_id[taken];
        members.clear();
        if (p.cluster[s0] < 0) {
            members.push_back(static_cast<std::uint32_t>(taken));
        } else {
            const std::int32_t cl = p.cluster[s0];
            for (std::uint32_t id = static_cast<std::uint32_t>(taken); id < n && members.size() < ccount[static_cast<std::size_t>(cl)]; ++id)
                if (p.cluster[p.slot_of_id[id]] == cl) members.push_back(id);
        }
        Vec2 centre{0.0, 0.0};
        for (const std::uint32_t id : members) centre = centre + p.x[p.slot_of_id[id]];
        centre = centre * (1.0 / static_cast<double>(members.size()));
        const Vec2 place{park_x0_ + static_cast<double>(st.removed % park_per_row_) * park_pitch_,
                         park_y0_ - static_cast<double>(st.removed / park_per_row_) * park_pitch_};
        ++st.removed;
        for (const std::uint32_t id : members) {
            const std::size_t s = p.slot_of_id[id];
            eroded.line(fmt::format("{},{:.6g},{:.6f},{:.6g},{:.6g}", id, (p.x[s].x - w_.profile.x_s) / h0_, S,
                                    st.max_burial[id], p.initial_depth[s] / h0_));
            st.eroded_area += area_of(p, s);
            p.fix(s);
            p.flags[s] = static_cast<std::uint8_t>((p.flags[s] | kFlagRemoved) & ~kFlagAsleep);
            p.x[s] = place + (p.x[s] - centre);
            p.force[s] = {};
            p.torque[s] = 0.0;
            if (id < x_then.size()) x_then[id] = p.x[s];
        }
    }
    sim.request_rebuild();
}

SurfaceLedger SurfaceErosion::ledger(const ParticleStore& p, const SurfaceState& st, double S,
                                     double wedge_area_m2) const {
    SurfaceLedger l;
    double present = 0.0;
    for (std::uint32_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.flags[s] & kFlagRemoved) ++l.removed_discs;
        else present += area_of(p, s);
    }
    l.influx = S;
    l.eroded = st.eroded_area;
    l.asked = st.requested_area;
    l.stored = present - (layer_length_ - S);
    l.error = l.influx - l.eroded - l.stored;
    l.wedge_area = wedge_area_m2 / (h0_ * h0_);
    return l;
}

}  // namespace orodem
