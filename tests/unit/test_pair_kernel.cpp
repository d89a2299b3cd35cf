// The SIMD pair kernel (engine/pair_kernel.cpp) against the plain per-pair
// loop it replaced (eval_contact() on one pair at a time), bit for bit: the
// forces f, c and the updated history ξ. The pairs cover every branch of the law: not touching,
// touching, sliding (large random ξ), bonded (clusters, in tension and
// compression), fixed discs (infinite mass), periodic images; and every law
// variant: the benchmark's (raw damping, no clamp), damping ratio (sqrt of
// m_eff) with the clamp, a tangential dashpot and cohesion, and a smooth law.
// Ranges of every length mod 8 exercise the block tails, in every kernel
// version the CPU runs (eight lanes in the AVX-512 one). The gather (phase
// B) is checked the same way against the plain per-disc sums and half kick.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "orodem/core/rng.hpp"
#include "orodem/engine/pair_kernel.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/neighbor/pair_builder.hpp"

using namespace orodem;

namespace {

/// The loop of Simulation::step() before the SIMD kernel, for one pair.
void reference_pair(const ParticleStore& p, ContactStore& cs, std::size_t k, double W, double dt,
                    const LawParams& law, bool update_history) {
    const std::uint32_t i = cs.i[k], j = cs.j[k];
    const Vec2 d = p.x[i] - (p.x[j] + Vec2{cs.shift[k] * W, 0.0});
    const double r2 = norm2(d);
    const double rsum = p.radius[i] + p.radius[j];
    const bool bonded = cs.bonded[k] != 0;
    if (!bonded && r2 >= rsum * rsum) {
        if (update_history) cs.xi[k] = {};
        cs.f[k] = {};
        cs.c[k] = 0.0;
        return;
    }
    const double r = std::sqrt(r2);
    const double mi = p.mass[i], mj = p.mass[j];
    const double m_eff = p.inv_mass[j] == 0.0 ? mi : p.inv_mass[i] == 0.0 ? mj : mi * mj / (mi + mj);
    const PairKinematics kin{(1.0 / r) * d, rsum - r, p.v[i] - p.v[j],
                             p.radius[i] * p.omega[i] + p.radius[j] * p.omega[j], m_eff};
    Vec2 xi = cs.xi[k];
    const PairForce pf = bonded ? eval_contact<true>(law, kin, dt, xi) : eval_contact<false>(law, kin, dt, xi);
    if (update_history) cs.xi[k] = xi;
    cs.f[k] = pf.f;
    cs.c[k] = pf.c;
}

struct PairSet {
    ParticleStore p;
    ContactStore cs;
    double W = 24.0;
};

/// A dense random packing (clusters and lone discs, overlapping), periodic in
/// x, with random velocities, spins, a few fixed discs and random history.
PairSet make_setup(std::uint64_t seed) {
    Rng rng(seed);
    PairSet s;
    const double H = 12.0;
    for (int c = 0; c < 40; ++c) {  // 2-disc clusters: bonds, stretched or compressed
        const Vec2 x0{rng.uniform(0.0, s.W), rng.uniform(0.0, H)};
        const double r0 = rng.uniform(0.3, 0.8), r1 = rng.uniform(0.3, 0.8);
        const double gap = (r0 + r1) * rng.uniform(0.9, 1.1);
        const double a = rng.uniform(0.0, 2.0 * M_PI);
        s.p.add(x0, r0, 1.0, c);
        s.p.add(x0 + gap * Vec2{std::cos(a), std::sin(a)}, r1, 1.0, c);
    }
    for (int k = 0; k < 500; ++k) s.p.add({rng.uniform(0.0, s.W), rng.uniform(0.0, H)}, rng.uniform(0.3, 0.8), 1.0);
    for (std::size_t i = 0; i < s.p.size(); ++i) {
        s.p.v[i] = {rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)};
        s.p.omega[i] = rng.uniform(-5.0, 5.0);
    }
    for (std::size_t i = 0; i < s.p.size(); i += 37) s.p.fix(i);
    s.p.rebuild_slot_map();
    const BondTopology bonds = build_bond_topology(s.p);
    WallContactStore ws;
    PairBuilder builder;
    builder.rebuild(s.p, bonds, {}, {0.3, true, s.W}, s.cs, ws);
    for (auto& xi : s.cs.xi) xi = {rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05)};
    return s;
}

