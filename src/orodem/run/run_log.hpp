// A run's two records, written together: log.txt (prose for people) and
// events.csv (the same events as numbers for programs: `orodem status`,
// `orodem sweep`/`resume` deciding which members are finished). Every
// line of log.txt that starts or ends a piece of the run, and every output
// line, is written through event(), which also appends its events.csv row;
// other lines go to log.txt only. The prose prefixes of the events are
// spelled here and nowhere else.
//
// events.csv: `event,step,S,dt,wall_s,steps_per_s,text` with event one of
// start, resume, output, finished, interrupted, time_limit, io_error,
// unstable, stopped; numbers empty where they do not apply; text the log.txt
// line, quoted. It is append-only: a resume cuts log.txt back to its
// checkpoint but keeps events.csv (the outputs after the checkpoint appear
// twice; the last one counts). A run started before events.csv existed gets
// one made from its log.txt when it is resumed, and read_events() reads such
// a run's log.txt the same way.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "orodem/io/files.hpp"

namespace orodem {

/// events.csv's header.
inline constexpr const char* kEventsHeader = "event,step,S,dt,wall_s,steps_per_s,text";

enum class RunEvent { start, resume, output, finished, interrupted, time_limit, io_error, unstable, stopped };

struct EventRecord {
    RunEvent kind = RunEvent::output;
    std::uint64_t step = 0;          // the run's step (0 where unknown)
    double S = std::nan("");         // shortening / h0 [-]
    double dt = std::nan("");        // timestep (start events) [s]
    double wall_s = std::nan("");    // wall time of the piece that ends here [s]
    double steps_per_s = std::nan("");  // rate since the previous output (outputs) [steps/s]
    std::string text;                // the log.txt line
};

/// The name of an event in events.csv ("start", "time_limit", ...).
const char* event_name(RunEvent e);
/// True for the events that end a piece of the run (finished, interrupted,
/// time_limit, io_error, unstable, stopped).
bool ends_a_piece(RunEvent e);
/// The prose form of the same test, for lines of a log.txt ("finished: ...").
bool ends_a_piece(const std::string& log_line);
/// ends_a_piece, or a resumed piece's start line ("resumed by ...").
bool starts_or_ends_a_piece(const std::string& log_line);

class RunLog {
public:
    /// Opens dir/log.txt and dir/events.csv for appending (events.csv made
    /// from log.txt first when the run was started by an older orodem).
    explicit RunLog(const std::string& dir);
    /// A log.txt line that is no event.
    void line(std::string_view text);
    /// A log.txt line (e.text) and its events.csv row.
    void event(const EventRecord& e);
    const std::string& dir() const { return dir_; }
    /// log.txt and events.csv made durable (LineFile::sync).
    void sync() {
        log_.sync();
        events_.sync();
    }

private:
    std::string dir_;
    LineFile log_;
    LineFile events_;
};

/// The events of the run in dir, oldest first: events.csv, or for a run
/// without one, the events read from its log.txt; empty when neither exists.
std::vector<EventRecord> read_events(const std::string& dir);
/// The last event that starts or ends a piece; nullptr when there is none.
const EventRecord* last_piece_event(const std::vector<EventRecord>& events);

}  // namespace orodem
