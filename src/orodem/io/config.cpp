// Config loader: a small schema reader over toml++. Each section is read by a
// Reader that records which keys it consumed; any key left over is an unknown
// key and is refused with the list of allowed keys. Values are checked for
// type and range here, before anything runs.
#include "orodem/io/config.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config_reader.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/older_runs.hpp"

namespace orodem {


namespace {

using namespace config_reader;

/// toml++ 3.3.0 (Debian 12) has undefined behaviour (it reaches TOML_UNREACHABLE
/// in is_non_ascii_horizontal_whitespace; marzer/tomlplusplus#190, #295) when
/// it asks whether some non-ASCII characters (U+00A1-U+0499 among others) are
/// whitespace. Found by tests/fuzz/fuzz_config. It asks that of characters
/// outside strings and comments, in the look-ahead over a bare value (which
/// runs on through quotes), in keys, and after a backslash in a multi-line
/// basic string. So non-ASCII text is let through to toml++ only in comments
/// and in a string value written `key = "..."` (the line's first '=', then
/// spaces or tabs, not inside an array or inline table), and not next to a
/// backslash of a multi-line basic string. Valid TOML with non-ASCII
/// characters elsewhere (quoted keys, strings in arrays) is refused too; the
/// config schema has no use for it. Returns the offset of the first such
/// character, or npos.
std::size_t non_ascii_toml_cannot_take(std::string_view s) {
    auto at = [&](std::size_t k) { return k < s.size() ? s[k] : '\0'; };
    auto high = [](char c) { return static_cast<unsigned char>(c) >= 0x80; };
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    constexpr std::size_t none = std::string_view::npos;
    std::size_t k = s.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte order mark, which toml++ skips
    int equals = 0;         // '=' outside strings on this logical line
    int depth = 0;          // brackets and braces opened after the line's first '='
    bool after_eq = false;  // only spaces and tabs since the last '='
    while (k < s.size()) {
        const char c = s[k];
        if (high(c)) return k;
        if (c == '#') {  // a comment, to the end of the line
            while (k < s.size() && s[k] != '\n') ++k;
            continue;
        }
        if (c == '"' || c == '\'') {
            const bool value = equals == 1 && depth == 0 && after_eq;  // non-ASCII allowed inside
            after_eq = false;
            if (at(k + 1) == c && at(k + 2) == c) {  // multi-line, closed by three to five quotes
                for (k += 3; k < s.size();) {
                    if (s[k] == c && at(k + 1) == c && at(k + 2) == c) {
                        while (at(k) == c) ++k;
                        break;
                    }
                    if (high(s[k]) && !value) return k;
                    if (c == '"' && s[k] == '\\') {  // an escape, or a line-ending backslash
                        ++k;
                        if (high(at(k))) return k;
                        if (!space(at(k))) {
                            ++k;
                            continue;
                        }
                        while (space(at(k))) ++k;
                        if (high(at(k))) return k;
                        continue;
                    }
                    ++k;
                }
            } else {  // one line, to the closing quote (or the end of the line: toml++ refuses it)
                for (++k; k < s.size() && s[k] != c && s[k] != '\n'; ++k) {
                    if (c == '"' && s[k] == '\\') ++k;
                    if (k < s.size() && high(s[k]) && !value) return k;
                }
                if (at(k) == c) ++k;
            }
            continue;
        }
        if (c == '\n' && depth <= 0) {  // a new key = value line
            equals = 0;
            depth = 0;
        }
        if (c == '=') ++equals;
        if (equals > 0 && (c == '[' || c == '{')) ++depth;
        if (equals > 0 && (c == ']' || c == '}')) --depth;
        after_eq = c == '=' || (after_eq && (c == ' ' || c == '\t'));
        ++k;
    }
    return none;
}

/// Refuses (ConfigError) text with a character non_ascii_toml_cannot_take finds, naming file:line:col.
void check_non_ascii(std::string_view text, const std::string& file) {
    const std::size_t bad = non_ascii_toml_cannot_take(text);
    if (bad == std::string_view::npos) return;
    std::size_t line = 1, col = 1;
    for (std::size_t k = 0; k < bad; ++k) {
        if (text[k] == '\n') line += 1, col = 1;
        else if ((static_cast<unsigned char>(text[k]) & 0xC0) != 0x80) col += 1;  // count characters, not bytes
    }
    throw ConfigError(fmt::format("{}:{}:{}: a non-ASCII character where orodem does not read one: only "
                                  "comments and string values (key = \"...\") may have them", file, line, col));
}

/// Applies one override "a.b.c=value" to the parsed table.
void apply_override(toml::table& root, const Override& o, const std::string& file) {
    toml::table parsed;
    try {
        const std::string doc = "v = " + o.second;
        if (non_ascii_toml_cannot_take(doc) != std::string_view::npos)
            throw ConfigError(fmt::format("--set {}={}: a non-ASCII character outside a string value", o.first,
                                          o.second));
        parsed = toml::parse(std::string_view(doc), fmt::format("--set {}={}", o.first, o.second));
    } catch (const toml::parse_error& e) {
        throw ConfigError(fmt::format("--set {}={}: value is not valid TOML ({}); strings need quotes, e.g. --set packing.kind='\"discs\"'",
                                      o.first, o.second, e.description()));
    }
    toml::table* t = &root;
    std::string_view path = o.first;
    for (;;) {
        const auto dot = path.find('.');
        if (dot == std::string_view::npos) break;
        const std::string part(path.substr(0, dot));
        auto* sub = t->get(part);
        if (!sub) {
            t->insert(part, toml::table{});
            sub = t->get(part);
        }
        if (!sub->is_table())
            throw ConfigError(fmt::format("--set {}: '{}' is not a table in {}", o.first, part, file));
        t = sub->as_table();
        path.remove_prefix(dot + 1);
    }
    t->insert_or_assign(std::string(path), std::move(*parsed.get("v")));  // a move keeps the value's source (--set)
}

/// The names of kExperiments, in its order.
const std::vector<const char*>& experiment_names() {
    static const std::vector<const char*> names = [] {
        std::vector<const char*> v;
        for (const Experiment& e : kExperiments) v.push_back(e.name);
        return v;
    }();
    return names;
}

/// calibrate.kinds, in the order its refusal lists them.
constexpr Named<PackingKind> kCalibrationKinds[] = {
    {PackingKind::discs, "discs"}, {PackingKind::clusters, "clusters"}, {PackingKind::hexagonal, "hexagonal"}};

/// wedge.base_law or calibrate.base_law. Its default is "coulomb", except in
/// a run directory's resolved config.toml (resolved_file) that lacks the key:
/// an older orodem wrote it, whose base was the eq. 5 traction (legacy set).
BaseLaw read_base_law(Reader& r, const toml::table* in, bool resolved_file, bool& legacy) {
    return r.choice("base_law", older_base_law_default(resolved_file, in && in->contains("base_law"), legacy), kBaseLaws);
}

/// The eq. 5 traction's own keys are refused under the Coulomb base.
void refuse_traction_keys(Reader& r, const toml::table* in, const char* table,
                          std::initializer_list<const char*> keys) {
    for (const char* key : keys)
        if (in && in->contains(key))
            r.refuse(key, fmt::format("applies to the eq. 5 traction only; remove it or set {}.base_law = "
                                      "\"traction\"", table));
}

/// [calibrate] of a calibration experiment (after [material] and [packing],
/// whose mu and kind are the defaults of the swept lists). `section` opens a
/// table in the resolved config.
template <class Section>
void read_calibrate(Config& c, Section&& section, const std::string& file, bool resolved_file) {
    auto [in, o] = section("calibrate");
    Reader r(in, "calibrate.", file, *o, toml::source_region{});
    CalibrateConfig& k = c.calibrate;
    const std::string& e = c.run.experiment;
    constexpr std::size_t kMaxValues = 20;
    k.kinds = r.choices("kinds", {c.packing.kind}, kCalibrationKinds);
    if (e == "biaxial") {
        k.material = r.string("material", k.material);
        k.compaction_mu = r.number("compaction_mu", k.compaction_mu, closed(-1.0, 10.0));
        if (k.compaction_mu < 0.0 && k.compaction_mu != -1.0)
            r.refuse("compaction_mu", "must be -1 (the tested μ) or a friction coefficient >= 0");
    }
    if (e == "repose" || (e == "biaxial" && k.material.empty()))
        k.mu_values = r.numbers("mu_values", {c.material.mu}, closed(0.0, 10.0), kMaxValues);
    // A specimen size [m] of at least `times` largest radii, so that it holds a few discs.
    auto size = [&](const char* key, double def, double times) {
        const double v = r.number(key, def, positive()), least = times * c.packing.r_max;
        if (v < least) r.refuse(key, fmt::format("must be at least {:g} r_max = {:g} m", times, least));
        return v;
    };
    if (e == "biaxial") {
        k.width = size("width", k.width, 8.0);
        k.height = size("height", k.height, 8.0);
        k.confining_stress = r.number("confining_stress", k.confining_stress, positive());
        k.max_inertial_number = r.number("max_inertial_number", k.max_inertial_number, {0.0, 0.1, true, false});
        // I = ε̇ d sqrt(ρ/σ_3) with the mean disc diameter d = r_min + r_max.
        const double t_i = (c.packing.r_min + c.packing.r_max) * std::sqrt(c.material.density / k.confining_stress);
        k.strain_rate = r.number("strain_rate", k.strain_rate, non_negative());
        if (k.strain_rate == 0.0) {
            k.strain_rate = k.max_inertial_number / t_i;
            o->insert_or_assign("strain_rate", k.strain_rate);
        } else if (k.strain_rate * t_i > k.max_inertial_number) {
            r.refuse("strain_rate",
                     fmt::format("gives the inertial number I = ε̇ d sqrt(ρ/σ_3) = {:.3g}, above "
                                 "calibrate.max_inertial_number = {:g} (not quasi-static); use at most {:.4g} 1/s",
                                 k.strain_rate * t_i, k.max_inertial_number, k.max_inertial_number / t_i));
        }
        k.max_strain = r.number("max_strain", k.max_strain, {0.0, 0.5, true, false});
        k.critical_from = r.number("critical_from", k.critical_from, {0.0, k.max_strain, false, true});
        k.output_strain = r.number("output_strain", k.output_strain, {0.0, 0.1, true, false});
        if (k.output_strain > 0.25 * (k.max_strain - k.critical_from))
            r.refuse("output_strain",
                     fmt::format("must be at most a quarter of the critical-state window max_strain - critical_from "
                                 "= {:g} (at least four rows to average)",
                                 k.max_strain - k.critical_from));
        k.servo_gain = r.number("servo_gain", k.servo_gain, {0.0, 1.0, true, false});
        k.servo_tolerance = r.number("servo_tolerance", k.servo_tolerance, {0.0, 0.5, true, false});
    } else if (e == "basal-friction") {
        k.mu_bp_values = r.numbers("mu_bp_values", {0.3}, closed(0.0, 10.0), kMaxValues);
        k.block_length = size("block_length", k.block_length, 8.0);
        k.block_height = size("block_height", k.block_height, 4.0);
        k.belt_speed = r.number("belt_speed", k.belt_speed, positive());
        k.base_law = read_base_law(r, in, resolved_file, c.legacy_base_law);
        if (k.base_law == BaseLaw::traction)
            k.traction_gain = r.number("traction_gain", k.traction_gain, {0.0, 1.5, true, false});
        else
            refuse_traction_keys(r, in, "calibrate", {"traction_gain"});
        // The block reaches steady sliding after a belt displacement and a
        // time (docs/validation.md): the run is a belt travel by default, and
        // at least min_duration long.
        k.belt_travel = r.number("belt_travel", k.belt_travel, positive());
        k.min_duration = r.number("min_duration", k.min_duration, non_negative());
        k.duration = r.number("duration", k.duration, non_negative());
        if (k.duration == 0.0) k.duration = std::max(k.belt_travel / k.belt_speed, k.min_duration);
        k.measure_from = r.number("measure_from", k.measure_from, {0.0, 1.0, false, true});
    } else {  // repose
        k.column_width = size("column_width", k.column_width, 4.0);
        k.column_height = size("column_height", k.column_height, 8.0);
        k.lift_speed = r.number("lift_speed", k.lift_speed, positive());
        k.fit_from = r.number("fit_from", k.fit_from, {0.0, 1.0, false, true});
        k.fit_to = r.number("fit_to", k.fit_to, {0.0, 1.0, true, false});
        if (k.fit_to <= k.fit_from)
            r.refuse("fit_to", fmt::format("must be above calibrate.fit_from = {:g}", k.fit_from));
    }
    r.finish();
}

/// The sedimentation keys of [surface] (docs/physics.md "Sedimentation in
/// the running wedge"): read only with surface.sediment other than "none", so
/// a config without them resolves as before.
void read_sedimentation(Config& c, Reader& r, toml::table& o) {
    SurfaceConfig& s = c.surface;
    s.sediment = r.choice("sediment", s.sediment, kSedimentSides);
    if (!s.sedimenting()) {
        o.erase("sediment");
        return;
    }
    s.base_level = r.number("base_level", s.base_level, closed(-1.0, 100.0));
    s.sediment_rate = r.number("sediment_rate", s.sediment_rate, non_negative());
    if (c.layered()) {
        s.sediment_material = r.string("sediment_material", c.layers.back().material);
        if (std::none_of(c.materials.begin(), c.materials.end(),
                         [&](const NamedMaterial& m) { return m.name == s.sediment_material; }))
            r.refuse("sediment_material", fmt::format("no [materials.{}] in the config", s.sediment_material));
    } else if (r.string("sediment_material", "") != "") {
        r.refuse("sediment_material", "names a [materials.NAME] table, and this config has none (one material: the "
                                      "sediment is [material]); remove the key");
    } else {
        o.erase("sediment_material");
    }
    s.sediment_reserve = r.number("sediment_reserve", s.sediment_reserve, non_negative());
    if (s.sediment_reserve == 0.0) {
        // The deficit below base_level over the layer's length, and as much
        // again for what the plate carries into the wedge by s_max, with half
        // again for the roughness of a loose fill [h0²].
        const double length = c.packing.length / c.packing.h0;
        s.sediment_reserve = 1.5 * std::max(0.0, s.base_level) * (length + c.wedge.s_max);
        o.insert_or_assign("sediment_reserve", s.sediment_reserve);
    }
}

/// [surface] of a wedge experiment (docs/physics.md "Erosion in the running
/// wedge"). Absent: nothing is read or resolved, so every other config
/// resolves as before. Each law reads its own parameter only.
void read_surface(Config& c, const toml::table& root, const std::string& file) {
    const toml::node* n = root.get("surface");
    if (!n) return;
    if (!n->is_table())
        throw ConfigError(fmt::format("{}: key 'surface' = {}: must be a table [surface]", where(file, n->source()), show(*n)));
    if (!is_wedge(c))
        throw ConfigError(fmt::format("{}: table [surface] is only read by the wedge experiments, not run.experiment = "
                                      "\"{}\"; remove it or set run.experiment to critical-wedge, exp1, exp2 or exp3",
                                      where(file, n->source()), c.run.experiment));
    if (experiment_of(c).push_wall)
        throw ConfigError(fmt::format("{}: table [surface] is not available for run.experiment = \"sandbox\" yet "
                                      "(erosion is tied to the conveyor's incoming plate); remove it",
                                      where(file, n->source())));
    c.resolved.insert_or_assign("surface", toml::table{});
    toml::table& o = *c.resolved.get("surface")->as_table();
    Reader r(n->as_table(), "surface.", file, o, toml::source_region{});
    SurfaceConfig& s = c.surface;
    s.present = true;
    s.law = r.choice("law", s.law, kSurfaceKinds, true);
    switch (s.law) {
        case SurfaceKind::none: break;
        case SurfaceKind::elevation: s.k = r.number("k", s.k, non_negative()); break;
        case SurfaceKind::slope: s.slope_k = r.number("slope_k", s.slope_k, non_negative()); break;
        case SurfaceKind::uniform: s.rate = r.number("rate", s.rate, non_negative()); break;
        case SurfaceKind::cap: s.cap_height = r.number("cap_height", s.cap_height, {-1.0, 1000.0, false, false}); break;
        case SurfaceKind::diffusion:
            s.kappa = r.number("kappa", s.kappa, non_negative());
            s.ends = r.choice("ends", s.ends, {"closed", "fixed"});
            if (s.ends == "fixed") {
                s.h_left = r.number("h_left", s.h_left, closed(-1.0, 1000.0));
                s.h_right = r.number("h_right", s.h_right, closed(-1.0, 1000.0));
            }
            break;
    }
    s.interval_steps = r.integer("interval_steps", s.interval_steps, 1, 100000000);
    s.column_width = r.number("column_width", s.column_width, non_negative());
    if (s.column_width == 0.0) {
        s.column_width = c.wedge.column_width / c.packing.h0;
        o.insert_or_assign("column_width", s.column_width);
    }
    read_sedimentation(c, r, o);
    r.finish();
}

Config read(const toml::table& root, const std::string& file, bool resolved_file) {
    Config c;
    toml::table& out = c.resolved;
    const toml::source_region none{};

    auto section = [&](const char* name) -> std::pair<const toml::table*, toml::table*> {
        const toml::node* n = root.get(name);
        if (n && !n->is_table())
            throw ConfigError(fmt::format("{}: key '{}' = {}: must be a table [{}]", where(file, n->source()),
                                          name, show(*n), name));
        out.insert_or_assign(name, toml::table{});
        return {n ? n->as_table() : nullptr, out.get(name)->as_table()};
    };

    // Top level: only known sections.
    for (auto&& [k, v] : root) {
        static const std::set<std::string> known = {"run",       "wedge",     "material", "packing",      "numerics",
                                                    "calibrate", "materials", "layers",   "retro_layers", "friction_pairs",
                                                    "surface",   "sandbox",   "flexure"};
        if (!known.count(std::string(k.str())))
            throw ConfigError(fmt::format("{}: unknown key '{}' = {}{}; allowed top-level tables: run, wedge, material, packing, "
                                          "numerics, calibrate, materials, layers, retro_layers, friction_pairs, surface, sandbox, flexure",
                                          where(file, k.source()), k.str(), show(v), did_you_mean(k.str(), known)));
    }

    {
        auto [in, o] = section("run");
        Reader r(in, "run.", file, *o, none);
        c.run.experiment = r.choice("experiment", c.run.experiment, experiment_names(), true);
        c.run.seed = static_cast<std::uint64_t>(r.integer("seed", static_cast<std::int64_t>(c.run.seed), 0, std::numeric_limits<std::int64_t>::max()));
        c.run.threads = static_cast<int>(r.integer("threads", c.run.threads, 0, 1024));
        c.run.output_interval = r.number("output_interval", c.run.output_interval, positive());
        if (is_wedge(c)) {
            c.run.checkpoint_every_outputs = static_cast<int>(
                r.integer("checkpoint_every_outputs", c.run.checkpoint_every_outputs, 1, 1000000));
            c.run.checkpoint_minutes = r.number("checkpoint_minutes", c.run.checkpoint_minutes, non_negative());
            c.run.max_wall_minutes = r.number("max_wall_minutes", c.run.max_wall_minutes, non_negative());
            c.run.max_overlap_ratio = r.number("max_overlap_ratio", c.run.max_overlap_ratio, {0.0, 1.0, true, false});
            c.run.warn_overlap_ratio = r.number("warn_overlap_ratio", c.run.warn_overlap_ratio, {0.0, 1.0, true, false});
            if (c.run.warn_overlap_ratio > c.run.max_overlap_ratio)
                r.refuse("warn_overlap_ratio",
                         fmt::format("must not exceed run.max_overlap_ratio = {:g} (the warning comes before the stop)",
                                     c.run.max_overlap_ratio));
            c.run.allow_initial_overlap = r.boolean("allow_initial_overlap", c.run.allow_initial_overlap);
            c.run.domain_height = r.number("domain_height", c.run.domain_height, non_negative());
            c.run.on_domain_exit = r.choice("on_domain_exit", c.run.on_domain_exit, {"error", "stop"});
        }
        r.finish();
    }
    if (is_wedge(c)) {
        auto [in, o] = section("wedge");
        Reader r(in, "wedge.", file, *o, none);
        WedgeConfig& w = c.wedge;
        w.v = r.number("v", w.v, positive());
        w.s_max = r.number("s_max", w.s_max, {0.0, 100.0, true, false});
        w.output_ds = r.number("output_ds", w.output_ds, {0.0, w.s_max, true, false});
        w.mu_bp = r.number("mu_bp", w.mu_bp, closed(0.0, 10.0));
        if (experiment_of(c).retroside == Retroside::coulomb)
            w.mu_br_over_mu_bp = r.number("mu_br_over_mu_bp", w.mu_br_over_mu_bp, closed(0.0, 1000.0));
        w.base_law = read_base_law(r, in, resolved_file, c.legacy_base_law);
        if (w.base_law == BaseLaw::traction) {
            w.traction_gain = r.number("traction_gain", w.traction_gain, {0.0, 1.5, true, false});
            // Uncapped, a disc's velocity change per step is (g_b + g_d) times its
            // slip: the sum must stay below 2 (ConveyorTraction).
            w.drag_gain = r.number("drag_gain", w.drag_gain, {0.0, 2.0 - w.traction_gain, false, true});
        } else {
            refuse_traction_keys(r, in, "wedge", {"traction_gain", "drag_gain"});
        }
        if (!experiment_of(c).push_wall)  // the sandbox's layer length is sandbox.length
            w.pro_margin = r.number("pro_margin", w.pro_margin, {2.0, 1000.0, false, false});
        if (!experiment_of(c).backstop)
            w.retro_length = r.number("retro_length", w.retro_length, {1.0, 1000.0, false, false});
        w.toe_threshold = r.number("toe_threshold", w.toe_threshold, {0.0, 10.0, true, false});
        w.column_width = r.number("column_width", w.column_width, non_negative());
        w.sleep = r.boolean("sleep", w.sleep);
        w.sleep_tolerance = r.number("sleep_tolerance", w.sleep_tolerance, {0.0, 1.0, true, false});
        w.sleep_buffer = r.number("sleep_buffer", w.sleep_buffer, {0.0, 100.0, true, false});
        w.sleep_buffer_pro = r.number("sleep_buffer_pro", w.sleep_buffer, {0.0, 100.0, true, false});
        w.inertia_floor = r.number("inertia_floor", w.inertia_floor, {1.0, 10.0, false, false});
        if (w.inertia_floor != 1.0 && w.base_law == BaseLaw::traction)
            r.refuse("inertia_floor", "applies under the Coulomb base only (the eq. 5 traction's gains and its eq. 6 "
                                      "bound are per unit of a disc's own mass); set wedge.inertia_floor = 1 (on the command "
                                      "line: --set wedge.inertia_floor=1) or wedge.base_law = \"coulomb\"");
        r.finish();
    } else if (const toml::node* n = root.get("wedge")) {
        throw ConfigError(fmt::format("{}: table [wedge] is only read by the wedge experiments, not run.experiment = \"{}\"; "
                                      "remove it or set run.experiment to critical-wedge, exp1, exp2 or exp3",
                                      where(file, n->source()), c.run.experiment));
    }
    if (experiment_of(c).push_wall) {
        auto [in, o] = section("sandbox");
        Reader r(in, "sandbox.", file, *o, none);
        SandboxConfig& b = c.sandbox;
        b.length = r.number("length", b.length, {1.0, 1000.0, false, false});
        b.surface_slope_deg = r.number("surface_slope_deg", b.surface_slope_deg, {0.0, 60.0, false, false});
        // The wall's travel must leave the pushed material between the walls.
        if (c.wedge.s_max > b.length - 0.5)
            r.refuse("length", fmt::format("must be at least wedge.s_max + 0.5 = {:g} h0 (the moving wall travels "
                                           "s_max h0 toward the fixed end wall)", c.wedge.s_max + 0.5));
        r.finish();
    } else if (const toml::node* n = root.get("sandbox")) {
        throw ConfigError(fmt::format("{}: table [sandbox] is only read by run.experiment = \"sandbox\", not \"{}\"; "
                                      "remove it or set run.experiment = \"sandbox\"",
                                      where(file, n->source()), c.run.experiment));
    }
    {
        auto [in, o] = section("material");
        Reader r(in, "material.", file, *o, none);
        MaterialConfig& m = c.material;
        m.density = r.number("density", m.density, positive());
        m.k_n = r.number("k_n", m.k_n, positive());
        m.k_s_over_k_n = r.number("k_s_over_k_n", m.k_s_over_k_n, closed(0.0, 10.0));
        m.mu = r.number("mu", m.mu, closed(0.0, 10.0));
        m.cohesion = r.number("cohesion", m.cohesion, non_negative());
        m.damping_kind = r.choice("damping_kind", m.damping_kind, kDampingKinds);
        if (m.damping_kind == DampingKind::restitution) {
            m.damping_normal = r.number("damping_normal", m.damping_normal, {0.0, 1.0, true, false});
            m.damping_tangential = r.number("damping_tangential", m.damping_tangential, closed(0.0, 1.0));
        } else if (m.damping_kind == DampingKind::ratio) {
            m.damping_normal = r.number("damping_normal", m.damping_normal, {0.0, 1.0, false, true});
            m.damping_tangential = r.number("damping_tangential", m.damping_tangential, closed(0.0, 1.0));
        } else {
            m.damping_normal = r.number("damping_normal", m.damping_normal, non_negative());
            m.damping_tangential = r.number("damping_tangential", m.damping_tangential, non_negative());
        }
        m.clamp_normal = r.boolean("clamp_normal", m.clamp_normal);
        r.finish();
    }
    {
        auto [in, o] = section("packing");
        Reader r(in, "packing.", file, *o, none);
        PackingConfig& p = c.packing;
        p.kind = r.choice("kind", p.kind, kPackingKinds);
        p.r_min = r.number("r_min", p.r_min, positive());
        p.r_max = r.number("r_max", p.r_max, positive());
        if (p.r_max < p.r_min)
            r.refuse("r_max", fmt::format("must be >= packing.r_min = {:g}", p.r_min));
        if (!is_calibration(c)) {  // the calibrations size their samples in [calibrate]
            p.h0 = r.number("h0", p.h0, positive());
            if (p.h0 < 4.0 * p.r_max)
                r.refuse("h0", fmt::format("must be at least 4 r_max = {:g} m (two disc layers)", 4.0 * p.r_max));
        }
        if (is_calibration(c)) {
            // no layer: packing.h0 and packing.length are not read (unknown keys)
        } else if (is_wedge(c)) {
            // Incoming plate long enough to reach s_max, plus the retroside cover.
            const WedgeConfig& w = c.wedge;
            const double retro = experiment_of(c).backstop ? 0.0 : w.retro_length;
            const double derived = experiment_of(c).push_wall ? c.sandbox.length * p.h0
                                                              : (w.s_max + w.pro_margin + retro) * p.h0;
            // A run directory's config.toml holds the derived value; that exact
            // value is accepted so the file loads again (orodem run --resume).
            if (in && in->get("length") && r.number("length", derived, positive()) != derived)
                r.refuse("length", fmt::format("is derived by the wedge experiments from wedge.s_max, wedge.pro_margin "
                                               "and wedge.retro_length (here {:g} m); remove it", derived));
            p.length = derived;
            o->insert_or_assign("length", p.length);
        } else {
            p.length = r.number("length", p.length, positive());
        }
        if (!is_calibration(c) && p.length < 8.0 * p.r_max)
            r.refuse("length", fmt::format("must be at least 8 r_max = {:g} m", 8.0 * p.r_max));
        const std::int64_t seed = r.integer("seed", 0, 0, std::numeric_limits<std::int64_t>::max());
        p.seed = seed == 0 ? c.run.seed : static_cast<std::uint64_t>(seed);
        o->insert_or_assign("seed", static_cast<std::int64_t>(p.seed));
        p.settle_ke_ratio = r.number("settle_ke_ratio", p.settle_ke_ratio, {0.0, 1.0, true, true});
        p.settle_damping_ratio = r.number("settle_damping_ratio", p.settle_damping_ratio, {0.0, 1.0, true, true});
        p.settle_max_steps = r.integer("settle_max_steps", p.settle_max_steps, 1, std::numeric_limits<std::int64_t>::max());
        p.wall_mu = r.number("wall_mu", p.wall_mu, closed(0.0, 10.0));
        p.cache_dir = r.string("cache_dir", p.cache_dir);
        r.finish();
    }
    {
        auto [in, o] = section("numerics");
        Reader r(in, "numerics.", file, *o, none);
        NumericsConfig& n = c.numerics;
        n.dt = r.number("dt", n.dt, non_negative());
        n.safety = r.number("safety", n.safety, {0.0, 0.5, true, false});
        n.skin = r.number("skin", n.skin, non_negative());
        if (n.skin == 0.0) n.skin = 0.4 * c.packing.r_min;
        o->insert_or_assign("skin", n.skin);
        n.gravity = r.number("gravity", n.gravity, non_negative());
        r.finish();
    }
    if (is_calibration(c)) read_calibrate(c, section, file, resolved_file);
    else if (const toml::node* n = root.get("calibrate"))
        throw ConfigError(fmt::format("{}: table [calibrate] is only read by the calibration experiments, not "
                                      "run.experiment = \"{}\"; remove it or set run.experiment to biaxial, "
                                      "basal-friction or repose (orodem calibrate)",
                                      where(file, n->source()), c.run.experiment));
    read_layers(c, root, file);
    if (is_wedge(c) && c.wedge.column_width == 0.0) {
        c.wedge.column_width = 2.0 * c.packing.r_max;
        out.get("wedge")->as_table()->insert_or_assign("column_width", c.wedge.column_width);
    }
    read_surface(c, root, file);
    read_flexure(c, root, file);
    return c;
}

}  // namespace

Override parse_override(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw ConfigError(fmt::format("--set '{}': expected key=value, e.g. --set material.mu=0.5", text));
    return {text.substr(0, eq), text.substr(eq + 1)};
}

Config parse_config(const std::string& text, const std::string& name, const std::vector<Override>& overrides) {
    check_non_ascii(text, name);
    toml::table root;
    try {
        root = toml::parse(std::string_view(text), std::string_view(name));
    } catch (const toml::parse_error& e) {
        throw ConfigError(fmt::format("{}: not valid TOML: {}", where(name, e.source()), e.description()));
    }
    for (const auto& o : overrides) apply_override(root, o, name);
    // A run directory's config.toml (to_toml) starts with this line.
    const bool resolved_file = text.rfind(kResolvedHeader, 0) == 0;
    Config c = read(root, name, resolved_file);
    c.path = name;
    return c;
}

Config load_config(const std::string& path, const std::vector<Override>& overrides) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw ConfigError(fmt::format("{}: is a directory, not a config file; give a .toml file (a run directory's "
                                      "own is {}/config.toml)",
                                      path, path));
    // A device (/dev/zero), a FIFO or a socket would block or never end: refused before opening.
    const auto status = std::filesystem::status(path, ec);
    if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw ConfigError(fmt::format("{}: not a regular file (a device, FIFO or socket); give a .toml file", path));
    constexpr std::uintmax_t kMaxConfigBytes = 16u << 20;  // far above any config (the largest preset is 5 kB)
    if (!ec && std::filesystem::exists(status) && std::filesystem::file_size(path, ec) > kMaxConfigBytes && !ec)
        throw ConfigError(fmt::format("{}: larger than {} MiB, not a config file; give a .toml file", path,
                                      kMaxConfigBytes >> 20));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ConfigError(fmt::format("{}: cannot open config file", path));
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse_config(ss.str(), path, overrides);
}

}  // namespace orodem