LawParams bench_law() {
    LawParams l;
    l.k_n = 1.0e5;
    l.k_s = 2.0 / 7.0 * l.k_n;
    l.mu = 0.3;
    l.damp_mass_n = 200.0;
    l.clamp_normal = false;
    return l;
}

LawParams ratio_law() {
    LawParams l;
    l.k_n = 2.0e5;
    l.k_s = 0.5e5;
    l.mu = 0.5;
    l.cohesion = 3.0;
    l.damp_sqrt_n = 2.0 * 0.3 * std::sqrt(l.k_n);
    l.damp_sqrt_s = 2.0 * 0.2 * std::sqrt(l.k_s);
    l.damp_mass_s = 10.0;
    return l;
}

LawParams smooth_law() {
    LawParams l = ratio_law();
    l.tangential = false;
    l.k_s = 0.0;
    return l;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

/// The kernel versions this CPU runs (each test restores the best one).
std::vector<KernelIsa> runnable_isas() {
    std::vector<KernelIsa> v = {KernelIsa::sse2};
    if (best_kernel_isa() != KernelIsa::sse2) v.push_back(KernelIsa::avx2);
    if (best_kernel_isa() == KernelIsa::avx512) v.push_back(KernelIsa::avx512);
    return v;
}

TEST(PairKernel, BitIdenticalToThePerPairLoop) {
    // In every kernel version (four lanes, and eight in the AVX-512 one).
    ASSERT_TRUE(zero_gamma_s(bench_law()));  // so the null γ_s column is exercised
    ASSERT_FALSE(zero_gamma_s(ratio_law()));
    for (const KernelIsa isa : runnable_isas()) {
    SCOPED_TRACE(isa_name(isa));
    select_kernel_isa(isa_name(isa));
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        for (const LawParams& law : {bench_law(), ratio_law(), smooth_law()}) {
            for (const bool update : {true, false}) {
                const PairSet s = make_setup(seed);
                const std::size_t n = s.cs.size();
                ASSERT_GT(n, 500u);
                const double dt = 1e-4;
                ContactStore want = s.cs;
                for (std::size_t k = 0; k < n; ++k) reference_pair(s.p, want, k, s.W, dt, law, update);
                // Ranges whose lengths take every residue mod 8 over the seeds.
                ContactStore got = s.cs;
                // No γ_s column when the law has no tangential dashpot (the
                // bench law; the engine's case): null reads as +0.
                std::vector<double> gn(n), gs(n);
                double* const gs_col = zero_gamma_s(law) ? nullptr : gs.data();
                pair_dashpots(law, s.p.mass.data(), s.p.inv_mass.data(), 0.0, got.i.data(), got.j.data(), 0, n, gn.data(),
                              gs_col);
                std::vector<double> ri(n), rj(n);
                pair_radii(s.p.radius.data(), got.i.data(), got.j.data(), 0, n, ri.data(), rj.data());
                const PairKernelData kd{s.p.x.data(),  s.p.v.data(),      s.p.omega.data(), ri.data(), rj.data(),
                                        got.i.data(),  got.j.data(),      got.shift.data(), got.bonded.data(),
                                        gn.data(),     gs_col,            got.xi.data(),    got.f.data(),
                                        got.c.data(),  s.W,               dt,               law,
                                        update,        s.p.size()};
                const std::size_t cuts[] = {0, 5 + seed, 18 + 3 * seed, 101 + seed, n / 2 + 2 * seed, n};
                for (std::size_t c = 0; c + 1 < std::size(cuts); ++c) eval_pair_range(kd, cuts[c], cuts[c + 1]);
                EXPECT_TRUE(same_bits(got.f, want.f)) << "seed " << seed;
                EXPECT_TRUE(same_bits(got.c, want.c)) << "seed " << seed;
                EXPECT_TRUE(same_bits(got.xi, want.xi)) << "seed " << seed;
            }
        }
    }
    }
    select_kernel_isa(nullptr);
}

