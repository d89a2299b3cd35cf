// The [run] keys of the wedge experiments (checkpoints, health limits,
// domain-exit policy): each out-of-range or ill-typed value is refused with
// a one-line ConfigError naming the key and what is allowed, and the
// defaults resolve to the documented values.
#include <gtest/gtest.h>

#include <string>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"

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
    struct Case {
        const char* line;
        const char* why;
    };
    const Case cases[] = {
        {"sleep = 1", "true or false"},
        {"sleep_tolerance = 0", "(0, 1]"},
        {"sleep_tolerance = 2", "(0, 1]"},
        {"sleep_buffer = 0", "(0, 100]"},
    };
    for (const Case& k : cases) {
        const std::string msg = refusal_of("[wedge]\n" + std::string(k.line) + "\n");
        EXPECT_NE(msg.find("run.toml:4:"), std::string::npos) << k.line << " -> " << msg;
        EXPECT_NE(msg.find("wedge.sleep"), std::string::npos) << k.line << " -> " << msg;
        EXPECT_NE(msg.find(k.why), std::string::npos) << k.line << " -> " << msg;
    }
}

TEST(ConfigRun, DragGainKeepsTheSumOfGainsBelowTwo) {
    EXPECT_DOUBLE_EQ(parse_config(kWedge, "run.toml", {}).wedge.drag_gain, 0.0);  // off unless asked for
    EXPECT_DOUBLE_EQ(parse_config(kWedge + "[wedge]\ndrag_gain = 0.05\n", "run.toml", {}).wedge.drag_gain, 0.05);
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
        const std::string msg = refusal_of("[wedge]\n" + std::string(k.lines) + "\n");
        EXPECT_NE(msg.find("wedge.drag_gain"), std::string::npos) << k.lines << " -> " << msg;
        EXPECT_NE(msg.find(k.why), std::string::npos) << k.lines << " -> " << msg;
    }
}
