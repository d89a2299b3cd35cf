// Phase A in SIMD lanes; see pair_kernel.hpp for the bit-identity argument.
// Every expression below mirrors, operation for operation, eval_contact() in
// physics/contact_law.hpp and the scalar pair loop this kernel replaced; keep
// them in step (tests/unit/test_pair_kernel.cpp compares the two on random
// pairs bit for bit; the LAMMPS reference and determinism tests would catch
// a drift too).
#include "orodem/engine/pair_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

// Vectors in by-value helpers change the calling convention between the ISA
// clones; they are all inlined, so the note is moot.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace orodem {
namespace {

constexpr std::size_t kLanes = 4;
using vd = double __attribute__((vector_size(kLanes * sizeof(double))));
using vm = decltype(vd{} < vd{});  // lane mask: all bits set where true

template <class F, std::size_t... L>
[[gnu::always_inline]] inline vd lanes_impl(F&& f, std::index_sequence<L...>) {
    return vd{f(L)...};
}
/// {f(0), f(1), ..., f(kLanes-1)}
template <class F>
[[gnu::always_inline]] inline vd lanes(F&& f) {
    return lanes_impl(f, std::make_index_sequence<kLanes>{});
}
[[gnu::always_inline]] inline vd vsqrt(vd a) {
    return lanes([&](std::size_t l) { return std::sqrt(a[l]); });
}
[[gnu::always_inline]] inline vd vfabs(vd a) {
    const vm magnitude = vm{} + 0x7fffffffffffffffLL;
    return reinterpret_cast<vd>(reinterpret_cast<vm>(a) & magnitude);
}

/// Pairs per chunk: gathered into SoA scratch first (short dependency
/// chains, many loads), then evaluated in lanes from contiguous scratch
/// (long chains of arithmetic), so that the CPU overlaps many pairs.
constexpr std::size_t kChunk = 32;
static_assert(kChunk % kLanes == 0);

struct alignas(64) Scratch {
    double dx[kChunk], dy[kChunk], r2[kChunk], rsum[kChunk], vrx[kChunk], vry[kChunk], spin[kChunk];
    double mi[kChunk], mj[kChunk], imi[kChunk], imj[kChunk], xi_x[kChunk], xi_y[kChunk], bonded[kChunk];
    double fx[kChunk], fy[kChunk], c[kChunk];
};

[[gnu::always_inline]] inline vd load(const double* a) {
    vd r;
    __builtin_memcpy(&r, a, sizeof r);
    return r;
}
[[gnu::always_inline]] inline void store(double* a, vd v) { __builtin_memcpy(a, &v, sizeof v); }

/// Pairs [k0, k0 + count), count <= kChunk.
[[gnu::always_inline]] inline void eval_chunk(const PairKernelData& d, std::size_t k0, std::size_t count,
                                              Scratch& t) {
    // Gather: the pair's geometry and kinematics, as the scalar loop computed them.
    const double W = d.period_x;
    for (std::size_t l = 0; l < kChunk; ++l) {
        const std::size_t k = k0 + (l < count ? l : count - 1);  // pad with the last pair
        const std::uint32_t i = d.i[k], j = d.j[k];
        const double dx = d.x[i].x - (d.x[j].x + d.shift[k] * W);
        const double dy = d.x[i].y - (d.x[j].y + 0.0);
        t.dx[l] = dx;
        t.dy[l] = dy;
        t.r2[l] = dx * dx + dy * dy;
        const double ri = d.radius[i], rj = d.radius[j];
        t.rsum[l] = ri + rj;
        t.vrx[l] = d.v[i].x - d.v[j].x;
        t.vry[l] = d.v[i].y - d.v[j].y;
        t.spin[l] = ri * d.omega[i] + rj * d.omega[j];
        t.mi[l] = d.mass[i];
        t.mj[l] = d.mass[j];
        t.imi[l] = d.inv_mass[i];
        t.imj[l] = d.inv_mass[j];
        t.xi_x[l] = d.xi[k].x;
        t.xi_y[l] = d.xi[k].y;
        t.bonded[l] = d.bonded[k];
    }
    const LawParams& p = d.law;
    // γ_s / k_s; +0 exactly when there is no tangential dashpot (then no division).
    const bool no_dashpot =
        p.damp_mass_s == 0.0 && !std::signbit(p.damp_mass_s) && p.damp_sqrt_s == 0.0 && p.k_s > 0.0;
    for (std::size_t l = 0; l < kChunk; l += kLanes) {
        const vd dx = load(t.dx + l), dy = load(t.dy + l), r2 = load(t.r2 + l), rsum = load(t.rsum + l);
        const vm bonded = load(t.bonded + l) != 0.0;
        // Touching unless r² >= (R_i + R_j)² (bonds always).
        const vm touch = bonded | ~(r2 >= rsum * rsum);
        const vd r = vsqrt(r2);
        const vd mi = load(t.mi + l), mj = load(t.mj + l);
        // A fixed disc is infinitely heavy: the pair's effective mass is the free disc's own.
        const vd m_eff = load(t.imj + l) == 0.0 ? mi : (load(t.imi + l) == 0.0 ? mj : mi * mj / (mi + mj));
        const vd s = 1.0 / r;
        const vd nx = s * dx, ny = s * dy;
        const vd delta = rsum - r;
        const vd vrx = load(t.vrx + l), vry = load(t.vry + l), spin = load(t.spin + l);

        // eval_contact, normal part.
        const vd v_n = vrx * nx + vry * ny;
        const vd vtx = (vrx - v_n * nx) + spin * ny;
        const vd vty = (vry - v_n * ny) + spin * (-nx);
        vd gamma_n = p.damp_mass_n * m_eff;
        if (p.damp_sqrt_n != 0.0) gamma_n += p.damp_sqrt_n * vsqrt(m_eff);
        vd f_n = p.k_n * delta - gamma_n * v_n;
        if (p.clamp_normal) f_n = (~bonded & (f_n < 0.0)) ? vd{} : f_n;

        // Tangential spring, projected onto the tangent line, with the Coulomb
        // limit for unbonded pairs.
        vd xi_x = load(t.xi_x + l), xi_y = load(t.xi_y + l);
        vd ftx{}, fty{};
        if (p.tangential) {
            xi_x = xi_x + d.dt * vtx;
            xi_y = xi_y + d.dt * vty;
            const vd along = xi_x * nx + xi_y * ny;
            xi_x = xi_x - along * nx;
            xi_y = xi_y - along * ny;
            vd gamma_s = p.damp_mass_s * m_eff;
            if (p.damp_sqrt_s != 0.0) gamma_s += p.damp_sqrt_s * vsqrt(m_eff);
            ftx = (-p.k_s) * xi_x - gamma_s * vtx;
            fty = (-p.k_s) * xi_y - gamma_s * vty;
            const vd f_max = p.mu * vfabs(f_n) + p.cohesion;
            const vd ft2 = ftx * ftx + fty * fty;
            const vm slide = ~bonded & (ft2 > f_max * f_max);
            // Sliding: scale F_t onto the limit and ξ so the spring (plus the dashpot) sits on it.
            const vd ratio = f_max / vsqrt(ft2);
            const vd g_over_k = no_dashpot ? vd{} : gamma_s / p.k_s;
            const vd dpx = g_over_k * vtx, dpy = g_over_k * vty;
            xi_x = slide ? ratio * (xi_x + dpx) - dpx : xi_x;
            xi_y = slide ? ratio * (xi_y + dpy) - dpy : xi_y;
            ftx = slide ? ratio * ftx : ftx;
            fty = slide ? ratio * fty : fty;
        }
        store(t.fx + l, touch ? f_n * nx + ftx : vd{});
        store(t.fy + l, touch ? f_n * ny + fty : vd{});
        store(t.c + l, touch ? nx * fty - ny * ftx : vd{});
        store(t.xi_x + l, touch ? xi_x : vd{});  // history starts afresh at the next touch
        store(t.xi_y + l, touch ? xi_y : vd{});
    }
    for (std::size_t l = 0; l < count; ++l) {
        const std::size_t k = k0 + l;
        d.f[k] = {t.fx[l], t.fy[l]};
        d.c[k] = t.c[l];
        if (d.update_history) d.xi[k] = {t.xi_x[l], t.xi_y[l]};
    }
}

}  // namespace

// Built for the baseline ISA and, chosen at load time by the CPU, for
// x86-64-v3 (AVX2) and x86-64-v4 (AVX-512): the same operations, wider registers.
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
void eval_pair_range(const PairKernelData& d, std::size_t begin, std::size_t end) {
    Scratch t;
    for (std::size_t k = begin; k < end; k += kChunk) eval_chunk(d, k, std::min(kChunk, end - k), t);
}

}  // namespace orodem
