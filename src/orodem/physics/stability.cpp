#include "orodem/physics/stability.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "orodem/core/error.hpp"

namespace orodem {

double stiffest_spring(const LawParams& p) {
    return std::max(p.k_n, p.tangential ? 3.0 * p.k_s : 0.0);
}

double critical_timestep(double m_min, double k_max) {
    return 2.0 * std::sqrt(m_min / (2.0 * kMaxCoordination * k_max));
}

TimestepInfo choose_timestep(double m_min, const LawParams& p, double dt_requested,
                             double safety) {
    TimestepInfo t;
    const double k_max = stiffest_spring(p);
    t.dt_crit = critical_timestep(m_min, k_max);
    t.t_collision = std::numbers::pi * std::sqrt(m_min / (2.0 * p.k_n));
    if (dt_requested > 0.0) {
        if (dt_requested > t.dt_crit)
            throw ConfigError(fmt::format(
                "dt = {:g} s is above the stability limit dt_crit = {:g} s "
                "(2 sqrt(m_min/(12 k_max)), m_min = {:g} kg, k_max = {:g} N/m); "
                "use dt <= {:g} or dt = 0 for automatic",
                dt_requested, t.dt_crit, m_min, k_max, t.dt_crit));
        t.dt = dt_requested;
    } else {
        t.dt = safety * std::sqrt(m_min / k_max);
    }
    return t;
}

}  // namespace orodem
