// Several materials (physics/materials.hpp, engine/materials.cpp) on one
// contact whose geometry is prescribed: disc B (kinematic: inverse mass 0,
// a set velocity) slides along the tangent of fixed disc A at speed u, so
// the sliding distance is known from the kinematics alone (u t, less the
// elastic stretch μ F_n / k_s taken before sliding starts). Checked: the
// pair-law rules against their formulas; the damage a rebuild puts on each
// disc (half the slip, in mean diameters) against the kinematic distance;
// the friction after it (|F_t| / F_n) against the weakening formula; healing;
// cohesion lost for good once the contact slides, and kept without the
// option.
#include <gtest/gtest.h>

#include <cmath>

#include "orodem/engine/simulation.hpp"
#include "orodem/physics/materials.hpp"
#include "physics/default_disc.hpp"

using namespace orodem;
using namespace orodem::test;

namespace {

MaterialLaw material(double mu, double mu_res, double d_w, double cohesion = 0.0, bool loss = false) {
    MaterialLaw m;
    MaterialConfig mc;
    mc.mu = mu;
    mc.cohesion = cohesion;
    m.law = make_law(mc);
    m.density = kRho;
    m.mu_residual = mu_res;
    m.weakening_distance = d_w;
    m.cohesion_loss = loss;
    return m;
}

struct Sliding {
    Simulation sim;
    double u = 0.02;       // B's speed along the tangent [m/s]
    double d_bar = 1.5;    // mean diameter, the unit of damage [m]
    Vec2 tangent{0.0, 1.0};
};

/// A fixed at the origin, B to its right overlapping by 1% of R, both of
/// material 0 of `table`, B moving along +y at u.
void set_up(Sliding& s, const MaterialTable& table) {
    Simulation& sim = s.sim;
    const double delta = 0.01 * kR;  // [m]
    sim.particles.add({0.0, 0.0}, kR, kRho);
    sim.particles.add({2.0 * kR - delta, 0.0}, kR, kRho);
    sim.particles.fix(0);
    sim.particles.fix(1);
    sim.particles.v[1] = s.u * s.tangent;
    sim.particles.material.assign(2, 0);
    sim.particles.layer.assign(2, 0);
    sim.particles.damage.assign(2, 0.0);
    sim.params.law = default_law();
    sim.params.dt = default_dt();
    sim.params.gravity = {};
    sim.params.skin = 10.0 * kR;  // no rebuild unless asked: the test chooses when damage is updated
    sim.materials = table;
    sim.materials.mean_diameter = s.d_bar;
    sim.initialize();
}

/// Steps for a distance `dist` of B's travel [m] (u > 0); returns the steps taken.
std::uint64_t slide(Sliding& s, double dist) {
    const auto n = static_cast<std::uint64_t>(std::llround(dist / (s.u * s.sim.params.dt)));
    for (std::uint64_t k = 0; k < n; ++k) s.sim.step();
    return n;
}

/// F_n of the pair now, along its normal [N].
double normal_force(const Simulation& sim) {
    const Vec2 d = sim.pair_branch(0);
    return std::fabs(dot(sim.contacts.f[0], (1.0 / norm(d)) * d));
}

/// |F_t| / F_n of the pair now (the force on B from the fixed disc A).
double friction_ratio(const Simulation& sim) {
    const std::size_t k = 0;  // the only pair
    const Vec2 d = sim.pair_branch(k);
    const Vec2 n = (1.0 / norm(d)) * d;
    const Vec2 f = sim.contacts.f[k];
    const double f_n = dot(f, n);
    return norm(f - f_n * n) / std::fabs(f_n);
}

MaterialTable table_of(const MaterialLaw& m) {
    MaterialTable t;
    t.materials = {m};
    t.pairs = {mix_materials(m, m)};
    return t;
}

}  // namespace

