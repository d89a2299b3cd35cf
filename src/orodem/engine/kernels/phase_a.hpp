// Phase A of the step: the contact law over O::n pairs a block; see
// pair_kernel.hpp for the bit-identity and determinism arguments. Every expression of phase A mirrors, operation for
// operation, eval_contact() in physics/contact_law.hpp and the scalar pair
// loop this kernel replaced; keep them in step (tests/unit/test_pair_kernel.cpp
// compares them bit for bit on random packings with fixed discs, bonds,
// sliding and three law variants; the LAMMPS reference and determinism tests
// would catch a drift too).
//
// Cost model (30,000-disc pile, docs/studies/kernel-history.md "Profile"): phase A is
// bound by how many of its instructions the core holds in flight, neither by
// memory nor by one block's chain alone (two passes per chunk and two
// interleaved blocks gained nothing); a block's chain (sqrt, then the
// division, then the law down to the sliding test) is long, so fewer
// instructions per pair let more blocks overlap. Per block: a fifth scalar
// index work, two fifths loads, shuffles and stores, a third arithmetic and
// selects. Hence eight lanes in the AVX-512 version (Lanes8: the index,
// column and arithmetic work per pair halves, 28% faster than four lanes on
// the Zen 5 host) and four in the others (Lanes4), contiguous loads and
// stores of the pair columns, each disc index held as one byte offset that
// addresses both column widths (opaque), x and v into lanes by in-lane
// unpacks (gather_vec2_off), ω built in vector registers at once
// (lanes_now), in eight lanes every disc column loaded straight into its
// quarter of the vector (Lanes8::quad, Lanes8::gather) and disc i's columns
// through an eight-slot window (Lanes8::window_i), and what changes only
// with the pairs or the masses as pair columns computed then, not every
// step: the dashpots (m_eff; pair_dashpots) and the radii (pair_radii). The
// sliding step is deferred (eval_blocks_deferred): on the pile about three
// blocks of eight pairs in ten have a sliding lane, and a branch on the
// Coulomb test, which ends a block's longest chain, mispredicted often
// enough that the blocks after it were thrown away.
// Private to engine/pair_kernel.cpp, which includes it once: the three
// ISA builds of each kernel must see these bodies in one translation unit,
// so that the always_inline helpers take the caller's target ISA.
#pragma once

#include "orodem/engine/kernels/lanes.hpp"

