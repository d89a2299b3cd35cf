#include "orodem/analysis/strain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "orodem/analysis/neighbour_grid.hpp"

namespace orodem {

StrainMeasures strain_measures(const Mat2& F) {
    // E = ½ (FᵀF − I).
    const double exx = 0.5 * (F.xx * F.xx + F.yx * F.yx - 1.0);
    const double eyy = 0.5 * (F.xy * F.xy + F.yy * F.yy - 1.0);
    const double exy = 0.5 * (F.xx * F.xy + F.yx * F.yy);
    StrainMeasures m;
    m.shear = std::sqrt(0.25 * (exx - eyy) * (exx - eyy) + exy * exy);
    m.volumetric = F.xx * F.yy - F.xy * F.yx - 1.0;
    m.rotation = std::atan2(F.yx - F.xy, F.xx + F.yy);
    return m;
}

void accumulate_gradient(std::vector<Mat2>& F_total, const std::vector<Mat2>& F_inc) {
    if (F_total.size() < F_inc.size()) F_total.resize(F_inc.size());
    for (std::size_t i = 0; i < F_inc.size(); ++i)
        if (std::isfinite(F_inc[i].xx)) F_total[i] = F_inc[i] * F_total[i];
}

StrainField local_strain(const std::vector<Vec2>& x0, const std::vector<Vec2>& x1, double radius) {
    const std::size_t n = std::min(x0.size(), x1.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    StrainField out;
    out.shear.assign(n, nan);
    out.volumetric.assign(n, nan);
    out.rotation.assign(n, nan);
    out.d2min.assign(n, nan);
    out.F.assign(n, Mat2{nan, nan, nan, nan});
    if (n == 0 || !(radius > 0.0)) return out;

    const NeighbourGrid grid(x0, radius);
    std::vector<std::uint32_t> nb;
    for (std::size_t i = 0; i < n; ++i) {
        grid.within(x0[i], i, nb);
        nb.erase(std::remove_if(nb.begin(), nb.end(), [n](std::uint32_t j) { return j >= n; }), nb.end());
        if (nb.size() < 3) continue;
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
        const Mat2 F{(yxx * xyy - yxy * xxy) / det, (yxy * xxx - yxx * xxy) / det, (yyx * xyy - yyy * xxy) / det,
                     (yyy * xxx - yyx * xxy) / det};
        double d2 = 0.0;
        for (std::uint32_t j : nb) {
            const Vec2 a = x0[j] - x0[i], b = x1[j] - x1[i];
            const Vec2 affine{F.xx * a.x + F.xy * a.y, F.yx * a.x + F.yy * a.y};
            d2 += norm2(b - affine);
        }
        const StrainMeasures m = strain_measures(F);
        out.shear[i] = m.shear;
        out.volumetric[i] = m.volumetric;
        out.rotation[i] = m.rotation;
        out.d2min[i] = d2 / static_cast<double>(nb.size());
        out.F[i] = F;
    }
    return out;
}

}  // namespace orodem
