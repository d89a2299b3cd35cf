// PairBuilder: O(N) contact detection with a cell grid and a Verlet skin.
//
// At a rebuild it (1) saves the tangential history of the old pairs by id-pair
// key, (2) wraps periodic positions, (3) counting-sorts the discs by cell
// (stable, so the order is a function of the previous order only) and
// permutes every particle column; cells are numbered column by column (x
// major), so the discs of one x column of cells occupy one slot range (the
// sleeping zones of engine/sleep rely on it), (4) lists candidate pairs with a half
// stencil (same cell with j > i, then cells E, NW, N, NE) plus the cluster
// bonds owned by their lower slot, count → exclusive scan → fill, so the pair
// order never depends on the thread split, (5) does the same for disc-wall
// candidates, and (6) moves ξ to the new pair slots by looking their keys up
// in a hash table of the old pairs' non-zero ξ (HistoryTable: each key is
// unique, so every lookup finds what any exact map would, and the result
// depends on no order). Pairs of one cluster are bonds and never enter
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

/// ξ by pair or wall key: open addressing with linear probing in a table of a
/// power-of-two size at least twice the entries, kept between rebuilds (no
/// allocation once grown). No key is ~0 (pair_key(a, b) has a < b; wall_key
/// has a 32-bit id), which marks an empty place.
class HistoryTable {
public:
    /// Empties the table, sized for n entries.
    void reset(std::size_t n);
    /// Adds a key not yet in the table.
    void insert(std::uint64_t key, Vec2 xi) {
        std::size_t h = place(key);
        while (keys_[h] != kEmpty) h = (h + 1) & mask_;
        keys_[h] = key;
        xi_[h] = xi;
    }
    /// ξ of key, {} when it is not in the table.
    Vec2 find(std::uint64_t key) const {
        for (std::size_t h = place(key);; h = (h + 1) & mask_) {
            if (keys_[h] == key) return xi_[h];
            if (keys_[h] == kEmpty) return {};
        }
    }

private:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
    std::size_t place(std::uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);  // Fibonacci hashing
    }
    std::vector<std::uint64_t> keys_;
    std::vector<Vec2> xi_;
    std::size_t mask_ = 0;
    int shift_ = 64;
};

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
    /// Checkpoint restore only (io/checkpoint.cpp); x_ref and this count are
    /// the builder's only state that outlives a rebuild (the rest is scratch).
    void set_rebuild_count(std::uint64_t n) { rebuilds_ = n; }

private:
    void sort_by_cell(ParticleStore& p, const Settings& s);
    void build_pairs(const ParticleStore& p, const BondTopology& bonds, const Settings& s,
                     ContactStore& c);
    void build_wall_pairs(const ParticleStore& p, const std::vector<Wall>& walls,
                          const Settings& s, WallContactStore& w);

    GridInfo grid_;
    std::vector<std::uint32_t> cell_of_;     // per slot
    std::vector<std::uint32_t> cell_start_;  // ncell+1
    std::vector<std::uint32_t> perm_;        // new slot -> old slot
    std::vector<unsigned char> scratch_;     // column permutation buffer
    std::vector<std::uint32_t> count_;       // per-slot pair counts
    HistoryTable old_hist_;                  // the old pairs' (then walls') non-zero ξ by key
    std::vector<Vec2> x_ref_;
    std::uint64_t rebuilds_ = 0;
};

/// Closest point of wall w to point q.
Vec2 closest_point(const Wall& w, Vec2 q);
/// Sets cp to the closest point of w to q; false when w has open ends and q
/// projects outside the segment (no contact possible).
bool wall_contact_point(const Wall& w, Vec2 q, Vec2& cp);

}  // namespace orodem
