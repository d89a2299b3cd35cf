// The [run] keys of the wedge experiments (checkpoints, health limits,
// domain-exit policy): each out-of-range or ill-typed value is refused with
// a one-line ConfigError naming the key and what is allowed, and the
// defaults resolve to the documented values.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"

using namespace orodem;

namespace {

const std::string kWedge = "[run]\nexperiment = \"exp1\"\n";

// The one-line ConfigError for the wedge config plus `lines` (any tables).
std::string refusal_of(const std::string& lines) {
    try {
        parse_config(kWedge + lines, "run.toml", {});
    } catch (const ConfigError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        return msg;
    }
    ADD_FAILURE() << "accepted: " << lines;
    return {};
}

}  // namespace

TEST(ConfigRun, DefaultsResolve) {
    const Config c = parse_config(kWedge, "run.toml", {});
    EXPECT_EQ(c.run.checkpoint_every_outputs, 1);
    EXPECT_DOUBLE_EQ(c.run.checkpoint_minutes, 10.0);
    EXPECT_DOUBLE_EQ(c.run.max_wall_minutes, 0.0);
    EXPECT_DOUBLE_EQ(c.run.max_overlap_ratio, 0.5);
    EXPECT_DOUBLE_EQ(c.run.warn_overlap_ratio, 0.1);
    EXPECT_FALSE(c.run.allow_initial_overlap);
    EXPECT_EQ(c.run.on_domain_exit, "error");
    EXPECT_DOUBLE_EQ(c.run.domain_height, 0.0);
    const Config d = parse_config(kWedge + "on_domain_exit = \"stop\"\nallow_initial_overlap = true\n", "run.toml", {});
    EXPECT_EQ(d.run.on_domain_exit, "stop");
    EXPECT_TRUE(d.run.allow_initial_overlap);
}

TEST(ConfigRun, EveryBadValueIsRefusedNamingKeyAndAllowedRange) {
    struct Case {
        const char* line;  // the offending line in [run]
        const char* key;   // the key the message must name
        const char* why;   // what the message must say is allowed
    };
    const Case cases[] = {
        {"checkpoint_every_outputs = 0", "run.checkpoint_every_outputs", "[1, 1000000]"},
        {"checkpoint_every_outputs = 1.5", "run.checkpoint_every_outputs", "integer"},
        {"checkpoint_minutes = -1", "run.checkpoint_minutes", ">= 0"},
        {"max_wall_minutes = -1", "run.max_wall_minutes", ">= 0"},
        {"max_overlap_ratio = 0", "run.max_overlap_ratio", "(0, 1]"},
        {"max_overlap_ratio = 1.5", "run.max_overlap_ratio", "(0, 1]"},
        {"warn_overlap_ratio = 0", "run.warn_overlap_ratio", "(0, 1]"},
        {"warn_overlap_ratio = 0.6", "run.warn_overlap_ratio", "must not exceed run.max_overlap_ratio = 0.5"},
        {"domain_height = -1", "run.domain_height", ">= 0"},
        {"allow_initial_overlap = 1", "run.allow_initial_overlap", "true or false"},
        {"on_domain_exit = \"delete\"", "run.on_domain_exit", "\"error\", \"stop\""},
        {"on_domain_exit = 3", "run.on_domain_exit", "\"error\", \"stop\""},
    };
    for (const Case& k : cases) {
        const std::string msg = refusal_of(std::string(k.line) + "\n");
        EXPECT_NE(msg.find("run.toml:3:"), std::string::npos) << k.line << " -> " << msg;
        EXPECT_NE(msg.find(k.key), std::string::npos) << k.line << " -> " << msg;
        EXPECT_NE(msg.find(k.why), std::string::npos) << k.line << " -> " << msg;
    }
}

TEST(ConfigRun, WedgeOnlyKeysAreUnknownForSettle) {
    try {
        parse_config("[run]\nexperiment = \"settle\"\non_domain_exit = \"stop\"\n", "run.toml", {});
        ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown key 'run.on_domain_exit'"), std::string::npos) << e.what();
    }
}

