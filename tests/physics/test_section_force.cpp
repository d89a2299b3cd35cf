// analysis/section_force: the force transmitted across a vertical section.
//
// Reference 1 (sign and bookkeeping): two hand-made pairs across x = 0.
// Reference 2 (independent): Newton's third law over the engine's own
// gather. For the discs L left of the section, the total force the step
// summed, Σ_L F_i (particles.force), is Σ_L m_i g + Σ_L (their wall
// contacts) + the force of the right part on L; pairs inside L cancel. So
// the force of L on the right part is −(Σ_L F_i − Σ_L m_i g − Σ_L walls),
// at any instant, settled or not; it must equal section_force to round-off
// of the sums (relative 1e-9 of the summed magnitudes). A packing of clusters
// has bonds across the section too.
#include <gtest/gtest.h>

#include <cmath>

#include "orodem/analysis/section_force.hpp"
#include "orodem/setup/scenario.hpp"

using namespace orodem;

TEST(SectionForce, SignsOfHandMadePairs) {
    ParticleStore p;
    p.x = {{-1.0, 0.0}, {1.0, 0.0}, {2.0, 0.0}, {-0.5, 3.0}};
    ContactStore c;
    c.i = {0, 2, 1};
    c.j = {1, 3, 2};
    c.shift = {0, 0, 0};
    // pair 0: i left, j right, repulsion pushes i in -x: the right disc gets +5.
    // pair 1: i right, j left: f on i is +3 in x, +1 in y.
    // pair 2: both right: not counted.
    c.f = {{-5.0, 0.0}, {3.0, 1.0}, {100.0, 100.0}};
    const Vec2 s = section_force(p, c, 0.0, 0.0);
    EXPECT_EQ(s.x, 8.0);
    EXPECT_EQ(s.y, 1.0);
    // A periodic image moves disc 3 to the right of the section: pair 1 no longer crosses.
    c.shift = {0, 1, 0};
    EXPECT_EQ(section_force(p, c, 0.0, 10.0).x, 5.0);
}

TEST(SectionForce, EqualsTheMomentumBalanceOfTheLeftPart) {
    Config c;
    c.material.density = 2500.0;  // [kg/m³]
    c.material.k_n = 1.0e8;       // [N/m]
    c.material.k_s_over_k_n = 1.0 / 3.0;
    c.material.mu = 0.3;
    c.packing.kind = PackingKind::clusters;
    c.packing.r_min = 0.5;    // [m]
    c.packing.r_max = 1.0;    // [m]
    c.packing.length = 20.0;  // [m]
    c.packing.h0 = 6.0;       // [m]
    c.packing.seed = 4;
    c.numerics.gravity = 9.81;
    Simulation sim = make_settle_simulation(c);
    sim.initialize();
    for (int n = 0; n < 4000; ++n) sim.step();  // falling and piling up: the identity holds at any instant
    const ParticleStore& p = sim.particles;
    const Vec2 g{0.0, -c.numerics.gravity};
    int bonds_across = 0;
    for (const double x_c : {5.0, 10.0, 13.3}) {
        SCOPED_TRACE(x_c);
        Vec2 left{}, scale{};
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (!(p.x[i].x < x_c)) continue;
            Vec2 walls{};
            for (std::uint32_t k = sim.wall_contacts.begin[i]; k < sim.wall_contacts.begin[i + 1]; ++k)
                walls += sim.wall_contacts.f[k];
            left += p.force[i] - p.mass[i] * g - walls;
            scale += Vec2{std::fabs(p.force[i].x) + std::fabs(walls.x), std::fabs(p.force[i].y) + p.mass[i] * 9.81};
        }
        for (std::size_t k = 0; k < sim.contacts.i.size(); ++k)
            if (sim.contacts.bonded[k] && (p.x[sim.contacts.i[k]].x < x_c) != (p.x[sim.contacts.j[k]].x < x_c))
                ++bonds_across;
        const Vec2 s = section_force(p, sim.contacts, x_c, 0.0);
        // The layer presses sideways: a real, compressive push of the order of
        // the lateral earth pressure, not zero.
        EXPECT_GT(std::fabs(s.x), 1e-3 * scale.y);
        EXPECT_NEAR(s.x, -left.x, 1e-9 * (scale.x + scale.y));
        EXPECT_NEAR(s.y, -left.y, 1e-9 * (scale.x + scale.y));
    }
    EXPECT_GT(bonds_across, 0);
}
