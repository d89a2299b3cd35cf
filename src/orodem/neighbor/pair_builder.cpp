#include "orodem/neighbor/pair_builder.hpp"
#include "orodem/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
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
    if (!w.infinite) {
        if (w.open_ends && (t < 0.0 || t > 1.0)) return false;
        t = std::clamp(t, 0.0, 1.0);
    }
    cp = w.a + t * d;
    return true;
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

void HistoryTable::reset(std::size_t n) {
    std::size_t size = 16;
    int bits = 4;
    while (size < 2 * n) {
        size <<= 1;
        ++bits;
    }
    keys_.assign(size, kEmpty);  // keeps the capacity: no allocation once grown
    xi_.resize(size);
    mask_ = size - 1;
    shift_ = 64 - bits;
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
    p.rebuild_slot_map();
    for (std::size_t c = 0; c < ncell; ++c)
        for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) cell_of_[k] = static_cast<std::uint32_t>(c);
}

void PairBuilder::build_pairs(const ParticleStore& p, const BondTopology& bonds,
                              const Settings& s, ContactStore& cs) {
    const std::size_t n = p.size();
    const int nx = grid_.nx, ny = grid_.ny;
    const double W = s.period_x;
    // visit(i, emit): calls emit(j, shift, bonded) for every pair owned by i,
    // always in the same order. Used for counting and for filling.
    auto visit = [&](std::size_t i, auto&& emit) {
        const std::uint32_t id_i = p.id[i];
        if (!bonds.begin.empty()) {
            for (std::uint32_t b = bonds.begin[id_i]; b < bonds.begin[id_i + 1]; ++b) {
                const std::uint32_t j = p.slot_of_id[bonds.partner[b]];
                if (j <= i) continue;
                int shift = 0;
                if (s.periodic_x) shift = static_cast<int>(std::lround((p.x[i].x - p.x[j].x) / W));
                emit(j, shift, true);
            }
        }
        const Vec2 xi = p.x[i];
        const double ri = p.radius[i];
        const std::int32_t cl = p.cluster[i];
        auto consider = [&](std::uint32_t j, int shift) {
            if (cl >= 0 && p.cluster[j] == cl) return;  // bonded: not a contact
            const Vec2 d = xi - (p.x[j] + Vec2{shift * W, 0.0});
            const double cut = ri + p.radius[j] + s.skin;
            if (norm2(d) < cut * cut) emit(j, shift, false);
        };
        const std::uint32_t c = cell_of_[i];
        const int cx = static_cast<int>(c / static_cast<std::uint32_t>(ny));
        const int cy = static_cast<int>(c % static_cast<std::uint32_t>(ny));
        for (std::uint32_t j = static_cast<std::uint32_t>(i) + 1; j < cell_start_[c + 1]; ++j) consider(j, 0);
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
            for (std::uint32_t j = cell_start_[cj]; j < cell_start_[cj + 1]; ++j) consider(j, shift);
        }
    };

    count_.assign(n, 0);
    const long long nn = static_cast<long long>(n);
#pragma omp parallel for schedule(static) if(nn >= kParallelMin)
    for (long long i = 0; i < nn; ++i) {
        std::uint32_t k = 0;
        visit(static_cast<std::size_t>(i), [&](std::uint32_t, int, bool) { ++k; });
        count_[static_cast<std::size_t>(i)] = k;
    }
    cs.begin.resize(n + 1);
    cs.begin[0] = 0;
    for (std::size_t i = 0; i < n; ++i) cs.begin[i + 1] = cs.begin[i] + count_[i];
    cs.resize(cs.begin[n]);
#pragma omp parallel for schedule(static) if(nn >= kParallelMin)
    for (long long ii = 0; ii < nn; ++ii) {
        const std::size_t i = static_cast<std::size_t>(ii);
        std::uint32_t k = cs.begin[i];
        visit(i, [&](std::uint32_t j, int shift, bool bonded) {
            cs.i[k] = static_cast<std::uint32_t>(i);
            cs.j[k] = j;
            cs.key[k] = pair_key(p.id[i], p.id[j]);
            cs.shift[k] = static_cast<std::int8_t>(shift);
            cs.bonded[k] = bonded ? 1 : 0;
            cs.f[k] = {};
            cs.c[k] = 0.0;
            ++k;
        });
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
    auto visit = [&](std::size_t i, auto&& emit) {
        for (std::size_t k = 0; k < walls.size(); ++k) {
            Vec2 cp;
            if (!wall_contact_point(walls[k], p.x[i], cp)) {
                // An open end: the disc may still move over the segment before
                // the next rebuild, so keep it as a candidate when within the skin.
                const Wall& wk = walls[k];
                const double len = norm(wk.b - wk.a);
                const double t = dot(p.x[i] - wk.a, wk.b - wk.a) / len;  // [m] along the wall
                if (t < -s.skin || t > len + s.skin) continue;
                cp = closest_point(wk, p.x[i]);
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
#pragma omp parallel for schedule(static) if(nn >= kParallelMin)
    for (long long ii = 0; ii < nn; ++ii) {
        const std::size_t i = static_cast<std::size_t>(ii);
        std::uint32_t k = w.begin[i];
        visit(i, [&](std::size_t wall) {
            w.wall[k] = static_cast<std::uint16_t>(wall);
            w.key[k] = wall_key(p.id[i], wall);
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
    // (1) Save history by key. Wall keys and pair keys go through the table
    // in turn (a pair's key and a wall contact's may coincide).
    auto save = [&](const auto& keys, const auto& xis, std::size_t count) {
        std::size_t touched = 0;
        for (std::size_t k = 0; k < count; ++k) touched += (xis[k].x != 0.0 || xis[k].y != 0.0) ? 1 : 0;
        old_hist_.reset(touched);
        for (std::size_t k = 0; k < count; ++k)
            if (xis[k].x != 0.0 || xis[k].y != 0.0) old_hist_.insert(keys[k], xis[k]);
    };
    auto restore = [&](const auto& keys, auto& xis, std::size_t count) {
        const long long m = static_cast<long long>(count);
#pragma omp parallel for schedule(static) if(m >= kParallelMin)
        for (long long k = 0; k < m; ++k)
            xis[static_cast<std::size_t>(k)] = old_hist_.find(keys[static_cast<std::size_t>(k)]);
    };

    save(cs.key, cs.xi, cs.size());
    sort_by_cell(p, s);
    build_pairs(p, bonds, s, cs);
    restore(cs.key, cs.xi, cs.size());

    save(ws.key, ws.xi, ws.size());
    build_wall_pairs(p, walls, s, ws);
    restore(ws.key, ws.xi, ws.size());

    x_ref_ = p.x;
}

}  // namespace orodem