TEST(ConfigRun, SleepKeysOfTheWedgeTable) {
    const Config c = parse_config(kWedge, "run.toml", {});
    EXPECT_FALSE(c.wedge.sleep);
    EXPECT_DOUBLE_EQ(c.wedge.sleep_tolerance, 0.01);
    EXPECT_DOUBLE_EQ(c.wedge.sleep_buffer, 2.0);
    EXPECT_DOUBLE_EQ(c.wedge.sleep_buffer_pro, 2.0);
    // The proside buffer follows sleep_buffer unless it is given.
    EXPECT_DOUBLE_EQ(parse_config(kWedge + "[wedge]\nsleep_buffer = 3\n", "run.toml", {}).wedge.sleep_buffer_pro, 3.0);
    const Config own = parse_config(kWedge + "[wedge]\nsleep_buffer = 3\nsleep_buffer_pro = 1\n", "run.toml", {});
    EXPECT_DOUBLE_EQ(own.wedge.sleep_buffer, 3.0);
    EXPECT_DOUBLE_EQ(own.wedge.sleep_buffer_pro, 1.0);
    struct Case {
        const char* line;
        const char* why;
    };
    const Case cases[] = {
        {"sleep = 1", "true or false"},
        {"sleep_tolerance = 0", "(0, 1]"},
        {"sleep_tolerance = 2", "(0, 1]"},
        {"sleep_buffer = 0", "(0, 100]"},
        {"sleep_buffer_pro = 0", "(0, 100]"},
        {"sleep_buffer_pro = 101", "(0, 100]"},
    };
    for (const Case& k : cases) {
        const std::string msg = refusal_of("[wedge]\n" + std::string(k.line) + "\n");
        EXPECT_NE(msg.find("run.toml:4:"), std::string::npos) << k.line << " -> " << msg;
        EXPECT_NE(msg.find("wedge.sleep"), std::string::npos) << k.line << " -> " << msg;
        EXPECT_NE(msg.find(k.why), std::string::npos) << k.line << " -> " << msg;
    }
}

TEST(ConfigRun, InertiaFloorIsAFactorOfRMinUnderTheCoulombBase) {
    EXPECT_DOUBLE_EQ(parse_config(kWedge, "run.toml", {}).wedge.inertia_floor, 1.0);  // off unless asked for
    EXPECT_DOUBLE_EQ(parse_config(kWedge + "[wedge]\ninertia_floor = 1.5\n", "run.toml", {}).wedge.inertia_floor, 1.5);
    struct Case {
        const char* lines;
        const char* why;
    };
    const Case cases[] = {
        {"inertia_floor = 0.5", "[1, 10]"},
        {"inertia_floor = 11", "[1, 10]"},
        {"base_law = \"traction\"\ninertia_floor = 1.5", "Coulomb base only"},
    };
    for (const Case& k : cases) {
        const std::string msg = refusal_of("[wedge]\n" + std::string(k.lines) + "\n");
        EXPECT_NE(msg.find("wedge.inertia_floor"), std::string::npos) << k.lines << " -> " << msg;
        EXPECT_NE(msg.find(k.why), std::string::npos) << k.lines << " -> " << msg;
    }
}

TEST(ConfigRun, DragGainKeepsTheSumOfGainsBelowTwo) {
    const std::string traction = "base_law = \"traction\"\n";
    EXPECT_DOUBLE_EQ(parse_config(kWedge, "run.toml", {}).wedge.drag_gain, 0.0);  // off unless asked for
    EXPECT_DOUBLE_EQ(
        parse_config(kWedge + "[wedge]\n" + traction + "drag_gain = 0.05\n", "run.toml", {}).wedge.drag_gain, 0.05);
    // Uncapped, the velocity change per step is (g_b + g_d) times the slip:
    // the allowed drag gain is [0, 2 - traction_gain).
    struct Case {
        const char* lines;
        const char* why;
    };
    const Case cases[] = {
        {"drag_gain = 1.0", "[0, 1)"},
        {"drag_gain = -0.1", "[0, 1)"},
        {"traction_gain = 1.5\ndrag_gain = 0.5", "[0, 0.5)"},
    };
    for (const Case& k : cases) {
        const std::string msg = refusal_of("[wedge]\n" + traction + std::string(k.lines) + "\n");
        EXPECT_NE(msg.find("wedge.drag_gain"), std::string::npos) << k.lines << " -> " << msg;
        EXPECT_NE(msg.find(k.why), std::string::npos) << k.lines << " -> " << msg;
    }
}

