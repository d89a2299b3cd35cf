// The integrator's passes: the half kick and the first half kick with the
// drift, one disc at a time and O::n discs a block (Simulation's
// integrator, operation for operation); phase B fuses the second half kick.
// Private to engine/pair_kernel.cpp, which includes it once: the three
// ISA builds of each kernel must see these bodies in one translation unit,
// so that the always_inline helpers take the caller's target ISA.
#pragma once

#include "orodem/engine/kernels/lanes.hpp"

namespace orodem {
namespace {
/// The half kick of one disc: Simulation::kick()'s operations.
[[gnu::always_inline]] inline void kick_disc(Vec2& v, double& omega, double inv_mass, double inv_inertia, Vec2 f,
                                             double t, double half) {
    v += (half * inv_mass) * f;
    omega += half * inv_inertia * t;
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
}  // namespace
}  // namespace orodem
