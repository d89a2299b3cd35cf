// A config as text and compared: the resolved config.toml that every run
// directory holds (to_toml), the text without the keys at their defaults that
// the checkpoint hash covers (to_toml_without_defaults), the comparison that
// names the first difference and leaves out the result-neutral keys, and the
// lenient reading of a run directory's config.toml (experiment and h0) for
// the commands that only draw it.
#include <algorithm>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

namespace {
/// TOML text of one scalar; doubles in the shortest form that reads back exactly.
std::string scalar_text(const toml::node& n) {
    if (auto a = n.as_array()) {  // [calibrate] lists: each element in the same form
        std::string t = "[";
        for (std::size_t k = 0; k < a->size(); ++k) t += (k ? ", " : "") + scalar_text(*a->get(k));
        return t + "]";
    }
    if (auto f = n.as_floating_point()) {
        std::string t = fmt::format("{}", f->get());
        if (t.find_first_of(".eEn") == std::string::npos) t += ".0";
        return t;
    }
    std::ostringstream os;
    os << toml::toml_formatter(n);
    return os.str();
}

void emit_table(std::ostringstream& os, const toml::table& t, const std::string& path) {
    if (!path.empty()) os << '[' << path << "]\n";
    for (auto&& [k, v] : t)
        if (!v.is_table() && !v.is_array_of_tables()) os << k.str() << " = " << scalar_text(v) << '\n';
    for (auto&& [k, v] : t)
        if (v.is_table()) {
            os << '\n';
            emit_table(os, *v.as_table(), path.empty() ? std::string(k.str()) : path + "." + std::string(k.str()));
        }
    // Arrays of tables ([[layers]] of a layered wedge): each element as [[path.key]] with its scalars.
    for (auto&& [k, v] : t)
        if (v.is_array_of_tables())
            for (const toml::node& e : *v.as_array()) {
                os << "\n[[" << (path.empty() ? std::string(k.str()) : path + "." + std::string(k.str())) << "]]\n";
                for (auto&& [ek, ev] : *e.as_table()) os << ek.str() << " = " << scalar_text(ev) << '\n';
            }
}
}  // namespace

std::string to_toml(const Config& c) {
    std::ostringstream os;
    os << kResolvedHeader;
    emit_table(os, c.resolved, "");
    return os.str();
}

namespace {
/// Removes from t every scalar whose text equals the one at the same place in d.
void drop_equal(toml::table& t, const toml::table& d) {
    std::vector<std::string> same;
    for (auto&& [k, v] : t) {
        const toml::node* dv = d.get(k.str());
        if (!dv) continue;
        if (auto* sub = v.as_table()) {
            if (dv->is_table()) drop_equal(*sub, *dv->as_table());
        } else if (!dv->is_table() && scalar_text(v) == scalar_text(*dv)) {
            same.emplace_back(k.str());
        }
    }
    for (const auto& k : same) t.erase(k);
}
}  // namespace

std::string to_toml_without_defaults(const Config& c) {
    Config n;
    n.resolved = c.resolved;
    try {
        // Older run directories' rules (io/older_runs.hpp): the defaults of
        // the orodem that wrote a legacy config, and the keys it did not write.
        const Config d = parse_config(older_config_defaults(c), "defaults");
        drop_keys_older_runs_lacked(n.resolved);
        drop_equal(n.resolved, d.resolved);
    } catch (const ConfigError&) {
        // An experiment without a valid all-defaults config keeps every key.
    }
    return to_toml(n);
}

bool same_toml_value(const std::string& a, const std::string& b) {
    auto canonical = [](const std::string& v) -> std::string {
        try {
            const toml::table t = toml::parse("v = " + v);
            if (const toml::node* n = t.get("v")) {
                if (auto i = n->as_integer()) return fmt::format("{}", static_cast<double>(i->get()));
                if (auto f = n->as_floating_point()) return fmt::format("{}", f->get());
                return scalar_text(*n);
            }
        } catch (const std::exception&) {
        }
        return "text:" + v;
    };
    return canonical(a) == canonical(b);
}

bool is_result_neutral(const std::string& dotted_key) {
    for (const ResultNeutralKey& k : kResultNeutralKeys)
        if (dotted_key == fmt::format("{}.{}", k.section, k.key)) return true;
    return false;
}

std::string first_config_difference(const Config& a, const Config& b) {
    auto lines = [](const Config& c) {
        std::vector<std::string> out;
        std::istringstream in(to_toml(c));
        std::string section, l;
        while (std::getline(in, l)) {
            if (!l.empty() && l[0] == '[') section = l;
            const std::size_t eq = l.find(" =");
            if (eq != std::string::npos && section.size() > 2 &&
                is_result_neutral(section.substr(1, section.size() - 2) + "." + l.substr(0, eq)))
                continue;
            out.push_back(section + " " + l);
        }
        return out;
    };
    const auto la = lines(a), lb = lines(b);
    for (std::size_t k = 0; k < std::max(la.size(), lb.size()); ++k) {
        const std::string x = k < la.size() ? la[k] : "(nothing)", y = k < lb.size() ? lb[k] : "(nothing)";
        if (x != y) return fmt::format("the run has '{}', this config has '{}'", x, y);
    }
    return "";
}

std::string experiment_in(const std::string& config_text) {
    try {
        const toml::table t = toml::parse(std::string_view(config_text));
        return t["run"]["experiment"].value_or(std::string());
    } catch (const toml::parse_error&) {
        return {};
    }
}

ConfigBasics read_config_basics(const std::string& path) {
    toml::table config;
    try {
        config = toml::parse(std::string_view(read_file(path)), std::string_view(path));
    } catch (const toml::parse_error& e) {
        throw IoError(fmt::format("'{}': not readable as TOML: {}", path, e.description()));
    }
    ConfigBasics b;
    b.h0 = config["packing"]["h0"].value_or(std::numeric_limits<double>::quiet_NaN());
    if (!(b.h0 > 0)) throw ConfigError(fmt::format("'{}': no positive packing.h0", path));
    b.experiment = config["run"]["experiment"].value_or(std::string("run"));
    b.s_max = config["wedge"]["s_max"].value_or(b.s_max);
    b.output_ds = config["wedge"]["output_ds"].value_or(b.output_ds);
    b.pro_margin = config["wedge"]["pro_margin"].value_or(b.pro_margin);
    b.retro_length = config["wedge"]["retro_length"].value_or(b.retro_length);
    // The sandbox: the wall stands (length - s_max) h0 from the fixed end wall at s_max.
    if (experiment_of(b.experiment).push_wall)
        b.pro_margin = config["sandbox"]["length"].value_or(SandboxConfig{}.length) - b.s_max;
    if (const toml::array* l = config["layers"].as_array()) b.layers = l->size();
    return b;
}

ConfigBasics config_basics(const Config& c) {
    ConfigBasics b;
    b.experiment = c.run.experiment;
    b.h0 = c.packing.h0;
    b.s_max = c.wedge.s_max;
    b.output_ds = c.wedge.output_ds;
    b.pro_margin = c.wedge.pro_margin;
    b.retro_length = c.wedge.retro_length;
    if (experiment_of(c).push_wall) b.pro_margin = c.sandbox.length - c.wedge.s_max;
    b.layers = c.layers.size();
    return b;
}

}  // namespace orodem
