// Helpers of the run wing's in-process tests (test_run_state.cpp,
// test_sweep_lib.cpp): a temporary folder, the tiny exp1 config, run
// directories made by hand from events.csv rows, and observers that keep
// what a sweep says and ask for stops on cue.
#pragma once

#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "orodem/run/observer.hpp"
#include "orodem/run/sweep.hpp"

namespace orodem::test {

namespace fs = std::filesystem;

/// A new temporary folder, removed with everything in it at the end.
struct TempFolder {
    fs::path path;
    explicit TempFolder(const std::string& tag) {
        std::string tmpl = (fs::temp_directory_path() / ("orodem-" + tag + "-XXXXXX")).string();
        if (::mkdtemp(tmpl.data())) path = tmpl;
    }
    ~TempFolder() {
        std::error_code ec;
        if (!path.empty()) fs::remove_all(path, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

inline void write_text(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << text;
}

inline std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// The tiny exp1 of the CLI tests (a few hundred discs, five outputs to
/// S = 0.5), its packing cached in `cache`; extra: more TOML lines for [run].
inline std::string tiny_exp1(const fs::path& cache, const std::string& extra = "") {
    return "[run]\nexperiment = \"exp1\"\n" + extra +
           "[wedge]\nv = 0.2\ns_max = 0.5\noutput_ds = 0.1\npro_margin = 3.0\nretro_length = 3.0\n"
           "[packing]\nh0 = 6.0\ncache_dir = \"" + cache.string() + "\"\n";
}

/// log.txt and events.csv of a run made by hand, with these events.csv rows
/// (event,step,S,dt,wall_s,steps_per_s,text; log.txt gets their texts).
inline void write_events(const fs::path& dir, std::initializer_list<std::string> rows) {
    std::string events = "event,step,S,dt,wall_s,steps_per_s,text\n", log;
    for (const std::string& r : rows) {
        events += r + "\n";
        const std::size_t quote = r.rfind(",\"") + 2;
        log += r.substr(quote, r.size() - quote - 1) + "\n";
    }
    write_text(dir / "events.csv", events);
    write_text(dir / "log.txt", log);
}

/// A run directory made by hand: the tiny exp1 as config.toml and, when rows
/// are given, their events (write_events).
inline void hand_run(const fs::path& dir, const fs::path& cache, std::initializer_list<std::string> rows) {
    write_text(dir / "config.toml", tiny_exp1(cache));
    if (rows.size() > 0) write_events(dir, rows);
}

/// events.csv rows of the usual pieces.
inline const std::string kStartRow = "start,0,,0.0001,,,\"orodem 0.1.0 run of c.toml (exp1) with 1 threads\"";
inline std::string output_row(double S, double rate) {
    std::ostringstream s;
    s << "output," << static_cast<std::uint64_t>(S * 300000) << "," << S << ",,," << rate << ",\"S = " << S << "\"";
    return s.str();
}
inline const std::string kFinishedRow = "finished,150000,0.5,,10,,\"finished: S = 0.500 after 150000 steps, 10.0 s wall\"";
inline const std::string kInterruptedRow =
    "interrupted,76000,0.2533,,42.5,,\"interrupted by SIGTERM at step 76000 (S = 0.2533) after 42.5 s wall; checkpoint x\"";
inline const std::string kUnstableRow = "unstable,30000,0.1,,5,,\"UNSTABLE: step 30000 (S = 0.1000): NaN\"";
inline const std::string kResumeRow = "resume,76000,0.2533,,,,\"resumed by orodem 0.1.0 from x at step 76000\"";

/// Keeps what a sweep says; its runs go to `run` (quiet unless replaced).
struct KeptLines : SweepObserver {
    QuietObserver quiet;
    RunObserver* run = &quiet;
    std::vector<std::string> out, err;
    void say(const std::string& line) override { out.push_back(line); }
    void trouble(const std::string& line) override { err.push_back(line); }
    RunObserver& runs() override { return *run; }
    /// Every line, stdout's then stderr's, one per line.
    std::string text() const {
        std::string t;
        for (const auto& l : out) t += l + "\n";
        for (const auto& l : err) t += l + "\n";
        return t;
    }
};

/// A stop request (SIGTERM) once `when` says so (asked at every look).
class StopWhen : public QuietObserver {
public:
    explicit StopWhen(std::function<bool()> when) : when_(std::move(when)) {}
    int stop_requested() const override { return when_() ? SIGTERM : 0; }

private:
    std::function<bool()> when_;
};

}  // namespace orodem::test
