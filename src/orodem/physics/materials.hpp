// Materials: several named materials in one run (layered stratigraphy), the
// law of a pair of them, and slip weakening of friction kept on the particle
// (docs/physics.md "Materials, layers and weakening"). Pure values and
// functions: the engine (engine/materials.cpp) keeps the per-particle damage
// and the per-pair columns, this file says what they mean.
//
// A pair of discs of materials a and b has
//   k_n = k_a                          when a and b have the same k_n,
//         2 k_a k_b / (k_a + k_b)      otherwise (two springs in series, each
//                                       of twice the material's stiffness, as
//                                       a disc contributes half a contact);
//   k_s likewise from each material's k_s;
//   μ_peak, μ_res = the smaller of the two materials' values (the weaker
//                    material shears first at an interface), unless the
//                    config names the pair (friction_pairs);
//   cohesion = the smaller of the two; lost for good after the contact
//              breaks when either material has cohesion_loss;
//   weakening distance d_w = the mean of the two.
// The damping (kind and values) is one for all materials, [material]'s; a
// restitution or damping ratio gives each pair its dashpot from the pair's
// own k (make_law).
//
// Weakening: particle p carries a damage D_p, the sliding distance of its
// contacts [mean disc diameters] (half of each contact's plastic slip goes to
// each of its two particles; a cluster's discs share one damage, the sum
// over the cluster), less healing. A contact's friction is
//   μ = μ_peak − (μ_peak − μ_res) min(1, D̄ / d_w),  D̄ = (D_i + D_j) / 2,
// so μ_res = μ_peak gives μ_peak exactly (the bytes of a run without
// weakening).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "orodem/physics/contact_law.hpp"

namespace orodem {

/// One material's contact properties as the engine uses them.
struct MaterialLaw {
    LawParams law;                    // k_n, k_s, μ_peak (law.mu), cohesion, damping of a pair of this material
    double density = 0.0;             // ρ [kg/m³]
    double mu_residual = 0.0;         // μ_res [-]; = law.mu: no weakening
    double weakening_distance = 1.0;  // d_w: damage over which μ falls from peak to residual [mean diameters]
    double healing_rate = 0.0;        // damage lost per second [mean diameters / s]
    bool cohesion_loss = false;       // a contact's cohesion is lost for good once it breaks
};

/// The law of a pair of materials (the rules in the header comment).
struct PairLaw {
    LawParams law;                    // μ = μ_peak
    double mu_residual = 0.0;         // [-]
    double weakening_distance = 1.0;  // [mean diameters]
    bool cohesion_loss = false;
    bool weakens() const { return mu_residual != law.mu; }
};

/// Series springs, the same value exactly when equal (no rounding): k_a when
/// k_a == k_b, else 2 k_a k_b / (k_a + k_b) [N/m].
inline double series_stiffness(double k_a, double k_b) {
    return k_a == k_b ? k_a : 2.0 * k_a * k_b / (k_a + k_b);
}

/// The pair law of materials a and b; `mu_peak`, `mu_residual` < 0: the
/// smaller of the two materials' (else the config's friction_pairs values).
inline PairLaw mix_materials(const MaterialLaw& a, const MaterialLaw& b, double mu_peak = -1.0,
                             double mu_residual = -1.0) {
    PairLaw p;
    p.law = a.law;  // damping kind and clamp are shared by all materials
    p.law.k_n = series_stiffness(a.law.k_n, b.law.k_n);
    p.law.k_s = series_stiffness(a.law.k_s, b.law.k_s);
    p.law.mu = mu_peak >= 0.0 ? mu_peak : std::min(a.law.mu, b.law.mu);
    p.law.cohesion = std::min(a.law.cohesion, b.law.cohesion);
    p.mu_residual = mu_residual >= 0.0 ? mu_residual : std::min(a.mu_residual, b.mu_residual);
    p.weakening_distance = a.weakening_distance == b.weakening_distance
                               ? a.weakening_distance
                               : 0.5 * (a.weakening_distance + b.weakening_distance);
    p.cohesion_loss = a.cohesion_loss || b.cohesion_loss;
    return p;
}

/// The weakened friction of a contact with mean damage `damage` [mean
/// diameters]: μ_peak − (μ_peak − μ_res) min(1, damage / d_w).
inline double weakened_mu(const PairLaw& p, double damage) {
    if (!p.weakens()) return p.law.mu;
    const double f = std::min(1.0, damage / p.weakening_distance);
    return p.law.mu - (p.law.mu - p.mu_residual) * f;
}

/// Every material of a run and the law of each ordered pair (a, b), row-major.
struct MaterialTable {
    std::vector<MaterialLaw> materials;  // by material id
    std::vector<PairLaw> pairs;          // pairs[a * n + b]
    double mean_diameter = 1.0;          // d̄ = r_min + r_max: the unit of damage [m]
    const PairLaw& pair(std::uint8_t a, std::uint8_t b) const { return pairs[a * materials.size() + b]; }
    bool any_weakening() const {
        return std::any_of(pairs.begin(), pairs.end(), [](const PairLaw& p) { return p.weakens(); });
    }
    bool any_cohesion_loss() const {
        return std::any_of(pairs.begin(), pairs.end(), [](const PairLaw& p) { return p.cohesion_loss && p.law.cohesion > 0.0; });
    }
    bool any_healing() const {
        return std::any_of(materials.begin(), materials.end(), [](const MaterialLaw& m) { return m.healing_rate > 0.0; });
    }
};

}  // namespace orodem
