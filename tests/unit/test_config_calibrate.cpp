// The calibration experiments' config (run.experiment = biaxial |
// basal-friction | repose, table [calibrate]): every refusal is a one-line
// ConfigError naming the key and what is allowed; keys of another experiment
// are unknown keys; defaults resolve (the swept lists default to
// material.mu / packing.kind, the strain rate to the inertial-number limit);
// the resolved TOML reads back to itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"

using namespace orodem;

namespace {

std::string head(const std::string& experiment) { return "[run]\nexperiment = \"" + experiment + "\"\n"; }

/// The message of the ConfigError the text gets; a test failure when accepted.
std::string refusal(const std::string& text) {
    try {
        parse_config(text, "calib.toml", {});
    } catch (const ConfigError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        return msg;
    }
    ADD_FAILURE() << "accepted:\n" << text;
    return {};
}

bool has(const std::string& hay, const std::string& needle) { return hay.find(needle) != std::string::npos; }
#define EXPECT_HAS(msg, needle) EXPECT_TRUE(has((msg), (needle))) << "missing \"" << (needle) << "\" in: " << (msg)

}  // namespace

TEST(ConfigCalibrate, ExperimentsAreCalibrationsNotWedges) {
    for (const char* e : {"biaxial", "basal-friction", "repose"}) {
        const Config c = parse_config(head(e), "calib.toml", {});
        EXPECT_TRUE(is_calibration(c)) << e;
        EXPECT_FALSE(is_wedge(c)) << e;
    }
    for (const char* e : {"settle", "exp1", "critical-wedge"})
        EXPECT_FALSE(is_calibration(parse_config(head(e), "calib.toml", {}))) << e;
}

TEST(ConfigCalibrate, DefaultsResolve) {
    const Config c = parse_config(head("biaxial") + "[material]\nmu = 0.4\n[packing]\nkind = \"discs\"\n",
                                  "calib.toml", {});
    const CalibrateConfig& k = c.calibrate;
    ASSERT_EQ(k.kinds.size(), 1u);
    EXPECT_EQ(k.kinds[0], PackingKind::discs);  // packing.kind
    ASSERT_EQ(k.mu_values.size(), 1u);
    EXPECT_DOUBLE_EQ(k.mu_values[0], 0.4);  // material.mu
    // Automatic strain rate: I = ε̇ d sqrt(ρ/σ_3) = max_inertial_number, d = r_min + r_max.
    const double expected = 1e-3 / ((0.5 + 1.0) * std::sqrt(2500.0 / 2.0e5));
    EXPECT_NEAR(k.strain_rate, expected, 1e-15);
    EXPECT_DOUBLE_EQ(k.width, 30.0);
    EXPECT_DOUBLE_EQ(k.max_strain, 0.2);
    const Config b = parse_config(head("basal-friction"), "calib.toml", {});
    ASSERT_EQ(b.calibrate.mu_bp_values.size(), 1u);
    EXPECT_DOUBLE_EQ(b.calibrate.mu_bp_values[0], 0.3);
    EXPECT_DOUBLE_EQ(b.calibrate.belt_speed, 0.1);
    // The run is a belt travel (8 m): 80 s at 0.1 m/s, 320 s at 0.025 m/s,
    // unless calibrate.duration is given.
    EXPECT_DOUBLE_EQ(b.calibrate.duration, 80.0);
    const Config slow = parse_config(head("basal-friction"), "calib.toml", {{"calibrate.belt_speed", "0.025"}});
    EXPECT_DOUBLE_EQ(slow.calibrate.duration, 320.0);
    const Config fast = parse_config(head("basal-friction"), "calib.toml", {{"calibrate.belt_speed", "0.4"}});
    EXPECT_DOUBLE_EQ(fast.calibrate.duration, 80.0);  // min_duration
    const Config fixed = parse_config(head("basal-friction"), "calib.toml",
                                      {{"calibrate.belt_speed", "0.025"}, {"calibrate.duration", "50.0"}});
    EXPECT_DOUBLE_EQ(fixed.calibrate.duration, 50.0);
}

TEST(ConfigCalibrate, ListsAreRead) {
    const Config c = parse_config(head("biaxial") +
                                      "[calibrate]\nkinds = [\"discs\", \"clusters\"]\nmu_values = [0, 0.1, 1.0]\n",
                                  "calib.toml", {});
    EXPECT_EQ(c.calibrate.kinds, (std::vector<PackingKind>{PackingKind::discs, PackingKind::clusters}));
    EXPECT_EQ(c.calibrate.mu_values, (std::vector<double>{0.0, 0.1, 1.0}));  // integers taken as numbers
}

