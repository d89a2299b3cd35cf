// Config loader: every refusal is a ConfigError whose one-line message names
// the key (with file:line:col where the key is in the file) and what is
// allowed (SPEC §5); defaults resolve; --set overrides; the resolved TOML
// reads back to itself exactly.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/setup/scenario.hpp"

using namespace orodem;

namespace {

// Line 1: [run], line 2: experiment. Anything appended starts on line 3.
const std::string kBase = "[run]\nexperiment = \"settle\"\n";
const std::string kName = "test.toml";

/// The message of the ConfigError that parsing text throws; a test failure
/// (and "") when the text is accepted.
std::string refusal(const std::string& text, const std::vector<Override>& overrides = {}) {
    try {
        parse_config(text, kName, overrides);
    } catch (const ConfigError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
        EXPECT_FALSE(msg.empty());
        return msg;
    }
    ADD_FAILURE() << "config was accepted:\n" << text;
    return {};
}

bool contains(const std::string& hay, const std::string& needle) {
    return hay.find(needle) != std::string::npos;
}

#define EXPECT_HAS(msg, needle) EXPECT_TRUE(contains((msg), (needle))) << "missing \"" << (needle) << "\" in: " << (msg)

/// Bitwise equality of two doubles (exact round trip, -0.0 distinguished).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

// ---------------------------------------------------------------- unknown keys

TEST(Config, UnknownKeyInSectionNamesKeyLineAndAllowedKeys) {
    const std::string msg = refusal(kBase + "[material]\nk_n = 1e8\nk_nn = 1e8\n");
    EXPECT_HAS(msg, "test.toml:5:");
    EXPECT_HAS(msg, "'material.k_nn'");
    EXPECT_HAS(msg, "unknown key");
    // The allowed keys are listed so that the typo is easy to fix.
    for (const char* k : {"density", "k_n", "k_s_over_k_n", "mu", "cohesion", "damping_kind", "damping_normal",
                          "damping_tangential", "clamp_normal"})
        EXPECT_HAS(msg, k);
}

TEST(Config, UnknownKeyInEverySectionIsRefused) {
    for (const char* section : {"run", "material", "packing", "numerics"}) {
        const std::string text = std::string(section) == "run"
                                     ? "[run]\nexperiment = \"settle\"\nbogus = 1\n"
                                     : kBase + "[" + section + "]\nbogus = 1\n";
        const std::string msg = refusal(text);
        EXPECT_HAS(msg, std::string("'") + section + ".bogus'");
        EXPECT_HAS(msg, "test.toml:");
    }
}

TEST(Config, UnknownTopLevelTableIsRefused) {
    const std::string msg = refusal(kBase + "[matrial]\nk_n = 1e8\n");
    EXPECT_HAS(msg, "test.toml:3:");
    EXPECT_HAS(msg, "'matrial'");
    EXPECT_HAS(msg, "did you mean 'material'?");
    for (const char* t : {"run", "material", "packing", "numerics"}) EXPECT_HAS(msg, t);  // the allowed tables
}

TEST(Config, UnknownTopLevelKeyIsRefused) {
    const std::string msg = refusal("seed = 3\n" + kBase);
    EXPECT_HAS(msg, "test.toml:1:");
    EXPECT_HAS(msg, "'seed'");
}

TEST(Config, NestedTableInsideSectionIsRefused) {
    const std::string msg = refusal(kBase + "[packing.extra]\nx = 1\n");
    EXPECT_HAS(msg, "'packing.extra'");
}

TEST(Config, SectionThatIsNotATableIsRefused) {
    const std::string msg = refusal(std::string("material = 5\n") + kBase);
    EXPECT_HAS(msg, "test.toml:1:");
    EXPECT_HAS(msg, "'material'");
    EXPECT_HAS(msg, "table");
}

// ---------------------------------------------------------------- wrong types

TEST(Config, StringForNumberIsRefused) {
    const std::string msg = refusal(kBase + "[material]\nk_n = \"1e8\"\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "'material.k_n'");
    EXPECT_HAS(msg, "\"1e8\"");
    EXPECT_HAS(msg, "a number");
    EXPECT_HAS(msg, "not a string");
}

TEST(Config, NumberForBooleanIsRefused) {
    const std::string msg = refusal(kBase + "[material]\nclamp_normal = 1\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "'material.clamp_normal'");
    EXPECT_HAS(msg, "true or false");
}

TEST(Config, FloatForIntegerOnlyKeyIsRefused) {
    std::string msg = refusal("[run]\nexperiment = \"settle\"\nseed = 1.5\n");
    EXPECT_HAS(msg, "test.toml:3:");
    EXPECT_HAS(msg, "'run.seed'");
    EXPECT_HAS(msg, "integer");
    msg = refusal(kBase + "[packing]\nsettle_max_steps = 1e5\n");
    EXPECT_HAS(msg, "'packing.settle_max_steps'");
    EXPECT_HAS(msg, "integer");
    msg = refusal("[run]\nexperiment = \"settle\"\nthreads = 2.0\n");
    EXPECT_HAS(msg, "'run.threads'");
}

TEST(Config, NumberForStringIsRefused) {
    std::string msg = refusal(kBase + "[packing]\nkind = 3\n");
    EXPECT_HAS(msg, "'packing.kind'");
    EXPECT_HAS(msg, "\"clusters\"");  // the allowed values are listed
    msg = refusal(kBase + "[packing]\ncache_dir = 3\n");
    EXPECT_HAS(msg, "'packing.cache_dir'");
    EXPECT_HAS(msg, "string");
}

TEST(Config, ArrayForNumberIsRefused) {
    const std::string msg = refusal(kBase + "[material]\nmu = [0.3, 0.4]\n");
    EXPECT_HAS(msg, "'material.mu'");
    EXPECT_HAS(msg, "test.toml:4:");
}

TEST(Config, IntegerIsAcceptedForNumber) {
    const Config c = parse_config(kBase + "[material]\nk_n = 100000\n", kName);
    EXPECT_EQ(c.material.k_n, 1.0e5);
}

// ---------------------------------------------------------------- required and choices

TEST(Config, MissingExperimentIsRefused) {
    std::string msg = refusal("");
    EXPECT_HAS(msg, "test.toml");
    EXPECT_HAS(msg, "'run.experiment'");
    EXPECT_HAS(msg, "\"settle\"");
    msg = refusal("[run]\nseed = 3\n[material]\nmu = 0.4\n");
    EXPECT_HAS(msg, "'run.experiment'");
}

TEST(Config, UnknownExperimentIsRefusedWithAllowedValues) {
    const std::string msg = refusal("[run]\nexperiment = \"wedge!\"\n");
    EXPECT_HAS(msg, "test.toml:2:");
    EXPECT_HAS(msg, "'run.experiment'");
    EXPECT_HAS(msg, "\"wedge!\"");
    EXPECT_HAS(msg, "\"settle\"");
}

TEST(Config, UnknownChoiceIsRefusedWithAllowedValues) {
    std::string msg = refusal(kBase + "[packing]\nkind = \"cluster\"\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "'packing.kind'");
    EXPECT_HAS(msg, "\"hexagonal\", \"discs\", \"clusters\"");
    msg = refusal(kBase + "[material]\ndamping_kind = \"viscous\"\n");
    EXPECT_HAS(msg, "'material.damping_kind'");
    EXPECT_HAS(msg, "\"restitution\"");
}

// ---------------------------------------------------------------- ranges

TEST(Config, NegativeStiffnessIsRefused) {
    std::string msg = refusal(kBase + "[material]\nk_n = -1e8\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "'material.k_n'");
    EXPECT_HAS(msg, "> 0");
    msg = refusal(kBase + "[material]\nk_n = 0\n");
    EXPECT_HAS(msg, "'material.k_n'");
}

TEST(Config, NonFiniteNumbersAreRefused) {
    EXPECT_HAS(refusal(kBase + "[material]\nk_n = inf\n"), "'material.k_n'");
    EXPECT_HAS(refusal(kBase + "[material]\ndensity = nan\n"), "'material.density'");
}

TEST(Config, RestitutionOutsideZeroOneIsRefused) {
    std::string msg = refusal(kBase + "[material]\ndamping_normal = 0\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "'material.damping_normal'");
    EXPECT_HAS(msg, "(0, 1]");
    msg = refusal(kBase + "[material]\ndamping_normal = 1.0001\n");
    EXPECT_HAS(msg, "'material.damping_normal'");
    EXPECT_HAS(msg, "1.0001");
    // The ends that are allowed: e = 1 (elastic) and a tiny e.
    EXPECT_NO_THROW(parse_config(kBase + "[material]\ndamping_normal = 1.0\n", kName));
    EXPECT_NO_THROW(parse_config(kBase + "[material]\ndamping_normal = 1e-3\n", kName));
}

TEST(Config, NegativeFrictionIsRefused) {
    std::string msg = refusal(kBase + "[material]\nmu = -0.1\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "'material.mu'");
    EXPECT_HAS(msg, "-0.1");
    EXPECT_NO_THROW(parse_config(kBase + "[material]\nmu = 0.0\n", kName));
    msg = refusal(kBase + "[packing]\nwall_mu = -1\n");
    EXPECT_HAS(msg, "'packing.wall_mu'");
    msg = refusal(kBase + "[material]\ncohesion = -1\n");
    EXPECT_HAS(msg, "'material.cohesion'");
}

TEST(Config, RMaxBelowRMinIsRefused) {
    const std::string msg = refusal(kBase + "[packing]\nr_min = 1.0\nr_max = 0.5\n");
    EXPECT_HAS(msg, "test.toml:5:");
    EXPECT_HAS(msg, "'packing.r_max'");
    EXPECT_HAS(msg, "r_min");
    // Equal radii are a valid (monodisperse) choice.
    EXPECT_NO_THROW(parse_config(kBase + "[packing]\nr_min = 1.0\nr_max = 1.0\n", kName));
}

TEST(Config, RMaxBelowDefaultRMinIsRefusedEvenWhenRMinIsNotInTheFile) {
    const std::string msg = refusal(kBase + "[packing]\nr_max = 0.25\n");
    EXPECT_HAS(msg, "'packing.r_max'");
    EXPECT_HAS(msg, "test.toml:4:");
}

TEST(Config, LayerTooThinIsRefused) {
    std::string msg = refusal(kBase + "[packing]\nr_max = 1.0\nh0 = 3.0\n");
    EXPECT_HAS(msg, "test.toml:5:");
    EXPECT_HAS(msg, "'packing.h0'");
    EXPECT_HAS(msg, "4 r_max");
    EXPECT_NO_THROW(parse_config(kBase + "[packing]\nr_max = 1.0\nh0 = 4.0\nlength = 20\n", kName));
    msg = refusal(kBase + "[packing]\nr_max = 1.0\nlength = 7.0\n");
    EXPECT_HAS(msg, "'packing.length'");
    // h0 is not in the file, but a large r_max makes the default too thin.
    msg = refusal(kBase + "[packing]\nr_max = 3.0\n");
    EXPECT_HAS(msg, "'packing.h0'");
}

TEST(Config, SafetyAboveHalfIsRefused) {
    std::string msg = refusal(kBase + "[numerics]\nsafety = 0.6\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "'numerics.safety'");
    EXPECT_HAS(msg, "0.5");
    EXPECT_HAS(refusal(kBase + "[numerics]\nsafety = 0\n"), "'numerics.safety'");
    EXPECT_NO_THROW(parse_config(kBase + "[numerics]\nsafety = 0.5\n", kName));
}

TEST(Config, OtherRangesAreRefused) {
    EXPECT_HAS(refusal(kBase + "[numerics]\ndt = -1e-4\n"), "'numerics.dt'");
    EXPECT_HAS(refusal(kBase + "[numerics]\nskin = -0.1\n"), "'numerics.skin'");
    EXPECT_HAS(refusal(kBase + "[numerics]\ngravity = -9.81\n"), "'numerics.gravity'");
    EXPECT_HAS(refusal(kBase + "[material]\ndensity = 0\n"), "'material.density'");
    EXPECT_HAS(refusal(kBase + "[packing]\nsettle_ke_ratio = 0\n"), "'packing.settle_ke_ratio'");
    EXPECT_HAS(refusal(kBase + "[packing]\nsettle_max_steps = 0\n"), "'packing.settle_max_steps'");
    EXPECT_HAS(refusal(kBase + "[packing]\nr_min = 0\n"), "'packing.r_min'");
    EXPECT_HAS(refusal("[run]\nexperiment = \"settle\"\nseed = -1\n"), "'run.seed'");
    EXPECT_HAS(refusal("[run]\nexperiment = \"settle\"\nthreads = -2\n"), "'run.threads'");
    EXPECT_HAS(refusal("[run]\nexperiment = \"settle\"\noutput_interval = 0\n"), "'run.output_interval'");
}

TEST(Config, TimestepAboveStabilityLimitIsRefused) {
    const Config ok = parse_config(kBase, kName);
    const TimestepInfo automatic = timestep_for(ok);
    EXPECT_GT(automatic.dt, 0.0);
    EXPECT_GT(automatic.margin(), 1.0);

    const Config big = parse_config(kBase + "[numerics]\ndt = 1.0\n", kName);
    try {
        timestep_for(big);
        ADD_FAILURE() << "dt = 1 s was accepted";
    } catch (const ConfigError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        EXPECT_HAS(msg, "numerics.dt");
        EXPECT_HAS(msg, "test.toml");
        EXPECT_HAS(msg, "stability limit");
    }
    // Just below the limit is accepted, just above refused.
    Config c = ok;
    c.numerics.dt = 0.99 * automatic.dt_crit;
    EXPECT_NO_THROW(timestep_for(c));
    EXPECT_EQ(timestep_for(c).dt, c.numerics.dt);
    c.numerics.dt = 1.01 * automatic.dt_crit;
    EXPECT_THROW(timestep_for(c), ConfigError);
}

// ---------------------------------------------------------------- syntax and overrides

TEST(Config, InvalidTomlNamesFileAndLine) {
    std::string msg = refusal(kBase + "[material]\nk_n = = 3\n");
    EXPECT_HAS(msg, "test.toml:4:");
    EXPECT_HAS(msg, "TOML");
    msg = refusal(kBase + "[material]\nmu = 0.3\nmu = 0.4\n");  // duplicate key
    EXPECT_HAS(msg, "test.toml:5:");
    msg = refusal("[run\nexperiment = \"settle\"\n");
    EXPECT_HAS(msg, "test.toml:1:");
    msg = refusal(kBase + "[packing]\nkind = \"discs\n");  // unterminated string
    EXPECT_HAS(msg, "test.toml:4:");
}

TEST(Config, OverrideWithoutEqualsIsRefused) {
    try {
        parse_override("material.mu");
        ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
        EXPECT_HAS(std::string(e.what()), "material.mu");
        EXPECT_HAS(std::string(e.what()), "key=value");
    }
    EXPECT_THROW(parse_override("=0.5"), ConfigError);
    const Override o = parse_override("packing.kind=\"a=b\"");
    EXPECT_EQ(o.first, "packing.kind");
    EXPECT_EQ(o.second, "\"a=b\"");
}

TEST(Config, OverrideWithInvalidTomlValueIsRefused) {
    std::string msg = refusal(kBase, {{"packing.kind", "discs"}});  // unquoted string
    EXPECT_HAS(msg, "packing.kind");
    EXPECT_HAS(msg, "--set");
    EXPECT_HAS(msg, "quotes");
    msg = refusal(kBase, {{"material.mu", ""}});
    EXPECT_HAS(msg, "material.mu");
    msg = refusal(kBase, {{"material.mu", "0.5 0.6"}});
    EXPECT_HAS(msg, "material.mu");
}

TEST(Config, OverrideOfUnknownKeyIsRefused) {
    std::string msg = refusal(kBase, {{"material.k_nn", "1e8"}});
    EXPECT_HAS(msg, "'material.k_nn'");
    EXPECT_HAS(msg, "k_n");  // allowed keys listed
    msg = refusal(kBase, {{"bogus.x", "1"}});
    EXPECT_HAS(msg, "'bogus'");
    // A path through a value: refused whether or not the value is in the file.
    msg = refusal(kBase, {{"material.mu.x", "1"}});
    EXPECT_HAS(msg, "material.mu");
    msg = refusal(kBase + "[material]\nmu = 0.3\n", {{"material.mu.x", "1"}});
    EXPECT_HAS(msg, "material.mu.x");
}

TEST(Config, OverrideWithWrongTypeOrRangeIsRefused) {
    std::string msg = refusal(kBase, {{"material.mu", "\"high\""}});
    EXPECT_HAS(msg, "'material.mu'");
    msg = refusal(kBase, {{"material.mu", "-1"}});
    EXPECT_HAS(msg, "'material.mu'");
    EXPECT_HAS(msg, "-1");
}

TEST(Config, OverridesReplaceAndAddValues) {
    const std::string text = kBase + "[material]\nmu = 0.3\n";
    const Config c = parse_config(text, kName,
                                  {{"material.mu", "0.5"}, {"packing.kind", "\"discs\""}, {"numerics.gravity", "0"},
                                   {"run.seed", "17"}});
    EXPECT_EQ(c.material.mu, 0.5);
    EXPECT_EQ(c.packing.kind, PackingKind::discs);
    EXPECT_EQ(c.numerics.gravity, 0.0);
    EXPECT_EQ(c.run.seed, 17u);
    EXPECT_EQ(c.packing.seed, 17u);  // the derived default follows the override
    // The resolved config records the overridden values.
    const std::string t = to_toml(c);
    EXPECT_HAS(t, "mu = 0.5\n");
    EXPECT_HAS(t, "kind = ");
    EXPECT_HAS(t, "discs");
    // The last of several overrides of one key wins.
    const Config d = parse_config(text, kName, {{"material.mu", "0.5"}, {"material.mu", "0.7"}});
    EXPECT_EQ(d.material.mu, 0.7);
}

TEST(Config, OverrideCanSupplyTheRequiredExperiment) {
    const Config c = parse_config("", kName, {{"run.experiment", "\"settle\""}});
    EXPECT_EQ(c.run.experiment, "settle");
}

// ---------------------------------------------------------------- defaults

TEST(Config, DefaultsResolve) {
    const Config c = parse_config(kBase, kName);
    const Config d;  // member initialisers
    EXPECT_EQ(c.path, kName);
    EXPECT_EQ(c.run.experiment, "settle");
    EXPECT_EQ(c.run.seed, d.run.seed);
    EXPECT_EQ(c.material.k_n, d.material.k_n);
    EXPECT_EQ(c.material.mu, d.material.mu);
    EXPECT_EQ(c.packing.kind, d.packing.kind);
    EXPECT_EQ(c.packing.r_min, d.packing.r_min);
    EXPECT_EQ(c.numerics.dt, 0.0);
    EXPECT_EQ(c.numerics.safety, d.numerics.safety);
    // Derived defaults.
    EXPECT_EQ(c.packing.seed, c.run.seed);
    EXPECT_EQ(c.numerics.skin, 0.4 * c.packing.r_min);
    // Every section and key is written out in the resolved config.
    for (const char* section : {"run", "material", "packing", "numerics"}) {
        ASSERT_TRUE(c.resolved.get(section)) << section;
        EXPECT_TRUE(c.resolved.get(section)->is_table()) << section;
    }
    EXPECT_EQ(c.resolved["packing"]["seed"].value<std::int64_t>(), static_cast<std::int64_t>(c.run.seed));
    EXPECT_EQ(c.resolved["numerics"]["skin"].value<double>(), 0.4 * c.packing.r_min);
    EXPECT_EQ(c.resolved["numerics"]["dt"].value<double>(), 0.0);
    EXPECT_EQ(c.resolved["material"]["k_n"].value<double>(), d.material.k_n);
    EXPECT_EQ(c.resolved["material"]["damping_kind"].value<std::string>(), name_of(d.material.damping_kind));
    EXPECT_EQ(c.resolved["packing"]["settle_max_steps"].value<std::int64_t>(), d.packing.settle_max_steps);
    EXPECT_EQ(c.resolved["run"]["threads"].value<std::int64_t>(), d.run.threads);
}

TEST(Config, PackingSeedDefaultsToRunSeed) {
    Config c = parse_config("[run]\nexperiment = \"settle\"\nseed = 42\n", kName);
    EXPECT_EQ(c.packing.seed, 42u);
    c = parse_config("[run]\nexperiment = \"settle\"\nseed = 42\n[packing]\nseed = 0\n", kName);
    EXPECT_EQ(c.packing.seed, 42u);  // 0 = "use run.seed"
    c = parse_config("[run]\nexperiment = \"settle\"\nseed = 42\n[packing]\nseed = 7\n", kName);
    EXPECT_EQ(c.packing.seed, 7u);
    EXPECT_EQ(c.run.seed, 42u);
}

TEST(Config, AutomaticSkinIsFractionOfSmallestRadius) {
    Config c = parse_config(kBase + "[packing]\nr_min = 0.25\nr_max = 1.0\n", kName);
    EXPECT_DOUBLE_EQ(c.numerics.skin, 0.1);
    c = parse_config(kBase + "[packing]\nr_min = 0.25\nr_max = 1.0\n[numerics]\nskin = 0.3\n", kName);
    EXPECT_EQ(c.numerics.skin, 0.3);
}

// ---------------------------------------------------------------- resolved TOML

TEST(Config, ResolvedTomlRoundTripsExactly) {
    const std::string text = "[run]\nexperiment = \"settle\"\noutput_interval = 0.1\nseed = 9223372036854775807\n"
                             "[material]\nmu = 0.123456789012\nk_n = 12345678.9\ndensity = 2650\ncohesion = 1e-300\n"
                             "[packing]\nkind = \"discs\"\nr_min = 0.1\nr_max = 0.30000000000000004\nh0 = 10\n"
                             "cache_dir = \"dir with 'quotes' \\\"and\\\" \\\\ back\\tslash\"\n"
                             "[numerics]\ngravity = 9.80665\ndt = 1e-7\n";
    const Config a = parse_config(text, kName);
    const std::string ta = to_toml(a);
    const Config b = parse_config(ta, "resolved.toml");
    const std::string tb = to_toml(b);
    EXPECT_EQ(ta, tb);

    // The doubles come back bit for bit, written in their shortest form.
    EXPECT_TRUE(same_bits(b.run.output_interval, 0.1));
    EXPECT_TRUE(same_bits(b.material.mu, 0.123456789012));
    EXPECT_TRUE(same_bits(b.material.k_n, 12345678.9));
    EXPECT_TRUE(same_bits(b.material.cohesion, 1e-300));
    EXPECT_TRUE(same_bits(b.packing.r_min, 0.1));
    EXPECT_TRUE(same_bits(b.packing.r_max, 0.30000000000000004));
    EXPECT_TRUE(same_bits(b.numerics.gravity, 9.80665));
    EXPECT_TRUE(same_bits(b.numerics.dt, 1e-7));
    EXPECT_TRUE(same_bits(b.numerics.skin, a.numerics.skin));
    EXPECT_HAS(ta, "output_interval = 0.1\n");
    EXPECT_HAS(ta, "mu = 0.123456789012\n");
    EXPECT_HAS(ta, "density = 2650.0\n");  // a float stays a float
    EXPECT_EQ(b.run.seed, 9223372036854775807ull);
    EXPECT_EQ(b.packing.seed, a.packing.seed);
    EXPECT_EQ(b.packing.cache_dir, "dir with 'quotes' \"and\" \\ back\tslash");
    EXPECT_EQ(b.packing.kind, PackingKind::discs);
}

TEST(Config, ResolvedTomlOfDefaultsRoundTrips) {
    const Config a = parse_config(kBase, kName);
    const std::string ta = to_toml(a);
    const Config b = parse_config(ta, "resolved.toml");
    EXPECT_EQ(ta, to_toml(b));
    EXPECT_EQ(a.packing.seed, b.packing.seed);
    EXPECT_TRUE(same_bits(a.numerics.skin, b.numerics.skin));
    EXPECT_TRUE(same_bits(a.packing.settle_ke_ratio, b.packing.settle_ke_ratio));
}

TEST(Config, LoadConfigOfMissingFileIsRefused) {
    try {
        load_config("/nonexistent/dir/orodem-missing.toml");
        ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
        EXPECT_HAS(std::string(e.what()), "/nonexistent/dir/orodem-missing.toml");
    }
}

TEST(Config, MisspelledKeysTablesAndValuesGetADidYouMean) {
    EXPECT_HAS(refusal(kBase + "[material]\nk_nn = 1e8\n"), "did you mean 'material.k_n'?");
    EXPECT_HAS(refusal(kBase + "[materal]\nk_n = 1e8\n"), "did you mean 'material'?");
    EXPECT_HAS(refusal(kBase + "[packing]\nkind = \"cluster\"\n"), "did you mean 'clusters'?");
    // Nothing near: no suggestion.
    EXPECT_EQ(refusal(kBase + "[material]\nzzzzzzzz = 1\n").find("did you mean"), std::string::npos);
}

TEST(Config, ValuesAreEchoedAsTyped) {
    // A double is echoed in its shortest round-trip form, as it was typed, not 0.29999999999999999.
    const std::string msg = refusal(kBase + "[material]\nmu = 0.3\nk_nn = 0.3\n");
    EXPECT_HAS(msg, "'material.k_nn' = 0.3;");
    EXPECT_HAS(refusal(kBase + "[material]\ndensity = -0.1\n"), "= -0.1:");
}
