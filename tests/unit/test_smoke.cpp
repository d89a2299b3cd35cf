#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace orodem;

// Newton's third law and a non-zero force for two overlapping discs at rest.
TEST(ContactLaw, PairForcesAreEqualAndOpposite) {
    LawParams law;
    law.k_n = 1000.0;
    law.k_s = 1000.0;
    law.mu = 0.5;
    Simulation sim = test::make_sim({{{0.0, 0.0}, 1.0}, {{1.9, 0.0}, 1.0}}, law, 1e-3);
    sim.initialize();
    const auto& p = sim.particles;
    const Vec2 f0 = p.force[p.slot_of_id[0]], f1 = p.force[p.slot_of_id[1]];
    EXPECT_NEAR(f0.x, -100.0, 1e-9);  // k_n δ = 1000 × 0.1 pushes disc 0 to -x
    EXPECT_DOUBLE_EQ(f0.x, -f1.x);
    EXPECT_DOUBLE_EQ(f0.y, 0.0);
}