TEST(ConfigCalibrate, ResolvedConfigReadsBackToItself) {
    for (const char* e : {"biaxial", "basal-friction", "repose"}) {
        const Config c = parse_config(head(e) + "[calibrate]\nkinds = [\"discs\", \"clusters\"]\n", "calib.toml", {});
        const std::string t = to_toml(c);
        EXPECT_EQ(to_toml(parse_config(t, "config.toml", {})), t) << e;
    }
    const Config c = parse_config(head("biaxial") + "[calibrate]\nmu_values = [0.1, 0.3]\n", "calib.toml", {});
    EXPECT_HAS(to_toml(c), "mu_values = [0.1, 0.3]");  // the lists in their shortest exact form
}

TEST(ConfigCalibrate, OverridesReachTheLists) {
    const Config c = parse_config(head("repose"), "calib.toml",
                                  {{"calibrate.mu_values", "[0.2, 0.7]"}, {"calibrate.kinds", "[\"clusters\"]"}});
    EXPECT_EQ(c.calibrate.mu_values, (std::vector<double>{0.2, 0.7}));
    EXPECT_EQ(c.calibrate.kinds, (std::vector<PackingKind>{PackingKind::clusters}));
}

TEST(ConfigCalibrate, CalibrateTableOutsideACalibrationIsRefused) {
    for (const char* e : {"settle", "exp1"}) {
        const std::string msg = refusal(head(e) + "[calibrate]\nwidth = 10.0\n");
        EXPECT_HAS(msg, "[calibrate]");
        EXPECT_HAS(msg, "orodem calibrate");
        EXPECT_HAS(msg, "calib.toml:3:");
    }
}

TEST(ConfigCalibrate, LayerKeysAreUnknownInACalibration) {
    // The calibrations size their samples in [calibrate]: packing.h0 and packing.length are not read.
    for (const char* key : {"h0 = 10.0", "length = 100.0"}) {
        const std::string msg = refusal(head("biaxial") + "[packing]\n" + key + "\n");
        EXPECT_HAS(msg, "unknown key");
        EXPECT_HAS(msg, "calib.toml:4:");
    }
}

TEST(ConfigCalibrate, KeysOfAnotherExperimentAreUnknown) {
    struct Case {
        const char* experiment;
        const char* line;
        const char* key;
        const char* allowed;  // one of the keys the message lists
    } cases[] = {
        {"biaxial", "block_length = 20.0", "calibrate.block_length", "confining_stress"},
        {"biaxial", "mu_bp_values = [0.1]", "calibrate.mu_bp_values", "mu_values"},
        {"basal-friction", "mu_values = [0.1]", "calibrate.mu_values", "mu_bp_values"},
        {"basal-friction", "width = 20.0", "calibrate.width", "block_height"},
        {"repose", "belt_speed = 0.1", "calibrate.belt_speed", "lift_speed"},
        {"repose", "bogus = 1", "calibrate.bogus", "fit_from"},
    };
    for (const Case& k : cases) {
        const std::string msg = refusal(head(k.experiment) + "[calibrate]\n" + k.line + "\n");
        EXPECT_HAS(msg, "unknown key");
        EXPECT_HAS(msg, std::string("'") + k.key + "'");
        EXPECT_HAS(msg, k.allowed);
        EXPECT_HAS(msg, "calib.toml:4:");
    }
}

