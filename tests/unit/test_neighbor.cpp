// Neighbour search against an independent O(N²) reference (SPEC §1 "Contact
// detection", "Contact history must survive neighbour-list rebuilds").
//
// Reference: every id pair (a, b), a < b, with
//   |x_a - x_b|_min-image < R_a + R_b + skin,
// except pairs of one cluster (cluster id >= 0), which are bonds and must be
// listed separately with ContactStore::bonded = 1, whatever their distance.
// Disc-wall candidates: every (id, wall) with distance(x, wall) < R + skin.
// The comparison is exact (sets of keys): both sides evaluate the same
// inequality on the same doubles, and the random sets below contain no pair
// within round-off of the cut-off (their distances are continuous random
// variables; a tie would need |d - cut| ~ 1e-16 m).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "orodem/core/rng.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/neighbor/pair_builder.hpp"

using namespace orodem;

namespace {

struct Layout {
    double W = 30.0;    // box width / period [m]
    double H = 20.0;    // box height [m]
    double skin = 0.2;  // [m]
    bool periodic = false;
};

/// Random polydisperse discs: `n_clusters` touching 3-disc triangles plus
/// `n_lone` lone discs, radii uniform in [0.3, 1.0], overlaps allowed (the
/// search must not care). In periodic mode some clusters straddle x = 0 and
/// some positions start outside [0, W) so that the builder has to wrap them.
ParticleStore random_discs(std::uint64_t seed, const Layout& L, int n_clusters, int n_lone,
                           bool outlier) {
    Rng rng(seed);
    ParticleStore p;
    for (int c = 0; c < n_clusters; ++c) {
        double r[3];
        for (double& rk : r) rk = rng.uniform(0.3, 1.0);
        Vec2 c0{rng.uniform(0.0, L.W), rng.uniform(0.0, L.H)};
        if (L.periodic && c % 4 == 0) c0.x = rng.uniform(-0.5, 0.5);  // straddles the seam
        const double a = rng.uniform(0.0, 2.0 * M_PI);
        const double d01 = r[0] + r[1], d02 = r[0] + r[2], d12 = r[1] + r[2];
        // Angle at disc 0 between 0->1 and 0->2 (law of cosines).
        const double cos0 = (d01 * d01 + d02 * d02 - d12 * d12) / (2.0 * d01 * d02);
        const double b = a + std::acos(cos0);
        p.add(c0, r[0], 1.0, c);
        p.add(c0 + d01 * Vec2{std::cos(a), std::sin(a)}, r[1], 1.0, c);
        p.add(c0 + d02 * Vec2{std::cos(b), std::sin(b)}, r[2], 1.0, c);
    }
    for (int k = 0; k < n_lone; ++k) {
        Vec2 x{rng.uniform(0.0, L.W), rng.uniform(0.0, L.H)};
        if (L.periodic && k % 10 == 0) x.x += (k % 20 == 0 ? 1.0 : -1.0) * L.W;  // needs wrapping
        p.add(x, rng.uniform(0.3, 1.0), 1.0, -1);
    }
    if (outlier) p.add({0.5 * L.W, 1.0e4}, 0.5, 1.0, -1);  // forces the O(N) cell enlargement
    return p;
}

double min_image_dx(double dx, const Layout& L) {
    return L.periodic ? dx - L.W * std::round(dx / L.W) : dx;
}

/// Brute-force candidate keys (unbonded) by id.
std::set<std::uint64_t> brute_pairs(const ParticleStore& p, const Layout& L) {
    std::set<std::uint64_t> out;
    const std::size_t n = p.size();
    for (std::uint32_t a = 0; a < n; ++a)
        for (std::uint32_t b = a + 1; b < n; ++b) {
            const std::size_t sa = p.slot_of_id[a], sb = p.slot_of_id[b];
            if (p.cluster[sa] >= 0 && p.cluster[sa] == p.cluster[sb]) continue;
            const double dx = min_image_dx(p.x[sa].x - p.x[sb].x, L);
            const double dy = p.x[sa].y - p.x[sb].y;
            const double cut = p.radius[sa] + p.radius[sb] + L.skin;
            if (dx * dx + dy * dy < cut * cut) out.insert(pair_key(a, b));
        }
    return out;
}

/// Brute-force bond keys: all intra-cluster id pairs.
std::set<std::uint64_t> brute_bonds(const ParticleStore& p) {
    std::set<std::uint64_t> out;
    const std::size_t n = p.size();
    for (std::uint32_t a = 0; a < n; ++a)
        for (std::uint32_t b = a + 1; b < n; ++b) {
            const std::int32_t ca = p.cluster[p.slot_of_id[a]];
            if (ca >= 0 && ca == p.cluster[p.slot_of_id[b]]) out.insert(pair_key(a, b));
        }
    return out;
}

std::set<std::uint64_t> brute_walls(const ParticleStore& p, const std::vector<Wall>& walls,
                                    const Layout& L) {
    std::set<std::uint64_t> out;
    for (std::uint32_t a = 0; a < p.size(); ++a) {
        const std::size_t s = p.slot_of_id[a];
        for (std::size_t w = 0; w < walls.size(); ++w) {
            // Independent point-segment distance (not closest_point()).
            const Vec2 ab = walls[w].b - walls[w].a, aq = p.x[s] - walls[w].a;
            double t = dot(aq, ab) / dot(ab, ab);
            if (!walls[w].infinite) t = std::min(1.0, std::max(0.0, t));
            const Vec2 d = aq - t * ab;
            const double cut = p.radius[s] + L.skin;
            if (dot(d, d) < cut * cut) out.insert(wall_key(a, w));
        }
    }
    return out;
}

/// Checks the builder's lists against the brute force; returns nothing, records failures.
void check_lists(const ParticleStore& p, const ContactStore& cs, const WallContactStore& ws,
                 const std::vector<Wall>& walls, const Layout& L, const char* stage) {
    SCOPED_TRACE(stage);
    const std::size_t n = p.size();
    // Slot map and CSR structure.
    for (std::size_t s = 0; s < n; ++s) ASSERT_EQ(p.slot_of_id[p.id[s]], s);
    ASSERT_EQ(cs.begin.size(), n + 1);
    ASSERT_EQ(cs.begin[n], cs.size());
    std::set<std::uint64_t> found, found_bonds;
    for (std::size_t s = 0; s < n; ++s)
        for (std::uint32_t k = cs.begin[s]; k < cs.begin[s + 1]; ++k) {
            ASSERT_EQ(cs.i[k], s);
            const std::uint32_t j = cs.j[k];
            ASSERT_LT(j, n);
            EXPECT_EQ(cs.key[k], pair_key(p.id[s], p.id[j]));
            // The stored periodic image must be the minimum image.
            const double dx_img = p.x[s].x - (p.x[j].x + cs.shift[k] * L.W);
            EXPECT_NEAR(dx_img, min_image_dx(p.x[s].x - p.x[j].x, L), 1e-9) << "key " << cs.key[k];
            auto& dst = cs.bonded[k] ? found_bonds : found;
            EXPECT_TRUE(dst.insert(cs.key[k]).second) << "pair listed twice: key " << cs.key[k];
        }
    // Incoming index: every pair exactly once, under its partner slot, ascending.
    ASSERT_EQ(cs.in_begin.size(), n + 1);
    ASSERT_EQ(cs.in_pair.size(), cs.size());
    std::vector<int> seen(cs.size(), 0);
    for (std::size_t s = 0; s < n; ++s)
        for (std::uint32_t q = cs.in_begin[s]; q < cs.in_begin[s + 1]; ++q) {
            const std::uint32_t k = cs.in_pair[q];
            ASSERT_LT(k, cs.size());
            EXPECT_EQ(cs.j[k], s);
            if (q > cs.in_begin[s]) {
                EXPECT_LT(cs.in_pair[q - 1], k);
            }
            ++seen[k];
        }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));

    const auto ref = brute_pairs(p, L);
    const auto ref_bonds = brute_bonds(p);
    EXPECT_EQ(found.size(), ref.size());
    EXPECT_TRUE(found == ref) << "missing " << [&] {
        std::size_t m = 0;
        for (auto k : ref) m += found.count(k) ? 0 : 1;
        return m;
    }() << ", extra " << [&] {
        std::size_t m = 0;
        for (auto k : found) m += ref.count(k) ? 0 : 1;
        return m;
    }();
    EXPECT_TRUE(found_bonds == ref_bonds);

    std::set<std::uint64_t> found_walls;
    ASSERT_EQ(ws.begin.size(), n + 1);
    for (std::size_t s = 0; s < n; ++s)
        for (std::uint32_t k = ws.begin[s]; k < ws.begin[s + 1]; ++k) {
            EXPECT_EQ(ws.key[k], wall_key(p.id[s], ws.wall[k]));
            EXPECT_TRUE(found_walls.insert(ws.key[k]).second);
        }
    EXPECT_TRUE(found_walls == brute_walls(p, walls, L));
}

