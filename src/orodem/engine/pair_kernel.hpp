// The two force phases of the step as kernels over index ranges:
//   A  eval_pair_range: the contact law for candidate pairs, eight pairs at a
//      time in SIMD lanes in the AVX-512 version, four in the others;
//   B  gather_range: per disc, gravity + its pair forces + its wall contacts,
//      then (optionally) the second half kick; four discs at a time in SIMD
//      lanes in the AVX2 and AVX-512 versions;
// and the integrator's per-disc passes, four discs at a time in the AVX2
// version and eight in the AVX-512 one: kick_drift_range (first half kick,
// drift, the rebuild test's displacement) and kick_range (second half kick).
//
// Bit-identity: every lane performs exactly the IEEE operations, in the same
// order, that eval_contact() and the scalar pair loop perform for one pair
// (+, -, *, /, sqrt are correctly rounded in every ISA; -ffp-contract=off
// forbids fused multiply-adds). Branches become selects: a lane computes
// both sides and keeps the one the scalar code would take, so a pair's
// result does not depend on its lane, its block or the ISA the kernel was
// compiled for. The kernels are built three times, for the baseline x86-64
// ISA (SSE2), x86-64-v3 (AVX2) and x86-64-v4 (AVX-512): the same operations
// in wider registers. The version is chosen once per process
// (select_kernel_isa): the best the CPU has, or the one ORODEM_ISA names, so
// a test can run a config with each and compare the outputs byte for byte
// (tests/cli/test_isa.cpp). tests/unit/test_pair_kernel.cpp checks phase A
// against the per-pair loop bit for bit.
//
// Determinism: a pair writes only its own slots (f, c, ξ), a disc only its
// own columns, and a disc sums its pair forces in a fixed order (owned pairs,
// then incoming pairs, then walls), so any split of a range among threads
// gives the same results.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "orodem/core/vec2.hpp"
#include "orodem/physics/contact_law.hpp"
#include "orodem/state/contacts.hpp"  // Wall

