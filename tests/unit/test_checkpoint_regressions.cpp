// Inputs the fuzzer (tests/fuzz/fuzz_checkpoint.cpp, scripts/fuzz) found
// crashing the checkpoint reader, kept so that the fix stays: every file
// under tests/fuzz/regressions/checkpoint/ is decoded exactly as the fuzz
// target decodes it, into the same small simulation, and must be accepted or
// refused with CheckpointError, leaving the simulation as it was. Any other
// exception, or a sanitizer report in the ASan/UBSan build (scripts/test),
// fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/checkpoint_fuzz_sim.hpp"
#include "fuzz_regressions.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/checkpoint.hpp"
#include "test_util.hpp"

using namespace orodem;
namespace fs = std::filesystem;

namespace {

/// Decodes file into sim; "" when accepted, else the CheckpointError message
/// (the simulation must then be unchanged). Other exceptions fail the test.
std::string decode(const std::string& file, Simulation& sim) {
    const std::uint64_t before = sim.state_hash();
    try {
        RunLoopState run;
        decode_checkpoint(file, fuzz::kConfigHash, sim, run);
        (void)sim.state_hash();
        return "";
    } catch (const CheckpointError& e) {
        EXPECT_EQ(sim.state_hash(), before) << "a refused checkpoint changed the simulation";
        return e.what();
    }
}

/// The checkpoint of the fuzz simulation after edit(sim), encoded as is.
template <class Edit>
std::string edited_checkpoint(Edit&& edit) {
    auto sim = fuzz::make_checkpoint_sim();
    edit(*sim);
    return encode_checkpoint(*sim, RunLoopState{}, fuzz::kConfigHash);
}

}  // namespace

TEST(CheckpointRegressions, EverySavedFuzzInputIsAcceptedOrRefusedCleanly) {
    test::SerialOmp serial;
    const auto inputs = test::fuzz_regressions("checkpoint");
    ASSERT_FALSE(inputs.empty()) << "no saved inputs in tests/fuzz/regressions/checkpoint";
    auto sim = fuzz::make_checkpoint_sim();
    for (const auto& [name, bytes] : inputs) {
        SCOPED_TRACE(name);
        const std::string file = fuzz::checkpoint_file_of(bytes, sim->step_count);
        try {
            (void)verify_checkpoint(file, fuzz::kConfigHash);
        } catch (const CheckpointError&) {
        }
        decode(file, *sim);
    }
}

TEST(CheckpointRegressions, ClusterIdsOutOfRangeOrBondsThatDoNotMatchAreRefused) {
    test::SerialOmp serial;
    auto sim = fuzz::make_checkpoint_sim();
    // The fuzz crash: a cluster id near 2^31 made the restore allocate a list per cluster id.
    for (const std::int32_t id : {std::numeric_limits<std::int32_t>::max(), 12, -2}) {
        const std::string msg = decode(edited_checkpoint([&](Simulation& s) { s.particles.cluster[7] = id; }), *sim);
        EXPECT_NE(msg.find("cluster id " + std::to_string(id)), std::string::npos) << msg;
    }
    // Ids in range, but clusters that the saved bonds do not match: a lone disc
    // joins cluster 0 (6 + 3 pairs for 6 bonded contacts), or all discs in one.
    std::string msg = decode(edited_checkpoint([](Simulation& s) {
                                 auto& cl = s.particles.cluster;
                                 *std::find(cl.begin(), cl.end(), -1) = 0;
                             }),
                             *sim);
    EXPECT_NE(msg.find("9 bonds in the clusters, 6 bonded contacts"), std::string::npos) << msg;
    msg = decode(edited_checkpoint([](Simulation& s) {
                     std::fill(s.particles.cluster.begin(), s.particles.cluster.end(), 0);
                 }),
                 *sim);
    EXPECT_NE(msg.find("66 bonds in the clusters, 6 bonded contacts"), std::string::npos) << msg;
    // The unedited checkpoint is accepted.
    EXPECT_EQ(decode(edited_checkpoint([](Simulation&) {}), *sim), "");
}
