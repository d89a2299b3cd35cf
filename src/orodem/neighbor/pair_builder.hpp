// PairBuilder: O(N) contact detection with a cell grid and a Verlet skin.
//
// At a rebuild it (1) keeps the old pair and wall lists (offsets, keys and ξ,
// swapped out of the stores, no copy), (2) wraps periodic positions, (3)
// counting-sorts the discs by cell (stable, so the order is a function of the
// previous order only) and permutes every particle column; cells are numbered
// column by column (x major), so the discs of one x column of cells occupy one
// slot range (the sleeping zones of engine/sleep rely on it), (4) lists
// candidate pairs with a half stencil (same cell with j > i, then cells E, NW,
// N, NE) plus the cluster bonds owned by their lower slot, in one scan into
// per-thread buffers (each thread a contiguous range of owners), then an
// exclusive scan of the counts and a copy to the offsets, so the pair order
// never depends on the thread split, and (5) lists the disc-wall candidates
// (count → exclusive scan → fill). While filling, each new pair takes its ξ
// from the old list: if it existed it was owned by the old slot of one of its
// two discs (built_slot_of_id_ gives both), so it is found by its
// key among those two owners' few old pairs, which lie near each other in
// memory as the slots are sorted by cell. Each key is unique, so this finds
// what an exact map by key would (a zero ξ comes back as +0), in parallel and
// independent of any order. Pairs of one cluster are bonds and never enter
// detection.
//
// A rebuild is needed when the largest disc displacement since the last one
// plus the largest wall displacement exceeds skin/2: then no pair can have
// come into contact unseen.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "orodem/state/contacts.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

struct GridInfo {
    double x0 = 0, y0 = 0;     // lower-left corner [m]
    double cell = 0;           // cell edge [m]
    int nx = 0, ny = 0;
};

class PairBuilder {
public:
    struct Settings {
        double skin = 0.0;          // Verlet skin [m]
        bool periodic_x = false;
        double period_x = 0.0;      // W [m]; x in [0, W) after a rebuild
    };

    /// Full rebuild; see the file note. Updates x_ref (positions at rebuild).
    void rebuild(ParticleStore& p, const BondTopology& bonds, const std::vector<Wall>& walls,
                 const Settings& s, ContactStore& contacts, WallContactStore& wall_contacts);

    const GridInfo& grid() const { return grid_; }
    /// First slot of cell column cx (cx in [0, nx]; nx gives the disc count),
    /// valid until the next rebuild.
    std::uint32_t column_start(int cx) const {
        return cell_start_[static_cast<std::size_t>(cx) * static_cast<std::size_t>(grid_.ny)];
    }
    const std::vector<Vec2>& x_ref() const { return x_ref_; }
    std::vector<Vec2>& x_ref() { return x_ref_; }
    std::uint64_t rebuild_count() const { return rebuilds_; }
    /// Checkpoint restore only (io/checkpoint.cpp); x_ref, this count and the
    /// slot order the lists were built in are the builder's only state that
    /// outlives a rebuild (the rest is scratch).
    void set_rebuild_count(std::uint64_t n) { rebuilds_ = n; }
    /// Checkpoint restore only: the restored pair and wall lists were built
    /// with the discs in the slots they have now (id -> slot).
    void set_built_order(const std::vector<std::uint32_t>& slot_of_id) { built_slot_of_id_ = slot_of_id; }

private:
    void sort_by_cell(ParticleStore& p, const Settings& s);
    void build_pairs(const ParticleStore& p, const BondTopology& bonds, const Settings& s,
                     ContactStore& c);
    void build_wall_pairs(const ParticleStore& p, const std::vector<Wall>& walls,
                          const Settings& s, WallContactStore& w);
    /// ξ of `key` in the old list (CSR offsets `begin` by old slot), looked
    /// for among the entries of old slots owner_a and owner_b; {} when absent
    /// or zero.
    static Vec2 old_xi(const std::vector<std::uint32_t>& begin, const std::vector<std::uint64_t>& keys,
                       const std::vector<Vec2>& xis, std::uint32_t owner_a, std::uint32_t owner_b,
                       std::uint64_t key);

    GridInfo grid_;
    std::vector<std::uint32_t> cell_of_;     // per slot
    std::vector<std::uint32_t> cell_start_;  // ncell+1
    std::vector<std::uint32_t> perm_;        // new slot -> old slot
    std::vector<unsigned char> scratch_;     // column permutation buffer
    std::vector<std::uint32_t> count_;       // per-slot pair counts
    struct Candidate {
        std::uint32_t j;      // partner slot
        std::int8_t shift;    // periodic image
        std::uint8_t bonded;  // 1: a cluster bond
    };
    std::vector<std::vector<Candidate>> found_;  // per thread: the pairs of its owners, in order
    double r_max_ = 0.0;                           // largest radius at the last sort [m]
    std::vector<std::pair<Vec2, Vec2>> wall_box_;  // per wall: where its candidates can be (lo, hi) [m]
    // The lists of the previous rebuild, by old slot (swapped out of the
    // stores at a rebuild): where the new pairs find their ξ.
    std::vector<std::uint32_t> old_begin_, old_wall_begin_;
    std::vector<std::uint64_t> old_key_, old_wall_key_;
    std::vector<Vec2> old_xi_, old_wall_xi_;
    std::vector<std::uint32_t> built_slot_of_id_;  // id -> slot when the lists were last built
    std::vector<Vec2> x_ref_;
    std::uint64_t rebuilds_ = 0;
};

/// Closest point of wall w to point q.
Vec2 closest_point(const Wall& w, Vec2 q);
/// Sets cp to the closest point of w to q; false when w has open ends and q
/// projects outside the segment (no contact possible).
bool wall_contact_point(const Wall& w, Vec2 q, Vec2& cp);
/// The unit tangent of w at q, along a→b: (b − a)/|b − a|, or a profiled
/// base's segment under q.
Vec2 wall_tangent(const Wall& w, Vec2 q);

}  // namespace orodem
