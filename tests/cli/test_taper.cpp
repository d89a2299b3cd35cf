// `orodem taper`: the critical slopes of both branches printed with their
// meaning (values: the ECCW reference of tests/unit/test_critical_taper.cpp,
// φ = 30°, φ_b = 10°, β = 0 → 3.4365° and 23.9463°), --mu-b as an
// alternative to --phib, and one-line errors with exit status 2.
#include <gtest/gtest.h>

#include "cli/cli_util.hpp"
#include <stdlib.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace cli;

namespace {

class TaperCli : public OrodemTest {
protected:
    /// Runs `orodem taper ARGS`.
    Result taper(const std::string& args) { return orodem("taper " + args); }
};

}  // namespace

TEST_F(TaperCli, PrintsBothCriticalSlopes) {
    const Result r = taper("--phi 30 --phib 10");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_HAS(r.out, "critical taper (compressive, lower branch): alpha = 3.437 deg");
    EXPECT_HAS(r.out, "critical taper (extensional, upper branch): alpha = 23.946 deg");
    EXPECT_HAS(r.out, "stable (slides on its base without failing inside) for 3.437 < alpha < 23.946 deg");
    EXPECT_HAS(r.out, "-10 <= beta <= 90 deg");
    EXPECT_HAS(r.out, "Dahlen 1984");
    EXPECT_HAS(r.out, "K = 2 sin phi/(1 - sin phi) = 2.0000");
}

TEST_F(TaperCli, BasalDipAndFrictionCoefficient) {
    // --mu-b tan(10°) is --phib 10.
    const Result mu = taper("--phi 30 --mu-b 0.17632698070846498");
    EXPECT_EQ(mu.status, 0) << mu.err;
    EXPECT_HAS(mu.out, "alpha = 3.437 deg");
    EXPECT_HAS(mu.out, "alpha = 23.946 deg");
    // A negative basal dip (base dipping toward the toe) as a plain argument.
    const Result dip = taper("--phi 30 --phib 10 --beta -5");
    EXPECT_EQ(dip.status, 0) << dip.err;
    EXPECT_HAS(dip.out, "alpha = 6.742 deg, alpha + beta = 1.742 deg");
    // The vertex of the stability field: both bounds at alpha = phi_b.
    const Result vertex = taper("--phi 30 --phib 10 --beta=-10");
    EXPECT_EQ(vertex.status, 0) << vertex.err;
    EXPECT_HAS(vertex.out, "lower branch): alpha = 10.000 deg");
    EXPECT_HAS(vertex.out, "upper branch): alpha = 10.000 deg");
}

TEST_F(TaperCli, BadInputExitsTwoWithOneLine) {
    struct Case {
        const char* args;
        const char* needle;
    };
    const Case cases[] = {
        {"--phi 0 --phib 0", "--phi 0: the internal friction angle must be in (0, 90) degrees"},
        {"--phi 90 --phib 10", "--phi 90:"},
        {"--phi 30 --phib 30", "--phib 30: the basal friction angle must be in [0, phi) = [0, 30) degrees"},
        {"--phi 30 --phib -1", "--phib -1:"},
        {"--phi 30 --mu-b 0.6", "--mu-b 0.6: the basal friction coefficient must be in [0, tan(phi)) = [0, 0.5774)"},
        {"--phi 30", "one of --phib DEG (angle) or --mu-b MU"},
        {"--phi 30 --phib 10 --beta 95", "--beta 95: no wedge is stable on this base; the basal dip must be in "
                                         "[-phi_b, 90] = [-10, 90] degrees"},
        {"--phi 30 --phib 10 --beta nan", "--beta nan:"},
    };
    for (const Case& c : cases) {
        const Result r = taper(c.args);
        SCOPED_TRACE(c.args);
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("orodem: error: ", 0), 0u) << r.err;
        EXPECT_HAS(r.err, c.needle);
        EXPECT_EQ(r.out, "");
    }
    // Parse errors (CLI11) also exit 2.
    EXPECT_EQ(taper("--phi abc --phib 10").status, 2);
    EXPECT_EQ(taper("--phi 30 --phib 10 --mu-b 0.1").status, 2);
    EXPECT_EQ(taper("--phib 10").status, 2);
}
