#include "orodem/run/thread_governor.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <utility>

#include <fmt/format.h>

namespace orodem {

ThreadGovernor::ThreadGovernor(int requested) : requested_(std::max(requested, 1)), current_(requested_) {}

bool ThreadGovernor::enabled_by_environment() {
    const char* v = std::getenv("ORODEM_ADAPT_THREADS");
    return !(v && std::strcmp(v, "0") == 0);
}

int ThreadGovernor::alternative() {
    const bool can_down = current_ > 1, can_up = current_ < requested_;
    const bool down = can_down && (!can_up || down_next_);
    down_next_ = !down_next_;
    return down ? std::max(1, current_ / 2) : std::min(requested_, current_ * 2);
}

void ThreadGovernor::record(std::uint64_t steps, double seconds) {
    if (requested_ <= 1 || steps == 0) return;
    window_s_ += seconds;
    window_steps_ += steps;
    if (phase_ == Phase::steady) since_probe_s_ += seconds;
    if (window_s_ < kWindowSeconds) return;
    const double per_step = window_s_ / static_cast<double>(window_steps_);
    window_s_ = 0.0;
    window_steps_ = 0;
    finish_window(per_step);
}

void ThreadGovernor::finish_window(double per_step) {
    // The windows: one discarded at the start (the team's creation, the first
    // pair lists' page faults), then at the current count, a probe at the
    // other, and one more at the current count; the probe wins only when it
    // beats the faster of the two around it by the margin, so that a
    // transient in one window (another process's burst) decides nothing.
    switch (phase_) {
        case Phase::warm_up:
            phase_ = Phase::steady;
            return;
        case Phase::steady:
            before_ = per_step;
            if (!probed_ || since_probe_s_ >= probe_every_) {
                probed_ = true;
                probe_ = alternative();
                if (probe_ != current_) phase_ = Phase::probe;
            }
            return;
        case Phase::probe:
            probe_per_step_ = per_step;
            phase_ = Phase::confirm;
            return;
        case Phase::confirm:
            break;
    }
    phase_ = Phase::steady;
    since_probe_s_ = 0.0;
    const double now = std::min(before_, per_step);
    if (!(probe_per_step_ < kMargin * now)) {
        probe_every_ = kProbeEvery;
        return;
    }
    log_ += fmt::format("threads: {} -> {} (a step took {:.3g} ms on {} threads, {:.3g} ms on {})\n", current_, probe_,
                        1e3 * now, current_, 1e3 * probe_per_step_, probe_);
    if (probe_ < requested_ && !noted_) {
        noted_ = true;
        note_ = fmt::format("{} threads took {:.1f} times as long per step as {} (another process is using the "
                            "cores?): continuing on {}, checking again every {:g} s; the results are the same at "
                            "any thread count (ORODEM_ADAPT_THREADS=0 keeps {})",
                            current_, now / probe_per_step_, probe_, probe_, kProbeEvery, requested_);
    }
    current_ = probe_;
    probe_every_ = kProbeAfterChange;  // a wrong turn (a burst of load in all three windows) is undone soon
}

std::string ThreadGovernor::take_note() { return std::exchange(note_, std::string()); }

std::string ThreadGovernor::take_log() { return std::exchange(log_, std::string()); }

void say_thread_changes(ThreadGovernor& g, RunLog& log, RunObserver& obs) {
    for (std::string lines = g.take_log(); !lines.empty();) {
        const std::size_t eol = lines.find('\n');
        log.line(lines.substr(0, eol));
        lines.erase(0, eol == std::string::npos ? lines.size() : eol + 1);
    }
    if (const std::string note = g.take_note(); !note.empty()) obs.warning(note, true);
}

}  // namespace orodem
