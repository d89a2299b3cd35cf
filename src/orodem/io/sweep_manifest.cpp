// The sweep manifest (sweep_manifest.hpp), read and written with toml++.
#include "orodem/io/sweep_manifest.hpp"

#include <filesystem>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

std::string sweep_manifest_path(const std::string& sweep_dir) { return sweep_dir + "/sweep.toml"; }

std::string sweep_member_dir(const std::string& sweep_dir, const SweepManifest& m, const std::string& value) {
    return fmt::format("{}/{}={}", sweep_dir, m.key, value);
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
    std::ostringstream out;
    out << "# orodem sweep: one run per value of `vary`, in <vary>=<value>/ with its resolved\n"
           "# config.toml. An interrupted sweep continues with: orodem resume <this folder>\n"
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
    return m;
}

}  // namespace orodem
