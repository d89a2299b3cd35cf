// The step kernels' dispatch: each kernel built for three ISAs (baseline
// SSE2, x86-64-v3 AVX2, x86-64-v4 AVX-512) from the bodies in
// engine/kernels/ (lanes.hpp: the lane policies; phase_a.hpp: the contact
// law per pair block; phase_b.hpp: the per-disc gather, its versions side by
// side; kick.hpp: the integrator's passes), chosen once at run time
// (select_kernel_isa, ORODEM_ISA) and called through one table. Every
// version gives the same bits (pair_kernel.hpp).
#include "orodem/engine/pair_kernel.hpp"

#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/engine/kernels/kick.hpp"
#include "orodem/engine/kernels/lanes.hpp"
#include "orodem/engine/kernels/phase_a.hpp"
#include "orodem/engine/kernels/phase_b.hpp"

namespace orodem {
namespace {

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
