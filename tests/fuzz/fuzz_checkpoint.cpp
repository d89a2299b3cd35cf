// libFuzzer target: the checkpoint reader on arbitrary bytes (docs/testing.md).
//
// An input that starts with the magic "ORODEMCK" is a whole checkpoint file.
// Any other input is taken as a payload and given a correct header (version,
// size, both checksums, the step and config hash of the small simulation in
// checkpoint_fuzz_sim.hpp), so that the fuzzer gets past the checksums to the
// contents. Both go through verify_checkpoint and decode_checkpoint into that
// simulation; they must accept the bytes or throw CheckpointError (or
// ConfigError for another config's hash). Any other exception escapes and
// aborts, which libFuzzer reports as a crash, as it does any sanitizer finding.
//
// With ORODEM_FUZZ_SEED_DIR set, writes two seeds there (a real payload and a
// real file of that simulation): scripts/fuzz uses them as its corpus.
#include <omp.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "checkpoint_fuzz_sim.hpp"
#include "orodem/core/error.hpp"

namespace {

orodem::Simulation* g_sim = nullptr;
std::uint64_t g_step = 0;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    omp_set_num_threads(1);
    static std::unique_ptr<orodem::Simulation> sim = orodem::fuzz::make_checkpoint_sim();
    g_sim = sim.get();
    g_step = sim->step_count;
    if (const char* dir = std::getenv("ORODEM_FUZZ_SEED_DIR")) {
        orodem::RunLoopState run;
        run.outputs = 2;
        run.x_then = sim->particles.x;
        run.pvd = {{0.0, "snapshots/S00.000.vtu"}, {0.25, "snapshots/S00.250.vtu"}};
        const std::string file = orodem::encode_checkpoint(*sim, run, orodem::fuzz::kConfigHash);
        const std::size_t header_size = orodem::fuzz::with_header("", g_step).size();
        std::ofstream(std::string(dir) + "/file.bin", std::ios::binary) << file;
        std::ofstream(std::string(dir) + "/payload.bin", std::ios::binary) << file.substr(header_size);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string file =
        orodem::fuzz::checkpoint_file_of({reinterpret_cast<const char*>(data), size}, g_step);
    try {
        (void)orodem::verify_checkpoint(file, orodem::fuzz::kConfigHash);
    } catch (const orodem::CheckpointError&) {
    } catch (const orodem::ConfigError&) {
    }
    try {
        orodem::RunLoopState run;
        orodem::decode_checkpoint(file, orodem::fuzz::kConfigHash, *g_sim, run);
        (void)g_sim->state_hash();  // reads every restored column through slot_of_id
    } catch (const orodem::CheckpointError&) {
    } catch (const orodem::ConfigError&) {
    }
    return 0;
}
