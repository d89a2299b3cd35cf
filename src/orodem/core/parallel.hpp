// Deterministic parallel helpers. A sum over particles is split into fixed
// chunks of kChunk items whatever the thread count; chunk partials are added
// in chunk order, so the result is bit-identical at 1, 2, ... N threads.
#pragma once

#include <cstddef>
#include <vector>

namespace orodem {

inline constexpr std::size_t kChunk = 4096;

/// Loops shorter than this run on one thread: for a few thousand items the
/// cost of waking the team exceeds the work (and on a loaded machine a
/// descheduled team member stalls everyone). Results do not depend on it.
inline constexpr long long kParallelMin = 4096;

/// Σ_{k<n} term(k), summed in fixed chunks and then in chunk order.
template <class F>
double deterministic_sum(std::size_t n, F&& term) {
    const std::size_t nchunks = (n + kChunk - 1) / kChunk;
    if (nchunks <= 1) {
        double s = 0.0;
        for (std::size_t k = 0; k < n; ++k) s += term(k);
        return s;
    }
    // Partials on the stack up to kStackChunks chunks (1M items): boundaries
    // call this every step, and a step must not allocate.
    constexpr std::size_t kStackChunks = 256;
    double stack_partial[kStackChunks];
    std::vector<double> heap_partial;
    double* partial = stack_partial;
    if (nchunks > kStackChunks) {
        heap_partial.assign(nchunks, 0.0);
        partial = heap_partial.data();
    }
    const long long nc = static_cast<long long>(nchunks);
#pragma omp parallel for schedule(static)
    for (long long c = 0; c < nc; ++c) {
        const std::size_t b = static_cast<std::size_t>(c) * kChunk;
        const std::size_t e = b + kChunk < n ? b + kChunk : n;
        double s = 0.0;
        for (std::size_t k = b; k < e; ++k) s += term(k);
        partial[static_cast<std::size_t>(c)] = s;
    }
    double s = 0.0;
    for (std::size_t c = 0; c < nchunks; ++c) s += partial[c];
    return s;
}

}  // namespace orodem
