// Critical-taper theory: the exact solution of Dahlen (1984, JGR 89,
// "Noncohesive critical Coulomb wedges: an exact solution") for a dry
// (λ = λ_b = 0), noncohesive, subaerial Coulomb wedge. The equations and the
// branches are in the design note at the top of critical_taper.cpp.
//
// Notation of the paper: α surface slope (positive: the surface dips toward
// the toe), β basal dip (positive: the base dips toward the hinterland, i.e.
// under the wedge), α + β the taper, φ the internal friction angle (μ = tan φ),
// φ_b the basal friction angle (μ_b = tan φ_b), ψ_0 and ψ_b the angles between
// the greatest compressive stress σ_1 and the surface and the base. All
// angles in the interface are in degrees.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace orodem {

/// The two critical surface slopes of a wedge with basal dip β: the wedge is
/// stable (it can slide on its base without failing internally) for
/// alpha_min_deg < α < alpha_max_deg, and critical (at failure everywhere and
/// sliding on its base) on either bound.
struct CriticalTaper {
    double alpha_min_deg = 0.0;  ///< lower, compressively critical slope α_min [deg]: the wedge is on the verge
                                 ///< of thrusting everywhere; a flatter wedge thickens internally when pushed
    double alpha_max_deg = 0.0;  ///< upper, extensionally critical slope α_max [deg]: the wedge is on the verge
                                 ///< of normal faulting everywhere; a steeper wedge collapses
    double psi_0_min_deg = 0.0;  ///< ψ_0 of the lower solution: angle from the surface to σ_1, in (−90, 90] [deg]
    double psi_b_min_deg = 0.0;  ///< ψ_b of the lower solution: angle from the base to σ_1, in (−90, 90] [deg]
    double psi_0_max_deg = 0.0;  ///< ψ_0 of the upper solution [deg]
    double psi_b_max_deg = 0.0;  ///< ψ_b of the upper solution [deg]
};

/// The basal dips for which a critical wedge exists: −φ_b ≤ β ≤ 90° (the two
/// vertices of the closed stability envelope, at (β, α) = (−φ_b, φ_b) and
/// (90°, −φ_b)).
struct TaperBetaRange {
    double min_deg = 0.0;  ///< −φ_b [deg]
    double max_deg = 0.0;  ///< 90 [deg]
};

/// One β of the envelope with both critical slopes, for plots.
struct CriticalTaperPoint {
    double beta_deg = 0.0;       ///< basal dip β [deg]
    double alpha_min_deg = 0.0;  ///< lower (compressive) critical slope [deg]
    double alpha_max_deg = 0.0;  ///< upper (extensional) critical slope [deg]
};

/// Throws std::invalid_argument unless phi_deg (φ) is in (0, 90) and
/// phi_b_deg (φ_b) in [0, φ): the base must be weaker than the wedge.
void check_taper_friction(double phi_deg, double phi_b_deg);

/// β range of the stability field for φ, φ_b (degrees); checks as above.
TaperBetaRange critical_taper_beta_range(double phi_deg, double phi_b_deg);

/// Exact critical surface slopes (Dahlen 1984) of a dry noncohesive wedge
/// with internal friction angle phi_deg, basal friction angle phi_b_deg and
/// basal dip beta_deg (all degrees). std::nullopt when β lies outside
/// [−φ_b, 90°], where no wedge is stable. Throws std::invalid_argument for
/// bad φ, φ_b (see check_taper_friction) or a non-finite β. Never NaN.
std::optional<CriticalTaper> critical_taper(double phi_deg, double phi_b_deg, double beta_deg);

/// The stability envelope for plots: `points` (≥ 2) basal dips evenly spaced
/// over [−φ_b, 90°] (both ends included), each with α_min and α_max. The two
/// branches meet at the ends. Throws std::invalid_argument as critical_taper.
std::vector<CriticalTaperPoint> critical_taper_envelope(double phi_deg, double phi_b_deg, std::size_t points);

}  // namespace orodem
