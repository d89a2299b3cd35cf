#include "orodem/neighbor/pair_builder.hpp"
#include "orodem/core/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace orodem {

Vec2 closest_point(const Wall& w, Vec2 q) {
    const Vec2 d = w.b - w.a;
    const double len2 = norm2(d);
    double t = dot(q - w.a, d) / len2;
    if (!w.infinite) t = std::clamp(t, 0.0, 1.0);
    return w.a + t * d;
}

bool wall_contact_point(const Wall& w, Vec2 q, Vec2& cp) {
    const Vec2 d = w.b - w.a;
    double t = dot(q - w.a, d) / norm2(d);
    if (w.profile) [[unlikely]] {
        if (w.open_ends && (t < 0.0 || t > 1.0)) return false;
        const BaseProfile& bp = *w.profile;
        const std::size_t k = bp.segment(q.x);
        const Vec2 p0{bp.node_x(k), bp.y[k]};
        const Vec2 e{bp.dx, bp.y[k + 1] - bp.y[k]};
        cp = p0 + (dot(q - p0, e) / norm2(e)) * e;  // on the line of the segment under q
        return true;
    }
    if (!w.infinite) {
        if (w.open_ends && (t < 0.0 || t > 1.0)) return false;
        t = std::clamp(t, 0.0, 1.0);
    }
    cp = w.a + t * d;
    return true;
}

Vec2 wall_tangent(const Wall& w, Vec2 q) {
    if (w.profile) [[unlikely]] {
        const BaseProfile& bp = *w.profile;
        const std::size_t k = bp.segment(q.x);
        const Vec2 e{bp.dx, bp.y[k + 1] - bp.y[k]};
        return (1.0 / norm(e)) * e;
    }
    return (1.0 / norm(w.b - w.a)) * (w.b - w.a);
}

namespace {

constexpr int kStencil[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};

template <class T>
void permute_column(std::vector<T>& col, const std::vector<std::uint32_t>& perm,
                    std::vector<unsigned char>& scratch) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t n = col.size();
    scratch.resize(n * sizeof(T));  // grows once, then reused
    T* tmp = reinterpret_cast<T*>(scratch.data());
    for (std::size_t s = 0; s < n; ++s) std::memcpy(&tmp[s], &col[perm[s]], sizeof(T));
    std::memcpy(col.data(), tmp, n * sizeof(T));
}

}  // namespace

Vec2 PairBuilder::old_xi(const std::vector<std::uint32_t>& begin, const std::vector<std::uint64_t>& keys,
                         const std::vector<Vec2>& xis, std::uint32_t owner_a, std::uint32_t owner_b,
                         std::uint64_t key) {
    for (const std::uint32_t o : {owner_a, owner_b})
        for (std::uint32_t q = begin[o]; q < begin[o + 1]; ++q)
            if (keys[q] == key) {
                const Vec2 xi = xis[q];
                // An untouched contact restarts at +0 (a -0 component is not carried).
                return (xi.x != 0.0 || xi.y != 0.0) ? xi : Vec2{};
            }
    return {};
}

void PairBuilder::sort_by_cell(ParticleStore& p, const Settings& s) {
    const std::size_t n = p.size();
    if (s.periodic_x) {
        for (auto& x : p.x) {
            x.x = std::fmod(x.x, s.period_x);
            if (x.x < 0.0) x.x += s.period_x;
            if (x.x >= s.period_x) x.x = 0.0;  // fmod of a tiny negative
        }
    }
    double r_max = 0.0;
    double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
    if (n > 0) {
        xmin = xmax = p.x[0].x;
        ymin = ymax = p.x[0].y;
    }
    for (std::size_t k = 0; k < n; ++k) {
        r_max = std::max(r_max, p.radius[k]);
        xmin = std::min(xmin, p.x[k].x); xmax = std::max(xmax, p.x[k].x);
        ymin = std::min(ymin, p.x[k].y); ymax = std::max(ymax, p.x[k].y);
    }
    if (s.periodic_x) { xmin = 0.0; xmax = s.period_x; }
    r_max_ = r_max;
    double cell = 2.0 * r_max + s.skin;
    // Keep the grid O(N) even if a few discs fly far away.
    const double area = (xmax - xmin + cell) * (ymax - ymin + cell);
    const double max_cells = 4.0 * static_cast<double>(n) + 64.0;
    if (area / (cell * cell) > max_cells) cell = std::sqrt(area / max_cells);
    grid_.cell = cell;
    grid_.x0 = xmin;
    grid_.y0 = ymin;
    if (s.periodic_x) {
        grid_.nx = std::max(1, static_cast<int>(std::floor(s.period_x / cell)));
        grid_.cell = std::max(cell, s.period_x / grid_.nx);  // whole cells per period
    } else {
        grid_.nx = static_cast<int>(std::floor((xmax - xmin) / cell)) + 1;
    }
    grid_.ny = static_cast<int>(std::floor((ymax - ymin) / grid_.cell)) + 1;
    const std::size_t ncell = static_cast<std::size_t>(grid_.nx) * grid_.ny;

    cell_of_.resize(n);
    cell_start_.assign(ncell + 1, 0);
    for (std::size_t k = 0; k < n; ++k) {
        int cx = static_cast<int>((p.x[k].x - grid_.x0) / grid_.cell);
        int cy = static_cast<int>((p.x[k].y - grid_.y0) / grid_.cell);
        cx = std::clamp(cx, 0, grid_.nx - 1);
        cy = std::clamp(cy, 0, grid_.ny - 1);
        cell_of_[k] = static_cast<std::uint32_t>(cx * grid_.ny + cy);  // column-major: slots ordered by x column
        ++cell_start_[cell_of_[k] + 1];
    }
    for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
    // Stable counting sort: the new order depends only on the old order.
    perm_.resize(n);
    count_.assign(ncell, 0);
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t c = cell_of_[k];
        perm_[cell_start_[c] + count_[c]++] = static_cast<std::uint32_t>(k);
    }
    p.for_each_column([&](auto& col) { permute_column(col, perm_, scratch_); });
    if (p.has_materials()) p.for_each_material_column([&](auto& col) { permute_column(col, perm_, scratch_); });
    p.rebuild_slot_map();
    for (std::size_t c = 0; c < ncell; ++c)
        for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) cell_of_[k] = static_cast<std::uint32_t>(c);
}