// wedge.base_law: "coulomb" by default; the eq. 5 traction's keys only with
// "traction"; a run directory's config.toml written before the key existed
// reads as "traction" (the law that run used) and hashes as it did then.
TEST(ConfigRun, BaseLawDefaultsToCoulombAndTheTractionKeysNeedTraction) {
    EXPECT_EQ(parse_config(kWedge, "run.toml", {}).wedge.base_law, BaseLaw::coulomb);
    EXPECT_EQ(parse_config(kWedge + "[wedge]\nbase_law = \"traction\"\n", "run.toml", {}).wedge.base_law, BaseLaw::traction);
    for (const char* key : {"traction_gain = 1.0", "drag_gain = 0.1"}) {
        const std::string msg = refusal_of("[wedge]\n" + std::string(key) + "\n");
        EXPECT_NE(msg.find("applies to the eq. 5 traction only"), std::string::npos) << msg;
        EXPECT_NE(msg.find("wedge.base_law = \"traction\""), std::string::npos) << msg;
    }
    const std::string bad = refusal_of("[wedge]\nbase_law = \"drag\"\n");
    EXPECT_NE(bad.find("'wedge.base_law'"), std::string::npos) << bad;
    EXPECT_NE(bad.find("\"coulomb\", \"traction\""), std::string::npos) << bad;
}

TEST(ConfigRun, AResolvedConfigWithoutBaseLawIsAnOlderRunOnTheTractionBase) {
    // A run directory's config.toml as the orodem before base_law wrote it:
    // to_toml of a traction config, with the base_law line taken out.
    const Config now = parse_config(kWedge + "[wedge]\nbase_law = \"traction\"\n", "run.toml", {});
    std::string old_text = to_toml(now);
    const auto at = old_text.find("base_law = 'traction'\n");
    ASSERT_NE(at, std::string::npos) << old_text;
    old_text.erase(at, std::string("base_law = 'traction'\n").size());
    const Config old = parse_config(old_text, "runs/x/config.toml", {});
    EXPECT_EQ(old.wedge.base_law, BaseLaw::traction);
    EXPECT_TRUE(old.legacy_base_law);
    // That orodem hashed the text without the keys at its defaults (the
    // traction law's gains, and no base_law key): for this all-defaults exp1,
    // nothing of [wedge] but column_width, the text of today's all-defaults
    // config (whose default law is dropped and which has no gains).
    EXPECT_EQ(to_toml_without_defaults(old), to_toml_without_defaults(parse_config(kWedge, "run.toml", {})));
    // The same text without the header line is a user's config: the default
    // law, which refuses the traction's gains by name.
    std::string msg;
    try {
        parse_config(old_text.substr(old_text.find("[run]")), "mine.toml", {});
    } catch (const ConfigError& e) {
        msg = e.what();
    }
    EXPECT_NE(msg.find("applies to the eq. 5 traction only"), std::string::npos) << msg;
}

