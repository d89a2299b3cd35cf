// Small fixed-width double vectors (GCC/Clang vector extensions) for the step
// kernels. Every operation is the lane-wise IEEE operation (+, -, *, /, sqrt,
// compare, select), so a lane computes bit for bit what scalar code computes;
// with -ffp-contract=off no multiply-add is ever fused, whatever the ISA the
// code is compiled for (the baseline x86-64 SSE2 splits a 4-lane vector in two).
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>

// Vector arguments change the calling convention between ISAs; every helper
// here is inlined, so the note is moot.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace orodem::simd {

using v2d = double __attribute__((vector_size(2 * sizeof(double))));
using v4d = double __attribute__((vector_size(4 * sizeof(double))));
using v4m = decltype(v4d{} < v4d{});  // lane mask: all bits set where true

template <class V>
[[gnu::always_inline]] inline V load(const void* p) {
    V r;
    __builtin_memcpy(&r, p, sizeof r);
    return r;
}
template <class V>
[[gnu::always_inline]] inline void store(void* p, V v) {
    __builtin_memcpy(p, &v, sizeof v);
}

template <class F, std::size_t... L>
[[gnu::always_inline]] inline v4d lanes_impl(F&& f, std::index_sequence<L...>) {
    return v4d{f(L)...};
}
/// {f(0), f(1), f(2), f(3)}
template <class F>
[[gnu::always_inline]] inline v4d lanes(F&& f) {
    return lanes_impl(f, std::make_index_sequence<4>{});
}
/// Lane-wise sqrt (vectorised where the file is built with -fno-math-errno).
[[gnu::always_inline]] inline v4d sqrt(v4d a) {
    return lanes([&](std::size_t l) { return std::sqrt(a[l]); });
}
[[gnu::always_inline]] inline v4d fabs(v4d a) {
    const v4m magnitude = v4m{} + 0x7fffffffffffffffLL;
    return reinterpret_cast<v4d>(reinterpret_cast<v4m>(a) & magnitude);
}
[[gnu::always_inline]] inline v2d low(v4d a) { return v2d{a[0], a[1]}; }
[[gnu::always_inline]] inline v2d high(v4d a) { return v2d{a[2], a[3]}; }

}  // namespace orodem::simd