void PairBuilder::build_pairs(const ParticleStore& p, const BondTopology& bonds,
                              const Settings& s, ContactStore& cs) {
    const std::size_t n = p.size();
    const int nx = grid_.nx, ny = grid_.ny;
    const double W = s.period_x;
    // scan(i, room): writes the pairs owned by i to room(bound), a buffer
    // of at least `bound` entries (the candidates' count), always in the same
    // order, and returns how many it wrote. Every candidate is written and
    // the count advances only for a pair within the cut-off, so the
    // distance test costs no branch (a mispredicted one per two or three
    // candidates, otherwise).
    auto scan = [&](std::size_t i, auto&& room) -> std::uint32_t {
        struct Range { std::uint32_t b, e; int shift; };
        Range r[5];
        int nr = 0;
        const std::uint32_t c = cell_of_[i];
        r[nr++] = {static_cast<std::uint32_t>(i) + 1, cell_start_[c + 1], 0};
        const int cx = static_cast<int>(c / static_cast<std::uint32_t>(ny));
        const int cy = static_cast<int>(c % static_cast<std::uint32_t>(ny));
        for (const auto& st : kStencil) {
            int jx = cx + st[0];
            const int jy = cy + st[1];
            if (jy >= ny) continue;
            int shift = 0;
            if (jx < 0 || jx >= nx) {
                // Any nx >= 1 wraps: with nx = 1 or 2 the same cell pair is
                // visited under different images (shift -1, 0, +1), and only
                // one image can be within the cut-off while W >= 2 (2 r_max +
                // skin). Skipping nx < 3 (as before) lost every pair across
                // the seam when far-flung discs enlarged the cells.
                if (!s.periodic_x) continue;
                shift = jx < 0 ? -1 : 1;
                jx = jx < 0 ? jx + nx : jx - nx;
            }
            const std::uint32_t cj = static_cast<std::uint32_t>(jx * ny + jy);
            r[nr++] = {cell_start_[cj], cell_start_[cj + 1], shift};
        }
        const std::uint32_t id_i = p.id[i];
        const std::uint32_t b0 = bonds.begin.empty() ? 0 : bonds.begin[id_i];
        const std::uint32_t b1 = bonds.begin.empty() ? 0 : bonds.begin[id_i + 1];
        std::size_t bound = b1 - b0;
        for (int q = 0; q < nr; ++q) bound += r[q].e - r[q].b;  // cell_start_ ascends: e >= b
        Candidate* const out = room(bound);
        std::uint32_t k = 0;
        for (std::uint32_t b = b0; b < b1; ++b) {  // the cluster bonds owned by i
            const std::uint32_t j = p.slot_of_id[bonds.partner[b]];
            int shift = 0;
            if (s.periodic_x) shift = static_cast<int>(std::lround((p.x[i].x - p.x[j].x) / W));
            out[k] = {j, static_cast<std::int8_t>(shift), 1};
            k += j > i ? 1 : 0;
        }
        const Vec2 xi = p.x[i];
        const double ri = p.radius[i];
        const std::int32_t cl = p.cluster[i];
        const Vec2* const x = p.x.data();
        const double* const radius = p.radius.data();
        const std::int32_t* const cluster = p.cluster.data();
        const double skin = s.skin;
        for (int q = 0; q < nr; ++q) {
            const int shift = r[q].shift;
            for (std::uint32_t j = r[q].b; j < r[q].e; ++j) {
                const Vec2 d = xi - (x[j] + Vec2{shift * W, 0.0});
                const double cut = ri + radius[j] + skin;
                // Within the cut-off, and not of the same cluster (bonded:
                // not a contact); bitwise, not short-circuit, so no branch.
                const std::uint32_t near = norm2(d) < cut * cut ? 1u : 0u;
                const std::uint32_t other = static_cast<std::uint32_t>(cluster[j] != cl) | static_cast<std::uint32_t>(cl < 0);
                out[k] = {j, static_cast<std::int8_t>(shift), 0};
                k += near & other;
            }
        }
        return k;
    };

    // One scan: each thread fills its own buffer with the pairs of a
    // contiguous range of owners (in owner order), then, once the offsets
    // are known, copies them to their places. The list is the same at any
    // thread count. The old pairs' ξ (swapped out by rebuild()): a pair of
    // the new list was owned, if it existed, by the slot one of its two discs
    // had when the old list was built, so it is found by its key among the
    // few pairs of those two old owners (none at a first build).
    count_.resize(n);
    cs.begin.resize(n + 1);
    const long long nn = static_cast<long long>(n);
    const int nth = nn >= kParallelMin ? omp_get_max_threads() : 1;
    if (found_.size() < static_cast<std::size_t>(nth)) found_.resize(static_cast<std::size_t>(nth));
    const bool carry = old_begin_.size() == n + 1 && built_slot_of_id_.size() == n;
    const std::uint32_t* const old_slot = built_slot_of_id_.data();
#pragma omp parallel num_threads(nth)
    {
        const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
        const std::size_t nt = static_cast<std::size_t>(omp_get_num_threads());
        const std::size_t b = n * t / nt, e = n * (t + 1) / nt;
        std::vector<Candidate>& buf = found_[t];
        std::size_t used = 0;
        for (std::size_t i = b; i < e; ++i) {
            const std::uint32_t k = scan(i, [&](std::size_t bound) {
                if (buf.size() < used + bound) buf.resize(std::max(used + bound, 2 * buf.size()));  // grows once
                return buf.data() + used;
            });
            count_[i] = k;
            used += k;
        }
#pragma omp barrier
#pragma omp single
        {
            cs.begin[0] = 0;
            for (std::size_t i = 0; i < n; ++i) cs.begin[i + 1] = cs.begin[i] + count_[i];
            cs.resize(cs.begin[n]);
        }
        std::size_t q = cs.begin[b];
        const Candidate* f = buf.data();
        for (std::size_t i = b; i < e; ++i) {
            const std::uint32_t id_i = p.id[i];
            for (std::uint32_t m = 0; m < count_[i]; ++m, ++q, ++f) {
                const std::uint32_t id_j = p.id[f->j];
                const std::uint64_t key = pair_key(id_i, id_j);
                cs.i[q] = static_cast<std::uint32_t>(i);
                cs.j[q] = f->j;
                cs.shift[q] = f->shift;
                cs.bonded[q] = f->bonded;
                cs.key[q] = key;
                cs.xi[q] = carry ? old_xi(old_begin_, old_key_, old_xi_, old_slot[id_i], old_slot[id_j], key) : Vec2{};
                cs.f[q] = {};
                cs.c[q] = 0.0;
            }
        }
    }
    // Incoming index by partner slot, ascending pair index within each slot.
    cs.in_begin.assign(n + 1, 0);
    for (std::size_t k = 0; k < cs.size(); ++k) ++cs.in_begin[cs.j[k] + 1];
    for (std::size_t i = 0; i < n; ++i) cs.in_begin[i + 1] += cs.in_begin[i];
    cs.in_pair.resize(cs.size());
    count_.assign(n, 0);
    for (std::size_t k = 0; k < cs.size(); ++k) {
        const std::uint32_t j = cs.j[k];
        cs.in_pair[cs.in_begin[j] + count_[j]++] = static_cast<std::uint32_t>(k);
    }
}

