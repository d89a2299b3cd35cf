// The sweep manifest (sweep_manifest.hpp), read and written with toml++.
#include "orodem/io/sweep_manifest.hpp"

#include <filesystem>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/series_reader.hpp"

namespace orodem {

std::string sweep_manifest_path(const std::string& sweep_dir) { return sweep_dir + "/sweep.toml"; }

std::vector<SweepMember> sweep_members(const SweepManifest& m) {
    std::vector<SweepMember> out;
    for (const auto& v : m.values) out.push_back({{m.key, v}});
    for (const SweepAxis& axis : m.more) {
        std::vector<SweepMember> grown;
        for (const SweepMember& member : out)
            for (const auto& v : axis.values) {
                grown.push_back(member);
                grown.back().emplace_back(axis.key, v);
            }
        out = std::move(grown);
    }
    return out;
}

bool varies_seed(const SweepManifest& m) {
    if (is_seed_key(m.key)) return true;
    for (const SweepAxis& axis : m.more)
        if (is_seed_key(axis.key)) return true;
    return false;
}

std::string sweep_axes_text(const SweepManifest& m) {
    std::string text = fmt::format("{} = {} values", m.key, m.values.size());
    for (const SweepAxis& axis : m.more) text += fmt::format(" x {} = {} values", axis.key, axis.values.size());
    return text;
}

std::string sweep_member_dir(const std::string& sweep_dir, const SweepMember& member) {
    std::string name;
    for (const auto& [key, value] : member) name += fmt::format("{}{}={}", name.empty() ? "" : ",", key, value);
    return sweep_dir + "/" + name;
}

std::string to_toml(const SweepManifest& m) {
    toml::array values, sets;
    for (const auto& v : m.values) values.push_back(v);
    for (const auto& s : m.sets) sets.push_back(s);
    toml::table t;
    t.insert("config", m.config);
    t.insert("vary", m.key);
    t.insert("values", values);
    t.insert("set", sets);
    if (!m.more.empty()) {  // absent for one key, so a one-key sweep's manifest keeps its bytes
        toml::array grid;
        for (const SweepAxis& axis : m.more) {
            toml::array axis_values;
            for (const auto& v : axis.values) axis_values.push_back(v);
            grid.push_back(toml::table{{"vary", axis.key}, {"values", axis_values}});
        }
        t.insert("grid", grid);
    }
    std::ostringstream out;
    out << (m.more.empty() ? "# orodem sweep: one run per value of `vary`, in <vary>=<value>/ with its resolved\n"
                           : "# orodem sweep: one run per combination of the values of `vary` and of each [[grid]]'s,\n"
                             "# in <key>=<value>,<key>=<value>.../ with its resolved\n")
        << "# config.toml. An interrupted sweep continues with: orodem resume <this folder>\n"
        << toml::toml_formatter(t) << "\n";
    return out.str();
}

SweepManifest read_sweep_manifest(const std::string& sweep_dir) {
    const std::string path = sweep_manifest_path(sweep_dir);
    if (!std::filesystem::exists(path))
        throw ConfigError(fmt::format("{}: not found; '{}' is not a sweep folder made by orodem sweep", path, sweep_dir));
    toml::table t;
    try {
        t = toml::parse(read_file(path), path);
    } catch (const toml::parse_error& e) {
        throw ConfigError(fmt::format("{}: not a sweep manifest: {}", path, e.description()));
    }
    SweepManifest m;
    auto string_at = [&](const char* key) {
        const auto v = t[key].value<std::string>();
        if (!v) throw ConfigError(fmt::format("{}: '{}' is missing or not a string", path, key));
        return *v;
    };
    auto strings_at = [&](const char* key) {
        const toml::array* a = t[key].as_array();
        if (!a) throw ConfigError(fmt::format("{}: '{}' is missing or not an array of strings", path, key));
        std::vector<std::string> out;
        for (const auto& n : *a) {
            const auto s = n.value<std::string>();
            if (!s) throw ConfigError(fmt::format("{}: '{}' holds a value that is not a string", path, key));
            out.push_back(*s);
        }
        return out;
    };
    m.config = string_at("config");
    m.key = string_at("vary");
    m.values = strings_at("values");
    m.sets = strings_at("set");
    if (m.key.empty() || m.values.empty())
        throw ConfigError(fmt::format("{}: 'vary' is empty or 'values' has none", path));
    if (const toml::node* g = t.get("grid")) {
        const toml::array* grid = g->as_array();
        if (!grid) throw ConfigError(fmt::format("{}: 'grid' is not an array of tables", path));
        for (const auto& n : *grid) {
            const toml::table* axis = n.as_table();
            const auto key = axis ? (*axis)["vary"].value<std::string>() : std::nullopt;
            const toml::array* values = axis ? (*axis)["values"].as_array() : nullptr;
            if (!key || key->empty() || !values || values->empty())
                throw ConfigError(fmt::format("{}: a [[grid]] entry needs 'vary' (a key) and 'values' (strings)", path));
            SweepAxis a{*key, {}};
            for (const auto& v : *values) {
                const auto text = v.value<std::string>();
                if (!text) throw ConfigError(fmt::format("{}: [[grid]] '{}' holds a value that is not a string", path, *key));
                a.values.push_back(*text);
            }
            m.more.push_back(std::move(a));
        }
    }
    return m;
}

}  // namespace orodem
