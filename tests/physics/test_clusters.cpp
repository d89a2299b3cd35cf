// 3-disc clusters ([36]-[37]; SPEC §1): the three intra-cluster pairs are
// permanent bonds, obeying the normal law for every δ (attractive in
// tension), so a cluster keeps its shape under load and never breaks up.
//
// Set-up: a layer of random clusters (generate_packing, kind "clusters") is
// settled in the settling box under normal gravity, then loaded by ramping
// gravity up ("strong gravity") to g_load, chosen so that the mean floor
// pressure P = M g_load / L equals 1e-3 k_n. For a packing of discs of size
// ~2R the mean contact force is ~ P·2R, hence the mean contact strain
// δ/(R_i + R_j) ~ P/k_n = 1e-3: a firm load (the force network's tails carry
// a few times the mean), yet bonds that obey the linear law stay well inside
// the 1% limit. A bond that could not take tension (or broke) would open
// without bound, since the load also puts some bonds in tension.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"

using namespace orodem;

namespace {

struct BondStrain {
    double max_abs = 0.0;       // max |d - (R_i + R_j)| / (R_i + R_j)
    double max_stretch = -1.0;  // max (d - (R_i + R_j)) / (R_i + R_j) (> 0: tension)
    std::size_t bonds = 0;      // bonded entries in the contact list
};

BondStrain bond_strain(const Simulation& sim) {
    const ParticleStore& p = sim.particles;
    const ContactStore& cs = sim.contacts;
    BondStrain b;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        if (!cs.bonded[k]) continue;
        const std::uint32_t i = cs.i[k], j = cs.j[k];
        const double rsum = p.radius[i] + p.radius[j];
        const double d = norm(p.x[i] - p.x[j]);  // the settling box is not periodic
        b.max_abs = std::max(b.max_abs, std::fabs(d - rsum) / rsum);
        b.max_stretch = std::max(b.max_stretch, (d - rsum) / rsum);
        ++b.bonds;
    }
    return b;
}

}  // namespace

TEST(Clusters, BondsHoldUnderStrongGravity) {
    Config c;
    c.material.density = 2500.0;  // [kg/m³]
    c.material.k_n = 1.0e9;       // [N/m]: stiff enough that 1 g gives a mean strain of only ~2e-4
    c.material.k_s_over_k_n = 1.0 / 3.0;
    c.material.mu = 0.3;
    c.packing.r_min = 0.5;     // [m]
    c.packing.r_max = 1.0;     // [m]
    c.numerics.gravity = 9.81;
    c.packing.kind = PackingKind::clusters;
    c.packing.length = 20.0;   // [m]
    c.packing.h0 = 6.0;        // [m]: ~30 clusters
    c.packing.seed = 1;
    Simulation sim = make_settle_simulation(c);
    const ParticleStore& p = sim.particles;
    ASSERT_EQ(p.size() % 3, 0u);
    const std::size_t n_clusters = p.size() / 3;
    for (std::size_t s = 0; s < p.size(); ++s) ASSERT_GE(p.cluster[s], 0);
    sim.initialize();
    ASSERT_EQ(sim.bonds.bond_count(), 3 * n_clusters);

    // Generation places each cluster's discs exactly touching.
    EXPECT_LT(bond_strain(sim).max_abs, 1e-12);

    settle(sim, c.packing, 0.05, nullptr);
    const BondStrain settled = bond_strain(sim);

    double M = 0.0;
    for (std::size_t s = 0; s < p.size(); ++s) M += p.mass[s];
    const double g = c.numerics.gravity;
    const double g_load = 1.0e-3 * c.material.k_n * c.packing.length / M;
    ASSERT_GT(g_load, 3.0 * g) << "the load should be well above the settling gravity";

    // Ramp g -> g_load linearly over 2000 steps (0.16 s, several periods of the
    // layer's slowest vertical mode, so the overshoot is mild), hold for 2000
    // more; every step, measure every bond.
    const int ramp = 2000, hold = 2000;
    BondStrain worst;
    std::size_t min_bonds = sim.contacts.size();
    for (int k = 0; k < ramp + hold; ++k) {
        const double f = std::min(1.0, (k + 1.0) / ramp);
        sim.params.gravity = {0.0, -(g + (g_load - g) * f)};
        sim.step();
        const BondStrain b = bond_strain(sim);
        worst.max_abs = std::max(worst.max_abs, b.max_abs);
        worst.max_stretch = std::max(worst.max_stretch, b.max_stretch);
        min_bonds = std::min(min_bonds, b.bonds);
    }
    const BondStrain end = bond_strain(sim);
    std::printf("[ clusters ] %zu clusters, g_load = %.2f g (P/k_n = 1e-3), max unbonded δ/min(R_i,R_j) "
                "at the end %.2e\n[ clusters ] bond strain |d - (Ri+Rj)|/(Ri+Rj): settled %.2e, "
                "max during load %.2e (max stretch %.2e), at the end %.2e\n",
                n_clusters, g_load / g, sim.max_overlap_ratio(), settled.max_abs, worst.max_abs,
                worst.max_stretch, end.max_abs);

    // Every bond stayed in the contact list (the builder lists all of them
    // at every rebuild, whatever their length).
    EXPECT_EQ(min_bonds, 3 * n_clusters);
    // The requirement: bond lengths within 1% of R_i + R_j throughout.
    EXPECT_LT(worst.max_abs, 0.01);
    // The load was felt and put some bonds in tension: they held (attraction).
    EXPECT_GT(worst.max_stretch, 0.0);
    EXPECT_LT(worst.max_stretch, 0.01);
    // Every cluster is still one piece: each disc within 1% of touching both
    // partners (a separated cluster would have drifted apart).
    for (std::int32_t cl = 0; cl < static_cast<std::int32_t>(n_clusters); ++cl) {
        std::size_t members[3], m = 0;
        for (std::size_t s = 0; s < p.size() && m < 3; ++s)
            if (p.cluster[s] == cl) members[m++] = s;
        ASSERT_EQ(m, 3u);
        for (int a = 0; a < 3; ++a)
            for (int b = a + 1; b < 3; ++b) {
                const std::size_t i = members[a], j = members[b];
                const double rsum = p.radius[i] + p.radius[j];
                EXPECT_LT(std::fabs(norm(p.x[i] - p.x[j]) - rsum) / rsum, 0.01) << "cluster " << cl;
            }
    }
}
