// Phase B of the step: per disc, gravity, its owned and incoming pairs' forces,
// its wall contacts and (fused) the second half kick, in one fixed order.
//
// Its versions side by side: the baseline one disc at a time (gather_disc);
// the AVX versions four discs a time, so the serial sums of one disc (its
// force and torque, term by term) stay in order while four run side by
// side: a disc per lane in the AVX2 version (gather_lanes), the four discs'
// forces as they lie in memory in the AVX-512 one (gather_avx512). Every
// version gives every disc gather_disc()'s operations in its order.
// Private to engine/pair_kernel.cpp, which includes it once: the three
// ISA builds of each kernel must see these bodies in one translation unit,
// so that the always_inline helpers take the caller's target ISA.
#pragma once

#include "orodem/engine/kernels/kick.hpp"
#include "orodem/neighbor/pair_builder.hpp"

namespace orodem {
namespace {
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
        const Vec2 u = wall_tangent(w, d.x[i]);  // a straight wall's (b − a)/|b − a|
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
}  // namespace
}  // namespace orodem
