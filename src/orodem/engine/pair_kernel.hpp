// Phase A of the step: the contact law for a range of candidate pairs,
// evaluated kLanes pairs at a time in SIMD lanes.
//
// Bit-identity: every lane performs exactly the IEEE operations, in the same
// order, that eval_contact() and the scalar pair loop perform for one pair
// (+, -, *, /, sqrt are correctly rounded in every ISA; -ffp-contract=off
// forbids fused multiply-adds). Branches become selects: a lane computes
// both sides and keeps the one the scalar code would take, so a pair's
// result does not depend on its lane, its block or the ISA the kernel was
// compiled for. The kernel is built for the baseline x86-64 ISA and, where
// the CPU has them, for AVX2 and AVX-512 (function multiversioning; the same
// results, wider vectors).
//
// Each pair writes only its own slots (f, c, ξ, and its two entries of the
// per-disc force list `contrib`, see ContactStore), so any split of [begin,
// end) among threads gives the same results.
#pragma once

#include <cstddef>
#include <cstdint>

#include "orodem/core/vec2.hpp"
#include "orodem/physics/contact_law.hpp"

namespace orodem {

/// Views of the columns the pair law reads and writes (no ownership).
struct PairKernelData {
    // particles, by slot
    const Vec2* x;
    const Vec2* v;
    const double* omega;
    const double* radius;
    const double* mass;
    const double* inv_mass;
    // pairs
    const std::uint32_t* i;
    const std::uint32_t* j;
    const std::int8_t* shift;
    const std::uint8_t* bonded;
    Vec2* xi;
    Vec2* f;
    double* c;
    double period_x;  // W [m]
    double dt;        // [s]
    LawParams law;
    bool update_history;
};

/// Evaluates pairs [begin, end): f[k], c[k] and (if update_history) ξ[k].
void eval_pair_range(const PairKernelData& d, std::size_t begin, std::size_t end);

}  // namespace orodem