Wall make_wall(Vec2 a, Vec2 b, bool infinite = false, bool rough = false, double mu = 0.0) {
    Wall w;
    w.a = a;
    w.b = b;
    w.infinite = infinite;
    w.rough = rough;
    w.mu = mu;
    return w;
}

std::vector<Wall> box_walls(const Layout& L) {
    std::vector<Wall> w;
    w.push_back(make_wall({0.0, 0.0}, {L.W, 0.0}, true, true, 0.3));  // floor: infinite line
    if (!L.periodic) {
        w.push_back(make_wall({0.0, 0.0}, {0.0, L.H}));
        w.push_back(make_wall({L.W, 0.0}, {L.W, L.H}));
    }
    w.push_back(make_wall({0.3 * L.W, 0.5 * L.H}, {0.6 * L.W, 0.7 * L.H}));  // a slanted segment
    return w;
}

/// Positions by id (wrapped into [0, W) in periodic mode) to check that every
/// column moved with its disc.
std::vector<Vec2> positions_by_id(const ParticleStore& p, const Layout& L) {
    std::vector<Vec2> x(p.size());
    for (std::uint32_t a = 0; a < p.size(); ++a) {
        Vec2 q = p.x[p.slot_of_id[a]];
        if (L.periodic) q.x -= L.W * std::floor(q.x / L.W);
        x[a] = q;
    }
    return x;
}

