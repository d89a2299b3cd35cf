// The schema reader of the config loader (io/config.cpp only): a Reader per
// TOML section takes each key with its type and range, records what it
// consumed, and reports any problem as "FILE:LINE:COL: key 'a.b' = VALUE: what
// is allowed" (ConfigError); a value given with --set names the --set. Kept
// apart from io/config.cpp so that the loader reads as the list of sections.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "orodem/core/error.hpp"
#include "orodem/core/named.hpp"
#include "orodem/io/config.hpp"

namespace orodem::config_reader {

inline std::string where(const std::string& file, const toml::source_region& src) {
    // A value given on the command line names its --set, not the file.
    if (src.path && src.path->rfind("--set ", 0) == 0) return *src.path;
    if (src.begin.line == 0) return file;
    return fmt::format("{}:{}:{}", file, src.begin.line, src.begin.column);
}

inline std::string show(const toml::node& n) {
    std::ostringstream os;
    if (auto s = n.as_string()) os << '"' << s->get() << '"';
    else if (auto f = n.as_floating_point()) os << fmt::format("{}", f->get());  // shortest round trip: 0.3, not 0.29999999999999999
    else if (n.is_table()) os << "a table";
    else if (n.is_array()) os << "an array";
    else n.visit([&](auto&& v) { os << v; });
    return os.str();
}

/// The Levenshtein distance of a and b (the edits that turn one into the other).
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diag = up;
        }
    }
    return row[b.size()];
}

/// "; did you mean 'x'?" for the candidate nearest to `key` when it is near (a third of its letters, at least
/// two), else "".
template <class Names>
std::string did_you_mean(std::string_view key, const Names& candidates, std::string_view prefix = "") {
    std::string best;
    std::size_t best_d = std::max<std::size_t>(2, key.size() / 3) + 1;
    for (const auto& c : candidates) {
        const std::string_view name(c);
        const std::size_t d = edit_distance(key, name);
        if (d < best_d) best_d = d, best = std::string(name);
    }
    return best.empty() ? std::string() : fmt::format("; did you mean '{}{}'?", prefix, best);
}

inline const char* type_name(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::string: return "a string";
        case toml::node_type::integer: return "an integer";
        case toml::node_type::floating_point: return "a number";
        case toml::node_type::boolean: return "a boolean";
        case toml::node_type::table: return "a table";
        case toml::node_type::array: return "an array";
        default: return "a date/time";
    }
}

struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false;  // lo itself not allowed
    bool hi_open = false;
    std::string text() const {
        const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
        if (has_lo && has_hi)
            return fmt::format("a number in {}{:g}, {:g}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
        if (has_lo) return fmt::format("a number {} {:g}", lo_open ? ">" : ">=", lo);
        if (has_hi) return fmt::format("a number {} {:g}", hi_open ? "<" : "<=", hi);
        return "a number";
    }
    bool contains(double v) const {
        if (!std::isfinite(v)) return false;
        if (lo_open ? !(v > lo) : !(v >= lo)) return false;
        if (hi_open ? !(v < hi) : !(v <= hi)) return false;
        return true;
    }
};
inline Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
inline Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
inline Range closed(double a, double b) { return {a, b, false, false}; }

class Reader {
public:
    Reader(const toml::table* t, std::string prefix, const std::string& file, toml::table& out,
           const toml::source_region& src)
        : t_(t), prefix_(std::move(prefix)), file_(file), out_(out), src_(src) {}

