#include "orodem/io/older_runs.hpp"

#include <fmt/format.h>

namespace orodem {

BaseLaw older_base_law_default(bool resolved_file, bool has_key, bool& legacy) {
    const bool old_run = resolved_file && !has_key;
    if (old_run) legacy = true;
    return old_run ? BaseLaw::traction : BaseLaw::coulomb;
}

std::string older_config_defaults(const Config& c) {
    std::string defaults = fmt::format("[run]\nexperiment = \"{}\"\n", c.run.experiment);
    if (c.legacy_base_law)
        defaults += fmt::format("[{}]\nbase_law = \"traction\"\n", is_calibration(c) ? "calibrate" : "wedge");
    return defaults;
}

void drop_keys_older_runs_lacked(toml::table& resolved) {
    toml::table* w = resolved["wedge"].as_table();
    if (!w) return;
    const toml::node* pro = w->get("sleep_buffer_pro");
    const toml::node* both = w->get("sleep_buffer");
    // Equal as written (the resolved config holds both as numbers of one type; -0 is not 0 here).
    auto text = [](const toml::node& n) { return n.is_number() ? fmt::format("{}", *n.value<double>()) : std::string("?"); };
    if (pro && both && pro->type() == both->type() && text(*pro) == text(*both)) w->erase("sleep_buffer_pro");
}

}  // namespace orodem
