// Error types with the exit status each maps to (SPEC §4, §5). The library
// throws; only apps/orodem turns an error into an exit status and one line.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace orodem {

enum class ExitCode : int {
    ok = 0,
    internal = 1,      // a bug: an unexpected exception
    config = 2,        // bad config or command line: nothing was run or written
    unstable = 3,      // the simulation blew up (NaN, overlap, speed, lost particle)
    io = 4,            // a file could not be read or written
    time_limit = 5,    // stopped at run.max_wall_minutes with a checkpoint; --resume continues
    missing_tool = 6,  // a program orodem calls is not installed (ffmpeg for orodem movie, sbatch)
    scheduler = 7,     // the batch scheduler (Slurm's sbatch) refused a submission
    interrupted = 130  // SIGINT (SIGTERM gives 143)
};

/// A refused config or command-line value. what() is the whole one-line message.
class ConfigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Refuses (ConfigError) a text holding a control character (a newline, a
/// tab, ...): folder names, swept values and batch-script options are
/// written into paths, scripts and one-line tables, where one would break
/// them (a newline in a Slurm option is a line of its own in the script).
inline void refuse_control_characters(std::string_view what, std::string_view text) {
    auto control = [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; };
    for (const char c : text)
        if (control(c)) {
            std::string shown;  // the message stays one line: each control character shown as '?'
            for (const char d : text.substr(0, 60)) shown += control(d) ? '?' : d;
            throw ConfigError(std::string(what) + " '" + shown +
                              "': holds a control character (a newline, a tab...); use printable characters only");
        }
}

/// A failed read or write; what() names the path and the OS error.
class IoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A program that orodem calls (ffmpeg) is not installed; what() names it
/// and the Debian package. Exit status 6.
class MissingToolError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The batch scheduler refused a job (sbatch's exit status and message in
/// what()). Exit status 7.
class SchedulerError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The physical state became invalid (NaN, overlap explosion, escaped particle).
class InstabilityError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A SIGINT/SIGTERM ended the command at a point with nothing to checkpoint
/// (e.g. while settling a packing); exit status 128 + signal.
class InterruptedError : public std::runtime_error {
public:
    InterruptedError(const std::string& what, int sig) : std::runtime_error(what), signal(sig) {}
    int signal;
};

/// Throws IoError("<what> '<path>': <strerror(errno)>").
[[noreturn]] void throw_io_error(const std::string& what, const std::string& path);

}  // namespace orodem
