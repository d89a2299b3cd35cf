// NeighbourGrid: the points within a fixed radius of a point, for the
// per-output analyses (strain, faults) that work on positions only. A hash
// grid of cell edge `radius` over the points, keyed by the cell's integer
// coordinates: building it and one query per point are O(N). The
// neighbours come back sorted by index, so every sum over them has a fixed
// order and its result does not depend on how the grid stores them.
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "orodem/core/vec2.hpp"

namespace orodem {

class NeighbourGrid {
public:
    /// x: the points [m]; radius > 0 [m]; use: when given, only the points
    /// with use[i] != 0 are in the grid (and can be found).
    NeighbourGrid(const std::vector<Vec2>& x, double radius, const std::vector<char>* use = nullptr);

    /// The indices j != i in the grid with |x_j − p| < radius, ascending, in `out`.
    void within(Vec2 p, std::size_t i, std::vector<std::uint32_t>& out) const;

private:
    std::uint64_t key(std::int64_t cx, std::int64_t cy) const {
        return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
    }
    std::int64_t cell(double v) const { return static_cast<std::int64_t>(std::floor(v / radius_)); }

    const std::vector<Vec2>& x_;
    double radius_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace orodem
