#include "orodem/setup/wedge.hpp"

#include <fmt/format.h>

#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/core/error.hpp"
#include "orodem/setup/scenario.hpp"

namespace orodem {

double belt_speed_limit(const Config& c) {
    const TimestepInfo t = timestep_for(c);
    return lightest_mass(c) * c.numerics.gravity / (c.material.k_n * t.dt);
}

void check_belt_speed(const Config& c) {
    const WedgeConfig& w = c.wedge;
    const TimestepInfo t = timestep_for(c);
    const double v_limit = belt_speed_limit(c);
    if (!(w.v < v_limit))
        throw ConfigError(fmt::format(
            "{}: key 'wedge.v' = {:g}: must satisfy eq. 6, v' < m g / (k_n dt) = {:g} m/s "
            "(m = {:g} kg lightest disc, g = {:g}, k_n = {:g}, dt = {:g} s); lower wedge.v or material.k_n",
            c.path, w.v, v_limit, lightest_mass(c), c.numerics.gravity, c.material.k_n, t.dt));
}

ProfileParams wedge_profile_params(const Config& c) {
    const WedgeConfig& w = c.wedge;
    const double h0 = c.packing.h0;
    const bool backstop = c.run.experiment == "critical-wedge";
    ProfileParams pp;
    pp.column = w.column_width;
    pp.x_min = -(w.s_max + w.pro_margin) * h0;  // the trailing end at the start
    pp.x_max = backstop ? 0.0 : w.retro_length * h0;
    pp.h0 = h0;
    pp.x_s = 0.0;
    pp.toe_threshold = w.toe_threshold * h0;
    pp.retro_side = !backstop;
    pp.backstop_margin = backstop ? 0.5 * h0 : 0.0;  // the backstop's own drag zone
    return pp;
}

double undeformed_surface(const ParticleStore& p, const ProfileParams& pp) {
    // The incoming layer away from both ends: from h0 inside the trailing
    // end to h0 before the S point.
    return mean_surface(p, pp.x_min + pp.h0, pp.x_s - pp.h0, pp.column);
}

WedgeSetup make_wedge(const Config& c, const ParticleStore& layer) {
    const WedgeConfig& w = c.wedge;
    const double h0 = c.packing.h0;
    const bool backstop = c.run.experiment == "critical-wedge";
    const TimestepInfo t = timestep_for(c);
    check_belt_speed(c);

    WedgeSetup ws;
    ws.pro_length = (w.s_max + w.pro_margin) * h0;
    ws.retro_length = backstop ? 0.0 : w.retro_length * h0;
    Simulation& sim = ws.sim;
    sim.particles = layer;
    ParticleStore& p = sim.particles;
    for (std::size_t s = 0; s < p.size(); ++s) {
        p.x[s].x -= ws.pro_length;
        p.side[s] = p.x[s].x > 0.0 ? 1 : 0;
    }
    sim.params.law = make_law(c.material);
    sim.params.dt = t.dt;
    sim.params.gravity = {0.0, -c.numerics.gravity};
    sim.params.skin = c.numerics.skin;

    const double far = 2.0 * h0;                 // bases reach beyond the end walls [m]
    const double tall = 1e3 * h0;                // end walls are effectively unbounded [m]
    const double x_pro = -ws.pro_length, x_retro = ws.retro_length;
    Wall pro_base{{x_pro - far, 0.0}, {0.0, 0.0}, {}, 0.0, false, false, 0.0};
    pro_base.open_ends = true;
    sim.walls.push_back(pro_base);
    if (backstop) {
        sim.walls.push_back({{0.0, 0.0}, {0.0, tall}, {}, 0.0, false, false, 0.0});
    } else {
        const bool coulomb = c.run.experiment == "exp3";
        Wall retro_base{{0.0, 0.0}, {x_retro + far, 0.0}, {}, 0.0, false, coulomb,
                        coulomb ? w.mu_br_over_mu_bp * w.mu_bp : 0.0};
        retro_base.open_ends = true;
        sim.walls.push_back(retro_base);
    }
    sim.walls.push_back({{x_pro, 0.0}, {x_pro, tall}, {w.v, 0.0}, 0.0, false, false, 0.0});
    if (!backstop) sim.walls.push_back({{x_retro, 0.0}, {x_retro, tall}, {}, 0.0, false, false, 0.0});

    // Sleeping zones (engine/sleep.cpp): the incoming plate rides at (v, 0)
    // left of the S point; the retroside rests (fixed or Coulomb base).
    SleepParams& sp = sim.params.sleep;
    sp.enabled = w.sleep;
    sp.x_split = 0.0;
    sp.u_left = {w.v, 0.0};
    sp.u_right = {};
    sp.left = true;
    sp.right = !backstop;
    sp.tolerance = w.sleep_tolerance * c.packing.r_min;
    sp.buffer = w.sleep_buffer * h0;

    auto base = std::make_unique<ConveyorTraction>(kWallProBase, w.v, w.mu_bp, w.traction_gain, w.drag_gain);
    ws.base = base.get();
    sim.boundaries.push_back(std::move(base));
    if (c.run.experiment == "exp1" || c.run.experiment == "exp2") {
        auto fixed = std::make_unique<FixedRetroside>(kWallRetro);
        ws.fixed_retro = fixed.get();
        sim.boundaries.push_back(std::move(fixed));
    }

    ws.profile = wedge_profile_params(c);
    // Undeformed surface: the incoming layer away from both ends.
    ws.profile.y_mean = undeformed_surface(p, ws.profile);
    return ws;
}

}  // namespace orodem
