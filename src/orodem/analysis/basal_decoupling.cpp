#include "orodem/analysis/basal_decoupling.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace orodem {

double basal_decoupling_x(const std::vector<Vec2>& x_then, const std::vector<Vec2>& x_now,
                          const std::vector<double>& radius, double belt_displacement, double bin_width) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!(belt_displacement > 0.0) || !(bin_width > 0.0)) return nan;
    const std::size_t n = std::min({x_then.size(), x_now.size(), radius.size()});
    // Bins k = 0, 1, ...: [−(k+1) w, −k w); sum of u and count per bin.
    std::vector<double> sum;
    std::vector<std::size_t> count;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = x_then[i], b = x_now[i];
        const double R = radius[i];
        if (!std::isfinite(a.x) || !std::isfinite(b.x) || !(a.x < 0.0) || a.y - R > 0.05 * R) continue;
        const auto k = static_cast<std::size_t>(std::floor(-a.x / bin_width));
        if (k >= sum.size()) {
            sum.resize(k + 1, 0.0);
            count.resize(k + 1, 0);
        }
        sum[k] += (b.x - a.x) / belt_displacement;
        ++count[k];
    }
    const auto centre = [&](std::size_t k) { return -(static_cast<double>(k) + 0.5) * bin_width; };
    std::size_t downstream = sum.size();  // the nearest non-empty bin between k and S (none yet)
    for (std::size_t k = 0; k < sum.size(); ++k) {
        if (count[k] == 0) continue;
        const double u = sum[k] / static_cast<double>(count[k]);
        if (u >= 0.5) {
            if (downstream == sum.size()) return 0.0;
            const double u_down = sum[downstream] / static_cast<double>(count[downstream]);
            return centre(k) + (u - 0.5) / (u - u_down) * (centre(downstream) - centre(k));
        }
        downstream = k;
    }
    return nan;
}

}  // namespace orodem
