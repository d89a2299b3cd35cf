// The phase timers of Simulation::step(): PhaseTimes accumulates the wall
// time of each phase, PhaseClock laps it, one clock read per phase
// boundary. Inside a parallel region only one thread at a time laps (a
// single or master block); timings never feed back into results.
#pragma once

#include <omp.h>

#include <cstdint>

namespace orodem {

/// Wall time spent in each phase of step(), accumulated since the start or
/// the last reset_phase_times() [s].
struct PhaseTimes {
    double integrate = 0.0;    // half kicks and drift (incl. the rebuild trigger's max displacement)
    double rebuild = 0.0;      // neighbour rebuilds (sort, pair lists, history)
    double pair_forces = 0.0;  // phase A: the law per disc pair
    double gather = 0.0;       // phase B: per-disc sums and wall contacts (plus the second
                               // half kick when no boundary can change forces, see step())
    double boundaries = 0.0;   // wall motion and Boundary hooks
    std::uint64_t steps = 0;   // steps timed
    std::uint64_t rebuilds = 0;  // neighbour rebuilds among them
    double total() const { return integrate + rebuild + pair_forces + gather + boundaries; }
};

/// Laps of one step: lap(&PhaseTimes::gather) adds the time since the last
/// lap (or the clock's start) to the gather phase; add() books a span
/// measured elsewhere (a thread's own chunks) and moves the lap mark past it.
class PhaseClock {
public:
    using Phase = double PhaseTimes::*;
    explicit PhaseClock(PhaseTimes& t) : times_(t), mark_(omp_get_wtime()) {}
    void lap(Phase p) {
        const double now = omp_get_wtime();
        times_.*p += now - mark_;
        mark_ = now;
    }
    void add(Phase p, double seconds) {
        times_.*p += seconds;
        mark_ += seconds;
    }

private:
    PhaseTimes& times_;
    double mark_;  // omp_get_wtime() at the last lap [s]
};

}  // namespace orodem
