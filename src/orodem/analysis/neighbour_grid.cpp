#include "orodem/analysis/neighbour_grid.hpp"

#include <algorithm>

namespace orodem {

NeighbourGrid::NeighbourGrid(const std::vector<Vec2>& x, double radius, const std::vector<char>* use)
    : x_(x), radius_(radius) {
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (use && !(*use)[i]) continue;
        if (!std::isfinite(x[i].x) || !std::isfinite(x[i].y)) continue;
        cells_[key(cell(x[i].x), cell(x[i].y))].push_back(static_cast<std::uint32_t>(i));
    }
}

void NeighbourGrid::within(Vec2 p, std::size_t i, std::vector<std::uint32_t>& out) const {
    out.clear();
    const double r2 = radius_ * radius_;
    const std::int64_t cx = cell(p.x), cy = cell(p.y);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
            const auto it = cells_.find(key(cx + dx, cy + dy));
            if (it == cells_.end()) continue;
            for (std::uint32_t j : it->second)
                if (j != i && norm2(x_[j] - p) < r2) out.push_back(j);
        }
    std::sort(out.begin(), out.end());
}

}  // namespace orodem
