// What the commands share on the command line: the common arguments, the
// config they load, the thread count, durations in words, and the terminal
// side of a run (TerminalObserver: the progress line, warnings on stderr,
// notes on stdout, and SIGINT/SIGTERM turned into stop requests).
#pragma once

#include <csignal>
#include <optional>
#include <string>
#include <vector>

#include "orodem/run/observer.hpp"

namespace orodem {

struct Config;

struct CommonArgs {
    std::string config;
    std::vector<std::string> sets;
    int threads = -1;  // -1: from the config
    bool force = false;  // run, sweep: start a run estimated above kLongRunHours
};

/// The config of a, its --set and --threads applied (load_config: ConfigError if bad).
Config load(const CommonArgs& a);
/// load, refusing a calibration config (ConfigError: orodem calibrate runs those).
Config load_for_run(const CommonArgs& a);
/// Applies run.threads (0: all cores).
void set_threads(const Config& c);
/// "42 s", "17 min" or "3.5 h".
std::string duration_text(double secs);

/// SIGINT/SIGTERM while a run or a sweep goes on: the handler only records
/// the first signal (the run stops with a checkpoint); a second is ignored
/// so that the shutdown checkpoint gets written; a third ends the process at
/// once with the default action (every file is written atomically or line by
/// line, so nothing is left corrupt; at worst a *.tmp file stays behind).
class StopSignals {
public:
    StopSignals();
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;
    /// The signal received since construction, 0 if none.
    int pending() const;

private:
    struct sigaction old_int_ {}, old_term_ {}, old_hup_ {};
};

/// A run on the terminal: on a terminal one progress line rewritten at most
/// once a second and at every output; elsewhere (a log file, nohup) a plain
/// line at every output only. Stop requests are the signals of StopSignals.
class TerminalObserver : public RunObserver {
public:
    TerminalObserver();
    void note(const std::string& text) override;
    void warning(const std::string& text, bool mid_run) override;
    void stopped(const std::string& what, const std::string& checkpoint, const std::string& continue_label,
                 const std::string& continue_command) override;
    void progress(const RunProgress& p) override;
    void settling(const std::string& text) override;
    void progress_done() override;
    void watch_stop_signals() override;
    void unwatch_stop_signals() override;
    int stop_requested() const override;

private:
    void show(const std::string& text);  // on a terminal only
    bool tty_;
    double shown_at_ = -1.0;  // elapsed_s when the run line was last shown [s]
    std::optional<StopSignals> signals_;
};

}  // namespace orodem
