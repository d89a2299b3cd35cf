// Phases A and B of the step; see pair_kernel.hpp for the bit-identity and
// determinism arguments. Every expression of phase A mirrors, operation for
// operation, eval_contact() in physics/contact_law.hpp and the scalar pair
// loop this kernel replaced; keep them in step (tests/unit/test_pair_kernel.cpp
// compares them bit for bit on random packings with fixed discs, bonds,
// sliding and three law variants; the LAMMPS reference and determinism tests
// would catch a drift too).
//
// Cost model (30,000-disc pile, docs/benchmarks.md "Profile"): phase A is
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
//
// Phase B takes four discs a time in the AVX versions, so the serial sums
// of one disc (its force and torque, term by term) stay in order while four
// run side by side: a disc per lane in the AVX2 version (gather_lanes), the
// four discs' forces as they lie in memory in the AVX-512 one
// (gather_avx512). The integrator's passes (kick_drift_lanes, kick_lanes)
// take four discs a time in the AVX2 version and eight in the AVX-512 one.
#include "orodem/engine/pair_kernel.hpp"

#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "orodem/core/error.hpp"

#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include <immintrin.h>

#include "orodem/core/simd.hpp"
#include "orodem/neighbor/pair_builder.hpp"

namespace orodem {
namespace {

using simd::v2d;
using vd = simd::v4d;
using vm = simd::v4m;
using simd::lanes;

[[gnu::always_inline]] inline vd cat(v2d a, v2d b) { return __builtin_shufflevector(a, b, 0, 1, 2, 3); }
[[gnu::always_inline]] inline vd even(vd a, vd b) { return __builtin_shufflevector(a, b, 0, 2, 4, 6); }
[[gnu::always_inline]] inline vd odd(vd a, vd b) { return __builtin_shufflevector(a, b, 1, 3, 5, 7); }
[[gnu::always_inline]] inline bool any(vm m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }
/// any(m) as one vmovmskpd in the AVX versions (kAvx): the sliding branch
/// waits on it at the end of a block's longest chain, and GCC reduces the
/// four lanes through general registers otherwise (phase A 6% faster on the
/// pile). Inline asm, as the intrinsic cannot be inlined into code built for
/// the baseline ISA; "x" keeps the operand in ymm0-15, which VEX encodes.
template <bool kAvx>
[[gnu::always_inline]] inline bool any_lane(vm m) {
    if constexpr (kAvx) {
        int bits;
        asm("vmovmskpd %1, %0" : "=r"(bits) : "x"(m));
        return bits != 0;
    } else {
        return any(m);
    }
}

/// `v`, opaque to the optimiser. A disc's byte offset into a double column
/// (index × 8) also addresses its Vec2 (× 2 in the address). Made
/// opaque, one register per index serves both widths; otherwise the compiler
/// keeps the index and the index × 16 and spills them (phase A about 4%
/// faster, 12% fewer instructions; docs/benchmarks.md).
[[gnu::always_inline]] inline std::size_t opaque(std::size_t v) {
    asm("" : "+r"(v));
    return v;
}

/// The double at byte offset `off` of column `a`.
[[gnu::always_inline]] inline double at_off(const double* a, std::size_t off) {
    double v;
    __builtin_memcpy(&v, reinterpret_cast<const char*>(a) + off, sizeof v);
    return v;
}

/// Lanes l of {x, y} columns from a Vec2 array at four byte offsets of a
/// double column (see opaque). The halves pair lanes 0 and 2, 1 and 3, so
/// that x and y are two in-lane unpacks (unpcklpd, unpckhpd) of them rather
/// than two cross-lane permutes, each with a register copy.
[[gnu::always_inline]] inline void gather_vec2_off(const Vec2* a, const std::size_t* off, vd& xs, vd& ys) {
    const char* base = reinterpret_cast<const char*>(a);
    const vd lo = cat(simd::load<v2d>(base + 2 * off[0]), simd::load<v2d>(base + 2 * off[2]));
    const vd hi = cat(simd::load<v2d>(base + 2 * off[1]), simd::load<v2d>(base + 2 * off[3]));
    xs = __builtin_shufflevector(lo, hi, 0, 4, 2, 6);
    ys = __builtin_shufflevector(lo, hi, 1, 5, 3, 7);
}

/// {f(0), f(1), f(2), f(3)}, built in vector registers here. Left to itself
/// GCC sinks the loads of ω (used only in the tangential part) into general
/// registers and spills them, then moves them across one by one.
template <class F>
[[gnu::always_inline]] inline vd lanes_now(F&& f) {
    v2d lo = {f(0), f(1)}, hi = {f(2), f(3)};
    asm("" : "+x"(lo), "+x"(hi));
    return cat(lo, hi);
}

// ---- Phase A: the lane policies ----
//
// The law is written once (law_to_slide, slide_step, outputs) over a policy O of O::n lanes:
// O::V the values, O::M a lane mask, and the few operations whose best form
// differs with the width. Lanes4 (two 128-bit halves in the baseline
// version, one ymm register in the AVX ones) masks with vector compares;
// Lanes8 (one zmm register, the AVX-512 version) with mask registers: GCC 12
// turns 512-bit vector compares in vector-extension code into eight scalar
// compares, so Lanes8 compares, blends and zeroes with one instruction each
// in inline asm (not intrinsics: those cannot be inlined into the template
// the baseline version also instantiates). Eight lanes halve the index,
// column and arithmetic instructions per pair of four, which fit twice the
// pairs in the core's reorder window (phase A 28% faster on the Zen 5 host,
// docs/benchmarks.md).

/// c of four discs' owned slots 0-3 (four doubles from each byte offset
/// OO[l] of column c) as four slot vectors of the discs: one load a disc and
/// a 4 × 4 transpose.
[[gnu::always_inline]] inline void owned_c4(const double* c, const std::size_t* OO, vd (&out)[4]) {
    const char* base = reinterpret_cast<const char*>(c);
    const vd c0 = simd::load<vd>(base + OO[0]), c1 = simd::load<vd>(base + OO[1]);
    const vd c2 = simd::load<vd>(base + OO[2]), c3 = simd::load<vd>(base + OO[3]);
    const vd lo01 = __builtin_shufflevector(c0, c1, 0, 4, 2, 6), hi01 = __builtin_shufflevector(c0, c1, 1, 5, 3, 7);
    const vd lo23 = __builtin_shufflevector(c2, c3, 0, 4, 2, 6), hi23 = __builtin_shufflevector(c2, c3, 1, 5, 3, 7);
    out[0] = __builtin_shufflevector(lo01, lo23, 0, 1, 4, 5);
    out[1] = __builtin_shufflevector(hi01, hi23, 0, 1, 4, 5);
    out[2] = __builtin_shufflevector(lo01, lo23, 2, 3, 6, 7);
    out[3] = __builtin_shufflevector(hi01, hi23, 2, 3, 6, 7);
}

template <bool kAvx>
struct Lanes4 {
    using V = vd;
    using M = vm;
    using Bits = std::uint32_t;  // one byte a lane (the shift and bond flags)
    using IV = std::int32_t __attribute__((vector_size(4 * sizeof(std::int32_t))));
    static constexpr std::size_t n = 4;
    static constexpr bool kWindow = false;  // see Lanes8::window_i
    [[gnu::always_inline]] static void owned_c(const double* c, const std::size_t* OO, V (&out)[4]) {
        owned_c4(c, OO, out);
    }
    [[gnu::always_inline]] static M nonzero(V a) { return a != 0.0; }
    [[gnu::always_inline]] static M ge(V a, V b) { return a >= b; }
    [[gnu::always_inline]] static M gt(V a, V b) { return a > b; }
    [[gnu::always_inline]] static M lt(V a, V b) { return a < b; }
    [[gnu::always_inline]] static M or_(M a, M b) { return a | b; }
    [[gnu::always_inline]] static M and_not(M a, M b) { return ~a & b; }  // b and not a
    [[gnu::always_inline]] static M not_(M a) { return ~a; }
    [[gnu::always_inline]] static V select(M m, V t, V f) { return m ? t : f; }
    [[gnu::always_inline]] static V keep(M m, V a) { return m ? a : V{}; }
    [[gnu::always_inline]] static bool any(M m) { return any_lane<kAvx>(m); }
    [[gnu::always_inline]] static V sqrt(V a) { return simd::sqrt(a); }
    [[gnu::always_inline]] static V fabs(V a) { return simd::fabs(a); }
    template <class F>
    [[gnu::always_inline]] static V lanes(F&& f) {
        return simd::lanes(f);
    }
    /// The doubles at byte offsets off[0 .. 3] of column a, in lanes 0 .. 3.
    [[gnu::always_inline]] static V gather(const double* a, const std::size_t* off) {
        return lanes_now([&](std::size_t l) { return at_off(a, off[l]); });
    }
    [[gnu::always_inline]] static void gather_vec2(const Vec2* a, const std::size_t* off, V& xs, V& ys) {
        gather_vec2_off(a, off, xs, ys);
    }
    /// x and y of the n Vec2 at p.
    [[gnu::always_inline]] static void xy_of(const Vec2* p, V& xs, V& ys) {
        const V a = simd::load<V>(p), b = simd::load<V>(p + n / 2);
        xs = even(a, b);
        ys = odd(a, b);
    }
    /// x and y of n Vec2 (a: the first n/2, b: the rest).
    [[gnu::always_inline]] static V xs_of(V a, V b) { return even(a, b); }
    [[gnu::always_inline]] static V ys_of(V a, V b) { return odd(a, b); }
    /// The Vec2 of lanes 0 .. n/2 - 1, and of the rest, from x and y.
    [[gnu::always_inline]] static V zip_lo(V x, V y) { return __builtin_shufflevector(x, y, 0, 4, 1, 5); }
    [[gnu::always_inline]] static V zip_hi(V x, V y) { return __builtin_shufflevector(x, y, 2, 6, 3, 7); }
};

using v8d = double __attribute__((vector_size(8 * sizeof(double))));
using v8m = decltype(v8d{} < v8d{});  // for the integer operations of fabs only (see above)

struct Lanes8 {
    using V = v8d;
    using M = std::uint8_t;  // in the asm, a mask register k1-k7 ("Yk")
    using Bits = std::uint64_t;
    static constexpr std::size_t n = 8;
    static constexpr bool kWindow = true;
    using VI = std::int64_t __attribute__((vector_size(8 * sizeof(std::int64_t))));
    using VU = std::uint32_t __attribute__((vector_size(8 * sizeof(std::uint32_t))));
    /// Lanes idx of the sixteen doubles lo, hi (vpermi2pd: the index's low four bits).
    [[gnu::always_inline]] static V pick16(V lo, V hi, VI idx) {
        V r;
        asm("vpermi2pd %2, %1, %0" : "=v"(r) : "v"(lo), "v"(hi), "0"(idx));
        return r;
    }
    /// Lanes idx of the eight doubles a (vpermpd: the index's low three bits).
    [[gnu::always_inline]] static V pick8(V a, VI idx) {
        V r;
        asm("vpermpd %1, %2, %0" : "=v"(r) : "v"(a), "v"(idx));
        return r;
    }
    /// Disc i's x, v and ω of the eight pairs k0 .. k0 + 7, when their discs
    /// i (ascending: the pairs are grouped by owner) lie within eight slots
    /// of the first, first + 8 <= n: two 64-byte loads of x and of v, one of
    /// ω, then a permute per vector, instead of eight indexed loads of each.
    /// Returns false (nothing loaded) otherwise.
    template <class B>
    [[gnu::always_inline]] static bool window_i(const Vec2* x, const Vec2* v, const double* omega,
                                                const std::uint32_t* i, std::size_t n_discs, B& b) {
        const std::uint32_t first = i[0];
        if (i[7] - first >= 8 || std::size_t{first} + 8 > n_discs) return false;
        VU iv;
        __builtin_memcpy(&iv, i, sizeof iv);
        const VI rel = __builtin_convertvector(iv - first, VI);
        const VI ix = rel + rel, iy = ix + 1;
        const V x_lo = simd::load<V>(x + first), x_hi = simd::load<V>(x + first + 4);
        b.xix = pick16(x_lo, x_hi, ix);
        b.xiy = pick16(x_lo, x_hi, iy);
        const V v_lo = simd::load<V>(v + first), v_hi = simd::load<V>(v + first + 4);
        b.vix = pick16(v_lo, v_hi, ix);
        b.viy = pick16(v_lo, v_hi, iy);
        b.wi = pick8(simd::load<V>(omega + first), rel);
        return true;
    }
    // vcmppd's predicates: NEQ_UQ, GE_OS, GT_OS, LT_OS (as C's != >= > <).
    template <int kPredicate>
    [[gnu::always_inline]] static M cmp(V a, V b) {
        M m;
        asm("vcmppd %3, %2, %1, %0" : "=Yk"(m) : "v"(a), "v"(b), "n"(kPredicate));
        return m;
    }
    [[gnu::always_inline]] static M nonzero(V a) { return cmp<0x04>(a, V{}); }
    [[gnu::always_inline]] static M ge(V a, V b) { return cmp<0x0d>(a, b); }
    [[gnu::always_inline]] static M gt(V a, V b) { return cmp<0x0e>(a, b); }
    [[gnu::always_inline]] static M lt(V a, V b) { return cmp<0x01>(a, b); }
    [[gnu::always_inline]] static M or_(M a, M b) { return static_cast<M>(a | b); }
    [[gnu::always_inline]] static M and_not(M a, M b) { return static_cast<M>(~a & b); }
    [[gnu::always_inline]] static M not_(M a) { return static_cast<M>(~a); }
    [[gnu::always_inline]] static V select(M m, V t, V f) {
        V r;
        asm("vblendmpd %2, %1, %0%{%3%}" : "=v"(r) : "v"(f), "v"(t), "Yk"(m));
        return r;
    }
    [[gnu::always_inline]] static V keep(M m, V a) {
        V r;
        asm("vmovapd %1, %0%{%2%}%{z%}" : "=v"(r) : "v"(a), "Yk"(m));
        return r;
    }
    [[gnu::always_inline]] static bool any(M m) { return m != 0; }
    template <class F>
    [[gnu::always_inline]] static V lanes(F&& f) {
        return lanes_impl(f, std::make_index_sequence<8>{});
    }
    template <class F, std::size_t... L>
    [[gnu::always_inline]] static V lanes_impl(F&& f, std::index_sequence<L...>) {
        return V{f(L)...};
    }
    [[gnu::always_inline]] static V sqrt(V a) {
        return lanes([&](std::size_t l) { return std::sqrt(a[l]); });
    }
    [[gnu::always_inline]] static V fabs(V a) {
        const v8m magnitude = v8m{} + 0x7fffffffffffffffLL;
        return reinterpret_cast<V>(reinterpret_cast<v8m>(a) & magnitude);
    }
    // The gathers below are inline asm: from vector-extension code GCC 12
    // builds a zmm of four 16-byte loads with register inserts and a copy
    // of each 256-bit half onto itself to zero the upper bits (53 such
    // copies in phase A's loop); here the inserts take their operand from
    // memory and nothing is copied.
    /// The 16-byte values at a, b, c, e as the quarters of one vector.
    [[gnu::always_inline]] static V quad(const v2d& a, const v2d& b, const v2d& c, const v2d& e) {
        V r, t;
        asm("vmovupd %2, %x0\n\t"
            "vinsertf64x2 $1, %3, %t0, %t0\n\t"
            "vmovupd %4, %x1\n\t"
            "vinsertf64x2 $1, %5, %t1, %t1\n\t"
            "vinsertf64x4 $1, %t1, %g0, %g0"
            : "=&v"(r), "=&v"(t)
            : "m"(a), "m"(b), "m"(c), "m"(e));
        return r;
    }
    /// The doubles at byte offsets off[0 .. 7] of column a, in lanes 0 .. 7.
    [[gnu::always_inline]] static V gather(const double* a, const std::size_t* off) {
        const char* base = reinterpret_cast<const char*>(a);
        const auto at = [&](std::size_t l) -> const double& { return *reinterpret_cast<const double*>(base + off[l]); };
        V r, t, u;
        asm("vmovsd %3, %x0\n\t"
            "vmovhpd %4, %x0, %x0\n\t"
            "vmovsd %5, %x1\n\t"
            "vmovhpd %6, %x1, %x1\n\t"
            "vinsertf64x2 $1, %x1, %t0, %t0\n\t"
            "vmovsd %7, %x1\n\t"
            "vmovhpd %8, %x1, %x1\n\t"
            "vmovsd %9, %x2\n\t"
            "vmovhpd %10, %x2, %x2\n\t"
            "vinsertf64x2 $1, %x2, %t1, %t1\n\t"
            "vinsertf64x4 $1, %t1, %g0, %g0"
            : "=&v"(r), "=&v"(t), "=&v"(u)
            : "m"(at(0)), "m"(at(1)), "m"(at(2)), "m"(at(3)), "m"(at(4)), "m"(at(5)), "m"(at(6)), "m"(at(7)));
        return r;
    }
    /// As gather_vec2_off: quarters {0, 2, 4, 6} and {1, 3, 5, 7}, then in-lane unpacks.
    [[gnu::always_inline]] static void gather_vec2(const Vec2* a, const std::size_t* off, V& xs, V& ys) {
        const char* base = reinterpret_cast<const char*>(a);
        const auto at = [&](std::size_t l) -> const v2d& { return *reinterpret_cast<const v2d*>(base + 2 * off[l]); };
        const V lo = quad(at(0), at(2), at(4), at(6)), hi = quad(at(1), at(3), at(5), at(7));
        xs = __builtin_shufflevector(lo, hi, 0, 8, 2, 10, 4, 12, 6, 14);
        ys = __builtin_shufflevector(lo, hi, 1, 9, 3, 11, 5, 13, 7, 15);
    }
    /// x and y of the eight Vec2 at p: a load and two two-source permutes
    /// whose second source is memory (vpermi2pd overwrites its index, a copy
    /// of the constant). From vector-extension shuffles GCC 12 emitted
    /// vpermt2pd, which overwrites a data operand, and sent ξ through the
    /// stack.
    [[gnu::always_inline]] static void xy_of(const Vec2* p, V& xs, V& ys) {
        using VI = std::int64_t __attribute__((vector_size(8 * sizeof(std::int64_t))));
        VI ix = {0, 2, 4, 6, 8, 10, 12, 14}, iy = {1, 3, 5, 7, 9, 11, 13, 15};
        const V a = simd::load<V>(p);
        using Vu = double __attribute__((vector_size(8 * sizeof(double)), aligned(alignof(Vec2))));
        const auto& hi = *reinterpret_cast<const Vu*>(p + 4);  // a Vec2's alignment, not the vector's
        asm("vpermi2pd %2, %1, %0" : "+v"(ix) : "v"(a), "m"(hi));
        asm("vpermi2pd %2, %1, %0" : "+v"(iy) : "v"(a), "m"(hi));
        xs = reinterpret_cast<V>(ix);
        ys = reinterpret_cast<V>(iy);
    }
    [[gnu::always_inline]] static V xs_of(V a, V b) {
        return __builtin_shufflevector(a, b, 0, 2, 4, 6, 8, 10, 12, 14);
    }
    [[gnu::always_inline]] static V ys_of(V a, V b) {
        return __builtin_shufflevector(a, b, 1, 3, 5, 7, 9, 11, 13, 15);
    }
    [[gnu::always_inline]] static V zip_lo(V x, V y) {
        return __builtin_shufflevector(x, y, 0, 8, 1, 9, 2, 10, 3, 11);
    }
    [[gnu::always_inline]] static V zip_hi(V x, V y) {
        return __builtin_shufflevector(x, y, 4, 12, 5, 13, 6, 14, 7, 15);
    }
};

/// The inputs of O::n pairs, one pair per lane.
template <class O>
struct Block {
    using V = typename O::V;
    V xix, xiy, xjx, xjy, shift, ri, rj, bonded, gamma_n, gamma_s, vix, viy, vjx, vjy, wi, wj, xi_x, xi_y;
};
/// The outputs.
template <class O>
struct Out {
    using V = typename O::V;
    V fx, fy, c, xi_x, xi_y;
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
    V f_n = p.k_n * delta - gamma_n * v_n;
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
        w.ftx = (-p.k_s) * w.xi_x - w.gamma_s * w.vtx;
        w.fty = (-p.k_s) * w.xi_y - w.gamma_s * w.vty;
        w.f_max = p.mu * O::fabs(f_n) + p.cohesion;
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
    const V g_over_k = no_dashpot ? V{} : w.gamma_s / p.k_s;
    const V dpx = g_over_k * w.vtx, dpy = g_over_k * w.vty;
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
    return o;
}

/// The whole law for the lanes, the sliding step taken when a lane slides.
template <class O>
[[gnu::always_inline]] inline Out<O> compute_block(const PairKernelData& d, const Block<O>& b) {
    Law<O> w = law_to_slide<O>(d, b);
    if (d.law.tangential && O::any(w.slide)) slide_step<O>(d.law, w);
    return outputs<O>(w);
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
}

/// The wall contacts of disc i, evaluated and added to f and t in order.
[[gnu::always_inline]] inline void wall_contacts(const GatherData& d, std::size_t i, Vec2& f, double& t) {
    const double ri = d.radius[i];
    for (std::uint32_t k = d.wall_begin[i]; k < d.wall_begin[i + 1]; ++k) {
        const Wall& w = d.walls[d.wall[k]];
        Vec2 cp;
        const bool over = wall_contact_point(w, d.x[i], cp);
        const Vec2 dx = d.x[i] - cp;
        const double r2 = norm2(dx);
        if (!over || r2 >= ri * ri) {
            d.wall_xi[k] = {};
            d.wall_f[k] = {};
            d.wall_c[k] = 0.0;
            continue;
        }
        const double dist = std::sqrt(r2);
        const Vec2 u = (1.0 / norm(w.b - w.a)) * (w.b - w.a);
        const Vec2 v_wall = w.velocity + w.surface_speed * u;
        const PairKinematics kin{(1.0 / dist) * dx, ri - dist, d.v[i] - v_wall, ri * d.omega[i], std::max(d.mass[i], d.m_inertia_min)};
        Vec2 xi = d.wall_xi[k];
        const PairForce pf = eval_contact<false>(d.wall_law[d.wall[k]], kin, d.dt, xi);
        if (d.update_history) d.wall_xi[k] = xi;
        d.wall_f[k] = pf.f;
        d.wall_c[k] = pf.c;
        f += pf.f;
        t -= ri * pf.c;
    }
}

/// The half kick of one disc: Simulation::kick()'s operations.
[[gnu::always_inline]] inline void kick_disc(Vec2& v, double& omega, double inv_mass, double inv_inertia, Vec2 f,
                                             double t, double half) {
    v += (half * inv_mass) * f;
    omega += half * inv_inertia * t;
}

/// Phase B for one disc.
[[gnu::always_inline]] inline void gather_disc(const GatherData& d, std::size_t i) {
    // f = m g, then f += f_k over the owned pairs and f -= f_k over the
    // incoming ones, t -= R_i c_k over both, in that order. A disc has 0-6
    // of each, so the first four of each are summed with no data-dependent
    // branch (a mispredicted loop exit costs more than the sums): four slots
    // are loaded and a slot past the end contributes the exact identity
    // instead (x + -0.0 == x and x - +0.0 == x for every x, ±0 included), so
    // the sums equal the plain loops bit for bit.
    const double ri = d.radius[i];
    const Vec2 g = d.mass[i] * d.gravity;
    v2d acc = {g.x, g.y};
    double t = 0.0;
    const std::uint32_t ob = d.begin[i], oe = d.begin[i + 1];
    const std::uint32_t ib = d.in_begin[i], ie = d.in_begin[i + 1];
    if (ob + 4 <= d.npairs && ib + 4 <= d.npairs && oe - ob <= 4 && ie - ib <= 4) {
        const double on = static_cast<double>(oe - ob), in = static_cast<double>(ie - ib);
        const v2d minus0 = {-0.0, -0.0};
        for (std::uint32_t s = 0; s < 4; ++s) {
            const v2d fk = simd::load<v2d>(d.f + ob + s);
            acc += (v2d{} + static_cast<double>(s)) < on ? fk : minus0;
        }
        const vd lane = {0.0, 1.0, 2.0, 3.0};
        const vd oc = ri * (lane < on ? simd::load<vd>(d.c + ob) : vd{});
        std::uint32_t k[4];
        for (std::uint32_t s = 0; s < 4; ++s) k[s] = d.in_pair[ib + s];  // valid pair indices, used or not
        for (std::uint32_t s = 0; s < 4; ++s) {
            const v2d fk = simd::load<v2d>(d.f + k[s]);
            acc -= (v2d{} + static_cast<double>(s)) < in ? fk : v2d{};
        }
        const vd ic = ri * (lane < in ? lanes([&](std::size_t l) { return d.c[k[l]]; }) : vd{});
        t -= oc[0];
        t -= oc[1];
        t -= oc[2];
        t -= oc[3];
        t -= ic[0];
        t -= ic[1];
        t -= ic[2];
        t -= ic[3];
    } else {
        // More than four of either (about one disc in a hundred), or the last discs.
        Vec2 f = {acc[0], acc[1]};
        for (std::uint32_t k = ob; k < oe; ++k) {
            f += d.f[k];
            t -= ri * d.c[k];
        }
        for (std::uint32_t q = ib; q < ie; ++q) {
            f -= d.f[d.in_pair[q]];
            t -= ri * d.c[d.in_pair[q]];
        }
        acc = v2d{f.x, f.y};
    }
    Vec2 f = {acc[0], acc[1]};
    wall_contacts(d, i, f, t);
    d.force[i] = f;
    d.torque[i] = t;
    if (d.kick) kick_disc(d.v[i], d.omega[i], d.inv_mass[i], d.inv_inertia[i], f, t, 0.5 * d.dt);  // fused
}

/// The half kick of O::n discs (Simulation::kick()'s operations): v and F
/// as the interleaved {x, y} of n/2 discs a vector (f_lo, f_hi), the rest a
/// disc per lane; returns the new velocities the same way.
template <class O, class V = typename O::V>
[[gnu::always_inline]] inline std::pair<V, V> kick_lanes(Vec2* v, double* omega, const double* inv_mass,
                                                         const double* inv_inertia, V f_lo, V f_hi, V t,
                                                         double half) {
    const V a = half * simd::load<V>(inv_mass);
    const V v_lo = simd::load<V>(v) + O::zip_lo(a, a) * f_lo, v_hi = simd::load<V>(v + O::n / 2) + O::zip_hi(a, a) * f_hi;
    simd::store(v, v_lo);
    simd::store(v + O::n / 2, v_hi);
    simd::store(omega, simd::load<V>(omega) + half * simd::load<V>(inv_inertia) * t);
    return {v_lo, v_hi};
}

/// Phase B for the O::n discs i0 .., a disc per lane: the same operations,
/// in the same order, as gather_disc() for each (gravity, the owned pairs,
/// the incoming pairs, the walls, the kick), so the results are the same
/// bit for bit. Lanes save what a disc at a time spends moving scalars: the
/// torque's serial sums take no lane extractions, the counts, masses and the
/// kick's columns load as vectors, and a slot's mask is one compare for all
/// the lanes' discs.
template <class O>
[[gnu::always_inline]] inline void gather_lanes(const GatherData& d, std::size_t i0) {
    using V = typename O::V;
    using M = typename O::M;
    using IV = typename O::IV;
    constexpr std::size_t n = O::n;
    const std::uint32_t* ob = d.begin + i0;
    const std::uint32_t* ib = d.in_begin + i0;
    // Slots past a disc's own pairs load a valid pair (then masked): the
    // last discs, whose four slots could run past the end, go one by one.
    if (ob[n - 1] + 4 > d.npairs || ib[n - 1] + 4 > d.npairs) {
        for (std::size_t l = 0; l < n; ++l) gather_disc(d, i0 + l);
        return;
    }
    // The counts (0 to a few dozen: int32 and double hold them exactly).
    const IV on_i = simd::load<IV>(ob + 1) - simd::load<IV>(ob);
    const IV in_i = simd::load<IV>(ib + 1) - simd::load<IV>(ib);
    const V on = __builtin_convertvector(on_i, V), in = __builtin_convertvector(in_i, V);
    const V ri = simd::load<V>(d.radius + i0);
    const V m = simd::load<V>(d.mass + i0);
    V fx = m * d.gravity.x, fy = m * d.gravity.y;
    V t{};
    const V minus0 = -V{};  // -0.0 in every lane
    std::size_t OO[n];  // the owned pairs' byte offsets into a double column
    for (std::size_t l = 0; l < n; ++l) OO[l] = opaque(std::size_t{ob[l]} * sizeof(double));
    // Owned slots 0-3: c of a disc's four slots is one load; 4 × 4
    // transposes turn the discs' rows into the slots' lanes.
    V oc[4];
    O::owned_c(d.c, OO, oc);
    const auto owned = [&](std::size_t s, const std::size_t* off, V gc) {
        V gx, gy;
        O::gather_vec2(d.f, off, gx, gy);
        const M use = O::lt(V{} + static_cast<double>(s), on);
        fx += O::select(use, gx, minus0);  // x + -0.0 == x for every x
        fy += O::select(use, gy, minus0);
        t -= ri * O::keep(use, gc);
    };
    const auto incoming = [&](std::size_t s, const std::size_t* off) {
        V gx, gy;
        O::gather_vec2(d.f, off, gx, gy);
        const V gc = O::lanes([&](std::size_t l) { return at_off(d.c, off[l]); });
        const M use = O::lt(V{} + static_cast<double>(s), in);
        fx -= O::keep(use, gx);  // x - +0.0 == x for every x
        fy -= O::keep(use, gy);
        t -= ri * O::keep(use, gc);
    };
    for (std::size_t s = 0; s < 4; ++s) {
        std::size_t off[n];
        for (std::size_t l = 0; l < n; ++l) off[l] = OO[l] + 8 * s;
        owned(s, off, oc[s]);
    }
    // More than four of either (about one disc in a hundred): the further
    // slots, a lane past its count reading its first (masked).
    const IV big = (on_i > 4) | (in_i > 4);
    std::uint64_t words[sizeof(IV) / 8];
    __builtin_memcpy(words, &big, sizeof words);
    std::uint64_t any_big = 0;
    for (const std::uint64_t w : words) any_big |= w;
    const bool more = any_big != 0;
    if (more) [[unlikely]] {
        std::int32_t on_max = 0;
        for (std::size_t l = 0; l < n; ++l) on_max = std::max(on_max, on_i[l]);
        for (std::int32_t s = 4; s < on_max; ++s) {
            std::size_t off[n];
            for (std::size_t l = 0; l < n; ++l) off[l] = s < on_i[l] ? OO[l] + 8 * s : OO[l];
            owned(s, off, O::lanes([&](std::size_t l) { return at_off(d.c, off[l]); }));
        }
    }
    for (std::size_t s = 0; s < 4; ++s) {
        std::size_t off[n];
        for (std::size_t l = 0; l < n; ++l) off[l] = opaque(std::size_t{d.in_pair[ib[l] + s]} * sizeof(double));
        incoming(s, off);
    }
    if (more) [[unlikely]] {
        std::int32_t in_max = 0;
        for (std::size_t l = 0; l < n; ++l) in_max = std::max(in_max, in_i[l]);
        for (std::int32_t s = 4; s < in_max; ++s) {
            std::size_t off[n];
            for (std::size_t l = 0; l < n; ++l)
                off[l] = std::size_t{d.in_pair[s < in_i[l] ? ib[l] + s : ib[l]]} * sizeof(double);
            incoming(s, off);
        }
    }
    if (d.wall_begin[i0] != d.wall_begin[i0 + n]) {  // a wall candidate: one disc at a time
        for (std::size_t l = 0; l < n; ++l) {
            Vec2 f = {fx[l], fy[l]};
            double tl = t[l];
            wall_contacts(d, i0 + l, f, tl);
            fx[l] = f.x;
            fy[l] = f.y;
            t[l] = tl;
        }
    }
    const V f_lo = O::zip_lo(fx, fy), f_hi = O::zip_hi(fx, fy);  // {fx0, fy0, fx1, fy1, ...}
    simd::store(d.force + i0, f_lo);
    simd::store(d.force + i0 + n / 2, f_hi);
    simd::store(d.torque + i0, t);
    if (d.kick) kick_lanes<O>(d.v + i0, d.omega + i0, d.inv_mass + i0, d.inv_inertia + i0, f_lo, f_hi, t, 0.5 * d.dt);
}

// GCC 12's AVX-512 intrinsics start from _mm512_undefined_pd(), which its
// own -Wmaybe-uninitialized flags (GCC bug 105593): silenced for the
// intrinsics' code below only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// ---- Phase B in the AVX-512 version (gather_avx512) ----
//
// Four discs a block, the force sums of a block kept as they lie in memory:
// {f_x, f_y} of disc l in lanes 2l and 2l + 1 of one zmm. A slot of the four
// discs is then four 16-byte loads straight into place (no transposes into x
// and y vectors, as gather_lanes needs), a slot past a disc's count is
// skipped by a masked add or subtraction (the lane keeps its value, as
// x + -0.0 and x - +0.0 leave it), and the sums store as the force column
// itself. The owned slots 0-3 of a disc are one 64-byte load of f and one
// 32-byte load of c, transposed; the incoming slots 0-3 come from the
// four-slot table (incoming_slots), whose offsets for a slot are four loads
// from one cache line, with no index arithmetic. The torque, a double a
// disc, is a ymm. Every disc gets the operations of gather_disc(), in the
// same order, so the results are the same bit for bit. Against gather_lanes
// on the pile (Zen 5, 7 alternating rounds): phase B 18% faster at one
// thread, 10% at two. Eight discs a block (more instructions in flight per
// block, fewer per disc) measured no faster.

/// The 16-byte values at byte offsets o0 .. o3 of base, as the quarters of one zmm.
[[gnu::target("arch=x86-64-v4"), gnu::always_inline]] inline __m512d quad_at(const char* base, std::size_t o0,
                                                                             std::size_t o1, std::size_t o2,
                                                                             std::size_t o3) {
    __m512d r;
    asm("vmovupd %1, %x0\n\t"
        "vinsertf64x2 $1, %2, %0, %0\n\t"
        "vinsertf64x2 $2, %3, %0, %0\n\t"
        "vinsertf64x2 $3, %4, %0, %0"
        : "=&v"(r)
        : "m"(*reinterpret_cast<const v2d*>(base + o0)), "m"(*reinterpret_cast<const v2d*>(base + o1)),
          "m"(*reinterpret_cast<const v2d*>(base + o2)), "m"(*reinterpret_cast<const v2d*>(base + o3)));
    return r;
}

/// The four doubles at byte offsets o[0 .. 3] of column a, in lanes 0 .. 3.
[[gnu::target("arch=x86-64-v4"), gnu::always_inline]] inline __m256d four_at(const double* a, const std::size_t* o) {
    const char* base = reinterpret_cast<const char*>(a);
    const auto at = [&](std::size_t l) -> const double& { return *reinterpret_cast<const double*>(base + o[l]); };
    __m256d r;
    __m128d u;
    asm("vmovsd %2, %x0\n\t"
        "vmovhpd %3, %x0, %x0\n\t"
        "vmovsd %4, %1\n\t"
        "vmovhpd %5, %1, %1\n\t"
        "vinsertf64x2 $1, %1, %0, %0"
        : "=&v"(r), "=&v"(u)
        : "m"(at(0)), "m"(at(1)), "m"(at(2)), "m"(at(3)));
    return r;
}

/// c of four discs' owned slots 0-3 as four slot vectors: one 32-byte load
/// a disc (byte offsets o[l] of column c) and a 4 × 4 transpose.
[[gnu::target("arch=x86-64-v4"), gnu::always_inline]] inline void owned_c_avx(const char* cb, const std::size_t* o,
                                                                              __m256d (&out)[4]) {
    const __m256d c0 = _mm256_loadu_pd(reinterpret_cast<const double*>(cb + o[0]));
    const __m256d c1 = _mm256_loadu_pd(reinterpret_cast<const double*>(cb + o[1]));
    const __m256d c2 = _mm256_loadu_pd(reinterpret_cast<const double*>(cb + o[2]));
    const __m256d c3 = _mm256_loadu_pd(reinterpret_cast<const double*>(cb + o[3]));
    const __m256d lo01 = _mm256_unpacklo_pd(c0, c1), hi01 = _mm256_unpackhi_pd(c0, c1);
    const __m256d lo23 = _mm256_unpacklo_pd(c2, c3), hi23 = _mm256_unpackhi_pd(c2, c3);
    out[0] = _mm256_permute2f128_pd(lo01, lo23, 0x20);
    out[1] = _mm256_permute2f128_pd(hi01, hi23, 0x20);
    out[2] = _mm256_permute2f128_pd(lo01, lo23, 0x31);
    out[3] = _mm256_permute2f128_pd(hi01, hi23, 0x31);
}

/// f of four discs' owned slots 0-3 (the 64 bytes from pair ob[l] of column
/// f) as four slot vectors, {f_x, f_y} of disc l in lanes 2l, 2l + 1: one
/// load a disc and a 4 × 4 transpose of 16-byte blocks.
[[gnu::target("arch=x86-64-v4"), gnu::always_inline]] inline void owned_f4(const char* fb, const std::uint32_t* ob,
                                                                           __m512d (&out)[4]) {
    const __m512d r0 = _mm512_loadu_pd(fb + std::size_t{ob[0]} * sizeof(Vec2));
    const __m512d r1 = _mm512_loadu_pd(fb + std::size_t{ob[1]} * sizeof(Vec2));
    const __m512d r2 = _mm512_loadu_pd(fb + std::size_t{ob[2]} * sizeof(Vec2));
    const __m512d r3 = _mm512_loadu_pd(fb + std::size_t{ob[3]} * sizeof(Vec2));
    const __m512d t0 = _mm512_shuffle_f64x2(r0, r1, 0x44), t1 = _mm512_shuffle_f64x2(r0, r1, 0xee);
    const __m512d t2 = _mm512_shuffle_f64x2(r2, r3, 0x44), t3 = _mm512_shuffle_f64x2(r2, r3, 0xee);
    out[0] = _mm512_shuffle_f64x2(t0, t2, 0x88);
    out[1] = _mm512_shuffle_f64x2(t0, t2, 0xdd);
    out[2] = _mm512_shuffle_f64x2(t1, t3, 0x88);
    out[3] = _mm512_shuffle_f64x2(t1, t3, 0xdd);
}

/// Phase B over discs [begin, end): four discs a block (see above), the rest one by one.
[[gnu::target("arch=x86-64-v4")]] void gather_avx512(const GatherData& d, std::size_t begin, std::size_t end) {
    // The columns as locals: the kernel's stores (which may alias anything)
    // then cannot force reloads of them.
    const std::uint32_t* const own_begin = d.begin;
    const std::uint32_t* const in_begin = d.in_begin;
    const std::uint32_t* const in_slots = d.in_slots;
    const char* const fb = reinterpret_cast<const char*>(d.f);
    const char* const cb = reinterpret_cast<const char*>(d.c);
    const std::size_t npairs = d.npairs;
    const __m512d gravity = _mm512_setr_pd(d.gravity.x, d.gravity.y, d.gravity.x, d.gravity.y, d.gravity.x,
                                           d.gravity.y, d.gravity.x, d.gravity.y);
    const __m256d half = _mm256_set1_pd(0.5 * d.dt);
    const bool kick = d.kick;
    // Disc l's count (int32) or double to lanes 2l, 2l + 1.
    const __m256i dup = _mm256_setr_epi32(0, 0, 1, 1, 2, 2, 3, 3);
    const __m512i dup_pd = _mm512_setr_epi64(0, 0, 1, 1, 2, 2, 3, 3);
    __m256i slot[4];  // the slot numbers as int32 lanes, compared with the counts
    for (int s = 0; s < 4; ++s) {
        slot[s] = _mm256_set1_epi32(s);
        asm("" : "+v"(slot[s]));  // held in registers, not rebuilt in every block
    }
    std::size_t i0 = begin;
    for (; i0 + 4 <= end; i0 += 4) {
        const std::uint32_t* ob = own_begin + i0;
        if (ob[3] + 4 > npairs) [[unlikely]] {  // slots past a disc's own pairs load a valid pair (then masked)
            for (std::size_t l = 0; l < 4; ++l) gather_disc(d, i0 + l);
            continue;
        }
        const std::uint32_t* ib = in_begin + i0;
        const __m128i on = _mm_sub_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(ob + 1)),
                                         _mm_loadu_si128(reinterpret_cast<const __m128i*>(ob)));
        const __m128i in = _mm_sub_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(ib + 1)),
                                         _mm_loadu_si128(reinterpret_cast<const __m128i*>(ib)));
        const __m256i on2 = _mm256_permutevar8x32_epi32(_mm256_zextsi128_si256(on), dup);
        const __m256i in2 = _mm256_permutevar8x32_epi32(_mm256_zextsi128_si256(in), dup);
        const __m256d ri = _mm256_loadu_pd(d.radius + i0);
        const __m512d m2 = _mm512_permutexvar_pd(dup_pd, _mm512_zextpd256_pd512(_mm256_loadu_pd(d.mass + i0)));
        __m512d f = _mm512_mul_pd(m2, gravity);  // m g, disc by disc
        __m256d t = _mm256_setzero_pd();
        {
            // Owned slots 0-3: a disc's four f are one 64-byte load and its
            // four c one 32-byte load; 4 × 4 transposes turn the discs' rows
            // into the slots' vectors.
            __m512d g[4];
            owned_f4(fb, ob, g);
            std::size_t o[4];
            for (std::size_t l = 0; l < 4; ++l) o[l] = std::size_t{ob[l]} * sizeof(double);
            __m256d oc[4];
            owned_c_avx(cb, o, oc);
            for (int s = 0; s < 4; ++s) {
                f = _mm512_mask_add_pd(f, _mm256_cmpgt_epi32_mask(on2, slot[s]), f, g[s]);
                t = _mm256_mask_sub_pd(t, _mm_cmpgt_epi32_mask(on, _mm256_castsi256_si128(slot[s])), t,
                                       _mm256_mul_pd(ri, oc[s]));
            }
        }
        // More than four of either (about one disc in a hundred): the further
        // slots, a lane past its count reading its first (masked).
        const __m128i four = _mm_set1_epi32(4);
        const bool more = (_mm_cmpgt_epi32_mask(on, four) | _mm_cmpgt_epi32_mask(in, four)) != 0;
        if (more) [[unlikely]] {
            alignas(16) std::int32_t onc[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(onc), on);
            const std::int32_t on_max = std::max(std::max(onc[0], onc[1]), std::max(onc[2], onc[3]));
            for (std::int32_t s = 4; s < on_max; ++s) {
                std::size_t off[4];
                for (std::size_t l = 0; l < 4; ++l) off[l] = std::size_t{ob[l] + (s < onc[l] ? s : 0)} * sizeof(double);
                const __m512d g = quad_at(fb, 2 * off[0], 2 * off[1], 2 * off[2], 2 * off[3]);
                f = _mm512_mask_add_pd(f, _mm256_cmpgt_epi32_mask(on2, _mm256_set1_epi32(s)), f, g);
                t = _mm256_mask_sub_pd(t, _mm_cmpgt_epi32_mask(on, _mm_set1_epi32(s)), t,
                                       _mm256_mul_pd(ri, four_at(d.c, off)));
            }
        }
        const std::uint32_t* q = in_slots + 4 * i0;
        for (int s = 0; s < 4; ++s) {
            std::size_t off[4];
            for (std::size_t l = 0; l < 4; ++l) off[l] = q[4 * l + s];
            const __m512d g = quad_at(fb, 2 * off[0], 2 * off[1], 2 * off[2], 2 * off[3]);
            f = _mm512_mask_sub_pd(f, _mm256_cmpgt_epi32_mask(in2, slot[s]), f, g);
            t = _mm256_mask_sub_pd(t, _mm_cmpgt_epi32_mask(in, _mm256_castsi256_si128(slot[s])), t,
                                   _mm256_mul_pd(ri, four_at(d.c, off)));
        }
        if (more) [[unlikely]] {
            alignas(16) std::int32_t inc[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(inc), in);
            const std::int32_t in_max = std::max(std::max(inc[0], inc[1]), std::max(inc[2], inc[3]));
            for (std::int32_t s = 4; s < in_max; ++s) {
                std::size_t off[4];
                for (std::size_t l = 0; l < 4; ++l)
                    off[l] = s < inc[l] ? std::size_t{d.in_pair[ib[l] + s]} * sizeof(double) : std::size_t{q[4 * l]};
                const __m512d g = quad_at(fb, 2 * off[0], 2 * off[1], 2 * off[2], 2 * off[3]);
                f = _mm512_mask_sub_pd(f, _mm256_cmpgt_epi32_mask(in2, _mm256_set1_epi32(s)), f, g);
                t = _mm256_mask_sub_pd(t, _mm_cmpgt_epi32_mask(in, _mm_set1_epi32(s)), t,
                                       _mm256_mul_pd(ri, four_at(d.c, off)));
            }
        }
        if (d.wall_begin[i0] != d.wall_begin[i0 + 4]) [[unlikely]] {  // a wall candidate: one disc at a time
            alignas(64) double fa[8];
            alignas(32) double ta[4];
            _mm512_store_pd(fa, f);
            _mm256_store_pd(ta, t);
            for (std::size_t l = 0; l < 4; ++l) {
                Vec2 fl = {fa[2 * l], fa[2 * l + 1]};
                wall_contacts(d, i0 + l, fl, ta[l]);
                fa[2 * l] = fl.x;
                fa[2 * l + 1] = fl.y;
            }
            f = _mm512_load_pd(fa);
            t = _mm256_load_pd(ta);
        }
        _mm512_storeu_pd(reinterpret_cast<double*>(d.force + i0), f);
        _mm256_storeu_pd(d.torque + i0, t);
        if (kick) {  // kick_disc's operations: v += (dt/2 / m) F, ω += (dt/2 / I) T
            double* v = reinterpret_cast<double*>(d.v + i0);
            const __m512d a2 = _mm512_permutexvar_pd(
                dup_pd, _mm512_zextpd256_pd512(_mm256_mul_pd(half, _mm256_loadu_pd(d.inv_mass + i0))));
            _mm512_storeu_pd(v, _mm512_add_pd(_mm512_loadu_pd(v), _mm512_mul_pd(a2, f)));
            const __m256d b = _mm256_mul_pd(half, _mm256_loadu_pd(d.inv_inertia + i0));
            _mm256_storeu_pd(d.omega + i0, _mm256_add_pd(_mm256_loadu_pd(d.omega + i0), _mm256_mul_pd(b, t)));
        }
    }
    for (; i0 < end; ++i0) gather_disc(d, i0);
}
#pragma GCC diagnostic pop

