// ContactStore: every candidate disc pair within the neighbour skin, owned by
// one of its discs (CSR by owner slot i), plus the permanent cluster bonds,
// which sit first in their owner's range. Candidates persist between
// rebuilds, so ξ lives in the pair's slot; at a rebuild it moves to the new
// slot by its id-pair key (history survives re-sorting).
//
// Per-step outputs f, c are written by exactly one iteration of the pair loop
// and summed per disc in a fixed order (outgoing, then incoming), so forces
// are bit-identical at any thread count.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "orodem/core/vec2.hpp"

namespace orodem {

/// Key of an unordered id pair: (min id << 32) | max id.
constexpr std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

struct ContactStore {
    std::vector<std::uint32_t> i;       // owner slot
    std::vector<std::uint32_t> j;       // partner slot
    std::vector<std::uint64_t> key;     // pair_key(id_i, id_j)
    std::vector<Vec2> xi;               // tangential spring history ξ [m], eq. 1
    std::vector<std::int8_t> shift;     // periodic image: x_j is taken at x_j + shift·W
    std::vector<std::uint8_t> bonded;   // 1: permanent cluster bond ([37])
    std::vector<Vec2> f;                // force on i this step [N]
    std::vector<double> c;              // n̂ × F_t [N]; torques -R_i c, -R_j c

    std::vector<std::uint32_t> begin;   // N+1 offsets: pairs owned by slot s
    std::vector<std::uint32_t> in_begin;  // N+1 offsets into in_pair by partner slot
    std::vector<std::uint32_t> in_pair;   // pair indices, grouped by j, ascending

    std::size_t size() const { return i.size(); }
    void resize(std::size_t n) {
        i.resize(n); j.resize(n); key.resize(n); xi.resize(n); shift.resize(n);
        bonded.resize(n); f.resize(n); c.resize(n);
    }
};

/// The shape of a base wall that follows the plate under the wedge
/// ([flexure] with two-way coupling, run/wedge_flexure.hpp): its height y(x)
/// [m] piecewise linear between nodes on a uniform grid, x_k = x0 + k dx
/// (the plate's nodes; y = −w). The height under a disc is one segment
/// lookup, O(1); beyond the grid the end segments go on straight.
struct BaseProfile {
    double x0 = 0.0;        // x of node 0 [m]
    double dx = 1.0;        // node spacing [m]
    double inv_dx = 1.0;    // 1 / dx [1/m]
    std::vector<double> y;  // height at the nodes [m], at least two

    /// The segment under x: its left node, in [0, size − 2].
    std::size_t segment(double x) const {
        const double t = std::floor((x - x0) * inv_dx);
        const double last = static_cast<double>(y.size() - 2);
        return t >= 0.0 ? static_cast<std::size_t>(std::min(t, last)) : 0;  // NaN: 0
    }
    /// x of node k [m].
    double node_x(std::size_t k) const { return x0 + static_cast<double>(k) * dx; }
    /// The height under x [m], linear on its segment.
    double height(double x) const {
        const std::size_t k = segment(x);
        const double s = (x - node_x(k)) * inv_dx;
        return y[k] + s * (y[k + 1] - y[k]);
    }
};

/// A straight wall ([28]): a segment a→b, or the infinite line through them.
/// It interacts with discs on either side using the disc-disc normal law with
/// R_j = ∞; rough walls add the tangential spring with their own μ.
struct Wall {
    Vec2 a;                   // first end point [m]
    Vec2 b;                   // second end point [m]
    Vec2 velocity;            // translation of the whole wall [m/s]
    double surface_speed = 0; // conveyor speed along (b-a)/|b-a| [m/s]
    bool infinite = false;    // true: the line through a and b
    bool rough = false;       // false: smooth, no tangential force
    double mu = 0.0;          // Coulomb coefficient of a rough wall [-]
    bool open_ends = false;   // true: no end caps; only discs whose centre projects
                              // inside [a, b] touch it (bases that meet at the S point)
    /// A base that follows the plate (two-way [flexure]): a horizontal wall
    /// a→b whose height is the profile's, y(x), instead of a.y; a disc
    /// touches the segment under its centre. Null: the straight wall. Not
    /// saved in checkpoints (run/wedge_flexure.cpp sets it again from the
    /// plate's saved deflection); immutable, shared by copies.
    std::shared_ptr<const BaseProfile> profile = nullptr;
};

/// Disc-wall candidate contacts, CSR by particle slot; history keyed by
/// (particle id << 16) | wall index.
struct WallContactStore {
    std::vector<std::uint16_t> wall;    // wall index
    std::vector<std::uint64_t> key;
    std::vector<Vec2> xi;               // tangential history ξ [m]
    std::vector<Vec2> f;                // force on the disc [N]
    std::vector<double> c;              // n̂ × F_t [N]; torque -R_i c
    std::vector<std::uint32_t> begin;   // N+1 offsets by particle slot

    std::size_t size() const { return wall.size(); }
    void resize(std::size_t n) {
        wall.resize(n); key.resize(n); xi.resize(n); f.resize(n); c.resize(n);
    }
};

constexpr std::uint64_t wall_key(std::uint32_t particle_id, std::size_t wall_index) {
    return (std::uint64_t{particle_id} << 16) | static_cast<std::uint64_t>(wall_index);
}

/// Cluster bonds by particle id (CSR): partners of id a are
/// partner[begin[a] .. begin[a+1]). Built once; never changes.
struct BondTopology {
    std::vector<std::uint32_t> begin;
    std::vector<std::uint32_t> partner;
    std::size_t bond_count() const { return partner.size() / 2; }
};

}  // namespace orodem
