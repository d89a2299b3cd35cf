#include "cli.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"

namespace orodem {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;   // the first SIGINT/SIGTERM/SIGHUP, 0 while none came
volatile std::sig_atomic_t g_signal_count = 0;  // how many came

// The first signal asks for a stop with a checkpoint; a second one (an
// impatient Ctrl-C, or timeout's follow-up) is ignored so that the shutdown
// checkpoint is written; a third ends the process at once with the signal's
// default action (signal and raise are async-signal-safe).
extern "C" void on_stop_signal(int sig) {
    if (g_stop_signal == 0) g_stop_signal = sig;
    g_signal_count = g_signal_count + 1;  // (no ++ on a volatile: deprecated in C++20)
    if (g_signal_count >= 3) {
        ::signal(sig, SIG_DFL);
        ::raise(sig);
    }
}

}  // namespace

StopSignals::StopSignals() {
    g_stop_signal = 0;
    g_signal_count = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
    ::sigaction(SIGHUP, &sa, &old_hup_);  // the terminal or the SSH session closed: a stop with a checkpoint, as SIGTERM
}

StopSignals::~StopSignals() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
    ::sigaction(SIGHUP, &old_hup_, nullptr);
}

int StopSignals::pending() const { return static_cast<int>(g_stop_signal); }

Config load(const CommonArgs& a) {
    std::vector<Override> ov;
    for (const auto& s : a.sets) ov.push_back(parse_override(s));
    if (a.threads >= 0) ov.push_back({"run.threads", std::to_string(a.threads)});
    return load_config(a.config, ov);
}

Config load_for_run(const CommonArgs& a) {
    Config c = load(a);
    if (is_calibration(c))
        throw ConfigError(fmt::format("{}: run.experiment = \"{}\" is a calibration experiment: run it with orodem "
                                      "calibrate {}", c.path, c.run.experiment, c.path));
    return c;
}

void set_threads(const Config& c) {
    if (c.run.threads > 0) omp_set_num_threads(c.run.threads);
}

std::string duration_text(double secs) {
    if (secs < 120.0) return fmt::format("{:.0f} s", secs);
    if (secs < 7200.0) return fmt::format("{:.0f} min", secs / 60.0);
    return fmt::format("{:.1f} h", secs / 3600.0);
}

TerminalObserver::TerminalObserver() : tty_(::isatty(STDOUT_FILENO) != 0) {}

void TerminalObserver::note(const std::string& text) { fmt::print("{}\n", text); }

void TerminalObserver::warning(const std::string& text, bool mid_run) {
    fmt::print(stderr, "{}orodem: warning: {}\n", mid_run ? "\n" : "", text);
}

void TerminalObserver::stopped(const std::string& what, const std::string& checkpoint,
                               const std::string& continue_label, const std::string& continue_command) {
    fmt::print(stderr, "orodem: {}; checkpoint written to {}\n{}: {}\n", what, checkpoint, continue_label,
               continue_command);
}

// S, its percentage of s_max, steps/s since this piece began and the time
// left, blank until a rate exists (one second of running).
void TerminalObserver::progress(const RunProgress& p) {
    const double now = p.elapsed_s;
    if (tty_ ? (!p.at_output && now - shown_at_ < 1.0) : !p.at_output) return;
    shown_at_ = now;
    const double rate =
        now >= 1.0 && p.step > p.first_step ? static_cast<double>(p.step - p.first_step) / now : 0.0;
    std::string text = fmt::format("S = {:.3f} of {:g} ({:.1f}%)", p.S, p.s_max, 100.0 * p.S / p.s_max);
    if (rate > 0.0)
        text += fmt::format(", {:.0f} steps/s, {} left", rate,
                            duration_text(static_cast<double>(p.total_steps - std::min(p.total_steps, p.step)) / rate));
    if (tty_) show(text);
    else fmt::print("{}\n", text);
}

void TerminalObserver::settling(const std::string& text) { show(text); }

void TerminalObserver::show(const std::string& text) {
    if (!tty_) return;
    fmt::print("\r\033[K{}", text);  // the line cleared and rewritten
    std::fflush(stdout);
}

void TerminalObserver::progress_done() {
    if (tty_) fmt::print("\n");
    shown_at_ = -1.0;
}

void TerminalObserver::watch_stop_signals() { signals_.emplace(); }
void TerminalObserver::unwatch_stop_signals() { signals_.reset(); }
int TerminalObserver::stop_requested() const { return signals_ ? signals_->pending() : 0; }

}  // namespace orodem