/// Discs [begin, end): O::n at a time (gather_lanes), the rest one by one;
/// O = void: one by one (the baseline version).
template <class O>
[[gnu::always_inline]] inline void gather_body(const GatherData& dref, std::size_t begin, std::size_t end) {
    const GatherData d = dref;
    std::size_t i = begin;
    if constexpr (!std::is_void_v<O>)
        for (; i + O::n <= end; i += O::n) gather_lanes<O>(d, i);
    for (; i < end; ++i) gather_disc(d, i);
}


template <class O>
[[gnu::always_inline]] inline void pair_body(const PairKernelData& dref, std::size_t begin, std::size_t end) {
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


/// The first half kick and the drift of disc i (Simulation's integrator, operation for operation).
[[gnu::always_inline]] inline double kick_drift_disc(const KickData& d, std::size_t i, double max_d2) {
    kick_disc(d.v[i], d.omega[i], d.inv_mass[i], d.inv_inertia[i], d.force[i], d.torque[i], d.half);
    d.x[i] += d.dt * d.v[i];
    d.theta[i] += d.dt * d.omega[i];
    return std::max(max_d2, norm2(d.x[i] - d.x_ref[i]));
}

/// kick_drift_disc for the O::n discs i0 ..: {v_x, v_y} and {x, y} of n/2
/// discs a vector, the rest a disc per lane; the same operations.
template <class O, class V = typename O::V>
[[gnu::always_inline]] inline V kick_drift_lanes(const KickData& d, std::size_t i0, V max_d2) {
    constexpr std::size_t h = O::n / 2;
    const auto [v_lo, v_hi] =
        kick_lanes<O>(d.v + i0, d.omega + i0, d.inv_mass + i0, d.inv_inertia + i0, simd::load<V>(d.force + i0),
                      simd::load<V>(d.force + i0 + h), simd::load<V>(d.torque + i0), d.half);
    const V w = simd::load<V>(d.omega + i0);
    const V x_lo = simd::load<V>(d.x + i0) + d.dt * v_lo, x_hi = simd::load<V>(d.x + i0 + h) + d.dt * v_hi;
    simd::store(d.x + i0, x_lo);
    simd::store(d.x + i0 + h, x_hi);
    simd::store(d.theta + i0, simd::load<V>(d.theta + i0) + d.dt * w);
    const V e_lo = x_lo - simd::load<V>(d.x_ref + i0), e_hi = x_hi - simd::load<V>(d.x_ref + i0 + h);
    const V s_lo = e_lo * e_lo, s_hi = e_hi * e_hi;
    const V r2 = O::xs_of(s_lo, s_hi) + O::ys_of(s_lo, s_hi);
    return O::select(O::lt(max_d2, r2), r2, max_d2);  // std::max, lane by lane
}

/// Discs [begin, end): O::n at a time, the rest one by one (O = void: all).
template <class O>
[[gnu::always_inline]] inline double kick_drift_body(const KickData& dref, std::size_t begin, std::size_t end,
                                                     double max_d2) {
    const KickData d = dref;  // a local copy: the stores cannot force reloads of the column pointers
    std::size_t i = begin;
    if constexpr (!std::is_void_v<O>) {
        typename O::V m = typename O::V{} + max_d2;
        for (; i + O::n <= end; i += O::n) m = kick_drift_lanes<O>(d, i, m);
        for (std::size_t l = 0; l < O::n; ++l) max_d2 = std::max(max_d2, m[l]);  // max is exact in any order
    }
    for (; i < end; ++i) max_d2 = kick_drift_disc(d, i, max_d2);
    return max_d2;
}

template <class O>
[[gnu::always_inline]] inline void kick_body(const KickData& dref, std::size_t begin, std::size_t end) {
    const KickData d = dref;
    std::size_t i = begin;
    if constexpr (!std::is_void_v<O>) {
        using V = typename O::V;
        for (; i + O::n <= end; i += O::n)
            kick_lanes<O>(d.v + i, d.omega + i, d.inv_mass + i, d.inv_inertia + i, simd::load<V>(d.force + i),
                          simd::load<V>(d.force + i + O::n / 2), simd::load<V>(d.torque + i), d.half);
    }
    for (; i < end; ++i) kick_disc(d.v[i], d.omega[i], d.inv_mass[i], d.inv_inertia[i], d.force[i], d.torque[i], d.half);
}

// The three builds of each kernel: the bodies above inlined into functions
// compiled for each ISA (the always_inline helpers take the caller's ISA).
void gather_sse2(const GatherData& d, std::size_t b, std::size_t e) { gather_body<void>(d, b, e); }
[[gnu::target("arch=x86-64-v3")]] void gather_avx2(const GatherData& d, std::size_t b, std::size_t e) {
    gather_body<Lanes4<true>>(d, b, e);
}
void pairs_sse2(const PairKernelData& d, std::size_t b, std::size_t e) { pair_body<Lanes4<false>>(d, b, e); }
[[gnu::target("arch=x86-64-v3")]] void pairs_avx2(const PairKernelData& d, std::size_t b, std::size_t e) {
    pair_body<Lanes4<true>>(d, b, e);
}
[[gnu::target("arch=x86-64-v4")]] void pairs_avx512(const PairKernelData& d, std::size_t b, std::size_t e) {
    pair_body<Lanes8>(d, b, e);
}

double kick_drift_sse2(const KickData& d, std::size_t b, std::size_t e, double m) {
    return kick_drift_body<void>(d, b, e, m);
}
[[gnu::target("arch=x86-64-v3")]] double kick_drift_avx2(const KickData& d, std::size_t b, std::size_t e, double m) {
    return kick_drift_body<Lanes4<true>>(d, b, e, m);
}
[[gnu::target("arch=x86-64-v4")]] double kick_drift_avx512(const KickData& d, std::size_t b, std::size_t e, double m) {
    return kick_drift_body<Lanes8>(d, b, e, m);
}
void kick_sse2(const KickData& d, std::size_t b, std::size_t e) { kick_body<void>(d, b, e); }
[[gnu::target("arch=x86-64-v3")]] void kick_avx2(const KickData& d, std::size_t b, std::size_t e) {
    kick_body<Lanes4<true>>(d, b, e);
}
[[gnu::target("arch=x86-64-v4")]] void kick_avx512(const KickData& d, std::size_t b, std::size_t e) {
    kick_body<Lanes8>(d, b, e);
}

struct Kernels {
    KernelIsa isa;
    void (*gather)(const GatherData&, std::size_t, std::size_t);
    void (*pairs)(const PairKernelData&, std::size_t, std::size_t);
    double (*kick_drift)(const KickData&, std::size_t, std::size_t, double);
    void (*kick)(const KickData&, std::size_t, std::size_t);
};
constexpr Kernels kVersions[] = {{KernelIsa::sse2, gather_sse2, pairs_sse2, kick_drift_sse2, kick_sse2},
                                 {KernelIsa::avx2, gather_avx2, pairs_avx2, kick_drift_avx2, kick_avx2},
                                 {KernelIsa::avx512, gather_avx512, pairs_avx512, kick_drift_avx512, kick_avx512}};

bool cpu_runs(KernelIsa isa) {
    __builtin_cpu_init();
    switch (isa) {
        case KernelIsa::sse2: return true;
        case KernelIsa::avx2:  // x86-64-v3
            return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                   __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("movbe");
        case KernelIsa::avx512:  // x86-64-v4
            return cpu_runs(KernelIsa::avx2) && __builtin_cpu_supports("avx512f") &&
                   __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd") &&
                   __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
    }
    return false;
}

// The version select_kernel_isa chose (main calls it before any thread
// runs a kernel; read-only afterwards), else the best one, found once
// (a function-local static: safe when the first call is from threads).
const Kernels* g_kernels = nullptr;

const Kernels& kernels() {
    if (g_kernels) return *g_kernels;
    static const Kernels& best = kVersions[static_cast<int>(best_kernel_isa())];
    return best;
}

}  // namespace