void run_case(std::uint64_t seed, bool periodic, bool outlier) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed << (periodic ? " periodic" : " box")
                                      << (outlier ? " +outlier" : ""));
    Layout L;
    L.periodic = periodic;
    ParticleStore p = random_discs(seed, L, 25, 180, outlier);
    const std::vector<double> radius_by_id = p.radius;  // ids == slots before the first rebuild
    const BondTopology bonds = build_bond_topology(p);
    ASSERT_EQ(bonds.bond_count(), 3u * 25u);
    const std::vector<Wall> walls = box_walls(L);
    const PairBuilder::Settings settings{L.skin, periodic, L.W};
    PairBuilder builder;
    ContactStore cs;
    WallContactStore ws;

    const auto x0 = positions_by_id(p, L);
    builder.rebuild(p, bonds, walls, settings, cs, ws);
    if (outlier) {
        // The far disc makes the cells so large that the period holds fewer
        // than 3 of them: the case where the wrapped stencil used to be skipped.
        if (periodic) {
            EXPECT_LT(builder.grid().nx, 3);
        }
    } else {
        // The first rebuild sorts by cell, so it must have permuted the slots
        // (a meaningfulness check: otherwise "after re-sorting" tests nothing).
        std::size_t moved = 0;
        for (std::size_t s = 0; s < p.size(); ++s) moved += p.id[s] != s ? 1 : 0;
        EXPECT_GT(moved, p.size() / 2);
    }
    // Every column travelled with its disc.
    const auto x1 = positions_by_id(p, L);
    for (std::uint32_t a = 0; a < p.size(); ++a) {
        EXPECT_NEAR(x1[a].x, x0[a].x, 1e-12 * L.W);
        EXPECT_EQ(x1[a].y, x0[a].y);
        EXPECT_EQ(p.radius[p.slot_of_id[a]], radius_by_id[a]);
    }
    check_lists(p, cs, ws, walls, L, "after first rebuild");

    // Set ξ on about half the pairs, bonds and wall candidates; keep an
    // independent reference by key.
    Rng rng(seed * 7919 + 1);
    std::map<std::uint64_t, Vec2> ref_xi, ref_wall_xi;
    for (std::size_t k = 0; k < cs.size(); ++k)
        if (rng.uniform() < 0.5) {
            cs.xi[k] = {rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3)};
            ref_xi[cs.key[k]] = cs.xi[k];
        }
    for (std::size_t k = 0; k < ws.size(); ++k)
        if (rng.uniform() < 0.5) {
            ws.xi[k] = {rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3)};
            ref_wall_xi[ws.key[k]] = ws.xi[k];
        }
    ASSERT_GT(ref_xi.size(), 100u);

    auto check_history = [&](const char* stage) {
        SCOPED_TRACE(stage);
        std::size_t kept = 0;
        for (std::size_t k = 0; k < cs.size(); ++k) {
            auto it = ref_xi.find(cs.key[k]);
            const Vec2 want = it == ref_xi.end() ? Vec2{} : it->second;
            EXPECT_EQ(cs.xi[k].x, want.x) << "key " << cs.key[k];
            EXPECT_EQ(cs.xi[k].y, want.y) << "key " << cs.key[k];
            kept += it != ref_xi.end() ? 1 : 0;
        }
        // Histories of pairs that left the list are dropped; the rest must all be found.
        std::size_t expected = 0;
        const auto ref_now = brute_pairs(p, L);
        const auto bonds_now = brute_bonds(p);
        for (const auto& [key, xi] : ref_xi) expected += (ref_now.count(key) || bonds_now.count(key)) ? 1 : 0;
        EXPECT_EQ(kept, expected);
        EXPECT_GT(kept, ref_xi.size() / 2);
        for (std::size_t k = 0; k < ws.size(); ++k) {
            auto it = ref_wall_xi.find(ws.key[k]);
            const Vec2 want = it == ref_wall_xi.end() ? Vec2{} : it->second;
            EXPECT_EQ(ws.xi[k].x, want.x);
            EXPECT_EQ(ws.xi[k].y, want.y);
        }
    };

    // (a) Small moves (up to skin/2 per disc: cells change for some discs, the
    // pair set changes a little), then a rebuild that re-sorts.
    for (auto& x : p.x) x += Vec2{rng.uniform(-0.5, 0.5) * L.skin, rng.uniform(-0.5, 0.5) * L.skin};
    std::vector<std::uint32_t> ids_before = p.id;
    builder.rebuild(p, bonds, walls, settings, cs, ws);
    if (!outlier) {
        EXPECT_NE(ids_before, p.id) << "the rebuild should have re-sorted some slots";
    }
    check_lists(p, cs, ws, walls, L, "after small moves");
    check_history("history after small moves");
    // Drop the references whose pair left the list: a later return starts afresh.
    std::map<std::uint64_t, Vec2> alive;
    for (std::size_t k = 0; k < cs.size(); ++k)
        if (ref_xi.count(cs.key[k])) alive[cs.key[k]] = ref_xi[cs.key[k]];
    ref_xi = alive;
    std::map<std::uint64_t, Vec2> alive_w;
    for (std::size_t k = 0; k < ws.size(); ++k)
        if (ref_wall_xi.count(ws.key[k])) alive_w[ws.key[k]] = ref_wall_xi[ws.key[k]];
    ref_wall_xi = alive_w;

    // (b) A random permutation of every particle column (as any re-sort could
    // do), then a rebuild: history must follow the keys, not the slots.
    std::vector<std::uint32_t> perm(p.size());
    std::iota(perm.begin(), perm.end(), 0u);
    for (std::size_t k = perm.size(); k > 1; --k)
        std::swap(perm[k - 1], perm[static_cast<std::size_t>(rng.uniform() * static_cast<double>(k))]);
    p.for_each_column([&](auto& col) {
        auto copy = col;
        for (std::size_t s = 0; s < col.size(); ++s) col[s] = copy[perm[s]];
    });
    p.rebuild_slot_map();
    builder.rebuild(p, bonds, walls, settings, cs, ws);
    check_lists(p, cs, ws, walls, L, "after random slot permutation");
    check_history("history after random slot permutation");

    // (c) Large moves (several skins: the pair set changes a lot), rebuild again.
    for (auto& x : p.x) x += Vec2{rng.uniform(-3.0, 3.0) * L.skin, rng.uniform(-3.0, 3.0) * L.skin};
    builder.rebuild(p, bonds, walls, settings, cs, ws);
    check_lists(p, cs, ws, walls, L, "after large moves");
}

}  // namespace

