// Linear spring-dashpot contact law with tangential history and a Coulomb
// limit (SPEC §1; paper eqs. 1-3, [23]-[25], [37]). Pure functions on values:
// no arrays, no state, so every branch can be tested against analytic results.
//
// Conventions for a pair (i, j): n̂ is the unit vector from j to i, the
// overlap δ = R_i + R_j - |x_i - x_j| > 0 while touching. The result is the
// force on i (j gets the opposite) and c = n̂ × F_t, from which the torques are
// τ_i = -R_i c and τ_j = -R_j c. Walls use the same law with R_j = ∞, the
// wall's velocity as v_j and no wall spin.
//
// Tangential history ξ is a 2-vector in the contact's tangent line: each step
// ξ += v_t dt and is then projected onto the current tangent line (ξ -= (ξ·n̂)n̂),
// the standard form of LAMMPS gran/hooke/history. For the small rotation of n̂
// in one step this equals the scalar ξ of SPEC §1 to second order in the
// rotation angle. On sliding ξ is rescaled so that |k_s ξ + γ_s v_t| = F_max.
//
// Damping: γ = damp_mass·m_eff + damp_sqrt·sqrt(m_eff). A damping ratio ζ
// gives damp_sqrt = 2ζ sqrt(k); the benchmark's raw coefficient γ̃ (F = m_eff γ̃ v)
// gives damp_mass = γ̃. One law, two parameterisations.
#pragma once

#include <cmath>

#include "orodem/core/vec2.hpp"

namespace orodem {

struct LawParams {
    double k_n = 0.0;          // normal spring [N/m]
    double k_s = 0.0;          // tangential spring [N/m]; 0 with smooth = frictionless
    double mu = 0.0;           // Coulomb coefficient μ = tan φ [-]
    double cohesion = 0.0;     // C: Coulomb limit F_max = μ|F_n| + C [N]
    double damp_mass_n = 0.0;  // γ_n contribution per unit m_eff [1/s]
    double damp_sqrt_n = 0.0;  // γ_n contribution per unit sqrt(m_eff) [sqrt(kg)/s]
    double damp_mass_s = 0.0;  // same for the tangential dashpot [1/s]
    double damp_sqrt_s = 0.0;  // [sqrt(kg)/s]
    bool clamp_normal = true;  // an unbonded contact never attracts (F_n >= 0)
    bool tangential = true;    // false: smooth (no tangential force, no history)
};

/// Kinematics of one touching pair, all in the frame of the contact.
struct PairKinematics {
    Vec2 n;            // unit normal from j to i
    double delta;      // overlap δ [m] (>0 touching; may be <0 for a stretched bond)
    Vec2 v_rel;        // v_i - v_j [m/s]
    double spin;       // R_i ω_i + R_j ω_j [m/s]
    double m_eff;      // m_i m_j / (m_i + m_j) [kg]
};

struct PairForce {
    Vec2 f;            // force on i [N]
    double c;          // n̂ × F_t [N]; torque on i is -R_i c, on j -R_j c
    double f_n;        // signed normal force magnitude along n̂ [N]
};

/// Damping ratio ζ of a linear spring-dashpot with restitution e (0 < e ≤ 1):
/// e = exp(-ζπ/sqrt(1-ζ²))  =>  ζ = -ln e / sqrt(π² + ln² e).
inline double damping_ratio_from_restitution(double e) {
    const double le = std::log(e);
    return -le / std::sqrt(M_PI * M_PI + le * le);
}

/// Evaluates the law for one step of length dt and updates the history ξ.
/// `bonded`: a permanent cluster bond: the normal law holds for all δ (it
/// attracts in tension, [37]) and the tangential spring has no Coulomb limit.
///
/// The step update of ξ happens only when kUpdateHistory is true; at set-up
/// (forces at t = 0) the law is evaluated on a copy so ξ is untouched.
template <bool kBonded>
inline PairForce eval_contact(const LawParams& p, const PairKinematics& k, double dt, Vec2& xi) {
    const Vec2 n = k.n;
    const double v_n = dot(k.v_rel, n);
    // Tangential relative velocity of the contact points:
    // (v_i - v_j) - v_n n̂ + (R_i ω_i + R_j ω_j)(n_y, -n_x).
    const Vec2 v_t = k.v_rel - v_n * n + k.spin * Vec2{n.y, -n.x};

    double gamma_n = p.damp_mass_n * k.m_eff;
    if (p.damp_sqrt_n != 0.0) gamma_n += p.damp_sqrt_n * std::sqrt(k.m_eff);
    double f_n = p.k_n * k.delta - gamma_n * v_n;
    if (!kBonded && p.clamp_normal && f_n < 0.0) f_n = 0.0;

    Vec2 f_t{};
    if (p.tangential) {
        xi += dt * v_t;
        xi -= dot(xi, n) * n;  // keep ξ in the current tangent line
        double gamma_s = p.damp_mass_s * k.m_eff;
        if (p.damp_sqrt_s != 0.0) gamma_s += p.damp_sqrt_s * std::sqrt(k.m_eff);
        f_t = -p.k_s * xi - gamma_s * v_t;
        if (!kBonded) {
            const double f_max = p.mu * std::fabs(f_n) + p.cohesion;
            const double ft2 = norm2(f_t);
            if (ft2 > f_max * f_max) {
                // Sliding: scale F_t onto the limit and ξ so the spring alone
                // (plus the dashpot) sits on it.
                const double ratio = f_max / std::sqrt(ft2);
                const Vec2 damp_part = (gamma_s / p.k_s) * v_t;
                xi = ratio * (xi + damp_part) - damp_part;
                f_t = ratio * f_t;
            }
        }
    }
    return {f_n * n + f_t, cross(n, f_t), f_n};
}

}  // namespace orodem

namespace orodem {

/// The result of the base spring for one disc and one step.
struct BaseSpringForce {
    double f;       // tangential force on the disc along the base direction û [N]
    bool sliding;   // true: |F_t| was capped at μ N this step
};

/// The Coulomb base law (SPEC §2; boundary/coulomb_base.hpp): a spring-slider
/// between a disc's centre and the belt surface, along the base direction û.
/// slip = v_i·û − v' is the disc centre's velocity relative to the belt [m/s];
/// ξ (along û) += slip dt; F = −k_s ξ − γ_s slip, limited by μ N (N the
/// base's normal force on the disc, ≥ 0). On sliding ξ is rescaled as in
/// eval_contact, so the spring plus the dashpot sits on the limit and the
/// disc slides with friction μ N. A disc whose force stays below μ N never
/// slips: its centre moves at v' up to the spring's elastic stretch ξ ≤ μ N / k_s.
inline BaseSpringForce eval_base_spring(double k_s, double gamma_s, double mu, double normal, double slip,
                                        double dt, double& xi) {
    xi += dt * slip;
    double f = -k_s * xi - gamma_s * slip;
    const double f_max = mu * normal;
    if (std::fabs(f) > f_max) {
        const double ratio = f_max / std::fabs(f);
        const double damp_part = (gamma_s / k_s) * slip;
        xi = ratio * (xi + damp_part) - damp_part;
        f = ratio * f;
        return {f, true};
    }
    return {f, false};
}

}  // namespace orodem