namespace {
/// A variant of `base` with other springs, friction and cohesion and the
/// same damping ratios (so the same dashpot kind): a second material.
LawParams material_variant(const LawParams& base, double k_scale, double mu, double cohesion) {
    LawParams l = base;
    l.k_n = base.k_n * k_scale;
    l.k_s = base.k_s * k_scale;
    l.mu = mu;
    l.cohesion = cohesion;
    if (base.damp_sqrt_n != 0.0) l.damp_sqrt_n = base.damp_sqrt_n * std::sqrt(k_scale);
    if (base.damp_sqrt_s != 0.0) l.damp_sqrt_s = base.damp_sqrt_s * std::sqrt(k_scale);
    return l;
}
}  // namespace

TEST(PairKernel, PerPairLawsBitIdenticalToThePerPairLoop) {
    // Several materials (PairKernelData::k_n_pair ...): each pair's own law
    // from the columns gives, bit for bit, eval_contact with that law; the
    // plastic slip recorded is what the Coulomb rescaling took off |ξ + the
    // dashpot part| (for no tangential dashpot, |ξ_trial| − F_max / k_s),
    // and a pair with history that no longer touches is marked.
    for (const KernelIsa isa : runnable_isas()) {
        SCOPED_TRACE(isa_name(isa));
        select_kernel_isa(isa_name(isa));
        for (const std::uint64_t seed : {1u, 2u, 3u}) {
            for (const LawParams& base : {bench_law(), ratio_law()}) {
                const LawParams laws[3] = {base, material_variant(base, 3.0, 0.1, 0.0),
                                           material_variant(base, 0.5, 0.7, 2.0)};
                const PairSet s = make_setup(seed);
                const std::size_t n = s.cs.size();
                const double dt = 1e-4;
                std::vector<std::size_t> which(n);
                for (std::size_t k = 0; k < n; ++k) which[k] = (s.cs.i[k] * 7 + s.cs.j[k]) % 3;
                ContactStore want = s.cs;
                for (std::size_t k = 0; k < n; ++k) reference_pair(s.p, want, k, s.W, dt, laws[which[k]], true);
                ContactStore got = s.cs;
                std::vector<double> gn(n), gs(n), kn(n), ks(n), mu(n), coh(n), slip(n, 0.0), ri(n), rj(n);
                std::vector<std::uint8_t> broke(n, 0);
                double* const gs_col = zero_gamma_s(base) ? nullptr : gs.data();
                for (std::size_t k = 0; k < n; ++k) {
                    const LawParams& l = laws[which[k]];
                    pair_dashpots(l, s.p.mass.data(), s.p.inv_mass.data(), 0.0, got.i.data(), got.j.data(), k, k + 1,
                                  gn.data(), gs_col);
                    kn[k] = l.k_n, ks[k] = l.k_s, mu[k] = l.mu, coh[k] = l.cohesion;
                }
                pair_radii(s.p.radius.data(), got.i.data(), got.j.data(), 0, n, ri.data(), rj.data());
                PairKernelData kd{s.p.x.data(),  s.p.v.data(),      s.p.omega.data(), ri.data(), rj.data(),
                                  got.i.data(),  got.j.data(),      got.shift.data(), got.bonded.data(),
                                  gn.data(),     gs_col,            got.xi.data(),    got.f.data(),
                                  got.c.data(),  s.W,               dt,               base,
                                  true,          s.p.size()};
                kd.k_n_pair = kn.data();
                kd.k_s_pair = ks.data();
                kd.mu_pair = mu.data();
                kd.cohesion_pair = coh.data();
                kd.slip = slip.data();
                kd.broke = broke.data();
                const std::size_t cuts[] = {0, 3 + seed, 21 + 3 * seed, 99 + seed, n / 2 + 2 * seed, n};
                for (std::size_t c = 0; c + 1 < std::size(cuts); ++c) eval_pair_range(kd, cuts[c], cuts[c + 1]);
                EXPECT_TRUE(same_bits(got.f, want.f)) << "seed " << seed;
                EXPECT_TRUE(same_bits(got.c, want.c)) << "seed " << seed;
                EXPECT_TRUE(same_bits(got.xi, want.xi)) << "seed " << seed;
                std::size_t sliding = 0, separated = 0;
                for (std::size_t k = 0; k < n; ++k) {
                    const Vec2 xi0 = s.cs.xi[k];
                    const bool touching = want.f[k].x != 0.0 || want.f[k].y != 0.0 || s.cs.bonded[k];
                    EXPECT_EQ(broke[k], (!touching && (xi0.x != 0.0 || xi0.y != 0.0)) ? 1 : 0) << k;
                    separated += broke[k];
                    if (!touching || s.cs.bonded[k] || !zero_gamma_s(base)) continue;
                    // No tangential dashpot: the trial ξ (projected) against the kept one.
                    const Vec2 d = s.p.x[s.cs.i[k]] - (s.p.x[s.cs.j[k]] + Vec2{s.cs.shift[k] * s.W, 0.0});
                    const Vec2 nn = (1.0 / norm(d)) * d;
                    const Vec2 vr = s.p.v[s.cs.i[k]] - s.p.v[s.cs.j[k]];
                    const double spin = s.p.radius[s.cs.i[k]] * s.p.omega[s.cs.i[k]] +
                                        s.p.radius[s.cs.j[k]] * s.p.omega[s.cs.j[k]];
                    const Vec2 vt = vr - dot(vr, nn) * nn + spin * Vec2{nn.y, -nn.x};
                    Vec2 trial = xi0 + dt * vt;
                    trial -= dot(trial, nn) * nn;
                    const double expect = norm(trial) - norm(want.xi[k]);
                    EXPECT_NEAR(slip[k], expect, 1e-12 + 1e-9 * norm(trial)) << k;
                    sliding += slip[k] > 0.0 ? 1 : 0;
                }
                if (zero_gamma_s(base)) {
                    EXPECT_GT(sliding, 20u);
                }
                EXPECT_GT(separated, 20u);
            }
        }
    }
    select_kernel_isa(nullptr);
}

