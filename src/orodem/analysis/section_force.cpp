#include "orodem/analysis/section_force.hpp"

namespace orodem {

Vec2 section_force(const ParticleStore& p, const ContactStore& c, double x_c, double period_x) {
    Vec2 sum{};
    for (std::size_t k = 0; k < c.i.size(); ++k) {
        const double xi = p.x[c.i[k]].x;
        const double xj = p.x[c.j[k]].x + static_cast<double>(c.shift[k]) * period_x;
        const bool i_right = xi >= x_c, j_right = xj >= x_c;
        if (i_right == j_right) continue;
        // f[k] is the force on i; j receives −f[k].
        if (i_right)
            sum += c.f[k];
        else
            sum -= c.f[k];
    }
    return sum;
}

}  // namespace orodem