TEST(ConfigCalibrate, EveryBadValueIsRefusedNamingKeyAndWhatIsAllowed) {
    struct Case {
        const char* experiment;
        const char* lines;  // in [calibrate]
        const char* key;    // the key the message must name
        const char* why;    // what the message must say is allowed
    } cases[] = {
        // the lists
        {"biaxial", "kinds = \"discs\"", "calibrate.kinds", "must be a list"},
        {"biaxial", "kinds = []", "calibrate.kinds", "must be a list"},
        {"biaxial", "kinds = [\"spheres\"]", "calibrate.kinds", "\"clusters\""},
        {"biaxial", "kinds = [\"discs\", \"discs\"]", "calibrate.kinds", "listed twice"},
        {"biaxial", "kinds = [1]", "calibrate.kinds", "not a list with an integer"},
        {"biaxial", "mu_values = 0.3", "calibrate.mu_values", "must be a list of 1 to 20"},
        {"biaxial", "mu_values = []", "calibrate.mu_values", "must be a list of 1 to 20"},
        {"biaxial", "mu_values = [-0.1]", "calibrate.mu_values", "[0, 10]"},
        {"biaxial", "mu_values = [11.0]", "calibrate.mu_values", "[0, 10]"},
        {"biaxial", "mu_values = [0.3, 0.3]", "calibrate.mu_values", "listed twice"},
        {"biaxial", "mu_values = [\"0.3\"]", "calibrate.mu_values", "not a list with a string"},
        {"repose", "mu_values = [0,1,2,3,4,5,6,7,8,9,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.5,2.5]",
         "calibrate.mu_values", "1 to 20"},
        {"basal-friction", "mu_bp_values = [0.1, -0.2]", "calibrate.mu_bp_values", "[0, 10]"},
        // biaxial
        {"biaxial", "width = 7.0", "calibrate.width", "at least 8 r_max"},
        {"biaxial", "height = 0.0", "calibrate.height", "> 0"},
        {"biaxial", "height = 5.0", "calibrate.height", "at least 8 r_max"},
        {"biaxial", "confining_stress = 0.0", "calibrate.confining_stress", "> 0"},
        {"biaxial", "max_inertial_number = 0.0", "calibrate.max_inertial_number", "(0, 0.1]"},
        {"biaxial", "max_inertial_number = 0.2", "calibrate.max_inertial_number", "(0, 0.1]"},
        {"biaxial", "strain_rate = -1.0", "calibrate.strain_rate", ">= 0"},
        {"biaxial", "strain_rate = 0.1", "calibrate.strain_rate", "inertial number"},
        {"biaxial", "max_strain = 0.0", "calibrate.max_strain", "(0, 0.5]"},
        {"biaxial", "max_strain = 0.6", "calibrate.max_strain", "(0, 0.5]"},
        {"biaxial", "critical_from = 0.2", "calibrate.critical_from", "[0, 0.2)"},
        {"biaxial", "output_strain = 0.0", "calibrate.output_strain", "(0, 0.1]"},
        {"biaxial", "output_strain = 0.02", "calibrate.output_strain", "a quarter of the critical-state window"},
        {"biaxial", "servo_gain = 0.0", "calibrate.servo_gain", "(0, 1]"},
        {"biaxial", "servo_gain = 1.5", "calibrate.servo_gain", "(0, 1]"},
        {"biaxial", "servo_tolerance = 0.0", "calibrate.servo_tolerance", "(0, 0.5]"},
        // basal friction
        {"basal-friction", "block_length = 5.0", "calibrate.block_length", "at least 8 r_max"},
        {"basal-friction", "block_height = 3.0", "calibrate.block_height", "at least 4 r_max"},
        {"basal-friction", "belt_speed = 0.0", "calibrate.belt_speed", "> 0"},
        {"basal-friction", "base_law = \"traction\"\ntraction_gain = 2.0", "calibrate.traction_gain", "(0, 1.5]"},
        {"basal-friction", "traction_gain = 1.0", "calibrate.traction_gain", "applies to the eq. 5 traction only"},
        {"basal-friction", "base_law = \"viscous\"", "calibrate.base_law", "\"coulomb\", \"traction\""},
        {"basal-friction", "duration = -1.0", "calibrate.duration", ">= 0"},
        {"basal-friction", "belt_travel = 0.0", "calibrate.belt_travel", "> 0"},
        {"basal-friction", "measure_from = 1.0", "calibrate.measure_from", "[0, 1)"},
        // repose
        {"repose", "column_width = 3.0", "calibrate.column_width", "at least 4 r_max"},
        {"repose", "column_height = 6.0", "calibrate.column_height", "at least 8 r_max"},
        {"repose", "lift_speed = 0.0", "calibrate.lift_speed", "> 0"},
        {"repose", "fit_from = 1.0", "calibrate.fit_from", "[0, 1)"},
        {"repose", "fit_to = 1.5", "calibrate.fit_to", "(0, 1]"},
        {"repose", "fit_from = 0.5\nfit_to = 0.4", "calibrate.fit_to", "above calibrate.fit_from"},
    };
    for (const Case& k : cases) {
        const std::string msg = refusal(head(k.experiment) + "[calibrate]\n" + k.lines + "\n");
        EXPECT_HAS(msg, std::string("'") + k.key + "'");
        EXPECT_HAS(msg, k.why);
        EXPECT_HAS(msg, "calib.toml:");
    }
}

TEST(ConfigCalibrate, SlowEnoughStrainRateIsAccepted) {
    // I = ε̇ d sqrt(ρ/σ_3) = 0.005 · 1.5 · 0.1118 = 8.4e-4 <= 1e-3.
    const Config c = parse_config(head("biaxial") + "[calibrate]\nstrain_rate = 0.005\n", "calib.toml", {});
    EXPECT_DOUBLE_EQ(c.calibrate.strain_rate, 0.005);
}