TEST(PairKernel, GatherBitIdenticalToThePlainSums) {
    // Phase B against: f = m g; f += f_k over owned pairs; f -= f_k over
    // incoming pairs (in_pair order); t likewise; then the half kick. In
    // every kernel version (the AVX ones take four discs a time), for
    // gravity with x = -0.0 too: a disc with no pairs keeps f_x = -0.0 only
    // if a masked slot adds exactly -0.0.
    for (const KernelIsa isa : runnable_isas())
    for (const Vec2 g : {Vec2{0.3, -9.81}, Vec2{-0.0, -9.81}})
    for (const std::uint64_t seed : {4u, 5u}) {
        SCOPED_TRACE(isa_name(isa));
        select_kernel_isa(isa_name(isa));
        PairSet s = make_setup(seed);
        const LawParams law = bench_law();
        const double dt = 1e-4;
        const std::size_t n = s.p.size(), m = s.cs.size();
        std::vector<double> gn(m), gs(m);
        pair_dashpots(law, s.p.mass.data(), s.p.inv_mass.data(), 0.0, s.cs.i.data(), s.cs.j.data(), 0, m, gn.data(),
                      gs.data());
        std::vector<double> ri(m), rj(m);
        pair_radii(s.p.radius.data(), s.cs.i.data(), s.cs.j.data(), 0, m, ri.data(), rj.data());
        const PairKernelData kd{s.p.x.data(),   s.p.v.data(),       s.p.omega.data(), ri.data(), rj.data(),
                                s.cs.i.data(),  s.cs.j.data(),      s.cs.shift.data(), s.cs.bonded.data(),
                                gn.data(),      gs.data(),          s.cs.xi.data(),   s.cs.f.data(),
                                s.cs.c.data(),  s.W,                dt,               law,
                                true,           s.p.size()};
        eval_pair_range(kd, 0, m);
        if (std::signbit(g.x))  // every f_x -0.0: a disc with no incoming pair sums to -0.0
            for (Vec2& f : s.cs.f) f.x = -0.0;
        std::vector<Vec2> want_f(n), want_v(n);
        std::vector<double> want_t(n), want_w(n);
        std::size_t over_four = 0;
        for (std::size_t i = 0; i < n; ++i) {
            Vec2 f = s.p.mass[i] * g;
            double t = 0.0;
            for (std::uint32_t k = s.cs.begin[i]; k < s.cs.begin[i + 1]; ++k) {
                f += s.cs.f[k];
                t -= s.p.radius[i] * s.cs.c[k];
            }
            for (std::uint32_t q = s.cs.in_begin[i]; q < s.cs.in_begin[i + 1]; ++q) {
                f -= s.cs.f[s.cs.in_pair[q]];
                t -= s.p.radius[i] * s.cs.c[s.cs.in_pair[q]];
            }
            over_four += (s.cs.begin[i + 1] - s.cs.begin[i] > 4 || s.cs.in_begin[i + 1] - s.cs.in_begin[i] > 4) ? 1 : 0;
            want_f[i] = f;
            want_t[i] = t;
            const double half = 0.5 * dt;
            want_v[i] = s.p.v[i] + (half * s.p.inv_mass[i]) * f;
            want_w[i] = s.p.omega[i] + half * s.p.inv_inertia[i] * t;
        }
        EXPECT_GT(over_four, 0u);  // the plain path for discs with many pairs is covered
        if (std::signbit(g.x)) {
            EXPECT_GT(std::count_if(want_f.begin(), want_f.end(), [](Vec2 f) { return std::signbit(f.x); }), 0);
        }
        const std::vector<std::uint32_t> no_walls(n + 1, 0);
        std::vector<std::uint32_t> in_slots(4 * n);
        incoming_slots(s.cs.in_begin.data(), s.cs.in_pair.data(), n, in_slots.data());
        const GatherData gd{s.p.x.data(),      s.p.v.data(),        s.p.omega.data(),    s.p.radius.data(),
                            s.p.mass.data(),   s.p.inv_mass.data(), s.p.inv_inertia.data(), s.p.force.data(),
                            s.p.torque.data(), s.cs.begin.data(),   s.cs.in_begin.data(), s.cs.in_pair.data(),
                            in_slots.data(),   s.cs.f.data(),     s.cs.c.data(),       s.cs.size(),
                            no_walls.data(),   nullptr,             nullptr,             nullptr,
                            nullptr,           nullptr,             nullptr,             g,
                            dt,                0.0,                 true,                true};
        gather_range(gd, 0, n / 3);
        gather_range(gd, n / 3, n);
        EXPECT_TRUE(same_bits(s.p.force, want_f));
        EXPECT_TRUE(same_bits(s.p.torque, want_t));
        EXPECT_TRUE(same_bits(s.p.v, want_v));
        EXPECT_TRUE(same_bits(s.p.omega, want_w));
    }
    select_kernel_isa(nullptr);
}