    double number(const char* key, double def, Range r) {
        const toml::node* n = find(key);
        double v = def;
        if (n) {
            if (auto f = n->as_floating_point()) v = f->get();
            else if (auto i = n->as_integer()) v = static_cast<double>(i->get());
            else fail(*n, key, fmt::format("must be {}, not {}", r.text(), type_name(*n)));
            if (!r.contains(v)) fail(*n, key, fmt::format("must be {}", r.text()));
        }
        out_.insert_or_assign(key, v);
        return v;
    }
    std::int64_t integer(const char* key, std::int64_t def, std::int64_t lo, std::int64_t hi) {
        const toml::node* n = find(key);
        std::int64_t v = def;
        if (n) {
            auto i = n->as_integer();
            if (!i) fail(*n, key, fmt::format("must be an integer in [{}, {}], not {}", lo, hi, type_name(*n)));
            v = i->get();
            if (v < lo || v > hi) fail(*n, key, fmt::format("must be an integer in [{}, {}]", lo, hi));
        }
        out_.insert_or_assign(key, v);
        return v;
    }
    bool boolean(const char* key, bool def) {
        const toml::node* n = find(key);
        bool v = def;
        if (n) {
            auto b = n->as_boolean();
            if (!b) fail(*n, key, fmt::format("must be true or false, not {}", type_name(*n)));
            v = b->get();
        }
        out_.insert_or_assign(key, v);
        return v;
    }
    std::string string(const char* key, const std::string& def) {
        const toml::node* n = find(key);
        std::string v = def;
        if (n) {
            auto s = n->as_string();
            if (!s) fail(*n, key, fmt::format("must be a string, not {}", type_name(*n)));
            v = s->get();
        }
        out_.insert_or_assign(key, v);
        return v;
    }
    /// required = true: a missing key is refused (there is no sensible default).
    std::string choice(const char* key, const std::string& def, const std::vector<const char*>& allowed,
                       bool required = false) {
        std::string list;
        for (const char* a : allowed) list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", a);
        const toml::node* n = find(key);
        std::string v = def;
        if (!n && required)
            throw ConfigError(fmt::format("{}: missing required key '{}{}'; allowed values: {}", file_, prefix_,
                                          key, list));
        if (n) {
            auto s = n->as_string();
            if (!s) fail(*n, key, fmt::format("must be one of {}, not {}", list, type_name(*n)));
            v = s->get();
            bool ok = false;
            for (const char* a : allowed) ok = ok || v == a;
            if (!ok) fail(*n, key, fmt::format("must be one of {}{}", list, did_you_mean(v, allowed)));
        }
        out_.insert_or_assign(key, v);
        return v;
    }
    /// One of an enum's names (Named table), returned as the enum; the name is what the resolved config holds.
    template <class E, std::size_t N>
    E choice(const char* key, E def, const Named<E> (&table)[N], bool required = false) {
        std::vector<const char*> names;
        for (const Named<E>& n : table) names.push_back(n.name);
        const std::string v = choice(key, name_in(table, def), names, required);
        for (const Named<E>& n : table)
            if (v == n.name) return n.value;
        return def;  // not reached: choice() refused any other name
    }
    /// A list of 1..N distinct names of an enum's table.
    template <class E, std::size_t N>
    std::vector<E> choices(const char* key, const std::vector<E>& def, const Named<E> (&table)[N]) {
        std::vector<std::string> def_names;
        for (E d : def) def_names.push_back(name_in(table, d));
        std::vector<const char*> names;
        for (const Named<E>& n : table) names.push_back(n.name);
        std::vector<E> out;
        for (const std::string& v : choices(key, def_names, names))
            for (const Named<E>& n : table)
                if (v == n.name) out.push_back(n.value);
        return out;
    }
    /// A list of 1..max_n distinct numbers, each in r (integers are taken as numbers).
    std::vector<double> numbers(const char* key, const std::vector<double>& def, Range r, std::size_t max_n) {
        const toml::node* n = find(key);
        std::vector<double> v = def;
        if (n) {
            const std::string what = fmt::format("must be a list of 1 to {} distinct values, each {}", max_n, r.text());
            auto a = n->as_array();
            if (!a) fail(*n, key, fmt::format("{}, not {}", what, type_name(*n)));
            if (a->empty() || a->size() > max_n) fail(*n, key, what);
            v.clear();
            for (const toml::node& e : *a) {
                double x = 0.0;
                if (auto f = e.as_floating_point()) x = f->get();
                else if (auto i = e.as_integer()) x = static_cast<double>(i->get());
                else fail(*n, key, fmt::format("{}, not a list with {}", what, type_name(e)));
                if (!r.contains(x)) fail(*n, key, what);
                for (double y : v)
                    if (y == x) fail(*n, key, fmt::format("{} ({:g} is listed twice)", what, x));
                v.push_back(x);
            }
        }
        toml::array out;
        for (double x : v) out.push_back(x);
        out_.insert_or_assign(key, std::move(out));
        return v;
    }
    /// A list of 1..N distinct strings, each one of `allowed`.
    std::vector<std::string> choices(const char* key, const std::vector<std::string>& def,
                                     const std::vector<const char*>& allowed) {
        std::string list;
        for (const char* a : allowed) list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", a);
        const std::string what = fmt::format("must be a list of distinct values, each one of {}", list);
        const toml::node* n = find(key);
        std::vector<std::string> v = def;
        if (n) {
            auto a = n->as_array();
            if (!a) fail(*n, key, fmt::format("{}, not {}", what, type_name(*n)));
            if (a->empty()) fail(*n, key, what);
            v.clear();
            for (const toml::node& e : *a) {
                auto str = e.as_string();
                if (!str) fail(*n, key, fmt::format("{}, not a list with {}", what, type_name(e)));
                bool ok = false;
                for (const char* al : allowed) ok = ok || str->get() == al;
                if (!ok) fail(*n, key, what);
                for (const auto& y : v)
                    if (y == str->get()) fail(*n, key, fmt::format("{} (\"{}\" is listed twice)", what, y));
                v.push_back(str->get());
            }
        }
        toml::array out;
        for (const auto& x : v) out.push_back(x);
        out_.insert_or_assign(key, std::move(out));
        return v;
    }
    /// A value error found after reading (e.g. r_min > r_max).
    [[noreturn]] void refuse(const char* key, const std::string& why) const {
        const toml::node* n = t_ ? t_->get(key) : nullptr;
        if (n) fail(*n, key, why);
        throw ConfigError(fmt::format("{}: key '{}{}': {}", where(file_, src_), prefix_, key, why));
    }
    void finish() const {
        if (!t_) return;
        for (auto&& [k, v] : *t_) {
            if (used_.count(std::string(k.str()))) continue;
            std::string allowed;
            std::vector<std::string> names;
            for (auto&& [ok, ov] : out_) {
                allowed += fmt::format("{}{}", allowed.empty() ? "" : ", ", ok.str());
                names.emplace_back(ok.str());
            }
            throw ConfigError(fmt::format("{}: unknown key '{}{}' = {}{}; allowed keys in [{}]: {}",
                                          where(file_, k.source().begin.line ? k.source() : v.source()), prefix_, k.str(), show(v),
                                          did_you_mean(k.str(), names, prefix_), prefix_.substr(0, prefix_.size() - 1), allowed));
        }
    }

private:
    const toml::node* find(const char* key) {
        used_.insert(key);
        return t_ ? t_->get(key) : nullptr;
    }
    [[noreturn]] void fail(const toml::node& n, const char* key, const std::string& why) const {
        throw ConfigError(fmt::format("{}: key '{}{}' = {}: {}", where(file_, n.source()), prefix_, key,
                                      show(n), why));
    }

    const toml::table* t_;
    std::string prefix_;
    const std::string& file_;
    toml::table& out_;
    toml::source_region src_;
    std::set<std::string> used_;
};

/// [materials.NAME], [[layers]], [[retro_layers]], [[friction_pairs]] of a
/// layered wedge and calibrate.material (io/config_layers.cpp); after
/// [material] and [calibrate]. Absent: nothing is read or resolved.
void read_layers(Config& c, const toml::table& root, const std::string& file);
/// [flexure] of exp1, exp2, exp3 (io/config_flexure.cpp); after [wedge],
/// [packing] and [numerics]. Absent: nothing is read or resolved.
void read_flexure(Config& c, const toml::table& root, const std::string& file);

}  // namespace orodem::config_reader
