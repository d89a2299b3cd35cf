// Inputs the fuzzer (tests/fuzz/fuzz_config.cpp, scripts/fuzz) found crashing
// the config loader, kept so that the fix stays: every file under
// tests/fuzz/regressions/config/ is fed to parse_config exactly as the fuzz
// target feeds it (lines "#set key=value" are also --set overrides), and must
// be accepted or refused with a one-line ConfigError; an accepted config must
// read back from its resolved TOML. Any other exception, or a sanitizer
// report in the ASan/UBSan build (scripts/test), fails the test.
//
// The non-ASCII guard in io/config.cpp (toml++ 3.3.0 has undefined behaviour
// on some non-ASCII characters where it looks for whitespace) must refuse
// those places and still accept non-ASCII text in comments and strings.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_regressions.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"

using namespace orodem;
namespace fs = std::filesystem;

namespace {

/// The "#set key=value" lines of text as overrides (as in fuzz_config.cpp);
/// false when one of them is not key=value (parse_override refuses it).
bool overrides_of(const std::string& text, std::vector<Override>& out) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("#set ", 0) != 0) continue;
        try {
            out.push_back(parse_override(line.substr(5)));
        } catch (const ConfigError&) {
            return false;
        }
    }
    return true;
}

/// Parses; "" when accepted (and the resolved TOML reads back to itself),
/// else the ConfigError message. Any other exception fails the test.
std::string outcome(const std::string& text, const std::vector<Override>& overrides = {}) {
    try {
        const Config c = parse_config(text, "fuzz.toml", overrides);
        const std::string resolved = to_toml(c);
        EXPECT_EQ(to_toml(parse_config(resolved, "config.toml")), resolved);
        return "";
    } catch (const ConfigError& e) {
        const std::string msg = e.what();
        EXPECT_FALSE(msg.empty());
        return msg;
    }
}

const std::string kBase = "[run]\nexperiment = \"settle\"\n";

}  // namespace

TEST(ConfigRegressions, EverySavedFuzzInputIsAcceptedOrRefusedCleanly) {
    const auto inputs = test::fuzz_regressions("config");
    ASSERT_FALSE(inputs.empty()) << "no saved inputs in tests/fuzz/regressions/config";
    for (const auto& [name, bytes] : inputs) {
        SCOPED_TRACE(name);
        const std::string& text = bytes;
        EXPECT_NO_FATAL_FAILURE(outcome(text));
        std::vector<Override> overrides;
        if (overrides_of(text, overrides) && !overrides.empty()) {
            EXPECT_NO_FATAL_FAILURE(outcome(text, overrides));
        }
    }
}

TEST(ConfigRegressions, NonAsciiWhereTomlppCannotTakeItIsRefusedWithItsPosition) {
    const std::string refused = "a non-ASCII character where orodem does not read one";
    auto refused_at = [&](const std::string& text, const std::string& where) {
        const std::string msg = outcome(text);
        EXPECT_NE(msg.find("fuzz.toml:" + where + ": " + refused), std::string::npos) << msg;
    };
    // The first fuzz crash: '×' (U+00D7) after a value.
    refused_at(kBase + "[packing]\nr_max = 1.0   \xC3\x97 2\n", "4:15");
    // The second: a quote inside a bare value; toml++ looks ahead through it.
    refused_at(kBase + "[packing]\nr_max = 1s\"\xCB\x82te\"\n", "4:12");
    refused_at(kBase + "[packing]\nr_max = 1=\"\xCB\x82\"\n", "4:12");
    refused_at(kBase + "[packing]\nr_max = [\n1=\"\xCB\x82\"]\n", "5:4");
    // At the start of a line (a Greek mu typed as a key), in a bare key, in a quoted key.
    refused_at(kBase + "[material]\n\xCE\xBC = 0.3\n", "4:1");
    refused_at(kBase + "[material]\nm\xCE\xBC = 0.3\n", "4:2");
    refused_at(kBase + "[packing]\n\"caf\xC3\xA9\" = 1\n", "4:5");
    // A string that is not the value of the line's key: in an array, after another string.
    refused_at(kBase + "[packing]\ncache_dir = [\"\xC2\xA7\"]\n", "4:15");
    refused_at(kBase + "[packing]\ncache_dir = \"a\" \"\xC2\xA7\"\n", "4:18");
    refused_at(kBase + "[packing]\ncache_dir = \"a\" \xC2\xA7\n", "4:17");
    // Right after a line-ending backslash, and after a backslash, in a multi-line basic string.
    refused_at(kBase + "[packing]\ncache_dir = \"\"\"\\\n  \xC2\xA7\"\"\"\n", "5:3");
    refused_at(kBase + "[packing]\ncache_dir = \"\"\"a\\\xC2\xA7\"\"\"\n", "4:18");
    // In a --set value.
    const std::string msg = outcome(kBase, {{"material.mu", "0.3\xC3\x97"}});
    EXPECT_NE(msg.find("--set material.mu=0.3\xC3\x97: a non-ASCII character"), std::string::npos) << msg;
}

TEST(ConfigRegressions, NonAsciiInCommentsAndStringValuesIsStillAccepted) {
    const std::string text =
        "\xEF\xBB\xBF"  // a UTF-8 byte order mark
        "# \xCE\xBC, \xC3\x97, m\xC2\xB2 in a comment\n" + kBase +
        "seed = 3 # \xC2\xA7 after a value\n"
        "[packing] # \xC2\xA7\n"
        "cache_dir = \"/tmp/caf\xC3\xA9 \\\" \xC2\xA7 # not a comment\"\n";
    EXPECT_EQ(outcome(text), "");
    EXPECT_EQ(outcome(kBase + "[packing]\ncache_dir=\t'/tmp/\xC2\xA7'\n"), "");
    EXPECT_EQ(outcome(kBase + "[packing]\ncache_dir = \"\"\"/tmp/\n\xC2\xA7\\\\\xC2\xA7\"\"\"\n"), "");
    EXPECT_EQ(outcome(kBase + "[packing]\ncache_dir = '''\n/tmp/\xC2\xA7 ''\xC2\xA7'''\n"), "");
    EXPECT_EQ(outcome(kBase + "[packing]\ncache_dir = \"\"\"\xC2\xA7\"\"\"\"\" # \xC2\xA7\n"), "");
    EXPECT_EQ(outcome(kBase + "[packing]\nkind = \"discs\"\ncache_dir = \"\xC2\xA7\"\n"), "");
    EXPECT_EQ(outcome(kBase, {{"packing.cache_dir", "\"/tmp/\xC2\xA7\""}}), "");
}
