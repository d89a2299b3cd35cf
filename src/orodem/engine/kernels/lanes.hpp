// The lane policies of the step kernels: Lanes4 and Lanes8 and the few
// vector helpers phases A and B and the integrator share.
// Private to engine/pair_kernel.cpp, which includes it once: the three
// ISA builds of each kernel must see these bodies in one translation unit,
// so that the always_inline helpers take the caller's target ISA.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include <immintrin.h>

#include "orodem/core/simd.hpp"
#include "orodem/engine/pair_kernel.hpp"

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
/// faster, 12% fewer instructions; docs/studies/kernel-history.md).
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
// docs/studies/kernel-history.md).

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
}  // namespace
}  // namespace orodem
