// StealingSplit (core/stealing_split.hpp): over a parallel region of any
// team size, every item of [0, n) is handed out exactly once, in chunks that
// stay inside one share, and a thread starts with its own share.
#include <omp.h>

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "orodem/core/stealing_split.hpp"

namespace orodem {
namespace {

struct Chunk {
    std::size_t b, e, tid;
};

/// Runs the split on a team of `team` threads (shares for `nth`) and returns
/// how often each item was handed out, plus the chunks per thread in order.
std::vector<int> hand_out(std::size_t n, std::size_t nth, int team, std::size_t align, std::size_t chunk,
                          std::vector<std::vector<Chunk>>& by_thread) {
    StealingSplit split;
    split.reset(n, nth, align, chunk);
    std::vector<int> count(n, 0);
    by_thread.assign(static_cast<std::size_t>(team), {});
#pragma omp parallel num_threads(team)
    {
        const std::size_t tid = static_cast<std::size_t>(omp_get_thread_num());
        split.run(tid, [&](std::size_t b, std::size_t e) {
            by_thread[tid].push_back({b, e, tid});
            for (std::size_t k = b; k < e; ++k) {
#pragma omp atomic
                ++count[k];
            }
        });
    }
    return count;
}

TEST(StealingSplit, EveryItemExactlyOnceForAnyTeamAndShareCount) {
    for (const std::size_t n : {0, 1, 7, 64, 1000, 4097, 30000})
        for (const std::size_t nth : {1, 2, 3, 4})
            for (const int team : {1, 2, 3, 5}) {
                std::vector<std::vector<Chunk>> by_thread;
                const std::vector<int> count = hand_out(n, nth, team, 8, 64, by_thread);
                for (std::size_t k = 0; k < n; ++k)
                    ASSERT_EQ(count[k], 1) << "item " << k << " n " << n << " shares " << nth << " team " << team;
            }
}

TEST(StealingSplit, OneThreadTakesItsShareThenTheOthersInOrder) {
    // Two shares of [0, 10000): 1250 units of 8, cut at 625 units = item 5000.
    std::vector<std::vector<Chunk>> by_thread;
    hand_out(10000, 2, 1, 8, 512, by_thread);
    std::vector<std::size_t> begins;
    for (const Chunk& c : by_thread[0]) begins.push_back(c.b);
    std::vector<std::size_t> expected;
    for (std::size_t b = 0; b < 5000; b += 512) expected.push_back(b);
    for (std::size_t b = 5000; b < 10000; b += 512) expected.push_back(b);
    EXPECT_EQ(begins, expected);
    EXPECT_EQ(by_thread[0][9].e, 5000u);  // the last chunk of share 0 ends at the cut
}

TEST(StealingSplit, ChunksStayInsideTheStaticSharesOnTwoThreads) {
    const std::size_t cut = 5000;  // as above
    for (int round = 0; round < 20; ++round) {
        std::vector<std::vector<Chunk>> by_thread;
        hand_out(10000, 2, 2, 8, 512, by_thread);
        for (const auto& chunks : by_thread)
            for (const Chunk& c : chunks) {
                EXPECT_LT(c.b, c.e);
                EXPECT_LE(c.e - c.b, 512u);
                EXPECT_TRUE(c.e <= cut || c.b >= cut) << "chunk [" << c.b << ", " << c.e << ") spans two shares";
                EXPECT_EQ(c.b % 8, 0u);
            }
    }
}

TEST(StealingSplit, ChunksAreAboutAnEighthOfAShareWithinTheirBoundsAndAligned) {
    // The pile at two threads: 72,000 pairs / 16 = 4,500, held to 2,048; an
    // intermediate-size wedge's 15,000 awake pairs: 937 -> 960 (a multiple of 64).
    EXPECT_EQ(StealingSplit::chunk_for(72000, 2, 64, 512, 2048), 2048u);
    EXPECT_EQ(StealingSplit::chunk_for(15000, 2, 64, 512, 2048), 960u);
    EXPECT_EQ(StealingSplit::chunk_for(6600, 2, 8, 256, 1024), 416u);  // 412.5 -> 412 -> 416
    EXPECT_EQ(StealingSplit::chunk_for(1000, 2, 8, 256, 1024), 256u);  // small ranges: the least
    EXPECT_EQ(StealingSplit::chunk_for(0, 0, 8, 256, 1024), 256u);     // no threads counted as one
    for (std::size_t n = 0; n < 100000; n += 977)
        for (const std::size_t team : {1, 2, 3, 8}) {
            const std::size_t c = StealingSplit::chunk_for(n, team, 64, 512, 2048);
            EXPECT_EQ(c % 64, 0u);
            EXPECT_GE(c, 512u);
            EXPECT_LE(c, 2048u);
            if (c > 512 && c < 2048) {
                const double eighth = static_cast<double>(n) / (8.0 * static_cast<double>(team));
                EXPECT_NEAR(static_cast<double>(c), eighth, 64.0) << n << " " << team;
            }
        }
}

}  // namespace
}  // namespace orodem
