// The step kernels' instruction-set versions (engine/pair_kernel.hpp) give
// byte-identical runs: a tiny exp1 run with each version this CPU has
// (ORODEM_ISA=sse2|avx2|avx512), at 1 and 2 threads, has the same series,
// fault table, pvd, snapshots, pictures and final checkpoint state (the
// simulation's and the structures' sections byte for byte; the run section
// holds log.txt's length, which names the version, and the header the
// checksums); the log and
// --version name the version; an unknown or missing version is refused with
// exit 2 and one line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "cli/cli_util.hpp"
#include "orodem/engine/pair_kernel.hpp"
#include "orodem/io/checkpoint.hpp"

using namespace cli;

namespace {

class Isa : public OrodemTest {
protected:
    /// orodem ARGS with ORODEM_ISA=isa in work_.
    Result with_isa(const std::string& isa, const std::string& args) { return orodem(args, "ORODEM_ISA=" + quote(isa)); }
};

/// The bytes of a checkpoint from its section `from` up to its section `to`
/// (each found by its tag as the file writes it: a 64-bit length, then the name).
std::string section(const std::string& ckpt, const std::string& from, const std::string& to) {
    auto tag = [](const std::string& name) {
        std::string t(8, '\0');
        t[0] = static_cast<char>(name.size());
        return t + name;
    };
    const std::size_t a = ckpt.find(tag(from)), b = ckpt.find(tag(to), a == std::string::npos ? 0 : a);
    if (a == std::string::npos || b == std::string::npos) return "(no section " + from + ")";
    return ckpt.substr(a, b - a);
}

}  // namespace

TEST_F(Isa, EveryKernelVersionGivesTheSameRun) {
    // Six outputs of a tiny exp1 (three pictures per output).
    write(work_ / "tiny.toml", "[run]\nexperiment = \"exp1\"\n"
                               "[wedge]\nv = 0.2\ns_max = 0.5\noutput_ds = 0.1\npro_margin = 3.0\nretro_length = 3.0\n"
                               "[packing]\nh0 = 6.0\ncache_dir = \"" + (work_ / "cache").string() + "\"\n");
    std::vector<std::string> versions = {"sse2"};
    if (orodem::best_kernel_isa() >= orodem::KernelIsa::avx2) versions.push_back("avx2");
    if (orodem::best_kernel_isa() >= orodem::KernelIsa::avx512) versions.push_back("avx512");
    if (versions.size() == 1) GTEST_SKIP() << "this CPU runs only the sse2 kernels: nothing to compare";
    std::string ref_ckpt;
    for (std::size_t k = 0; k < versions.size(); ++k) {
        const std::string dir = "run-" + versions[k];
        const std::string threads = k % 2 == 0 ? "1" : "2";
        const Result r = with_isa(versions[k], "run tiny.toml --out " + dir + " --threads " + threads);
        ASSERT_EQ(r.status, 0) << versions[k] << ": " << r.err;
        EXPECT_NE(slurp(work_ / dir / "log.txt").find(versions[k] + " step kernels"), std::string::npos) << versions[k];
        const auto ckpts = orodem::list_checkpoints((work_ / dir / "checkpoint").string());
        ASSERT_FALSE(ckpts.empty());
        if (k == 0) {
            ref_ckpt = slurp(ckpts.back().second);
            continue;
        }
        expect_same_outputs(work_ / ("run-" + versions[0]), work_ / dir);
        const std::string ckpt = slurp(ckpts.back().second);
        EXPECT_TRUE(section(ckpt, "particles", "run") == section(ref_ckpt, "particles", "run")) << versions[k];
        EXPECT_TRUE(section(ckpt, "structures", "end") == section(ref_ckpt, "structures", "end")) << versions[k];
        EXPECT_GT(section(ckpt, "particles", "run").size(), 1000u);
    }
}

TEST_F(Isa, VersionIsNamedAndBadVersionsAreRefused) {
    const Result v = with_isa("sse2", "--version");
    ASSERT_EQ(v.status, 0) << v.err;
    EXPECT_NE(v.out.find("(step kernels: sse2)"), std::string::npos) << v.out;
    const Result bad = with_isa("neon", "--version");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err, "orodem: error: ORODEM_ISA=neon: not a kernel version; allowed: sse2, avx2, avx512 (or unset: "
                       "the best the CPU runs)\n");
}