TEST(PairKernel, KickAndDriftBitIdenticalToThePlainLoop) {
    // The integrator's passes against Simulation's per-disc loop, in every
    // kernel version, over ranges of every length mod 4, and the rebuild
    // test's maximum displacement.
    PairSet s = make_setup(6);
    const std::size_t n = s.p.size();
    Rng rng(7);
    std::vector<Vec2> x_ref(n);
    for (std::size_t i = 0; i < n; ++i) {
        s.p.force[i] = {rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
        s.p.torque[i] = rng.uniform(-1.0, 1.0);
        x_ref[i] = s.p.x[i] + Vec2{rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3)};
    }
    const double dt = 1e-4, half = 0.5 * dt;
    ParticleStore want = s.p;
    double want_max = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        want.v[i] += (half * want.inv_mass[i]) * want.force[i];
        want.omega[i] += half * want.inv_inertia[i] * want.torque[i];
        want.x[i] += dt * want.v[i];
        want.theta[i] += dt * want.omega[i];
        want_max = std::max(want_max, norm2(want.x[i] - x_ref[i]));
    }
    ParticleStore want2 = want;  // then the second half kick
    for (std::size_t i = 0; i < n; ++i) {
        want2.v[i] += (half * want2.inv_mass[i]) * want2.force[i];
        want2.omega[i] += half * want2.inv_inertia[i] * want2.torque[i];
    }
    for (const KernelIsa isa : runnable_isas()) {
        SCOPED_TRACE(isa_name(isa));
        select_kernel_isa(isa_name(isa));
        ParticleStore p = s.p;
        const KickData kd{p.x.data(),     p.v.data(),      p.omega.data(),    p.theta.data(),
                          p.force.data(), p.torque.data(), p.inv_mass.data(), p.inv_inertia.data(),
                          x_ref.data(),   dt,              half};
        const std::size_t cuts[] = {0, 5, 7, 18, n / 2 + 1, n};
        double got_max = 0.0;
        for (std::size_t c = 0; c + 1 < std::size(cuts); ++c) got_max = kick_drift_range(kd, cuts[c], cuts[c + 1], got_max);
        EXPECT_TRUE(same_bits(p.v, want.v));
        EXPECT_TRUE(same_bits(p.omega, want.omega));
        EXPECT_TRUE(same_bits(p.x, want.x));
        EXPECT_TRUE(same_bits(p.theta, want.theta));
        EXPECT_EQ(got_max, want_max);
        for (std::size_t c = 0; c + 1 < std::size(cuts); ++c) kick_range(kd, cuts[c], cuts[c + 1]);
        EXPECT_TRUE(same_bits(p.v, want2.v));
        EXPECT_TRUE(same_bits(p.omega, want2.omega));
    }
    select_kernel_isa(nullptr);
}

