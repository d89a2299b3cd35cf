// The thread team of the step's parallel regions: each thread's share of a
// range, the team a region over n items gets, and the chunk sizes of the
// phases (engine/step.cpp, engine/phases.cpp). Any split gives the same
// results: every parallel loop writes only slots its iteration owns.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <utility>

#include "orodem/core/parallel.hpp"
#include "orodem/core/stealing_split.hpp"

namespace orodem::team {

/// [begin, end) of this thread of the region's team over n items, cut at multiples of
/// `align` items (no two threads write one cache line). Any split gives the
/// same results; this one is contiguous per thread.
inline std::pair<std::size_t, std::size_t> thread_range(std::size_t n, std::size_t align) {
    return StealingSplit::share(n, static_cast<std::size_t>(omp_get_num_threads()),
                                static_cast<std::size_t>(omp_get_thread_num()), align);
}

/// Phases A and B in a parallel region: chunks of at most this many pairs
/// and discs (StealingSplit), about 8 µs of work each on the pile, and at
/// least kPairChunkMin and kDiscChunkMin (a chunk's own cost, the bases' law
/// and the timers of the wedge step's phase B included, stays a few per cent).
inline constexpr std::size_t kPairChunk = 2048, kDiscChunk = 1024;
inline constexpr std::size_t kPairChunkMin = 512, kDiscChunkMin = 256;

/// The threads of a parallel region over n items with `if(n >= kParallelMin)`.
inline std::size_t team_for(std::size_t n) {
    return static_cast<long long>(n) >= kParallelMin ? static_cast<std::size_t>(omp_get_max_threads()) : 1;
}

inline std::size_t this_thread() { return static_cast<std::size_t>(omp_get_thread_num()); }


/// The integrator's per-disc passes (kick_drift_range, kick_range) run over
/// chunks of this many discs in an omp for (the rebuild test's maximum
/// reduced over the threads). Any split gives the same results: a disc's
/// own operations, and a maximum is exact in any order. Small, as the static
/// split gives a thread up to one chunk more than the other: with 1,024
/// the first of two threads drifted an intermediate-size wedge 1.3-1.6
/// times as long as the second.
inline constexpr long long kKickChunk = 128;

/// The number of kKickChunk chunks of discs [b, e), and chunk c's discs.
inline long long kick_chunks(long long b, long long e) { return (e - b + kKickChunk - 1) / kKickChunk; }
inline std::pair<std::size_t, std::size_t> kick_chunk(long long b, long long e, long long c) {
    return {static_cast<std::size_t>(b + c * kKickChunk), static_cast<std::size_t>(std::min(e, b + (c + 1) * kKickChunk))};
}


}  // namespace orodem::team
