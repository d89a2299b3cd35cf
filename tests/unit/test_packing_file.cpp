// The packing cache's reader (io/packing_file.hpp) on files that pass the
// checksum but hold values no settled layer has: each is refused with its
// reason (the run settles again), never used; an intact file round-trips.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "orodem/io/packing_file.hpp"

using namespace orodem;

namespace {

ParticleStore two_discs() {
    ParticleStore p;
    p.add({1.0, 1.0}, 0.5, 2500.0, 0);
    p.add({2.0, 1.0}, 0.6, 2500.0, 0);
    return p;
}

std::string why_refused(const ParticleStore& p) {
    std::string why;
    EXPECT_FALSE(decode_packing(encode_packing(p, 7), 7, 2500.0, &why).has_value());
    return why;
}

}  // namespace

TEST(PackingFile, IntactRoundTrip) {
    const ParticleStore p = two_discs();
    const auto q = decode_packing(encode_packing(p, 7), 7, 2500.0);
    ASSERT_TRUE(q.has_value());
    ASSERT_EQ(q->size(), 2u);
    EXPECT_EQ(q->radius[1], 0.6);
    std::string why;
    EXPECT_FALSE(decode_packing(encode_packing(p, 7), 8, 2500.0, &why).has_value());
    EXPECT_EQ(why, "made from other parameters");
}

TEST(PackingFile, ValuesNoLayerHasAreRefusedDespiteAValidChecksum) {
    ParticleStore p = two_discs();
    p.radius[0] = 0.0;
    EXPECT_NE(why_refused(p).find("radius"), std::string::npos);
    p = two_discs();
    p.radius[1] = -0.5;
    EXPECT_NE(why_refused(p).find("radius"), std::string::npos);
    p = two_discs();
    p.x[0].x = 1e300;
    EXPECT_NE(why_refused(p).find("not a position"), std::string::npos);
    p = two_discs();
    p.x[1].y = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(why_refused(p).find("not a position"), std::string::npos);
    p = two_discs();
    p.cluster[0] = 2000000000;
    EXPECT_NE(why_refused(p).find("cluster id"), std::string::npos);
    p = two_discs();
    p.cluster[1] = -7;
    EXPECT_NE(why_refused(p).find("cluster id"), std::string::npos);
    p = two_discs();
    p.initial_depth[0] = std::numeric_limits<double>::infinity();
    EXPECT_NE(why_refused(p).find("initial depth"), std::string::npos);
}
