#include "orodem/run/run_log.hpp"

#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "orodem/core/error.hpp"

namespace fs = std::filesystem;

namespace orodem {

namespace {

constexpr const char* kHeader = kEventsHeader;

struct EventSpelling {
    RunEvent kind;
    const char* name;    // in events.csv
    const char* prefix;  // of its log.txt line
};

// The log.txt prefixes of the events (the lines of the run loop, the
// settling and the resume); the order is the match order.
constexpr EventSpelling kEvents[] = {
    {RunEvent::start, "start", "orodem "},
    {RunEvent::resume, "resume", "resumed by"},
    {RunEvent::output, "output", "S = "},
    {RunEvent::finished, "finished", "finished:"},
    {RunEvent::interrupted, "interrupted", "interrupted by"},
    {RunEvent::time_limit, "time_limit", "stopped at the wall-time limit"},
    {RunEvent::io_error, "io_error", "stopped by an I/O error"},
    {RunEvent::unstable, "unstable", "UNSTABLE:"},
    {RunEvent::stopped, "stopped", "STOPPED:"},
};

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

/// The number after `key` in text; NaN when absent.
double number_after(const std::string& text, const std::string& key) {
    const std::size_t at = text.find(key);
    if (at == std::string::npos) return std::nan("");
    try {
        return std::stod(text.substr(at + key.size()));
    } catch (const std::exception&) {
        return std::nan("");
    }
}

std::string number_field(double v) { return std::isfinite(v) ? fmt::format("{:.17g}", v) : std::string(); }

std::string csv_row(const EventRecord& e) {
    std::string quoted = "\"";
    for (char ch : e.text) {
        if (ch == '"') quoted += '"';
        quoted += ch;
    }
    quoted += '"';
    return fmt::format("{},{},{},{},{},{},{}", event_name(e.kind), e.step, number_field(e.S), number_field(e.dt),
                       number_field(e.wall_s), number_field(e.steps_per_s), quoted);
}

/// The events of a log.txt written as prose only (a run started by an
/// orodem without events.csv). The step of an output is not in the prose (0).
std::vector<EventRecord> events_from_log(const std::string& text) {
    std::vector<EventRecord> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (starts_with(line, "dt = ")) {  // the timestep line follows the start line
            for (auto it = out.rbegin(); it != out.rend(); ++it)
                if (it->kind == RunEvent::start) {
                    if (std::isnan(it->dt)) it->dt = number_after(line, "dt = ");
                    break;
                }
            continue;
        }
        for (const EventSpelling& s : kEvents) {
            if (!starts_with(line, s.prefix)) continue;
            EventRecord e;
            e.kind = s.kind;
            e.text = line;
            if (s.kind == RunEvent::output) {
                e.S = number_after(line, "S = ");
                e.steps_per_s = number_after(line, "asleep; ");
            }
            if (const std::size_t at = line.find(" s wall"); ends_a_piece(s.kind) && at != std::string::npos) {
                const std::size_t sp = line.rfind(' ', at - 1);  // the number is the word before " s wall"
                e.wall_s = sp == std::string::npos ? std::nan("") : number_after(line.substr(sp + 1), "");
            }
            out.push_back(std::move(e));
            break;
        }
    }
    return out;
}

std::vector<EventRecord> parse_events(const std::string& text, const std::string& path) {
    std::vector<EventRecord> out;
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);  // header
    for (std::size_t n = 2; std::getline(in, line); ++n) {
        std::vector<std::string> f;
        std::size_t at = 0;
        for (int k = 0; k < 6; ++k) {
            const std::size_t comma = line.find(',', at);
            if (comma == std::string::npos)
                throw IoError(fmt::format("'{}': line {} has fewer than 7 fields; expected {}", path, n, kHeader));
            f.push_back(line.substr(at, comma - at));
            at = comma + 1;
        }
        EventRecord e;
        bool known = false;
        for (const EventSpelling& s : kEvents)
            if (f[0] == s.name) e.kind = s.kind, known = true;
        if (!known) throw IoError(fmt::format("'{}': line {}: unknown event '{}'", path, n, f[0]));
        auto num = [](const std::string& s) { return s.empty() ? std::nan("") : std::stod(s); };
        try {
            e.step = f[1].empty() ? 0 : std::stoull(f[1]);
            e.S = num(f[2]);
            e.dt = num(f[3]);
            e.wall_s = num(f[4]);
            e.steps_per_s = num(f[5]);
        } catch (const std::exception&) {
            throw IoError(fmt::format("'{}': line {}: a number field is not a number", path, n));
        }
        std::string t = line.substr(at);
        if (t.size() >= 2 && t.front() == '"' && t.back() == '"') t = t.substr(1, t.size() - 2);
        for (std::size_t p = 0; (p = t.find("\"\"", p)) != std::string::npos; ++p) t.erase(p, 1);
        e.text = std::move(t);
        out.push_back(std::move(e));
    }
    return out;
}

}  // namespace

const char* event_name(RunEvent e) {
    for (const EventSpelling& s : kEvents)
        if (s.kind == e) return s.name;
    return "?";
}

bool ends_a_piece(RunEvent e) {
    return e != RunEvent::start && e != RunEvent::resume && e != RunEvent::output;
}

bool ends_a_piece(const std::string& log_line) {
    for (const EventSpelling& s : kEvents)
        if (ends_a_piece(s.kind) && starts_with(log_line, s.prefix)) return true;
    return false;
}

bool starts_or_ends_a_piece(const std::string& log_line) {
    return ends_a_piece(log_line) || starts_with(log_line, "resumed by");
}

RunLog::RunLog(const std::string& dir) : dir_(dir) {
    const std::string log_path = dir + "/log.txt", events_path = dir + "/events.csv";
    std::error_code ec;
    const bool had_events = fs::exists(events_path, ec);
    const bool had_log = fs::exists(log_path, ec);
    log_ = LineFile(log_path);
    events_ = LineFile(events_path);
    if (!had_events) {
        events_.line(kHeader);
        if (had_log)
            for (const EventRecord& e : events_from_log(read_file(log_path))) events_.line(csv_row(e));
    }
}

void RunLog::line(std::string_view text) { log_.line(text); }

void RunLog::event(const EventRecord& e) {
    log_.line(e.text);
    events_.line(csv_row(e));
}

std::vector<EventRecord> read_events(const std::string& dir) {
    std::error_code ec;
    if (fs::exists(dir + "/events.csv", ec)) return parse_events(read_file(dir + "/events.csv"), dir + "/events.csv");
    if (fs::exists(dir + "/log.txt", ec)) return events_from_log(read_file(dir + "/log.txt"));
    return {};
}

const EventRecord* last_piece_event(const std::vector<EventRecord>& events) {
    for (auto it = events.rbegin(); it != events.rend(); ++it)
        if (it->kind == RunEvent::resume || ends_a_piece(it->kind)) return &*it;
    return nullptr;
}

}  // namespace orodem
