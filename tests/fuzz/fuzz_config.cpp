// libFuzzer target: the config loader on arbitrary bytes (docs/testing.md).
//
// The input is a config file. Each line that starts with "#set " (a TOML
// comment, so the file itself is unchanged) also gives one --set override,
// "#set key=value", applied as `orodem run --set` would apply it.
//
// parse_config must either accept the text or throw ConfigError: any other
// exception escapes and aborts (std::terminate), which libFuzzer reports as a
// crash, as it does any sanitizer finding. An accepted config must also read
// back: its resolved TOML (what a run directory's config.toml holds, read
// again by --resume) loads to the same text; otherwise the target aborts.
// And what `orodem check` derives from it before generating anything
// (sizes, timestep, base checks, plate estimate) must answer or refuse.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "orodem/core/error.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"

namespace {

/// What `orodem check` derives from an accepted config before it generates
/// anything (the size check first): each must answer or refuse with a
/// ConfigError, at once, whatever the numbers (1e308, denormals, -0, huge
/// counts). A hang shows as a libFuzzer timeout.
void derived(const orodem::Config& c) {
    try {
        (void)orodem::estimated_disc_count(c.packing);
        orodem::check_model_size(c);
        (void)orodem::timestep_for(c);
        if (orodem::is_wedge(c)) {
            orodem::check_wedge_base(c);
            (void)orodem::inertial_number(c);
            (void)orodem::plate_estimate(c);
            (void)orodem::wedge_profile_params(c);
        }
    } catch (const orodem::ConfigError&) {
        // a refusal is a correct answer
    }
}

void check(const std::string& text, const std::vector<orodem::Override>& overrides) {
    orodem::Config c;
    try {
        c = orodem::parse_config(text, "fuzz.toml", overrides);
    } catch (const orodem::ConfigError&) {
        return;  // a refusal is a correct answer
    }
    const std::string resolved = orodem::to_toml(c);
    try {
        const orodem::Config again = orodem::parse_config(resolved, "config.toml");
        if (orodem::to_toml(again) != resolved) {
            std::fprintf(stderr, "resolved config reads back differently:\n%s\n---\n%s\n", resolved.c_str(),
                         orodem::to_toml(again).c_str());
            std::abort();
        }
    } catch (const orodem::ConfigError& e) {
        std::fprintf(stderr, "resolved config is refused: %s\n%s\n", e.what(), resolved.c_str());
        std::abort();
    }
    (void)orodem::config_hash(c);
    derived(c);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    check(text, {});

    std::vector<orodem::Override> overrides;
    for (std::size_t at = 0; at < text.size();) {
        std::size_t end = text.find('\n', at);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(at, end - at);
        if (line.rfind("#set ", 0) == 0) {
            try {
                overrides.push_back(orodem::parse_override(line.substr(5)));
            } catch (const orodem::ConfigError&) {
                return 0;
            }
        }
        at = end + 1;
    }
    if (!overrides.empty()) check(text, overrides);
    return 0;
}
