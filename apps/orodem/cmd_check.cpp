// orodem check CONFIG: the resolved config and what follows from it (the
// timestep, the belt speed against its bounds, the inertial number, the plate
// length the deformation front needs, the step count and the run time),
// without running anything.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/physics/stability.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/run/runner.hpp"
#include "orodem/setup/calibration.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"

#include "cli.hpp"
#include "commands.hpp"

namespace orodem {

namespace {

/// What orodem check prints for a calibration config.
int check_calibration(const Config& c) {
    const TimestepInfo t = timestep_for(c);
    check_calibration_size(c);
    const CalibrateConfig& k = c.calibrate;
    std::cout << to_toml(c);
    fmt::print("# derived (run it with: orodem calibrate {})\n", c.path);
    fmt::print("dt                     = {:.6g} s (stability limit {:.6g} s, margin {:.2f}x)\n", t.dt, t.dt_crit,
               t.margin());
    const std::string& e = c.run.experiment;
    const std::size_t values = e == "basal-friction" ? k.mu_bp_values.size() : k.mu_values.size();
    fmt::print("tests                  = {} ({} packing kinds x {} values)\n", k.kinds.size() * values,
               k.kinds.size(), values);
    auto discs = [&](PackingKind kind, double length, double h0) {
        return generate_packing(calibration_sample(c, kind, length, h0), c.material.density).size();
    };
    for (PackingKind kind : k.kinds) {
        if (e == "biaxial") {
            const std::size_t n = discs(kind, k.width, std::max(c.packing.r_max,
                                                                0.82 * k.height / 0.9 - 3.0 * c.packing.r_max));
            const double steps = k.max_strain / (k.strain_rate * t.dt);
            fmt::print("{:<22} = {} discs, {:.3g} steps of shear ({:.3g} disc-steps) plus compaction\n", kind, n,
                       steps, steps * static_cast<double>(n));
        } else if (e == "basal-friction") {
            fmt::print("{:<22} = about {} discs before the cut, {:.3g} steps of belt motion\n", kind,
                       discs(kind, k.block_length, k.block_height), k.duration / t.dt);
        } else {
            fmt::print("{:<22} = about {} discs before the cut, plus the floor\n", kind,
                       discs(kind, k.column_width, k.column_height));
        }
    }
    if (e == "biaxial") {
        const double d = mean_disc_diameter(c);
        fmt::print("strain rate            = {:.4g} 1/s, inertial number I = {:.3g} (limit {:g})\n", k.strain_rate,
                   k.strain_rate * d * std::sqrt(c.material.density / k.confining_stress), k.max_inertial_number);
    } else if (e == "basal-friction" && k.base_law == BaseLaw::coulomb) {
        check_base_dashpot(c);
        fmt::print("belt speed v'          = {:g} m/s (Coulomb base)\n", k.belt_speed);
    } else if (e == "basal-friction") {
        const double v_limit = lightest_mass(c) * c.numerics.gravity / (c.material.k_n * t.dt);
        fmt::print("belt speed v'          = {:g} m/s (eq. 6 traction base; limit {:.4g} m/s, margin {:.1f}x)\n",
                   k.belt_speed, v_limit, v_limit / k.belt_speed);
        if (!(k.belt_speed < v_limit))
            throw ConfigError(fmt::format("{}: key 'calibrate.belt_speed' = {:g}: must satisfy eq. 6, v' < m g / "
                                          "(k_n dt) = {:g} m/s",
                                          c.path, k.belt_speed, v_limit));
    }
    return 0;
}

}  // namespace

int cmd_check(const CommonArgs& a) {
    const Config c = load(a);
    if (is_calibration(c)) return check_calibration(c);
    const RunNumbers numbers = check_runnable(c);
    const TimestepInfo& t = numbers.timestep;
    // Up to a million discs are generated and counted (well under a second);
    // beyond, the area estimate (within 3%) answers at once.
    constexpr double kCountUpTo = 1.0e6;
    const double estimate = estimated_disc_count(c.packing);
    const std::size_t n = estimate <= kCountUpTo ? generated_particle_count(c)
                                                 : static_cast<std::size_t>(std::llround(estimate));
    std::cout << to_toml(c);
    fmt::print("# derived\n");
    fmt::print("particles generated    = {} discs ({}), before the cut to h0{}\n", n, c.packing.kind,
               estimate <= kCountUpTo ? "" : " (estimated from the layer's area, within 3%)");
    fmt::print("layer                  = {:g} m long, h0 = {:g} m\n", c.packing.length, c.packing.h0);
    fmt::print("dt                     = {:.6g} s ({})\n", t.dt, c.numerics.dt > 0 ? "requested" : "automatic");
    fmt::print("stability limit        = {:.6g} s (margin {:.2f}x)\n", t.dt_crit, t.margin());
    fmt::print("collision time t_c     = {:.6g} s ({:.1f} steps)\n", t.t_collision, t.t_collision / t.dt);
    if (is_wedge(c)) {
        const double steps = c.wedge.s_max * c.packing.h0 / (c.wedge.v * t.dt);
        if (c.wedge.base_law == BaseLaw::traction)
            fmt::print("belt speed v'          = {:g} m/s (eq. 6 traction base; limit {:.4g} m/s, margin {:.1f}x)\n",
                       c.wedge.v, numbers.belt_speed_limit, numbers.belt_speed_limit / c.wedge.v);
        else
            fmt::print("belt speed v'          = {:g} m/s (Coulomb base, mu_bp = {:g})\n", c.wedge.v, c.wedge.mu_bp);
        fmt::print("inertial number I      = {:.3g} (v'/h0 (r_min + r_max) sqrt(rho / (rho g h0)); quasi-static "
                   "below 1e-3)\n",
                   numbers.inertial_number);
        if (const double m_f = inertia_floor_mass(c); m_f > 0.0) {
            const double mean_ratio = inertia_floor_mean_mass_ratio(c);  // [-]
            fmt::print("inertia floor          = {:g} r_min (discs below {:g} m move with the mass and moment of inertia "
                       "of a {:g} m disc, {:.4g} kg, and keep their own weight; their I is up to {:g} times the above; "
                       "the layer's mean inertial mass is {:.3g} times its own, its I about {:.3g})\n",
                       c.wedge.inertia_floor, c.wedge.inertia_floor * c.packing.r_min,
                       c.wedge.inertia_floor * c.packing.r_min, m_f, c.wedge.inertia_floor,
                       mean_ratio, numbers.inertial_number * std::sqrt(mean_ratio));
        }
        const PlateEstimate& pe = numbers.plate;
        fmt::print("plate beyond s_max     = {:g} h0 (wedge.pro_margin); the deformation front reaches about {:.1f} h0 "
                   "from the S point by S = {:g} (critical taper {:.2f} deg for phi = {:.1f} deg, phi_b = {:.1f} deg), "
                   "so at least {:.1f} h0 is needed\n",
                   c.wedge.pro_margin, pe.front_h0, c.wedge.s_max, pe.alpha_deg, pe.phi_deg, pe.phi_b_deg,
                   pe.pro_margin_min);
        if (const std::string w = short_plate_warning(c, pe); !w.empty()) fmt::print(stderr, "orodem: warning: {}\n", w);
        const RunTimeEstimate e = estimate_run_time(c, static_cast<double>(n), t.dt);
        fmt::print("steps to S = {:g}       = {:.3g} ({:.3g} {}disc-steps)\n", c.wedge.s_max, steps, e.work,
                   c.wedge.sleep ? "awake " : "");
        fmt::print("estimated run time     = {} on 1 thread, {} on 2 (at {:.2g} and {:.2g} {}disc-steps/s measured on "
                   "the 2-core development host{}; machines differ by 2-3x; plus settling if not cached){}\n",
                   duration_text(e.seconds_1), duration_text(e.seconds_2), e.work / e.seconds_1,
                   e.work / e.seconds_2, c.wedge.sleep ? "awake " : "", c.wedge.sleep ? ", 45% of the discs awake" : "",
                   e.seconds_2 > 3600.0 * kLongRunHours
                       ? fmt::format("; above {:g} h: orodem run refuses it without --force", kLongRunHours)
                       : "");
        if (c.wedge.drag_gain > 0.0) {
            // The uncapped drag at full slip, g_d m v'/dt, on a disc of the mean
            // radius R over the weight rho g h0 2R of a column h0 tall on its
            // width: pi g_d R v' / (2 g h0 dt). It depends on dt and h0, so a
            // config scaled to another size needs another g_d for the same drag.
            const double R = 0.5 * (c.packing.r_min + c.packing.r_max);  // [m]
            const double drag_over_weight =
                M_PI * c.wedge.drag_gain * R * c.wedge.v / (2.0 * c.numerics.gravity * c.packing.h0 * t.dt);
            fmt::print("basal drag at full slip = {:.3g} of the weight of a column h0 tall over a disc of the mean "
                       "radius (g_d = {:g}; the Coulomb part is at most mu_bp = {:g} of the weight on the base)\n",
                       drag_over_weight, c.wedge.drag_gain, c.wedge.mu_bp);
        }
    }
    fmt::print("packing cache          = {}\n", packing_cache_path(c));
    return 0;
}

}  // namespace orodem
