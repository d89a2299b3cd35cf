// The layered wedge's tables of the config loader (io/config.cpp):
// [materials.NAME], [[layers]], [[retro_layers]] and [[friction_pairs]], and
// the named material of the biaxial and basal-friction calibrations. Kept
// apart from io/config.cpp so that the loader reads as the list of sections.
#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/config_reader.hpp"

namespace orodem::config_reader {

/// [materials.NAME], [[layers]], [[retro_layers]] and [[friction_pairs]] of a
/// layered wedge (after [material], whose values the materials default to).
/// Absent: nothing is read or resolved, so a one-material config resolves as
/// before. The layers name known materials and add up to 1 h0; a residual μ
/// is at most the peak.
void read_layers(Config& c, const toml::table& root, const std::string& file) {
    const toml::node* mats = root.get("materials");
    const toml::node* layers = root.get("layers");
    const toml::node* retro = root.get("retro_layers");
    const toml::node* pairs = root.get("friction_pairs");
    if (!mats && !layers && !retro && !pairs) {
        if (!c.calibrate.material.empty())
            throw ConfigError(fmt::format("{}: key 'calibrate.material' = \"{}\": no [materials.{}] in the config", file,
                                          c.calibrate.material, c.calibrate.material));
        return;
    }
    const toml::source_region none{};
    auto fail = [&](const toml::node* n, const std::string& why) -> void {
        throw ConfigError(fmt::format("{}: {}", n ? where(file, n->source()) : file, why));
    };
    // The biaxial test of a named material (calibrate.material) reads its [materials.NAME] alone.
    const bool biaxial = c.run.experiment == "biaxial" && !c.calibrate.material.empty();
    // The basal-friction block of a layered config: [[layers]] in fractions of calibrate.block_height.
    const bool basal = c.run.experiment == "basal-friction" && mats && layers && !retro;
    if (!is_wedge(c) && !(biaxial && mats && !layers && !retro && !pairs) && !basal)
        fail(mats ? mats : layers ? layers : retro ? retro : pairs,
             fmt::format("[materials] and [[layers]] are read by the wedge experiments only (and [materials] by the "
                         "biaxial test of calibrate.material, [materials] and [[layers]] by basal-friction), not "
                         "run.experiment = \"{}\"",
                         c.run.experiment));
    if (!mats || !mats->is_table() || mats->as_table()->empty())
        fail(mats ? mats : layers, "a layered wedge needs its materials: one table [materials.NAME] per material");
    if (!layers && !biaxial)
        fail(mats, "[materials] are used through [[layers]] (from the base up, each a material and a thickness in h0)");
    toml::table& out = c.resolved;
    out.insert_or_assign("materials", toml::table{});
    toml::table& out_mats = *out.get("materials")->as_table();
    std::vector<std::string> names;
    for (auto&& [name, node] : *mats->as_table()) {
        const std::string key(name.str());
        if (!node.is_table())
            fail(&node, fmt::format("key 'materials.{}' = {}: must be a table [materials.{}]", key, show(node), key));
        if (c.materials.size() == 64) fail(&node, "at most 64 materials");
        for (char ch : key)
            if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
                fail(&node, fmt::format("material name '{}': letters, digits, '_' and '-' only", key));
        out_mats.insert_or_assign(key, toml::table{});
        const std::string prefix = "materials." + key + ".";
        Reader r(node.as_table(), prefix, file, *out_mats.get(key)->as_table(), none);
        NamedMaterial nm;
        nm.name = key;
        nm.m = c.material;
        nm.m.density = r.number("density", nm.m.density, positive());
        nm.m.k_n = r.number("k_n", nm.m.k_n, positive());
        nm.m.k_s_over_k_n = r.number("k_s_over_k_n", nm.m.k_s_over_k_n, {0.0, 10.0, true, false});
        nm.m.mu = r.number("mu", nm.m.mu, closed(0.0, 10.0));
        nm.mu_residual = r.number("mu_residual", nm.m.mu, closed(0.0, 10.0));
        if (nm.mu_residual > nm.m.mu)
            r.refuse("mu_residual", fmt::format("must be at most {}mu = {:g} (weakening lowers the friction)", prefix, nm.m.mu));
        nm.weakening_distance = r.number("weakening_distance", nm.weakening_distance, {0.0, 1e6, true, false});
        nm.healing = r.number("healing", nm.healing, non_negative());
        nm.m.cohesion = r.number("cohesion", nm.m.cohesion, non_negative());
        nm.cohesion_loss = r.boolean("cohesion_loss", nm.cohesion_loss);
        r.finish();
        names.push_back(key);
        c.materials.push_back(std::move(nm));
    }
    if (biaxial) {
        if (std::find(names.begin(), names.end(), c.calibrate.material) == names.end())
            throw ConfigError(fmt::format("{}: key 'calibrate.material' = \"{}\": no [materials.{}]{}", file,
                                          c.calibrate.material, c.calibrate.material,
                                          config_reader::did_you_mean(c.calibrate.material, names)));
        for (const NamedMaterial& nm : c.materials)
            if (nm.name == c.calibrate.material) c.calibrate.mu_values = {nm.m.mu};
        return;
    }
    auto read_stack = [&](const toml::node* node, const char* key, std::vector<LayerConfig>& stack) {
        const std::string what = fmt::format("[[{}]]: an array of tables, each with material = \"NAME\" and thickness [h0]", key);
        if (!node->is_array_of_tables() || node->as_array()->empty() || node->as_array()->size() > 64)
            fail(node, fmt::format("key '{}' = {}: must be {} (1 to 64 layers)", key, show(*node), what));
        toml::array out_stack;
        double total = 0.0;
        std::size_t k = 0;
        for (const toml::node& e : *node->as_array()) {
            toml::table t;
            Reader r(e.as_table(), fmt::format("{}[{}].", key, k), file, t, e.source());
            LayerConfig l;
            l.material = r.string("material", "");
            if (std::find(names.begin(), names.end(), l.material) == names.end()) {
                std::string list;
                for (const std::string& n : names) list += fmt::format("{}{}", list.empty() ? "" : ", ", n);
                r.refuse("material", fmt::format("no [materials.{}]; the materials are: {}{}", l.material, list,
                                                 config_reader::did_you_mean(l.material, names)));
            }
            l.thickness = r.number("thickness", 0.0, {0.0, 1.0, true, false});
            r.finish();
            total += l.thickness;
            stack.push_back(l);
            out_stack.push_back(std::move(t));
            ++k;
        }
        if (std::fabs(total - 1.0) > 1e-9)
            fail(node, fmt::format("[[{}]]: the thicknesses add up to {:g} h0; they must add up to 1 (the layer is h0 thick)",
                                   key, total));
        out.insert_or_assign(key, std::move(out_stack));
    };
    read_stack(layers, "layers", c.layers);
    if (retro) {
        if (experiment_of(c).backstop) fail(retro, "[[retro_layers]]: the critical wedge has no retroside");
        read_stack(retro, "retro_layers", c.retro_layers);
    } else {
        c.retro_layers = c.layers;
    }
    if (pairs) {
        if (!pairs->is_array_of_tables())
            fail(pairs, "key 'friction_pairs' must be [[friction_pairs]]: tables with a, b (material names), mu and mu_residual");
        toml::array out_pairs;
        std::size_t k = 0;
        for (const toml::node& e : *pairs->as_array()) {
            toml::table t;
            Reader r(e.as_table(), fmt::format("friction_pairs[{}].", k), file, t, e.source());
            FrictionPair fp;
            for (auto [key, name] : {std::pair{"a", &fp.a}, std::pair{"b", &fp.b}}) {
                *name = r.string(key, "");
                if (std::find(names.begin(), names.end(), *name) == names.end())
                    r.refuse(key, fmt::format("no [materials.{}]{}", *name, config_reader::did_you_mean(*name, names)));
            }
            fp.mu = r.number("mu", 0.0, closed(0.0, 10.0));
            fp.mu_residual = r.number("mu_residual", fp.mu, closed(0.0, 10.0));
            if (fp.mu_residual > fp.mu) r.refuse("mu_residual", fmt::format("must be at most mu = {:g}", fp.mu));
            r.finish();
            for (const FrictionPair& q : c.friction_pairs)
                if ((q.a == fp.a && q.b == fp.b) || (q.a == fp.b && q.b == fp.a))
                    fail(&e, fmt::format("friction_pairs[{}]: the pair {} / {} is given twice", k, fp.a, fp.b));
            c.friction_pairs.push_back(fp);
            out_pairs.push_back(std::move(t));
            ++k;
        }
        out.insert_or_assign("friction_pairs", std::move(out_pairs));
    }
}

}  // namespace orodem::config_reader