const char* isa_name(KernelIsa isa) {
    switch (isa) {
        case KernelIsa::sse2: return "sse2";
        case KernelIsa::avx2: return "avx2";
        case KernelIsa::avx512: return "avx512";
    }
    return "?";
}

KernelIsa best_kernel_isa() {
    if (cpu_runs(KernelIsa::avx512)) return KernelIsa::avx512;
    if (cpu_runs(KernelIsa::avx2)) return KernelIsa::avx2;
    return KernelIsa::sse2;
}

KernelIsa select_kernel_isa(const char* requested) {
    if (!requested || !*requested) {
        g_kernels = &kVersions[static_cast<int>(best_kernel_isa())];
        return g_kernels->isa;
    }
    for (const Kernels& k : kVersions) {
        if (std::string_view(requested) != isa_name(k.isa)) continue;
        if (!cpu_runs(k.isa))
            throw ConfigError(fmt::format("ORODEM_ISA={}: this CPU lacks {}; it runs {}", requested, isa_name(k.isa),
                                          cpu_runs(KernelIsa::avx2) ? "sse2 and avx2" : "sse2 only"));
        g_kernels = &k;
        return k.isa;
    }
    throw ConfigError(fmt::format("ORODEM_ISA={}: not a kernel version; allowed: sse2, avx2, avx512 (or unset: the "
                                  "best the CPU runs)",
                                  requested));
}

