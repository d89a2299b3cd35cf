// ThreadGovernor: the thread count of a run's chunks of steps, chosen so
// that more threads never make a run slower than fewer. On a machine where
// another process holds a core, a thread that waits at one of the step's
// barriers spins while the thread it waits for is not running, and two
// threads can take several times as long per step as one (measured:
// intermediate exp1 with one core busy, 50.7 s on 2 threads against 11.0 s
// on one; docs/benchmarks.md "Threads on a busy machine"). The results are
// the same at any thread count (docs/ARCHITECTURE.md "Determinism"), so the
// count may change between any two chunks: the governor times the chunks,
// now and then runs one window at the other count (half the current, or
// back up towards the requested one), and keeps the faster when it is
// faster by a clear margin. It reads no clock itself (the caller reports
// each chunk's steps and seconds), so its decisions are tested with made-up
// timings.
#pragma once

#include <cstdint>
#include <string>

#include "orodem/run/observer.hpp"
#include "orodem/run/run_log.hpp"

namespace orodem {

class ThreadGovernor {
public:
    static constexpr double kWindowSeconds = 0.3;   // a window: at least this much wall time of chunks [s]
    static constexpr double kProbeEvery = 30.0;     // wall time between probes of the other count [s]
    static constexpr double kProbeAfterChange = 5.0;  // ... and after a change of the count [s]
    static constexpr double kMargin = 0.85;         // switch when the other count's time per step is below this fraction

    /// requested: the threads the run asked for (run.threads, or all cores); 1 or less: never changes.
    explicit ThreadGovernor(int requested);
    /// The count for the next chunk.
    int threads() const { return phase_ == Phase::probe ? probe_ : current_; }
    /// A chunk of `steps` steps took `seconds` at threads().
    void record(std::uint64_t steps, double seconds);
    /// A line to say once, when the count first drops below the requested one (else "").
    std::string take_note();
    /// The changes since the last call, one line each, for the log (else "").
    std::string take_log();
    /// False when ORODEM_ADAPT_THREADS=0 is set: the requested count is kept.
    static bool enabled_by_environment();

private:
    void finish_window(double per_step);
    int alternative();
    enum class Phase { warm_up, steady, probe, confirm };
    int requested_;
    int current_;
    Phase phase_ = Phase::warm_up;
    int probe_ = 0;
    double window_s_ = 0.0;        // wall time of the current window so far [s]
    std::uint64_t window_steps_ = 0;
    double before_ = 0.0;          // the last steady window's time per step at current_ [s]
    double probe_per_step_ = 0.0;  // the probe window's [s]
    double since_probe_s_ = 0.0;   // wall time since the last probe ended [s]
    double probe_every_ = kProbeEvery;
    bool probed_ = false;          // a probe has run (the first comes after one window)
    bool down_next_ = true;        // the next probe tries fewer threads (when both ways are open)
    bool noted_ = false;
    std::string note_, log_;
};

/// The governor's changes since the last call as log lines, and its note once as a warning.
void say_thread_changes(ThreadGovernor& g, RunLog& log, RunObserver& obs);

}  // namespace orodem