void PairBuilder::build_wall_pairs(const ParticleStore& p, const std::vector<Wall>& walls,
                                   const Settings& s, WallContactStore& w) {
    const std::size_t n = p.size();
    // A disc can be a candidate of a wall only within r_max + skin of it, so
    // only inside the wall's bounding box grown by that much (by 1% more,
    // for the rounding of the closest point); a line's box is unbounded along
    // it, or everywhere if it is not horizontal or vertical. Most discs are
    // outside every box: four comparisons instead of the closest point. A
    // NaN position fails no comparison and takes the full test, as before.
    const double inf = std::numeric_limits<double>::infinity();
    const double grow = 1.01 * (r_max_ + s.skin);
    wall_box_.resize(walls.size());
    for (std::size_t k = 0; k < walls.size(); ++k) {
        const Wall& wk = walls[k];
        Vec2 lo{std::min(wk.a.x, wk.b.x) - grow, std::min(wk.a.y, wk.b.y) - grow};
        Vec2 hi{std::max(wk.a.x, wk.b.x) + grow, std::max(wk.a.y, wk.b.y) + grow};
        if (wk.profile) {  // a base following the plate: its heights' range
            const auto [ylo, yhi] = std::minmax_element(wk.profile->y.begin(), wk.profile->y.end());
            lo.y = *ylo - grow;
            hi.y = *yhi + grow;
        }
        if (wk.infinite) {
            if (wk.a.y != wk.b.y) { lo.y = -inf; hi.y = inf; }  // not horizontal: unbounded in y
            if (wk.a.x != wk.b.x) { lo.x = -inf; hi.x = inf; }  // not vertical: unbounded in x
        }
        wall_box_[k] = {lo, hi};
    }
    auto visit = [&](std::size_t i, auto&& emit) {
        const Vec2 xi = p.x[i];
        for (std::size_t k = 0; k < walls.size(); ++k) {
            const auto& [lo, hi] = wall_box_[k];
            if (xi.x < lo.x || xi.x > hi.x || xi.y < lo.y || xi.y > hi.y) continue;
            Vec2 cp;
            if (!wall_contact_point(walls[k], p.x[i], cp)) {
                // An open end: the disc may still move over the segment before
                // the next rebuild, so keep it as a candidate when within the skin.
                const Wall& wk = walls[k];
                const double len = norm(wk.b - wk.a);
                const double t = dot(p.x[i] - wk.a, wk.b - wk.a) / len;  // [m] along the wall
                if (t < -s.skin || t > len + s.skin) continue;
                cp = closest_point(wk, p.x[i]);
                if (wk.profile) cp.y = wk.profile->height(cp.x);  // the end of a base following the plate
            }
            const Vec2 d = p.x[i] - cp;
            const double cut = p.radius[i] + s.skin;
            if (norm2(d) < cut * cut) emit(k);
        }
    };
    count_.assign(n, 0);
    const long long nn = static_cast<long long>(n);
#pragma omp parallel for schedule(static) if(nn >= kParallelMin)
    for (long long i = 0; i < nn; ++i) {
        std::uint32_t k = 0;
        visit(static_cast<std::size_t>(i), [&](std::size_t) { ++k; });
        count_[static_cast<std::size_t>(i)] = k;
    }
    w.begin.resize(n + 1);
    w.begin[0] = 0;
    for (std::size_t i = 0; i < n; ++i) w.begin[i + 1] = w.begin[i] + count_[i];
    w.resize(w.begin[n]);
    // As for the pairs: a disc's old wall contacts, at its slot of the old list.
    const bool carry = old_wall_begin_.size() == n + 1 && built_slot_of_id_.size() == n;
    const std::uint32_t* const old_slot = built_slot_of_id_.data();
#pragma omp parallel for schedule(static) if(nn >= kParallelMin)
    for (long long ii = 0; ii < nn; ++ii) {
        const std::size_t i = static_cast<std::size_t>(ii);
        std::uint32_t k = w.begin[i];
        visit(i, [&](std::size_t wall) {
            const std::uint64_t key = wall_key(p.id[i], wall);
            w.wall[k] = static_cast<std::uint16_t>(wall);
            w.key[k] = key;
            const std::uint32_t o = carry ? old_slot[p.id[i]] : 0;
            w.xi[k] = carry ? old_xi(old_wall_begin_, old_wall_key_, old_wall_xi_, o, o, key) : Vec2{};
            w.f[k] = {};
            w.c[k] = 0.0;
            ++k;
        });
    }
}

void PairBuilder::rebuild(ParticleStore& p, const BondTopology& bonds,
                          const std::vector<Wall>& walls, const Settings& s, ContactStore& cs,
                          WallContactStore& ws) {
    ++rebuilds_;
    // (1) Keep the old lists' offsets, keys and ξ (swapped, not copied: the
    // buffers alternate between the stores and the builder, no allocation
    // once grown); the new lists take each pair's ξ from them in (4) and (5).
    std::swap(old_begin_, cs.begin);
    std::swap(old_key_, cs.key);
    std::swap(old_xi_, cs.xi);
    std::swap(old_wall_begin_, ws.begin);
    std::swap(old_wall_key_, ws.key);
    std::swap(old_wall_xi_, ws.xi);
    sort_by_cell(p, s);
    build_pairs(p, bonds, s, cs);
    build_wall_pairs(p, walls, s, ws);
    built_slot_of_id_ = p.slot_of_id;  // the order these lists were built in (no allocation once sized)
    x_ref_ = p.x;
}

}  // namespace orodem
