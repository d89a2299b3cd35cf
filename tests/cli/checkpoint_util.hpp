// Waiting for a run's first checkpoint after step 0 before signalling it (the
// interrupt-and-resume tests of runs and sweeps).
#pragma once

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <initializer_list>
#include <thread>

#include "cli/cli_util.hpp"
#include "orodem/io/checkpoint.hpp"

namespace cli {

/// True once dir/checkpoint holds a checkpoint of a step after 0.
inline bool has_later_checkpoint(const fs::path& run) {
    for (const auto& [step, path] : orodem::list_checkpoints((run / "checkpoint").string()))
        if (step > 0) return true;
    return false;
}

/// Waits (up to 60 s) for a checkpoint after step 0, then sends sig(s).
inline bool signal_after_checkpoint(const Proc& p, const fs::path& run, std::initializer_list<int> sigs) {
    const auto t0 = std::chrono::steady_clock::now();
    while (!has_later_checkpoint(run)) {
        if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(60)) return false;
        int st = 0;
        if (waitpid(p.pid, &st, WNOHANG) == p.pid) return false;  // ended before any checkpoint
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    for (int s : sigs) kill(p.pid, s);
    return true;
}

}  // namespace cli