namespace orodem {

/// Views of the columns the pair law reads and writes (no ownership).
struct PairKernelData {
    // particles, by slot
    const Vec2* x;
    const Vec2* v;
    const double* omega;
    // pairs
    const double* r_i;  // R of the pair's disc i [m] (pair_radii)
    const double* r_j;  // R of disc j [m]
    const std::uint32_t* i;
    const std::uint32_t* j;
    const std::int8_t* shift;
    const std::uint8_t* bonded;
    const double* gamma_n;  // normal dashpot of the pair [N s/m] (pair_dashpots)
    const double* gamma_s;  // tangential dashpot of the pair [N s/m]; null: +0 for every pair (zero_gamma_s)
    Vec2* xi;
    Vec2* f;
    double* c;
    double period_x;  // W [m]
    double dt;        // [s]
    LawParams law;
    bool update_history;
    std::size_t n_discs;  // slots in x, v, ω (bounds phase A's window loads of disc i)
    // Several materials (Simulation::materials): each pair's law as columns,
    // read instead of law.k_n, k_s, mu and cohesion, and each pair's plastic
    // slip and separation recorded (phase_a.hpp PerPair); null with one material.
    const double* k_n_pair = nullptr;       // [N/m]
    const double* k_s_pair = nullptr;       // [N/m]
    const double* mu_pair = nullptr;        // μ, weakened by the discs' damage [-]
    const double* cohesion_pair = nullptr;  // C, 0 once lost [N]
    double* slip = nullptr;                 // plastic tangential slip since the last rebuild, added to [m]
    std::uint8_t* broke = nullptr;          // set to 1 when a pair with history no longer touches
};

/// The dashpots of pairs [begin, end) from the discs' masses, as eval_contact
/// computes them: γ = damp_mass m_eff (+ damp_sqrt sqrt(m_eff) where damp_sqrt
/// is not 0), m_eff = m_i m_j / (m_i + m_j), or the free disc's mass when the
/// other one is fixed or asleep (inverse mass 0). They change only when the
/// pairs or an inverse mass do, so the engine computes them then instead of
/// in every step (a division and, with restitution damping, a square root
/// per pair less in phase A). The masses are the inertial ones, max(m,
/// m_inertia_min) [kg] (SimParams::m_inertia_min).
void pair_dashpots(const LawParams& law, const double* mass, const double* inv_mass, double m_inertia_min,
                   const std::uint32_t* i, const std::uint32_t* j, std::size_t begin, std::size_t end,
                   double* gamma_n, double* gamma_s);

/// True when pair_dashpots would give every pair γ_s = +0 exactly (no
/// tangential dashpot: damp_mass_s is +0 and damp_sqrt_s is 0, as in the
/// benchmark pile and every shipped config). The engine then keeps no γ_s
/// column: PairKernelData::gamma_s is null and pair_dashpots takes null for
/// it (8 bytes a pair less to read each step).
inline bool zero_gamma_s(const LawParams& law) {
    return law.damp_mass_s == 0.0 && !std::signbit(law.damp_mass_s) && law.damp_sqrt_s == 0.0;
}

/// The radii of pairs [begin, end)'s discs as pair columns: phase A loads
/// four pairs' R_i and R_j as two vectors instead of eight scalars. They
/// change only with the pair list.
void pair_radii(const double* radius, const std::uint32_t* i, const std::uint32_t* j, std::size_t begin,
                std::size_t end, double* r_i, double* r_j);

/// The instruction-set versions of the kernels.
enum class KernelIsa { sse2, avx2, avx512 };
const char* isa_name(KernelIsa isa);  // "sse2" | "avx2" | "avx512"
/// The best version this CPU runs.
KernelIsa best_kernel_isa();
/// Chooses the version for the rest of the process: `requested` ("sse2",
/// "avx2", "avx512"; null or empty: the best), e.g. the environment's
/// ORODEM_ISA. Returns the chosen one; a name that is not a version, or a
/// version this CPU lacks, throws ConfigError naming what is allowed.
KernelIsa select_kernel_isa(const char* requested);
/// The version in use (the best until select_kernel_isa is called).
KernelIsa kernel_isa();

/// Evaluates pairs [begin, end): f[k], c[k] and (if update_history) ξ[k].
void eval_pair_range(const PairKernelData& d, std::size_t begin, std::size_t end);

/// The four-slot table of the incoming pairs, for phase B's AVX-512
/// version: out[4 s + q] (s < n discs, q < 4) is the byte offset
/// (pair index × 8) of disc s's incoming pair q, or, past its count, of
/// its first incoming pair (pair 0 if it has none; then masked). It changes
/// only with the pair list. More than 2^29 pairs throw std::length_error.
void incoming_slots(const std::uint32_t* in_begin, const std::uint32_t* in_pair, std::size_t n,
                    std::uint32_t* out);

/// Views for the gather (no ownership).
struct GatherData {
    // particles, by slot
    const Vec2* x;
    Vec2* v;
    double* omega;
    const double* radius;
    const double* mass;
    const double* inv_mass;
    const double* inv_inertia;
    Vec2* force;
    double* torque;
    // pairs (ContactStore): owned by slot s: begin[s] ..; incoming: in_pair[in_begin[s] ..]
    const std::uint32_t* begin;
    const std::uint32_t* in_begin;
    const std::uint32_t* in_pair;
    const std::uint32_t* in_slots;  // 4 a disc: its incoming slots 0-3 as byte offsets (incoming_slots)
    const Vec2* f;
    const double* c;
    std::size_t npairs;
    // disc-wall candidates (WallContactStore) and the walls
    const std::uint32_t* wall_begin;
    const std::uint16_t* wall;
    Vec2* wall_xi;
    Vec2* wall_f;
    double* wall_c;
    const Wall* walls;
    const LawParams* wall_law;  // per wall
    Vec2 gravity;  // [m/s²]
    double dt;     // [s]
    double m_inertia_min;  // a wall contact's dashpot mass is max(m_i, this) (SimParams::m_inertia_min) [kg]
    bool update_history;
    bool kick;     // also v += F/m dt/2, ω += T/I dt/2
};

/// Discs [begin, end): force = m g + Σ f over owned pairs - Σ f over incoming
/// pairs (each in order) + wall contacts (evaluated here, in order), torque
/// -R (Σ c ...) likewise term by term; then the half kick if d.kick.
void gather_range(const GatherData& d, std::size_t begin, std::size_t end);

/// Views for the integrator's per-disc passes (no ownership).
struct KickData {
    Vec2* x;
    Vec2* v;
    double* omega;
    double* theta;
    const Vec2* force;
    const double* torque;
    const double* inv_mass;
    const double* inv_inertia;
    const Vec2* x_ref;  // positions at the last rebuild
    double dt;          // [s]
    double half;        // dt / 2 [s]
};

/// Discs [begin, end): v += (dt/2 / m) F, ω += (dt/2 / I) T, x += dt v,
/// θ += dt ω; returns the larger of `max_d2` and every |x - x_ref|² [m²].
double kick_drift_range(const KickData& d, std::size_t begin, std::size_t end, double max_d2);
/// Discs [begin, end): v += (dt/2 / m) F, ω += (dt/2 / I) T.
void kick_range(const KickData& d, std::size_t begin, std::size_t end);

}  // namespace orodem
