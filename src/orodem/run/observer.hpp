// How a run reaches the person (or program) that started it. run/ prints
// nothing and installs no signal handler: the terminal's progress line, the
// warnings on stderr, the stdout notes and the stop signals come through
// this interface (TerminalObserver in apps/orodem/cli.cpp implements it for the command
// line; tests and other drivers may implement it otherwise). The calls are
// made between steps, never inside one.
#pragma once

#include <csignal>

#include <cstdint>
#include <string>

namespace orodem {

/// The name of a stop signal (SIGINT, SIGTERM, SIGHUP) for log lines and messages.
inline const char* stop_signal_name(int sig) {
    return sig == SIGINT ? "SIGINT" : sig == SIGHUP ? "SIGHUP" : "SIGTERM";
}

/// A wedge run's progress at a chunk boundary or an output.
struct RunProgress {
    double S = 0.0;                // [-]
    double s_max = 0.0;            // [-]
    std::uint64_t first_step = 0;  // this piece's first step
    std::uint64_t step = 0;
    std::uint64_t total_steps = 0;
    double elapsed_s = 0.0;        // wall time since this piece began [s]
    bool at_output = false;        // an output was just written
};

class RunObserver {
public:
    virtual ~RunObserver() = default;
    /// A line of information on standard output ("packing reused from ...").
    virtual void note(const std::string& text) = 0;
    /// A warning for standard error; mid_run: a progress line may be showing.
    virtual void warning(const std::string& text, bool mid_run) = 0;
    /// A run stops early (signal, wall-time limit): what happened, where the
    /// checkpoint is, and the command that continues the run.
    virtual void stopped(const std::string& what, const std::string& checkpoint, const std::string& continue_label,
                         const std::string& continue_command) = 0;
    /// The run's progress (a driver decides how often to show it).
    virtual void progress(const RunProgress& p) = 0;
    /// The settling's progress: a status line.
    virtual void settling(const std::string& text) = 0;
    /// The progress line ends (the run or the settling is over).
    virtual void progress_done() = 0;
    /// From now until unwatch_stop_signals, a stop request (SIGINT/SIGTERM on
    /// the command line) is recorded instead of ending the process.
    virtual void watch_stop_signals() = 0;
    virtual void unwatch_stop_signals() = 0;
    /// The stop request received since watch_stop_signals (a signal number), 0 if none.
    virtual int stop_requested() const = 0;
};

/// Watches for stop requests while in scope.
class StopWatch {
public:
    explicit StopWatch(RunObserver& o) : o_(o) { o_.watch_stop_signals(); }
    ~StopWatch() { o_.unwatch_stop_signals(); }
    StopWatch(const StopWatch&) = delete;
    StopWatch& operator=(const StopWatch&) = delete;

private:
    RunObserver& o_;
};

/// An observer that shows nothing and receives no stop request (tests, library use).
class QuietObserver : public RunObserver {
public:
    void note(const std::string&) override {}
    void warning(const std::string&, bool) override {}
    void stopped(const std::string&, const std::string&, const std::string&, const std::string&) override {}
    void progress(const RunProgress&) override {}
    void settling(const std::string&) override {}
    void progress_done() override {}
    void watch_stop_signals() override {}
    void unwatch_stop_signals() override {}
    int stop_requested() const override { return 0; }
};

}  // namespace orodem
