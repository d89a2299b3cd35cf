// [flexure] of the config loader (io/config.cpp): the elastic plate under a
// wedge (docs/physics.md "Flexure under the wedge"). Kept apart from
// io/config.cpp so that the loader reads as the list of sections.
#include <cmath>

#include <fmt/format.h>

#include "orodem/core/angles.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/config_reader.hpp"
#include "orodem/physics/flexure.hpp"

namespace orodem {

PlateParams flexure_plate_params(const Config& c) {
    const FlexureConfig& f = c.flexure;
    PlateParams p;
    p.E = f.E;
    p.nu = f.nu;
    p.Te = f.Te > 0.0 ? f.Te : 1.0;  // unused when D > 0
    p.D = f.D;
    p.rho_mantle = f.rho_mantle;
    p.rho_infill = f.rho_infill;
    p.g = c.numerics.gravity;
    p.broken = f.plate == PlateKind::broken;
    p.x_break = 0.0;  // the S point
    return p;
}

}  // namespace orodem

namespace orodem::config_reader {

namespace {

constexpr double kFlexureConfigMaxNodes = 2.0e6;  // a plate grid beyond this is refused [-]

}  // namespace

/// [flexure] of exp1, exp2 or exp3 (after [wedge], [packing] and
/// [numerics]). Absent: nothing is read or resolved.
void read_flexure(Config& c, const toml::table& root, const std::string& file) {
    const toml::node* n = root.get("flexure");
    if (!n) return;
    if (!n->is_table())
        throw ConfigError(fmt::format("{}: key 'flexure' = {}: must be a table [flexure]", where(file, n->source()), show(*n)));
    const Experiment& e = experiment_of(c);
    if (!is_wedge(c) || e.backstop || e.push_wall)
        throw ConfigError(fmt::format("{}: table [flexure] is only read by exp1, exp2 and exp3 (a plate under a doubly "
                                      "vergent wedge), not run.experiment = \"{}\"; remove it",
                                      where(file, n->source()), c.run.experiment));
    c.resolved.insert_or_assign("flexure", toml::table{});
    toml::table& o = *c.resolved.get("flexure")->as_table();
    Reader r(n->as_table(), "flexure.", file, o, toml::source_region{});
    FlexureConfig& f = c.flexure;
    f.present = true;
    f.plate = r.choice("plate", f.plate, kPlateKinds);
    f.coupling = r.choice("coupling", f.coupling, kFlexureCouplings);
    f.Te = r.number("Te", f.Te, non_negative());
    f.D = r.number("D", f.D, non_negative());
    f.E = r.number("E", f.E, positive());
    f.nu = r.number("nu", f.nu, {0.0, 0.5, false, true});
    f.rho_mantle = r.number("rho_mantle", f.rho_mantle, positive());
    f.rho_infill = r.number("rho_infill", f.rho_infill, non_negative());
    f.interval_steps = r.integer("interval_steps", f.interval_steps, 1, 100000000);
    f.dx = r.number("dx", f.dx, non_negative());
    f.extension = r.number("extension", f.extension, closed(2.0, 100.0));
    r.finish();
    if ((f.Te > 0.0) == (f.D > 0.0))
        r.refuse(f.D > 0.0 ? "D" : "Te", "give one of flexure.Te (elastic thickness [m]) and flexure.D (flexural "
                                         "rigidity [N m]), not both or neither");
    if (!(f.rho_mantle > f.rho_infill))
        r.refuse("rho_mantle", fmt::format("must be above flexure.rho_infill = {:g}", f.rho_infill));
    if (!(c.numerics.gravity > 0.0))
        throw ConfigError(fmt::format("{}: [flexure] needs numerics.gravity > 0 (the plate's restoring force)", file));
    const double h0 = c.packing.h0;
    const double alpha = flexure_plate_params(c).flexural_parameter();  // [m]
    if (!(std::isfinite(alpha) && alpha > 0.0))
        r.refuse(f.D > 0.0 ? "D" : "Te", fmt::format("gives no finite flexural parameter (alpha = {:g} m)", alpha));
    if (f.dx * h0 > kFlexureMaxDxPerAlpha * alpha)
        r.refuse("dx", fmt::format("must be at most alpha/40 = {:g} h0 (alpha = {:g} h0; the resolution rule of "
                                   "physics/flexure.hpp); 0 takes alpha/40",
                                   kFlexureMaxDxPerAlpha * alpha / h0, alpha / h0));
    const double dx = f.dx > 0.0 ? f.dx * h0 : kFlexureMaxDxPerAlpha * alpha;
    const double model = (c.wedge.s_max + c.wedge.pro_margin + c.wedge.retro_length) * h0;
    const double nodes = (model + 2.0 * f.extension * alpha) / dx;
    if (!(nodes <= kFlexureConfigMaxNodes))
        r.refuse(f.D > 0.0 ? "D" : "Te",
                 fmt::format("the plate grid would have {:.3g} nodes (alpha = {:.3g} h0 against a model {:.3g} h0 "
                             "long, dx = {:.3g} h0); at most {:.0e}: a stiffer plate or a larger flexure.dx",
                             nodes, alpha / h0, model / h0, dx / h0, kFlexureConfigMaxNodes));
}

}  // namespace orodem::config_reader