TEST(Materials, PairRulesFollowTheirFormulas) {
    MaterialLaw a = material(0.6, 0.4, 1.0, 5.0), b = material(0.3, 0.3, 3.0, 2.0, true);
    b.law.k_n = 4.0e8;
    b.law.k_s = 1.0e8;
    const PairLaw p = mix_materials(a, b);
    EXPECT_DOUBLE_EQ(p.law.k_n, 2.0 * a.law.k_n * 4.0e8 / (a.law.k_n + 4.0e8));  // series springs
    EXPECT_DOUBLE_EQ(p.law.k_s, 2.0 * a.law.k_s * 1.0e8 / (a.law.k_s + 1.0e8));
    EXPECT_EQ(p.law.mu, 0.3);            // the weaker material's peak
    EXPECT_EQ(p.mu_residual, 0.3);
    EXPECT_EQ(p.law.cohesion, 2.0);
    EXPECT_EQ(p.weakening_distance, 2.0);
    EXPECT_TRUE(p.cohesion_loss);
    // Equal materials: the material's own values, bit for bit.
    const PairLaw same = mix_materials(a, a);
    EXPECT_EQ(same.law.k_n, a.law.k_n);
    EXPECT_EQ(same.law.k_s, a.law.k_s);
    // Named pair values win.
    EXPECT_EQ(mix_materials(a, b, 0.45, 0.2).law.mu, 0.45);
    EXPECT_EQ(mix_materials(a, b, 0.45, 0.2).mu_residual, 0.2);
    // Weakening: linear in damage, residual beyond d_w, peak without weakening.
    const PairLaw w = mix_materials(a, a);
    EXPECT_DOUBLE_EQ(weakened_mu(w, 0.0), 0.6);
    EXPECT_DOUBLE_EQ(weakened_mu(w, 0.25), 0.6 - 0.2 * 0.25);
    EXPECT_DOUBLE_EQ(weakened_mu(w, 5.0), 0.4);
    const PairLaw none = mix_materials(material(0.5, 0.5, 1.0), material(0.5, 0.5, 1.0));
    EXPECT_EQ(weakened_mu(none, 100.0), 0.5);
}

TEST(Materials, DamageIsHalfTheSlipInMeanDiametersAndWeakensTheFriction) {
    const double mu = 0.6, mu_res = 0.3, d_w = 0.01;  // d_w in mean diameters
    Sliding s;
    set_up(s, table_of(material(mu, mu_res, d_w)));
    const double travel = 0.02;  // [m]
    slide(s, travel);
    EXPECT_NEAR(friction_ratio(s.sim), mu, 1e-9);  // peak until damage is updated
    // The elastic stretch before sliding: μ F_n / k_s, F_n = k_n δ.
    const double f_n = normal_force(s.sim);
    const double stretch = mu * f_n / s.sim.params.law.k_s;
    const double expect = 0.5 * (travel - stretch) / s.d_bar;  // [mean diameters]
    s.sim.request_rebuild();
    s.sim.step();
    const std::size_t a = s.sim.particles.slot_of_id[0], b = s.sim.particles.slot_of_id[1];
    // 1%: the prescribed straight path opens the overlap by s²/(2 d) ≈ 2e-4 m
    // of 5e-3 m over the travel, so F_n and the stretch drift by a few percent
    // of a stretch that is itself 3% of the travel.
    EXPECT_NEAR(s.sim.particles.damage[a], expect, 0.01 * expect);
    EXPECT_EQ(s.sim.particles.damage[a], s.sim.particles.damage[b]);
    // The friction now follows the damage.
    slide(s, 0.001);
    const double D = s.sim.particles.damage[a];
    EXPECT_NEAR(friction_ratio(s.sim), mu - (mu - mu_res) * std::min(1.0, D / d_w), 1e-6);
    EXPECT_LT(friction_ratio(s.sim), mu - 0.1);  // really weakened (can fail)
}

TEST(Materials, HealingLowersTheDamageAtItsRate) {
    MaterialLaw m = material(0.6, 0.3, 1.0);
    m.healing_rate = 1e-3;  // [mean diameters / s]
    Sliding s;
    s.u = 0.0;  // no slip: healing only
    set_up(s, table_of(m));
    s.sim.particles.damage.assign(2, 0.5);
    const std::uint64_t n = 2000;
    for (std::uint64_t k = 0; k < n; ++k) s.sim.step();
    s.sim.request_rebuild();
    s.sim.step();
    // The rebuild updates the damage before the step's time advances: at
    // n dt since the first rebuild (at t = 0).
    const double t = s.sim.time - s.sim.params.dt;
    EXPECT_NEAR(s.sim.particles.damage[0], 0.5 - 1e-3 * t, 1e-14);
}

TEST(Materials, CohesionIsLostForGoodOnceTheContactSlides) {
    for (const bool loss : {true, false}) {
        SCOPED_TRACE(loss ? "cohesion_loss" : "no cohesion_loss");
        const double C = 2.0e3;  // [N], about 0.4 of μ F_n here
        Sliding s;
        set_up(s, table_of(material(0.6, 0.6, 1.0, C, loss)));
        slide(s, 0.01);
        const double f_n = normal_force(s.sim);
        // Sliding with cohesion: |F_t| = μ F_n + C.
        EXPECT_NEAR(friction_ratio(s.sim) * f_n, 0.6 * f_n + C, 1e-6 * C);
        s.sim.request_rebuild();
        s.sim.step();
        EXPECT_EQ(s.sim.cohesion_lost().size(), loss ? 1u : 0u);
        slide(s, 0.005);
        const double f_n2 = normal_force(s.sim);
        EXPECT_NEAR(friction_ratio(s.sim) * f_n2, 0.6 * f_n2 + (loss ? 0.0 : C), 1e-6 * C);
    }
}