KernelIsa kernel_isa() { return kernels().isa; }

void gather_range(const GatherData& d, std::size_t begin, std::size_t end) { kernels().gather(d, begin, end); }

void pair_dashpots(const LawParams& law, const double* mass, const double* inv_mass, double m_inertia_min,
                   const std::uint32_t* i, const std::uint32_t* j, std::size_t begin, std::size_t end,
                   double* gamma_n, double* gamma_s) {
    for (std::size_t k = begin; k < end; ++k) {
        // The inertial masses (max(m, 0) is m, bit for bit).
        const double mi = std::max(mass[i[k]], m_inertia_min), mj = std::max(mass[j[k]], m_inertia_min);
        // A fixed disc is infinitely heavy: the pair's effective mass is the free disc's own.
        const double m_eff = inv_mass[j[k]] == 0.0 ? mi : (inv_mass[i[k]] == 0.0 ? mj : mi * mj / (mi + mj));
        double gn = law.damp_mass_n * m_eff;
        if (law.damp_sqrt_n != 0.0) gn += law.damp_sqrt_n * std::sqrt(m_eff);
        double gs = law.damp_mass_s * m_eff;
        if (law.damp_sqrt_s != 0.0) gs += law.damp_sqrt_s * std::sqrt(m_eff);
        gamma_n[k] = gn;
        if (gamma_s) gamma_s[k] = gs;
    }
}

