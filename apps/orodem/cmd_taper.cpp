// `orodem taper --phi DEG (--phib DEG | --mu-b MU) [--beta DEG]`: the two
// critical surface slopes of a dry noncohesive Coulomb wedge from the exact
// solution of Dahlen (1984) (analysis/critical_taper), with their meaning,
// and the small-angle approximation of Davis, Suppe & Dahlen (1983) beside
// the lower one. Bad values: ConfigError naming the option (exit 2).
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "orodem/analysis/critical_taper.hpp"
#include "orodem/core/angles.hpp"
#include "orodem/core/error.hpp"

#include "commands.hpp"

namespace orodem {

int cmd_taper(double phi_deg, double phi_b_deg, double mu_b, double beta_deg) {
    if (!std::isfinite(phi_deg) || phi_deg <= 0.0 || phi_deg >= 90.0)
        throw ConfigError(fmt::format("--phi {:g}: the internal friction angle must be in (0, 90) degrees", phi_deg));
    const bool have_phib = !std::isnan(phi_b_deg), have_mu_b = !std::isnan(mu_b);
    if (have_phib == have_mu_b)
        throw ConfigError("give the basal friction as one of --phib DEG (angle) or --mu-b MU (coefficient)");
    if (have_mu_b) {
        const double mu = std::tan(phi_deg / kDeg);
        if (!std::isfinite(mu_b) || mu_b < 0.0 || mu_b >= mu)
            throw ConfigError(fmt::format("--mu-b {:g}: the basal friction coefficient must be in [0, tan(phi)) = "
                                          "[0, {:.4f}) (a base weaker than the wedge)",
                                          mu_b, mu));
        phi_b_deg = std::atan(mu_b) * kDeg;
    } else if (!std::isfinite(phi_b_deg) || phi_b_deg < 0.0 || phi_b_deg >= phi_deg) {
        throw ConfigError(fmt::format("--phib {:g}: the basal friction angle must be in [0, phi) = [0, {:g}) degrees "
                                      "(a base weaker than the wedge)",
                                      phi_b_deg, phi_deg));
    }
    if (!std::isfinite(beta_deg))
        throw ConfigError(fmt::format("--beta {:g}: the basal dip must be a finite angle in degrees", beta_deg));
    const TaperBetaRange range = critical_taper_beta_range(phi_deg, phi_b_deg);
    const auto t = critical_taper(phi_deg, phi_b_deg, beta_deg);
    if (!t)
        throw ConfigError(fmt::format("--beta {:g}: no wedge is stable on this base; the basal dip must be in "
                                      "[-phi_b, 90] = [{:g}, {:g}] degrees",
                                      beta_deg, range.min_deg, range.max_deg));

    const double mu_b_used = std::tan(phi_b_deg / kDeg);
    fmt::print("Critical taper of a dry noncohesive Coulomb wedge (exact solution of Dahlen 1984)\n");
    fmt::print("  phi   = {:g} deg (mu   = tan phi   = {:.4f})  internal friction\n", phi_deg,
               std::tan(phi_deg / kDeg));
    fmt::print("  phi_b = {:g} deg (mu_b = tan phi_b = {:.4f})  basal friction\n", phi_b_deg, mu_b_used);
    fmt::print("  beta  = {:g} deg  basal dip, positive toward the hinterland\n", beta_deg);
    fmt::print("critical taper (compressive, lower branch): alpha = {:.3f} deg, alpha + beta = {:.3f} deg\n",
               t->alpha_min_deg, t->alpha_min_deg + beta_deg);
    fmt::print("  at failure everywhere, on the verge of thrusting, and sliding on its base (sigma_1 at {:.2f} deg to "
               "the surface); a flatter wedge thickens internally before it slides\n",
               t->psi_0_min_deg);
    fmt::print("critical taper (extensional, upper branch): alpha = {:.3f} deg, alpha + beta = {:.3f} deg\n",
               t->alpha_max_deg, t->alpha_max_deg + beta_deg);
    fmt::print("  at failure everywhere, on the verge of normal faulting, and sliding on its base (sigma_1 at {:.2f} "
               "deg to the surface); a steeper wedge collapses\n",
               t->psi_0_max_deg);
    fmt::print("stable (slides on its base without failing inside) for {:.3f} < alpha < {:.3f} deg; critical wedges "
               "exist for {:g} <= beta <= {:g} deg\n",
               t->alpha_min_deg, t->alpha_max_deg, range.min_deg, range.max_deg);
    const double s = std::sin(phi_deg / kDeg), k = 2.0 * s / (1.0 - s);
    const double taper_small = (beta_deg / kDeg + mu_b_used) / (1.0 + k) * kDeg;
    fmt::print("small-angle approximation (Davis et al. 1983): alpha + beta = (beta + mu_b)/(1 + K) = {:.3f} deg, "
               "alpha = {:.3f} deg, K = 2 sin phi/(1 - sin phi) = {:.4f}\n",
               taper_small, taper_small - beta_deg, k);
    return 0;
}

}  // namespace orodem