TEST(PairKernel, CoversEveryBranch) {
    // The random set really has pairs apart, touching, sliding and bonded.
    const PairSet s = make_setup(1);
    ContactStore cs = s.cs;
    std::size_t apart = 0, touching = 0, sliding = 0, bonded = 0, fixed = 0;
    const LawParams law = bench_law();
    for (std::size_t k = 0; k < cs.size(); ++k) {
        reference_pair(s.p, cs, k, s.W, 1e-4, law, true);
        bonded += cs.bonded[k];
        fixed += (s.p.inv_mass[cs.i[k]] == 0.0 || s.p.inv_mass[cs.j[k]] == 0.0) ? 1 : 0;
        if (cs.f[k].x == 0.0 && cs.f[k].y == 0.0) {
            ++apart;
            continue;
        }
        ++touching;
        if (cs.bonded[k]) continue;
        // Sliding: the tangential force sits on the Coulomb limit μ|F_n|.
        const Vec2 d = s.p.x[cs.i[k]] - (s.p.x[cs.j[k]] + Vec2{cs.shift[k] * s.W, 0.0});
        const Vec2 n = (1.0 / norm(d)) * d;
        const double f_n = dot(cs.f[k], n);
        const Vec2 f_t = cs.f[k] - f_n * n;
        sliding += norm(f_t) > 0.999999 * law.mu * std::fabs(f_n) ? 1 : 0;
    }
    EXPECT_GT(apart, 50u);
    EXPECT_GT(touching, 100u);
    EXPECT_GT(sliding, 20u);
    EXPECT_GT(bonded, 20u);
    EXPECT_GT(fixed, 10u);
}
