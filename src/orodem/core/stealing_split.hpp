// StealingSplit: the static split of [0, n) among a parallel region's
// threads, with stealing at the tails. Each thread works through its own
// contiguous share (the share it would have under a static split, so it
// keeps to the slots whose data it touched in the phase before) in chunks
// that it claims from the share's counter, then claims what is left of the
// other shares. On a host that slows one vCPU for a while (another tenant,
// an interrupt), the barrier after the phase no longer waits for that
// thread's whole lag: the other thread takes its last chunks.
//
// Determinism: which thread runs a chunk changes no result when every item
// writes only its own slots (phases A and B, the kick, the bases' law per
// disc range), so the results are those of any split. The counters are
// integer atomics (no floating-point atomics); claiming is relaxed, as the
// region's barriers publish the chunks' writes.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <memory>
#include <utility>

namespace orodem {

class StealingSplit {
public:
    /// Shares for `nth` threads over [0, n), cut at multiples of `align`
    /// items (no two threads write one cache line but at a stolen chunk's
    /// ends), claimed `chunk` items at a time (a multiple of align). Call
    /// outside the parallel region; allocates only when nth grows.
    void reset(std::size_t n, std::size_t nth, std::size_t align, std::size_t chunk) {
        if (nth > cap_) {
            shares_ = std::make_unique<Share[]>(nth);
            cap_ = nth;
        }
        nth_ = nth;
        chunk_ = chunk;
        for (std::size_t t = 0; t < nth; ++t) {
            const auto [b, e] = share(n, nth, t, align);
            shares_[t].next.store(b, std::memory_order_relaxed);
            shares_[t].end = e;
        }
    }

    /// Thread t's static share [begin, end) of [0, n) among nth threads, cut
    /// at multiples of `align` items; contiguous, in thread order.
    static std::pair<std::size_t, std::size_t> share(std::size_t n, std::size_t nth, std::size_t t,
                                                     std::size_t align) {
        const std::size_t units = (n + align - 1) / align;
        return {std::min(n, align * (units * t / nth)), std::min(n, align * (units * (t + 1) / nth))};
    }

    /// The chunk for n items over `team` threads: about eight chunks in each
    /// thread's share, within [least, most] (both multiples of align), a
    /// multiple of align. The thread that finishes its share first then
    /// waits at the phase's barrier for less than a chunk of the other's.
    static std::size_t chunk_for(std::size_t n, std::size_t team, std::size_t align, std::size_t least,
                                 std::size_t most) {
        const std::size_t c = std::clamp(n / (8 * std::max<std::size_t>(team, 1)), least, most);
        return (c + align - 1) / align * align;
    }

    /// Inside the region, by every thread (tid of a team of any size): f(b, e)
    /// on chunks [b, e) of its own share, then of the others', until none is
    /// left. Every item of [0, n) is passed exactly once over the team.
    template <class F>
    void run(std::size_t tid, F&& f) {
        for (std::size_t k = 0; k < nth_; ++k) {
            Share& s = shares_[(tid + k) % nth_];
            for (;;) {
                const std::size_t b = s.next.fetch_add(chunk_, std::memory_order_relaxed);
                if (b >= s.end) break;
                f(b, std::min(b + chunk_, s.end));
            }
        }
    }

private:
    struct alignas(64) Share {
        std::atomic<std::size_t> next{0};
        std::size_t end = 0;
    };
    std::unique_ptr<Share[]> shares_;
    std::size_t cap_ = 0, nth_ = 0, chunk_ = 0;
};

}  // namespace orodem