// The size check's estimate (no allocation) against the discs generation
// really makes, for each packing kind: within 3% (the last row or cluster
// and the random radii are the difference).
TEST(ModelSize, TheDiscEstimateMatchesGenerationAndAbsurdSizesAreRefusedAtOnce) {
    for (const char* kind : {"hexagonal", "discs", "clusters"}) {
        const Config c = parse_config(std::string("[run]\nexperiment = \"settle\"\n[packing]\nkind = \"") + kind +
                                          "\"\nlength = 400.0\nh0 = 20.0\n",
                                      "size.toml", {});
        const double n = static_cast<double>(generated_particle_count(c));
        EXPECT_NEAR(estimated_disc_count(c.packing) / n, 1.0, 0.03) << kind << ": " << n;
        EXPECT_NO_THROW(check_model_size(c));
    }
    for (const char* h0 : {"1e308", "5000.0"}) {
        const Config c = parse_config(kWedge + "[packing]\nh0 = " + h0 + "\n", "size.toml", {});
        try {
            check_model_size(c);
            ADD_FAILURE() << "h0 = " << h0 << " was accepted";
        } catch (const ConfigError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("discs and need about"), std::string::npos) << m;
            EXPECT_NE(m.find("lower packing.h0"), std::string::npos) << m;
        }
    }
}

// The plate estimate's inputs: the calibrated bulk friction (docs/validation.md
// biaxial table) interpolated in mu_i, and the critical taper on it.
TEST(PlateEstimate, BulkFrictionFromTheCalibrationTableAndTheFrontFromTheTaper) {
    EXPECT_DOUBLE_EQ(bulk_friction_deg(PackingKind::clusters, 0.3), 24.4);
    EXPECT_DOUBLE_EQ(bulk_friction_deg(PackingKind::discs, 0.2), 0.5 * (12.0 + 15.6));
    EXPECT_DOUBLE_EQ(bulk_friction_deg(PackingKind::clusters, 2.0), 28.4);  // beyond the table: its last row
    EXPECT_DOUBLE_EQ(bulk_friction_deg(PackingKind::hexagonal, 0.0), 7.2);  // the discs' row
    Config c = parse_config(kWedge + "[wedge]\nmu_bp = 0.1\ns_max = 8.0\n", "run.toml", {});
    const PlateEstimate e = plate_estimate(c);
    EXPECT_DOUBLE_EQ(e.phi_deg, 24.4);
    EXPECT_NEAR(e.phi_b_deg, std::atan(0.1) * 180.0 / M_PI, 1e-12);
    EXPECT_NEAR(e.alpha_deg, 2.40, 0.01);  // orodem taper --phi 24.4 --mu-b 0.1
    EXPECT_NEAR(e.front_h0, std::sqrt(16.0 / std::tan(e.alpha_deg * M_PI / 180.0)), 1e-12);
    EXPECT_DOUBLE_EQ(e.pro_margin_min, e.front_h0 + 2.0);
    // A base stronger than the material: phi_b is capped 0.5 deg below phi.
    c = parse_config(kWedge + "[wedge]\nmu_bp = 0.8\n", "run.toml", {});
    EXPECT_DOUBLE_EQ(plate_estimate(c).phi_b_deg, 24.4 - 0.5);
}

TEST(AbsurdValues, DerivedNumbersOutOfAnyRunAreRefusedBeforeAnythingIsWritten) {
    // Each passes its key's own range but makes the run's numbers absurd (docs/reliability.md "Absurd values"):
    // refused by derive_run_numbers, which `orodem check` and `orodem run` call before writing, with the key named.
    const std::pair<const char*, const char*> cases[] = {
        {"wedge.v=1e-308", "steps; at most"},        {"wedge.v=1e-9", "steps; at most"},
        {"wedge.output_ds=5e-324", "outputs"},       {"wedge.v=1e308", "more than half packing.r_min"},
        {"numerics.gravity=1e308", "at most 1000"}, {"numerics.dt=5e-324", "at least 1e-12 s"},
        {"material.k_n=1e308", "at least 1e-12 s"}, {"numerics.skin=1000", "at most 2 packing.r_max"},
        {"numerics.gravity=0", "must settle under gravity"},
    };
    for (const auto& [kv, why] : cases) {
        const Config c = parse_config(kWedge, "run.toml", {parse_override(kv)});
        try {
            derive_run_numbers(c);
            ADD_FAILURE() << kv << " was accepted";
        } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << kv << ": " << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << kv << ": one line";
        }
    }
    EXPECT_NO_THROW(derive_run_numbers(parse_config(kWedge, "run.toml", {})));
}
