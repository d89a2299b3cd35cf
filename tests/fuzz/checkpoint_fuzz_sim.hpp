// The small simulation that tests/fuzz/fuzz_checkpoint.cpp decodes into, and
// the header it gives a fuzzed payload; shared with the replay of the saved
// inputs in tests/unit/test_checkpoint_regressions.cpp, so both build the
// same state and the same file bytes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/core/bytes.hpp"
#include "orodem/core/hash.hpp"
#include "orodem/engine/simulation.hpp"
#include "orodem/io/checkpoint.hpp"

namespace orodem::fuzz {

inline constexpr std::uint64_t kConfigHash = 0x0123456789abcdefULL;

/// Twelve discs (two three-disc clusters) on a conveyor base beside an end
/// wall, stepped 200 steps so that contacts, wall contacts and bonds exist.
/// Run it on one OpenMP thread.
inline std::unique_ptr<Simulation> make_checkpoint_sim() {
    auto s = std::make_unique<Simulation>();
    for (int k = 0; k < 12; ++k) {
        const int cluster = k < 3 ? 0 : (k < 6 ? 1 : -1);
        s->particles.add({0.5 + 0.95 * (k % 6), 0.5 + 0.95 * (k / 6)}, 0.5, 2500.0, cluster);
    }
    s->walls.push_back(Wall{{-1.0, 0.0}, {8.0, 0.0}, {}, 0.1, true, true, 0.3, false});
    s->walls.push_back(Wall{{-0.5, -1.0}, {-0.5, 5.0}, {}, 0.0, false, false, 0.0, false});
    s->params.law.k_n = 1.0e7;
    s->params.law.k_s = 1.0e7 / 3.0;
    s->params.law.mu = 0.3;
    s->params.dt = 1.0e-4;
    s->params.skin = 0.2;
    s->boundaries.push_back(std::make_unique<ConveyorTraction>(0, 0.1, 0.3, 1.0));
    s->boundaries.push_back(std::make_unique<FixedRetroside>(1));
    s->initialize();
    s->advance(200);
    return s;
}

/// The checkpoint file for a payload: the header encode_checkpoint writes
/// (checkpoint.hpp), with the given step, kConfigHash and correct checksums.
inline std::string with_header(std::string_view payload, std::uint64_t step) {
    auto fnv = [](std::string_view b) {
        Fnv1a h;
        h.add_bytes(b.data(), b.size());
        return h.value();
    };
    ByteWriter h;
    h.bytes().append("ORODEMCK", 8);
    h.put(kCheckpointVersion);
    h.put_string(ORODEM_VERSION);
    h.put(kConfigHash);
    h.put(step);
    h.put(static_cast<std::uint64_t>(payload.size()));
    h.put(fnv(payload));
    h.put(fnv(h.bytes()));
    std::string out = std::move(h.bytes());
    out += payload;
    return out;
}

/// A fuzz input as a checkpoint file: whole when it starts with the magic
/// bytes, else a payload given the header above.
inline std::string checkpoint_file_of(std::string_view input, std::uint64_t step) {
    if (input.substr(0, 8) == "ORODEMCK") return std::string(input);
    return with_header(input, step);
}

}  // namespace orodem::fuzz
