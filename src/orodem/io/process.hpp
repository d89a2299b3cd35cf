// Child processes for the programs orodem hands work to: ffmpeg (orodem
// movie), sbatch / squeue / sacct (sweeps on Slurm) and the sweep's own
// members (orodem sweep-member). One way to start them: posix_spawnp, stdin
// from /dev/null, stdout and stderr together into a file (truncated or
// appended) or into the caller's pipe, optionally in a process group of
// their own (so that a terminal's Ctrl-C reaches the parent only).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace orodem {

/// The full path of an executable `name` on PATH; "" when there is none.
std::string find_on_path(const std::string& name);

/// Where a child's stdout and stderr go, and how it is started.
struct ChildIo {
    std::string log;         // file for stdout and stderr (when out_fd < 0)
    bool append = false;     // append to log instead of truncating it
    int out_fd = -1;         // or this descriptor (a pipe's write end)
    int close_fd = -1;       // a descriptor the child closes (the pipe's read end)
    bool new_group = false;  // the child leads a process group of its own
    bool parent_env = false; // the child's environment gets ORODEM_PARENT_PID=<this process> (die_with_parent)
};

/// Starts args[0] (a path, or a name looked up on PATH) with args; pid set on
/// success. Returns 0, or the error number of a failed start.
int spawn_child(const std::vector<std::string>& args, const ChildIo& io, pid_t& pid);

/// In a child started with parent_env: asks the kernel for SIGTERM when the
/// parent ends (prctl PR_SET_PDEATHSIG), however it ends; false when the
/// parent has ended already (the child should stop at once). True, doing
/// nothing, in a process started otherwise.
bool die_with_parent();

/// Waits for pid (retrying on EINTR): its exit status, -1 when a signal ended it.
int wait_child(pid_t pid);

/// A program's exit status (-1: it could not be started or did not exit)
/// and its standard output and error together.
struct ProgramResult {
    int status = -1;
    std::string output;
};

/// Runs args, collecting what it prints.
ProgramResult run_program(const std::vector<std::string>& args);

}  // namespace orodem