TEST(Neighbor, MatchesBruteForceInABox) {
    for (std::uint64_t seed : {1u, 2u, 3u, 4u}) run_case(seed, false, false);
}

TEST(Neighbor, MatchesBruteForcePeriodicX) {
    for (std::uint64_t seed : {11u, 12u, 13u, 14u}) run_case(seed, true, false);
}

TEST(Neighbor, MatchesBruteForceWithAFarOutlier) {
    // One disc far above the rest: the grid enlarges its cells to stay O(N).
    run_case(21, false, true);
    run_case(22, true, true);
}

TEST(Neighbor, NarrowPeriodicBoxFewCells) {
    // A period only a few cells wide (nx = 2 .. 4; cell = 2 r_max + skin
    // <= 2.2 m) is where the wrapped stencil could list a pair twice or miss
    // one. Every W here is >= 2 (2 r_max + skin), so each pair has at most one
    // image within the cut-off and the minimum-image reference is unambiguous.
    std::set<int> nx_seen;
    for (double W : {4.5, 6.3, 8.0, 10.5}) {
        SCOPED_TRACE(::testing::Message() << "W " << W);
        Layout L;
        L.periodic = true;
        L.W = W;
        L.H = 30.0;
        ParticleStore p = random_discs(static_cast<std::uint64_t>(W * 10), L, 6, 60, false);
        const BondTopology bonds = build_bond_topology(p);
        const std::vector<Wall> walls = box_walls(L);
        PairBuilder builder;
        ContactStore cs;
        WallContactStore ws;
        builder.rebuild(p, bonds, walls, {L.skin, true, L.W}, cs, ws);
        nx_seen.insert(builder.grid().nx);
        check_lists(p, cs, ws, walls, L, "narrow periodic");
    }
    EXPECT_TRUE(nx_seen.count(2) && nx_seen.count(3)) << "the widths should give 2 and 3 cells";
}

