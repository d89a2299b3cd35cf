// ThreadGovernor (run/thread_governor.hpp) on made-up timings: on a busy
// machine, where two threads take several times as long per step as one,
// it drops to one thread within its first two seconds and says so once; when
// two threads are faster it keeps them, probing one thread only every
// kProbeEvery seconds; when the machine frees up it goes back up; with one
// thread requested it never changes.
#include <gtest/gtest.h>

#include <cstdint>

#include "orodem/run/thread_governor.hpp"

using namespace orodem;

namespace {

/// Runs chunks of 100 steps for `seconds` of wall time, each chunk taking per_step(threads) a step; returns the
/// wall time spent and the count at the end.
template <class F>
double run_for(ThreadGovernor& g, double seconds, F per_step) {
    double t = 0.0;
    while (t < seconds) {
        const double dt = 100 * per_step(g.threads());
        g.record(100, dt);
        t += dt;
    }
    return t;
}

}  // namespace

TEST(ThreadGovernor, ABusyMachineDropsToOneThreadAtOnceAndSaysSoOnce) {
    ThreadGovernor g(2);
    EXPECT_EQ(g.threads(), 2);
    auto busy = [](int th) { return th == 2 ? 4.6e-3 : 1.0e-3; };  // [s per step]: 2 threads 4.6 times slower
    run_for(g, 2.0, busy);  // a discarded window, one at 2 threads, a probe at 1, one more at 2
    EXPECT_EQ(g.threads(), 1);
    const std::string note = g.take_note();
    EXPECT_NE(note.find("2 threads took 4.6 times as long per step as 1"), std::string::npos) << note;
    EXPECT_NE(g.take_log().find("threads: 2 -> 1"), std::string::npos);
    run_for(g, 100.0, busy);  // probes of 2 threads every 30 s keep failing
    EXPECT_EQ(g.threads(), 1);
    EXPECT_EQ(g.take_note(), "");  // said once
}

TEST(ThreadGovernor, AnIdleMachineKeepsTwoThreadsAndProbesRarely) {
    ThreadGovernor g(2);
    int probes = 0, last = 2;
    double t = 0.0;
    while (t < 120.0) {
        const int th = g.threads();
        if (th == 1 && last == 2) ++probes;
        last = th;
        const double dt = 100 * (th == 2 ? 0.55e-3 : 1.0e-3);
        g.record(100, dt);
        t += dt;
    }
    EXPECT_EQ(g.threads(), 2);
    EXPECT_LE(probes, 1 + static_cast<int>(120.0 / ThreadGovernor::kProbeEvery));  // one at the start, then every 30 s
    EXPECT_GE(probes, 2);
    EXPECT_EQ(g.take_note(), "");
    EXPECT_EQ(g.take_log(), "");
}

TEST(ThreadGovernor, GoesBackUpWhenTheMachineFreesUp) {
    ThreadGovernor g(2);
    run_for(g, 2.0, [](int th) { return th == 2 ? 4.6e-3 : 1.0e-3; });
    ASSERT_EQ(g.threads(), 1);
    run_for(g, 2 * ThreadGovernor::kProbeEvery, [](int th) { return th == 2 ? 0.55e-3 : 1.0e-3; });
    EXPECT_EQ(g.threads(), 2);
    EXPECT_NE(g.take_log().find("threads: 1 -> 2"), std::string::npos);
}

TEST(ThreadGovernor, SmallDifferencesDoNotSwitch) {
    ThreadGovernor g(2);
    run_for(g, 100.0, [](int th) { return th == 2 ? 1.0e-3 : 0.9e-3; });  // one thread only 10% faster: within the margin
    EXPECT_EQ(g.threads(), 2);
}

TEST(ThreadGovernor, OneThreadRequestedNeverChanges) {
    ThreadGovernor g(1);
    run_for(g, 100.0, [](int) { return 1.0e-3; });
    EXPECT_EQ(g.threads(), 1);
}

TEST(ThreadGovernor, ManyThreadsHalveUnderLoad) {
    ThreadGovernor g(16);
    // 5 cores free: the work divides over up to 5 threads, and each thread beyond them adds a wait at the barriers.
    auto per_step = [](int th) { return 1.0e-3 / (th < 5 ? th : 5) * (th > 5 ? 1 + (th - 5) : 1); };
    run_for(g, 200.0, per_step);
    EXPECT_LE(g.threads(), 5);
    EXPECT_GE(g.threads(), 2);
}

TEST(ThreadGovernor, ABurstInOneWindowDecidesNothing) {
    // Two threads are faster, but another process's burst slows the window before the first probe 4.6 times:
    // the window after the probe is fast again, so the count stays.
    ThreadGovernor g(2);
    double t = 0.0;
    while (t < 10.0) {
        const bool burst = t > 0.3 && t < 0.7;
        const double per_step = g.threads() == 2 ? (burst ? 2.5e-3 : 0.55e-3) : 1.0e-3;
        g.record(100, 100 * per_step);
        t += 100 * per_step;
    }
    EXPECT_EQ(g.threads(), 2);
    EXPECT_EQ(g.take_log(), "");
}
