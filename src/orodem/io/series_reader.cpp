#include "orodem/io/series_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <string_view>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

namespace {

std::vector<std::string_view> split(std::string_view line, char sep) {
    std::vector<std::string_view> out;
    for (std::size_t pos = 0;;) {
        const auto next = line.find(sep, pos);
        out.push_back(line.substr(pos, next == std::string_view::npos ? std::string_view::npos : next - pos));
        if (next == std::string_view::npos) break;
        pos = next + 1;
    }
    return out;
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

/// One field as a number; false if it is not one.
bool parse_number(std::string_view field, double& v) {
    field = trim(field);
    if (field.empty()) {
        v = std::numeric_limits<double>::quiet_NaN();
        return true;
    }
    const std::string s(field);
    char* end = nullptr;
    v = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size();
}

/// A TOML value as label text: numbers in shortest form, strings unquoted.
std::string value_text(const toml::node& n) {
    if (auto v = n.as_floating_point()) return fmt::format("{}", v->get());
    if (auto v = n.as_integer()) return fmt::format("{}", v->get());
    if (auto v = n.as_boolean()) return v->get() ? "true" : "false";
    if (auto v = n.as_string()) return v->get();
    if (auto a = n.as_array()) {
        std::string s = "[";
        for (std::size_t k = 0; k < a->size(); ++k) s += (k ? ", " : "") + value_text(*a->get(k));
        return s + "]";
    }
    if (auto d = n.as_date()) return fmt::format("{}-{:02}-{:02}", d->get().year, d->get().month, d->get().day);
    return "?";
}

/// Every leaf of t as "a.b.c" -> value text.
void flatten(const toml::table& t, const std::string& prefix, std::map<std::string, std::string>& out) {
    for (const auto& [key, node] : t) {
        const std::string name = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        if (const toml::table* sub = node.as_table()) flatten(*sub, name, out);
        else out[name] = value_text(node);
    }
}

}  // namespace

const std::vector<double>* Series::column(const std::string& name) const {
    for (std::size_t c = 0; c < names.size(); ++c)
        if (names[c] == name) return &values[c];
    return nullptr;
}

Series read_series_csv(const std::string& path) {
    const std::string text = read_file(path);
    Series s;
    s.path = path;
    std::vector<std::string_view> lines = split(text, '\n');
    // A complete file ends with '\n' (the last piece is empty); otherwise the
    // last line is a partial write and is dropped.
    lines.pop_back();
    if (lines.empty() || trim(lines.front()).empty())
        throw IoError(fmt::format("'{}': empty file, expected a header row", path));
    for (std::string_view name : split(lines.front(), ',')) s.names.emplace_back(trim(name));
    s.values.resize(s.names.size());
    for (std::size_t l = 1; l < lines.size(); ++l) {
        if (trim(lines[l]).empty()) continue;
        const auto fields = split(lines[l], ',');
        if (fields.size() != s.names.size())
            throw IoError(fmt::format("'{}': line {} has {} fields, the header has {}", path, l + 1, fields.size(),
                                      s.names.size()));
        for (std::size_t c = 0; c < fields.size(); ++c) {
            double v = 0.0;
            if (!parse_number(fields[c], v))
                throw IoError(fmt::format("'{}': line {}, column '{}': '{}' is not a number", path, l + 1,
                                          s.names[c], trim(fields[c])));
            s.values[c].push_back(v);
        }
    }
    return s;
}

namespace {

/// Keys that change only the random packing (the seed groups of seed_groups).
const std::set<std::string> kSeedKeys = {"run.seed", "packing.seed"};

/// Each config text flattened to "a.b.c" -> value text; throws IoError
/// naming the source of a text that is not TOML.
std::vector<std::map<std::string, std::string>> flat_configs(const std::vector<std::string>& config_texts,
                                                             const std::vector<std::string>& names,
                                                             const std::vector<std::string>& sources) {
    std::vector<std::map<std::string, std::string>> flat(config_texts.size());
    for (std::size_t i = 0; i < config_texts.size(); ++i) {
        const std::string source = i < sources.size() ? sources[i] : (i < names.size() ? names[i] : "config");
        try {
            flatten(toml::parse(std::string_view(config_texts[i]), std::string_view(source)), "", flat[i]);
        } catch (const toml::parse_error& e) {
            throw IoError(fmt::format("'{}': not readable as TOML: {} (line {})", source, e.description(),
                                      e.source().begin.line));
        }
    }
    return flat;
}

}  // namespace

std::vector<std::string> legend_labels(const std::vector<std::string>& config_texts,
                                       const std::vector<std::string>& names,
                                       const std::vector<std::string>& sources, bool ignore_seeds) {
    const std::size_t n = config_texts.size();
    const auto flat = flat_configs(config_texts, names, sources);
    std::set<std::string> keys;
    for (const auto& f : flat)
        for (const auto& [k, v] : f) keys.insert(k);
    std::vector<std::string> differing;
    for (const std::string& k : keys) {
        if (is_result_neutral(k) || (ignore_seeds && kSeedKeys.count(k))) continue;
        for (std::size_t i = 1; i < n; ++i) {
            const auto a = flat[0].find(k), b = flat[i].find(k);
            const bool same = (a == flat[0].end()) == (b == flat[i].end()) &&
                              (a == flat[0].end() || a->second == b->second);
            if (!same) {
                differing.push_back(k);
                break;
            }
        }
    }
    std::vector<std::string> labels(n);
    for (std::size_t i = 0; i < n; ++i) {
        std::string& label = labels[i];
        const std::size_t shown = std::min<std::size_t>(differing.size(), 3);
        for (std::size_t d = 0; d < shown; ++d) {
            const auto it = flat[i].find(differing[d]);
            label += fmt::format("{}{} = {}", d ? ", " : "", differing[d],
                                 it == flat[i].end() ? "(absent)" : it->second);
        }
        if (differing.size() > shown) label += fmt::format(", +{} more", differing.size() - shown);
    }
    const bool distinct = std::set<std::string>(labels.begin(), labels.end()).size() == n;
    if (differing.empty() || !distinct)
        for (std::size_t i = 0; i < n; ++i) labels[i] = i < names.size() ? names[i] : fmt::format("run {}", i + 1);
    return labels;
}

std::size_t csv_leading_columns(const std::string& file_header, const std::string& header, const std::string& path) {
    if (file_header.empty() ||
        (file_header != header && header.compare(0, file_header.size() + 1, file_header + ",") != 0))
        throw ConfigError(fmt::format("'{}' has the columns '{}', which are not the first ones of this orodem's "
                                      "'{}'; continue the run with the orodem that started it",
                                      path, file_header, header));
    return 1 + static_cast<std::size_t>(std::count(file_header.begin(), file_header.end(), ','));
}

std::string csv_first_fields(const std::string& line, std::size_t n) {
    if (n == 0) return {};
    std::size_t at = 0;
    for (std::size_t k = 0; k < n; ++k) {
        at = line.find(',', at);
        if (at == std::string::npos) return line;
        ++at;
    }
    return line.substr(0, at - 1);
}

bool is_seed_key(const std::string& key) { return kSeedKeys.count(key) > 0; }

std::vector<std::size_t> seed_groups(const std::vector<std::string>& config_texts,
                                     const std::vector<std::string>& names,
                                     const std::vector<std::string>& sources) {
    auto flat = flat_configs(config_texts, names, sources);
    for (auto& f : flat) {
        for (const ResultNeutralKey& k : kResultNeutralKeys) f.erase(fmt::format("{}.{}", k.section, k.key));
        for (const std::string& k : kSeedKeys) f.erase(k);
    }
    std::vector<std::size_t> group(flat.size());
    std::vector<std::size_t> first;  // the first run of each group
    for (std::size_t i = 0; i < flat.size(); ++i) {
        const auto same = std::find_if(first.begin(), first.end(), [&](std::size_t j) { return flat[j] == flat[i]; });
        group[i] = static_cast<std::size_t>(same - first.begin());
        if (same == first.end()) first.push_back(i);
    }
    return group;
}

SeriesEnsemble seed_ensemble(const std::vector<const Series*>& members) {
    if (members.empty()) throw ConfigError("seed_ensemble: no runs");
    const std::vector<std::string>& names = members.front()->names;
    auto key = [](double S) { return std::llround(S * 1e6); };  // S matched to 1e-6
    std::map<long long, double> grid;                             // key -> S of its first occurrence
    std::vector<std::vector<const std::vector<double>*>> cols(members.size());
    std::vector<std::map<long long, std::size_t>> row_of(members.size());
    for (std::size_t m = 0; m < members.size(); ++m) {
        const Series& s = *members[m];
        const std::vector<double>* S = s.column("S");
        if (!S) throw ConfigError(fmt::format("'{}' has no column 'S': not the series of a wedge run", s.path));
        for (const std::string& name : names) {
            cols[m].push_back(s.column(name));
            if (!cols[m].back())
                throw ConfigError(fmt::format("'{}' has no column '{}', which '{}' has", s.path, name,
                                              members.front()->path));
        }
        for (std::size_t r = 0; r < S->size(); ++r)
            if (std::isfinite((*S)[r])) {
                grid.emplace(key((*S)[r]), (*S)[r]);
                row_of[m].emplace(key((*S)[r]), r);
            }
    }
    SeriesEnsemble e;
    for (Series* out : {&e.mean, &e.lo, &e.hi}) {
        out->path = members.front()->path;
        out->names = names;
        out->values.assign(names.size(), {});
    }
    e.count.assign(names.size(), {});
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [k, S] : grid)
        for (std::size_t c = 0; c < names.size(); ++c) {
            if (names[c] == "S") {  // the matched S itself; count: the members that have this row
                for (Series* out : {&e.mean, &e.lo, &e.hi}) out->values[c].push_back(S);
                e.count[c].push_back(static_cast<int>(std::count_if(
                    row_of.begin(), row_of.end(), [&, k = k](const auto& rows) { return rows.count(k) > 0; })));
                continue;
            }
            double sum = 0.0, lo = INFINITY, hi = -INFINITY;
            int n = 0;
            for (std::size_t m = 0; m < members.size(); ++m) {  // members in the given order: a fixed sum order
                const auto at = row_of[m].find(k);
                if (at == row_of[m].end()) continue;
                const double v = (*cols[m][c])[at->second];
                if (!std::isfinite(v)) continue;
                sum += v, lo = std::min(lo, v), hi = std::max(hi, v), ++n;
            }
            e.mean.values[c].push_back(n ? sum / n : nan);
            e.lo.values[c].push_back(n ? lo : nan);
            e.hi.values[c].push_back(n ? hi : nan);
            e.count[c].push_back(n);
        }
    return e;
}

}  // namespace orodem
