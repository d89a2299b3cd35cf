#include "orodem/analysis/strain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace orodem {

StrainField local_strain(const std::vector<Vec2>& x0, const std::vector<Vec2>& x1, double radius) {
    const std::size_t n = std::min(x0.size(), x1.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    StrainField out;
    out.shear.assign(n, nan);
    out.volumetric.assign(n, nan);
    out.rotation.assign(n, nan);
    out.d2min.assign(n, nan);
    if (n == 0 || !(radius > 0.0)) return out;

    // Cell grid of edge `radius` over the reference positions, keyed by the
    // cell's integer coordinates.
    auto cell_of = [&](Vec2 p) {
        return std::pair<std::int64_t, std::int64_t>{static_cast<std::int64_t>(std::floor(p.x / radius)),
                                                     static_cast<std::int64_t>(std::floor(p.y / radius))};
    };
    auto key = [](std::int64_t cx, std::int64_t cy) {
        return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
    };
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
    for (std::size_t i = 0; i < n; ++i) {
        const auto [cx, cy] = cell_of(x0[i]);
        cells[key(cx, cy)].push_back(static_cast<std::uint32_t>(i));
    }
    const double r2 = radius * radius;
    std::vector<std::uint32_t> nb;
    for (std::size_t i = 0; i < n; ++i) {
        nb.clear();
        const auto [cx, cy] = cell_of(x0[i]);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                const auto it = cells.find(key(cx + dx, cy + dy));
                if (it == cells.end()) continue;
                for (std::uint32_t j : it->second)
                    if (j != i && norm2(x0[j] - x0[i]) < r2) nb.push_back(j);
            }
        if (nb.size() < 3) continue;
        std::sort(nb.begin(), nb.end());  // a fixed summation order
        // X = Σ r0 r0ᵀ (symmetric), Y = Σ r1 r0ᵀ.
        double xxx = 0, xxy = 0, xyy = 0, yxx = 0, yxy = 0, yyx = 0, yyy = 0;
        for (std::uint32_t j : nb) {
            const Vec2 a = x0[j] - x0[i], b = x1[j] - x1[i];
            xxx += a.x * a.x;
            xxy += a.x * a.y;
            xyy += a.y * a.y;
            yxx += b.x * a.x;
            yxy += b.x * a.y;
            yyx += b.y * a.x;
            yyy += b.y * a.y;
        }
        const double det = xxx * xyy - xxy * xxy;
        if (!(std::fabs(det) > 1e-12 * (xxx * xyy + xxy * xxy))) continue;  // collinear neighbours
        // X⁻¹ = [[xyy, −xxy], [−xxy, xxx]] / det;  F = Y X⁻¹.
        const double fxx = (yxx * xyy - yxy * xxy) / det, fxy = (yxy * xxx - yxx * xxy) / det;
        const double fyx = (yyx * xyy - yyy * xxy) / det, fyy = (yyy * xxx - yyx * xxy) / det;
        double d2 = 0.0;
        for (std::uint32_t j : nb) {
            const Vec2 a = x0[j] - x0[i], b = x1[j] - x1[i];
            const Vec2 affine{fxx * a.x + fxy * a.y, fyx * a.x + fyy * a.y};
            d2 += norm2(b - affine);
        }
        // E = ½ (FᵀF − I).
        const double exx = 0.5 * (fxx * fxx + fyx * fyx - 1.0);
        const double eyy = 0.5 * (fxy * fxy + fyy * fyy - 1.0);
        const double exy = 0.5 * (fxx * fxy + fyx * fyy);
        out.shear[i] = std::sqrt(0.25 * (exx - eyy) * (exx - eyy) + exy * exy);
        out.volumetric[i] = fxx * fyy - fxy * fyx - 1.0;
        out.rotation[i] = std::atan2(fyx - fxy, fxx + fyy);
        out.d2min[i] = d2 / static_cast<double>(nb.size());
    }
    return out;
}

}  // namespace orodem