namespace orodem {
namespace {
/// A lane policy O with the pair's law taken from the pair columns
/// (PairKernelData::k_n_pair ..., several materials) instead of the one
/// LawParams, and the pair's plastic slip and separations recorded. The
/// same expressions with a lane's value where the one law has a scalar, so
/// a run whose columns all hold the one law's values gives the same bits.
template <class O>
struct PerPair : O {
    static constexpr bool kPerPair = true;
};
template <class O>
constexpr bool per_pair = requires { O::kPerPair; };

/// The inputs of O::n pairs, one pair per lane.
template <class O>
struct Block {
    using V = typename O::V;
    V xix, xiy, xjx, xjy, shift, ri, rj, bonded, gamma_n, gamma_s, vix, viy, vjx, vjy, wi, wj, xi_x, xi_y;
    V k_n, k_s, mu, cohesion;  // PerPair only: the pair's law
};
/// The outputs.
template <class O>
struct Out {
    using V = typename O::V;
    V fx, fy, c, xi_x, xi_y;
    V slip, broke;  // PerPair only: plastic slip this step [m]; 1 where a pair with history separated
};

/// Loads a block; `K` are the pair indices of the lanes.
template <class O>
[[gnu::always_inline]] inline Block<O> load_block(const PairKernelData& d, const std::size_t* K, bool contiguous) {
    using V = typename O::V;
    constexpr std::size_t n = O::n;
    Block<O> b;
    // Disc i's columns, then disc j's: in eight lanes, the sixteen byte
    // offsets live at once would not fit the general registers.
    bool have_i = false;
    if constexpr (O::kWindow)
        if (contiguous) have_i = O::window_i(d.x, d.v, d.omega, d.i + K[0], d.n_discs, b);
    if (!have_i) {
        std::size_t I[n];  // the discs' byte offsets into the double columns
        for (std::size_t l = 0; l < n; ++l) I[l] = opaque(std::size_t{d.i[K[l]]} * sizeof(double));
        O::gather_vec2(d.x, I, b.xix, b.xiy);
        O::gather_vec2(d.v, I, b.vix, b.viy);
        b.wi = O::gather(d.omega, I);
    }
    {
        std::size_t J[n];
        for (std::size_t l = 0; l < n; ++l) J[l] = opaque(std::size_t{d.j[K[l]]} * sizeof(double));
        O::gather_vec2(d.x, J, b.xjx, b.xjy);
        O::gather_vec2(d.v, J, b.vjx, b.vjy);
        b.wj = O::gather(d.omega, J);
    }
    // Periodic images and bonds are rare in a block (all its bytes zero): then
    // skip the byte-to-double conversions.
    typename O::Bits shifts = 1, bonds = 1;
    if (contiguous) {
        __builtin_memcpy(&shifts, d.shift + K[0], sizeof shifts);
        __builtin_memcpy(&bonds, d.bonded + K[0], sizeof bonds);
    }
    b.shift = shifts == 0 ? V{} : O::lanes([&](std::size_t l) { return static_cast<double>(d.shift[K[l]]); });
    b.bonded = bonds == 0 ? V{} : O::lanes([&](std::size_t l) { return static_cast<double>(d.bonded[K[l]]); });
    if (contiguous) {
        O::xy_of(d.xi + K[0], b.xi_x, b.xi_y);
        b.gamma_n = simd::load<V>(d.gamma_n + K[0]);
        b.gamma_s = d.gamma_s ? simd::load<V>(d.gamma_s + K[0]) : V{};
        b.ri = simd::load<V>(d.r_i + K[0]);
        b.rj = simd::load<V>(d.r_j + K[0]);
    } else {
        std::size_t KO[n];  // the pairs' byte offsets into a double column
        for (std::size_t l = 0; l < n; ++l) KO[l] = K[l] * sizeof(double);
        O::gather_vec2(d.xi, KO, b.xi_x, b.xi_y);
        b.gamma_n = O::lanes([&](std::size_t l) { return d.gamma_n[K[l]]; });
        b.gamma_s = d.gamma_s ? O::lanes([&](std::size_t l) { return d.gamma_s[K[l]]; }) : V{};
        b.ri = O::lanes([&](std::size_t l) { return d.r_i[K[l]]; });
        b.rj = O::lanes([&](std::size_t l) { return d.r_j[K[l]]; });
    }
    if constexpr (per_pair<O>) {
        if (contiguous) {
            b.k_n = simd::load<V>(d.k_n_pair + K[0]);
            b.k_s = simd::load<V>(d.k_s_pair + K[0]);
            b.mu = simd::load<V>(d.mu_pair + K[0]);
            b.cohesion = simd::load<V>(d.cohesion_pair + K[0]);
        } else {
            b.k_n = O::lanes([&](std::size_t l) { return d.k_n_pair[K[l]]; });
            b.k_s = O::lanes([&](std::size_t l) { return d.k_s_pair[K[l]]; });
            b.mu = O::lanes([&](std::size_t l) { return d.mu_pair[K[l]]; });
            b.cohesion = O::lanes([&](std::size_t l) { return d.cohesion_pair[K[l]]; });
        }
    }
    return b;
}

/// A block's law up to the Coulomb test: what the sliding step and the
/// outputs need (law_to_slide, then slide_step where a lane slides, then
/// outputs).
template <class O>
struct Law {
    using V = typename O::V;
    using M = typename O::M;
    M touch, slide;
    V nx, ny, f_n, ftx, fty, xi_x, xi_y, f_max, vtx, vty, gamma_s;
    V k_s, slip, broke;  // PerPair only
};

/// The law for the lanes: eval_contact() and the scalar loop, operation for
/// operation, up to the Coulomb test.
template <class O>
[[gnu::always_inline]] inline Law<O> law_to_slide(const PairKernelData& d, const Block<O>& b) {
    using V = typename O::V;
    using M = typename O::M;
    Law<O> w;
    const M bonded = O::nonzero(b.bonded);
    // d = x_i - (x_j + (shift W, 0)); touching unless r² >= (R_i + R_j)² (bonds always).
    const V dx = b.xix - (b.xjx + b.shift * d.period_x);
    const V dy = b.xiy - (b.xjy + 0.0);
    const V r2 = dx * dx + dy * dy;
    const V rsum = b.ri + b.rj;
    w.touch = O::or_(bonded, O::not_(O::ge(r2, rsum * rsum)));
    const V r = O::sqrt(r2);
    const V s = 1.0 / r;
    const V nx = s * dx, ny = s * dy;
    w.nx = nx;
    w.ny = ny;
    const V delta = rsum - r;
    const V vrx = b.vix - b.vjx, vry = b.viy - b.vjy;
    const V spin = b.ri * b.wi + b.rj * b.wj;

    // Normal part.
    const LawParams& p = d.law;
    const V v_n = vrx * nx + vry * ny;
    w.vtx = (vrx - v_n * nx) + spin * ny;
    w.vty = (vry - v_n * ny) + spin * (-nx);
    const V gamma_n = b.gamma_n;  // from the masses, per pair (pair_dashpots)
    V f_n;
    if constexpr (per_pair<O>) {
        f_n = b.k_n * delta - gamma_n * v_n;
        w.k_s = b.k_s;
        w.slip = V{};
        // A pair that had a history (touched last step) and no longer touches.
        const M had = O::or_(O::nonzero(b.xi_x), O::nonzero(b.xi_y));
        w.broke = O::keep(O::and_not(w.touch, had), V{} + 1.0);
    } else {
        f_n = p.k_n * delta - gamma_n * v_n;
    }
    if (p.clamp_normal) f_n = O::select(O::and_not(bonded, O::lt(f_n, V{})), V{}, f_n);
    w.f_n = f_n;

    // Tangential spring, projected onto the tangent line, with the Coulomb
    // limit for unbonded pairs.
    w.xi_x = b.xi_x;
    w.xi_y = b.xi_y;
    w.ftx = V{};
    w.fty = V{};
    w.f_max = V{};
    w.slide = M{};  // no lane
    w.gamma_s = b.gamma_s;
    if (p.tangential) {
        V xi_x = w.xi_x + d.dt * w.vtx;
        V xi_y = w.xi_y + d.dt * w.vty;
        const V along = xi_x * nx + xi_y * ny;
        w.xi_x = xi_x - along * nx;
        w.xi_y = xi_y - along * ny;
        if constexpr (per_pair<O>) {
            w.ftx = (-b.k_s) * w.xi_x - w.gamma_s * w.vtx;
            w.fty = (-b.k_s) * w.xi_y - w.gamma_s * w.vty;
            w.f_max = b.mu * O::fabs(f_n) + b.cohesion;
        } else {
            w.ftx = (-p.k_s) * w.xi_x - w.gamma_s * w.vtx;
            w.fty = (-p.k_s) * w.xi_y - w.gamma_s * w.vty;
            w.f_max = p.mu * O::fabs(f_n) + p.cohesion;
        }
        const V ft2 = w.ftx * w.ftx + w.fty * w.fty;
        w.slide = O::and_not(bonded, O::gt(ft2, w.f_max * w.f_max));
    }
    return w;
}

/// Sliding: F_t scaled onto the limit and ξ so the spring (plus the
/// dashpot) sits on it, in the lanes of w.slide (a select per lane: the
/// others keep their values).
template <class O>
[[gnu::always_inline]] inline void slide_step(const LawParams& p, Law<O>& w) {
    using V = typename O::V;
    const V ratio = w.f_max / O::sqrt(w.ftx * w.ftx + w.fty * w.fty);
    // γ_s / k_s: +0 exactly when there is no tangential dashpot (then no division).
    const bool no_dashpot = zero_gamma_s(p) && p.k_s > 0.0;
    V g_over_k;
    if constexpr (per_pair<O>)
        g_over_k = no_dashpot ? V{} : w.gamma_s / w.k_s;
    else
        g_over_k = no_dashpot ? V{} : w.gamma_s / p.k_s;
    const V dpx = g_over_k * w.vtx, dpy = g_over_k * w.vty;
    if constexpr (per_pair<O>) {
        // The plastic part of this step's tangential displacement: what the
        // rescaling takes off |ξ + dashpot part|.
        const V ex = w.xi_x + dpx, ey = w.xi_y + dpy;
        w.slip = O::keep(w.slide, (1.0 - ratio) * O::sqrt(ex * ex + ey * ey));
    }
    w.xi_x = O::select(w.slide, ratio * (w.xi_x + dpx) - dpx, w.xi_x);
    w.xi_y = O::select(w.slide, ratio * (w.xi_y + dpy) - dpy, w.xi_y);
    w.ftx = O::select(w.slide, ratio * w.ftx, w.ftx);
    w.fty = O::select(w.slide, ratio * w.fty, w.fty);
}

template <class O>
[[gnu::always_inline]] inline Out<O> outputs(const Law<O>& w) {
    Out<O> o;
    o.fx = O::keep(w.touch, w.f_n * w.nx + w.ftx);
    o.fy = O::keep(w.touch, w.f_n * w.ny + w.fty);
    o.c = O::keep(w.touch, w.nx * w.fty - w.ny * w.ftx);
    o.xi_x = O::keep(w.touch, w.xi_x);  // history starts afresh at the next touch
    o.xi_y = O::keep(w.touch, w.xi_y);
    if constexpr (per_pair<O>) {
        o.slip = w.slip;
        o.broke = w.broke;
    }
    return o;
}

/// The whole law for the lanes, the sliding step taken when a lane slides.
template <class O>
[[gnu::always_inline]] inline Out<O> compute_block(const PairKernelData& d, const Block<O>& b) {
    Law<O> w = law_to_slide<O>(d, b);
    if (d.law.tangential && O::any(w.slide)) slide_step<O>(d.law, w);
    return outputs<O>(w);
}

/// PerPair: adds the lanes' plastic slip to the pairs' slip and marks the
/// separated ones (lanes 0 .. valid - 1 at pairs k0 ..).
template <class O>
[[gnu::always_inline]] inline void record_slip(const PairKernelData& d, std::size_t k0, std::size_t valid, const Out<O>& o) {
    for (std::size_t l = 0; l < valid; ++l) {
        d.slip[k0 + l] += o.slip[l];
        if (o.broke[l] != 0.0) d.broke[k0 + l] = 1;
    }
}

/// Stores a block's outputs at pairs k0 .. k0 + O::n - 1.
template <class O>
[[gnu::always_inline]] inline void store_block(const PairKernelData& d, std::size_t k0, const Out<O>& o) {
    constexpr std::size_t n = O::n;
    simd::store(d.f + k0, O::zip_lo(o.fx, o.fy));
    simd::store(d.f + k0 + n / 2, O::zip_hi(o.fx, o.fy));
    simd::store(d.c + k0, o.c);
    if (d.update_history) {
        simd::store(d.xi + k0, O::zip_lo(o.xi_x, o.xi_y));
        simd::store(d.xi + k0 + n / 2, O::zip_hi(o.xi_x, o.xi_y));
        if constexpr (per_pair<O>) record_slip<O>(d, k0, n, o);
    }
}

/// The pair indices k0 .. k0 + O::n - 1.
template <class O>
[[gnu::always_inline]] inline std::array<std::size_t, O::n> block_pairs(std::size_t k0) {
    return [k0]<std::size_t... L>(std::index_sequence<L...>) {
        return std::array<std::size_t, O::n>{(k0 + L)...};
    }(std::make_index_sequence<O::n>{});
}

/// O::n whole pairs at k0: contiguous loads and stores of the pair columns.
template <class O>
[[gnu::always_inline]] inline void eval_block(const PairKernelData& d, std::size_t k0) {
    const auto K = block_pairs<O>(k0);
    store_block<O>(d, k0, compute_block<O>(d, load_block<O>(d, K.data(), true)));
}

/// A block whose sliding step is left for later (eval_deferred).
template <class O>
struct Deferred {
    Law<O> w;
    std::size_t k0;
};

/// O::n whole pairs at k0, the sliding step deferred: the outputs as if no
/// lane slid are stored, and the block's law is written to `rec`, which the
/// caller keeps (advances past) only when a lane slides. No branch waits on
/// the Coulomb test, which ends the block's longest chain: a block that
/// slides would otherwise be a mispredicted branch about every fifth block
/// of eight pairs on the pile, with the next blocks' work thrown away.
template <class O>
[[gnu::always_inline]] inline bool eval_block_deferred(const PairKernelData& d, std::size_t k0, bool keep_dashpot,
                                                       Deferred<O>& rec) {
    const auto K = block_pairs<O>(k0);
    const Law<O> w = law_to_slide<O>(d, load_block<O>(d, K.data(), true));
    store_block<O>(d, k0, outputs<O>(w));
    rec.k0 = k0;
    rec.w.touch = w.touch;
    rec.w.slide = w.slide;
    rec.w.nx = w.nx;
    rec.w.ny = w.ny;
    rec.w.f_n = w.f_n;
    rec.w.ftx = w.ftx;
    rec.w.fty = w.fty;
    rec.w.xi_x = w.xi_x;
    rec.w.xi_y = w.xi_y;
    rec.w.f_max = w.f_max;
    rec.w.vtx = w.vtx;  // (+0 / k_s) v_t is ±0 by v_t's sign: kept even without a dashpot
    rec.w.vty = w.vty;
    if (keep_dashpot) rec.w.gamma_s = w.gamma_s;
    if constexpr (per_pair<O>) {
        rec.w.k_s = w.k_s;
        rec.w.slip = w.slip;
        rec.w.broke = typename O::V{};  // recorded by the store above; the store after the sliding step adds only the slip
    }
    return O::any(w.slide);
}

/// Whole blocks from k over [k, end): chunks of kChunk blocks, each first
/// with its sliding steps deferred (eval_block_deferred), then the sliding
/// step of the blocks where a lane slides and their outputs stored again.
/// The same operations per pair as eval_block, so the same results.
template <class O>
[[gnu::always_inline]] inline std::size_t eval_blocks_deferred(const PairKernelData& d, std::size_t k,
                                                               std::size_t end) {
    constexpr std::size_t kChunk = 32;  // blocks; the records stay in L1
    const bool keep_dashpot = !(zero_gamma_s(d.law) && d.law.k_s > 0.0);
    Deferred<O> rec[kChunk + 1];  // + 1: the last block's record is written whether kept or not
    while (k + O::n <= end) {
        std::size_t kept = 0;
        for (std::size_t b = 0; b < kChunk && k + O::n <= end; ++b, k += O::n)
            kept += eval_block_deferred<O>(d, k, keep_dashpot, rec[kept]) ? 1 : 0;
        for (std::size_t r = 0; r < kept; ++r) {
            Law<O> w = rec[r].w;
            if (!keep_dashpot) w.gamma_s = typename O::V{};  // not read: γ_s / k_s is +0
            slide_step<O>(d.law, w);
            store_block<O>(d, rec[r].k0, outputs<O>(w));
        }
    }
    return k;
}

/// The last 1 .. O::n - 1 pairs of a range: lanes past the end repeat the last pair and are not stored.
template <class O>
[[gnu::always_inline]] inline void eval_tail(const PairKernelData& d, std::size_t k0, std::size_t valid) {
    std::size_t K[O::n];
    for (std::size_t l = 0; l < O::n; ++l) K[l] = k0 + (l < valid ? l : valid - 1);
    const Out<O> o = compute_block<O>(d, load_block<O>(d, K, false));
    for (std::size_t l = 0; l < valid; ++l) {
        const std::size_t k = k0 + l;
        d.f[k] = {o.fx[l], o.fy[l]};
        d.c[k] = o.c[l];
        if (d.update_history) d.xi[k] = {o.xi_x[l], o.xi_y[l]};
    }
    if constexpr (per_pair<O>)
        if (d.update_history) record_slip<O>(d, k0, valid, o);
}

template <class O>
[[gnu::always_inline]] inline void pair_body_law(const PairKernelData& dref, std::size_t begin, std::size_t end) {
    // A local copy: the kernel's stores (memcpy, may alias anything) then
    // cannot force reloads of the column pointers.
    const PairKernelData d = dref;
    std::size_t k = begin;
    if (d.law.tangential)
        k = eval_blocks_deferred<O>(d, k, end);
    else
        for (; k + O::n <= end; k += O::n) eval_block<O>(d, k);
    if (k < end) eval_tail<O>(d, k, end - k);
}

/// Phase A over pairs [begin, end): the one law, or the pair columns' laws
/// when the run has several materials (PairKernelData::k_n_pair).
template <class O>
[[gnu::always_inline]] inline void pair_body(const PairKernelData& d, std::size_t begin, std::size_t end) {
    if (d.k_n_pair)
        pair_body_law<PerPair<O>>(d, begin, end);
    else
        pair_body_law<O>(d, begin, end);
}
}  // namespace
}  // namespace orodem