void incoming_slots(const std::uint32_t* in_begin, const std::uint32_t* in_pair, std::size_t n,
                    std::uint32_t* out) {
    // A byte offset k × 8 fits 32 bits while k < 2^29 (a pair list of some
    // 30 GB, far beyond any run's memory; checked all the same).
    if (n > 0 && in_begin[n] > (std::uint32_t{1} << 29))
        throw std::length_error(fmt::format("{} disc pairs: phase B's incoming-slot table holds at most 2^29", in_begin[n]));
    for (std::size_t s = 0; s < n; ++s) {
        const std::uint32_t b = in_begin[s], count = in_begin[s + 1] - b;
        for (std::uint32_t q = 0; q < 4; ++q)
            out[4 * s + q] = count == 0 ? 0u : in_pair[b + (q < count ? q : 0)] * std::uint32_t{sizeof(double)};
    }
}

void pair_radii(const double* radius, const std::uint32_t* i, const std::uint32_t* j, std::size_t begin,
                std::size_t end, double* r_i, double* r_j) {
    for (std::size_t k = begin; k < end; ++k) {
        r_i[k] = radius[i[k]];
        r_j[k] = radius[j[k]];
    }
}

void eval_pair_range(const PairKernelData& d, std::size_t begin, std::size_t end) { kernels().pairs(d, begin, end); }

double kick_drift_range(const KickData& d, std::size_t begin, std::size_t end, double max_d2) {
    return kernels().kick_drift(d, begin, end, max_d2);
}

void kick_range(const KickData& d, std::size_t begin, std::size_t end) { kernels().kick(d, begin, end); }

}  // namespace orodem
