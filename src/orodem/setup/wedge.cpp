#include "orodem/setup/wedge.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "orodem/analysis/critical_taper.hpp"
#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/coulomb_base.hpp"
#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/core/angles.hpp"
#include "orodem/core/error.hpp"
#include "orodem/setup/layers.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"

namespace orodem {

double belt_speed_limit(const Config& c, double dt) {
    return lightest_mass(c) * c.numerics.gravity / (governing_material(c).k_n * dt);
}

double belt_speed_limit(const Config& c) { return belt_speed_limit(c, timestep_for(c).dt); }

void check_belt_speed(const Config& c, double dt) {
    const WedgeConfig& w = c.wedge;
    const double v_limit = belt_speed_limit(c, dt);
    if (!(w.v < v_limit))
        throw ConfigError(fmt::format(
            "{}: key 'wedge.v' = {:g}: must satisfy eq. 6, v' < m g / (k_n dt) = {:g} m/s "
            "(m = {:g} kg lightest disc, g = {:g}, k_n = {:g}, dt = {:g} s); lower wedge.v or material.k_n",
            c.path, w.v, v_limit, lightest_mass(c), c.numerics.gravity, governing_material(c).k_n, dt));
}

void check_belt_speed(const Config& c) { check_belt_speed(c, timestep_for(c).dt); }

void check_base_dashpot(const Config& c) { check_base_dashpot(c, timestep_for(c).dt); }

void check_base_dashpot(const Config& c, double dt) {
    // The Coulomb base's critically damped dashpot on the lightest disc:
    // explicit and stable for γ_s dt / m < 2, i.e. 2 ζ sqrt(k_s/m) dt < 2;
    // kept below 1 for a margin (the automatic dt gives about 0.12).
    const bool coulomb = (is_calibration(c) ? c.calibrate.base_law : c.wedge.base_law) == BaseLaw::coulomb;
    if (!coulomb) return;
    const double k_s = governing_material(c).k_n * governing_material(c).k_s_over_k_n;
    const double rate = 2.0 * kBaseDampingRatio * std::sqrt(k_s / lightest_inertial_mass(c)) * dt;
    if (!(rate < 1.0))
        throw ConfigError(fmt::format("{}: numerics.dt = {:g} s is too long for the Coulomb base's dashpot "
                                      "(2 sqrt(k_s/m) dt = {:.3g} for the lightest disc, must be below 1); lower "
                                      "numerics.dt or numerics.safety",
                                      c.path, dt, rate));
}

void check_wedge_base(const Config& c, double dt) {
    if (c.wedge.base_law == BaseLaw::traction) check_belt_speed(c, dt);
    check_base_dashpot(c, dt);
}

void check_wedge_base(const Config& c) { check_wedge_base(c, timestep_for(c).dt); }

namespace {

/// Refuses (ConfigError, exit 2, before anything is written) the values that
/// pass each key's own range but make the run's derived numbers absurd: a
/// timestep that is no longer a number of the problem's scale (k_n, dt), a
/// run of more steps than any machine finishes, outputs closer than a step,
/// a belt that jumps more than half the smallest radius a step, no gravity
/// for a layer that must settle, an extreme gravity, a skin wider than the
/// discs. The limits are far outside every meaningful run
/// (docs/reliability.md "Absurd values").
void check_derived_numbers(const Config& c, const TimestepInfo& t) {
    constexpr double kMaxSteps = 1e11;    // some 10 days at 1e5 steps/s [-]
    constexpr double kMaxOutputs = 1e5;   // [-]
    constexpr double kMaxGravity = 1e3;   // [m/s²]
    auto refuse = [&](const std::string& why) { throw ConfigError(fmt::format("{}: {}", c.path, why)); };
    if (!(t.dt >= 1e-12) || !std::isfinite(t.dt))
        refuse(fmt::format("the timestep would be dt = {:g} s (numerics.dt, or automatic from material.k_n = {:g} N/m and "
                           "the lightest disc); it must be at least 1e-12 s",
                           t.dt, c.material.k_n));
    const bool settles = !is_calibration(c);
    if (settles && !(c.numerics.gravity > 0.0))
        refuse("numerics.gravity = 0: the layer must settle under gravity; give g > 0 (9.81 m/s² on Earth)");
    if (c.numerics.gravity > kMaxGravity)
        refuse(fmt::format("numerics.gravity = {:g} m/s²: at most {:g}", c.numerics.gravity, kMaxGravity));
    if (c.numerics.skin > 2.0 * c.packing.r_max)
        refuse(fmt::format("numerics.skin = {:g} m: at most 2 packing.r_max = {:g} m (0 = 0.4 r_min)", c.numerics.skin,
                           2.0 * c.packing.r_max));
    if (!is_wedge(c)) return;
    const WedgeConfig& w = c.wedge;
    const double steps = w.s_max * c.packing.h0 / (w.v * t.dt), outputs = w.s_max / w.output_ds;
    if (!(steps <= kMaxSteps))
        refuse(fmt::format("wedge.s_max = {:g} at wedge.v = {:g} m/s and dt = {:.3g} s is {:.3g} steps; at most {:.0e}: "
                           "raise wedge.v or numerics.dt (orodem check prints the run time)",
                           w.s_max, w.v, t.dt, steps, kMaxSteps));
    if (outputs > kMaxOutputs)
        refuse(fmt::format("wedge.output_ds = {:g} gives {:.3g} outputs to S = {:g}; at most {:.0e}", w.output_ds, outputs,
                           w.s_max, kMaxOutputs));
    if (w.v * t.dt > 0.5 * c.packing.r_min)
        refuse(fmt::format("wedge.v = {:g} m/s moves the belt {:.3g} m a step, more than half packing.r_min ({:g} m); "
                           "lower wedge.v or numerics.dt", w.v, w.v * t.dt, 0.5 * c.packing.r_min));
    if (w.output_ds * c.packing.h0 < w.v * t.dt)
        refuse(fmt::format("wedge.output_ds = {:g} is less than one step of the belt ({:.3g} of h0); raise it",
                           w.output_ds, w.v * t.dt / c.packing.h0));
}

}  // namespace

RunNumbers derive_run_numbers(const Config& c) {
    RunNumbers n;
    n.timestep = timestep_for(c);
    check_derived_numbers(c, n.timestep);
    n.belt_speed_limit = belt_speed_limit(c, n.timestep.dt);
    if (is_wedge(c)) {
        check_wedge_base(c, n.timestep.dt);
        n.inertial_number = inertial_number(c);
        n.plate = plate_estimate(c);
    }
    return n;
}

double inertial_number(const Config& c) {
    const double h0 = c.packing.h0;
    const double shear_rate = c.wedge.v / h0;                       // γ̇ [1/s]
    const double d = c.packing.r_min + c.packing.r_max;             // mean disc diameter [m]
    const double P = c.material.density * c.numerics.gravity * h0;  // pressure at the base of the layer [Pa]
    return shear_rate * d * std::sqrt(c.material.density / P);
}

double bulk_friction_deg(PackingKind kind, double mu_i) {
    // φ_cs [deg] at μ_i = 0, 0.1, 0.3, 0.5, 1.0 (biaxial tests, about 1,400 discs, I = 1e-3).
    static constexpr double kMu[] = {0.0, 0.1, 0.3, 0.5, 1.0};
    static constexpr double kDiscs[] = {7.2, 12.0, 15.6, 16.8, 16.4};
    static constexpr double kClusters[] = {9.1, 17.6, 24.4, 30.2, 28.4};
    const double* phi = kind == PackingKind::clusters ? kClusters : kDiscs;
    if (mu_i >= kMu[4]) return phi[4];
    std::size_t k = 0;
    while (mu_i > kMu[k + 1]) ++k;
    const double f = (mu_i - kMu[k]) / (kMu[k + 1] - kMu[k]);
    return phi[k] + f * (phi[k + 1] - phi[k]);
}

PlateEstimate plate_estimate(const Config& c) {
    PlateEstimate e;
    e.phi_deg = bulk_friction_deg(c.packing.kind, c.material.mu);
    e.phi_b_deg = std::min(std::atan(c.wedge.mu_bp) * kDeg, e.phi_deg - 0.5);
    // φ_b = 0: no friction on the base, the plate is pushed by the trailing
    // wall alone and no taper forms; the estimate then has no meaning (inf).
    const std::optional<CriticalTaper> t =
        e.phi_b_deg > 0.0 ? critical_taper(e.phi_deg, e.phi_b_deg, 0.0) : std::nullopt;
    e.alpha_deg = t ? t->alpha_min_deg : 0.0;
    e.front_h0 = e.alpha_deg > 0.0 ? std::sqrt(2.0 * c.wedge.s_max / std::tan(e.alpha_deg / kDeg))
                                   : std::numeric_limits<double>::infinity();
    e.pro_margin_min = e.front_h0 + 2.0;
    return e;
}

ProfileParams wedge_profile_params(const Config& c) {
    const WedgeConfig& w = c.wedge;
    const double h0 = c.packing.h0;
    const bool backstop = experiment_of(c).backstop;
    ProfileParams pp;
    pp.column = w.column_width;
    if (experiment_of(c).push_wall) {
        // The push-wall sandbox: the layer from the moving wall's start at
        // -length h0 to the fixed end wall at 0. Its wedge rises against the
        // moving wall and falls toward the fixed end: the "retro" flank of
        // the measures (beta, the retro toe) is the push-wall wedge's surface
        // slope and front; x_S is the wall's start, so the peak's offset is
        // measured from there (docs/experiments.md "The push-wall sandbox").
        pp.x_min = -c.sandbox.length * h0;
        pp.x_max = 0.0;
        pp.h0 = h0;
        pp.x_s = pp.x_min;
        pp.toe_threshold = w.toe_threshold * h0;
        pp.retro_side = true;
        pp.backstop_margin = 0.0;
        return pp;
    }
    pp.x_min = -(w.s_max + w.pro_margin) * h0;  // the trailing end at the start
    pp.x_max = backstop ? 0.0 : w.retro_length * h0;
    pp.h0 = h0;
    pp.x_s = 0.0;
    pp.toe_threshold = w.toe_threshold * h0;
    pp.retro_side = !backstop;
    pp.backstop_margin = backstop ? 0.5 * h0 : 0.0;  // the backstop's own drag zone
    return pp;
}

double undeformed_surface(const ParticleStore& p, const ProfileParams& pp, const Config& c) {
    if (!experiment_of(c).push_wall) return undeformed_surface(p, pp);
    // The sandbox: a wedge cut to a slope stands on the bare base (0); a flat
    // layer's far half, which the push reaches last.
    if (c.sandbox.surface_slope_deg > 0.0) return 0.0;
    return mean_surface(p, 0.5 * (pp.x_min + pp.x_max), pp.x_max, pp.column);
}

double undeformed_surface(const ParticleStore& p, const ProfileParams& pp) {
    // The incoming layer away from both ends: from h0 inside the trailing
    // end to h0 before the S point.
    return mean_surface(p, pp.x_min + pp.h0, pp.x_s - pp.h0, pp.column);
}

WedgeSetup make_wedge(const Config& c, const ParticleStore& layer) {
    return make_wedge(c, layer, derive_run_numbers(c));
}

WedgeSetup make_wedge(const Config& c, const ParticleStore& layer, const RunNumbers& n) {
    const WedgeConfig& w = c.wedge;
    const double h0 = c.packing.h0;
    const bool backstop = experiment_of(c).backstop;
    const bool push_wall = experiment_of(c).push_wall;  // the sandbox
    const TimestepInfo& t = n.timestep;

    WedgeSetup ws;
    ws.pro_length = push_wall ? c.sandbox.length * h0 : (w.s_max + w.pro_margin) * h0;
    ws.retro_length = backstop ? 0.0 : w.retro_length * h0;
    Simulation& sim = ws.sim;
    sim.particles = layer;
    ParticleStore& p = sim.particles;
    // The sandbox's wedge: the layer's top cut to a slope from the wall (at x = 0 before the shift).
    if (push_wall && c.sandbox.surface_slope_deg > 0.0 && p.size() > 0)
        cut_layer_to_slope(p, h0, 0.0, c.sandbox.surface_slope_deg);
    for (std::size_t s = 0; s < p.size(); ++s) {
        p.x[s].x -= ws.pro_length;
        p.side[s] = p.x[s].x > 0.0 ? 1 : 0;
    }
    sim.params.law = make_law(c.material);
    sim.params.dt = t.dt;
    if (c.layered()) sim.materials = material_table(c);
    sim.params.gravity = {0.0, -c.numerics.gravity};
    sim.params.skin = c.numerics.skin;
    // The inertia floor (wedge.inertia_floor): light discs move with the
    // inertia of a disc of radius inertia_floor r_min; weights are unchanged.
    sim.params.m_inertia_min = inertia_floor_mass(c);
    if (c.layered()) assign_layers(c, p);  // materials, layers and masses (setup/layers.cpp)
    if (sim.params.m_inertia_min > 0.0)
        for (std::size_t s = 0; s < p.size(); ++s)
            if (!(p.flags[s] & (kFlagFixed | kFlagAsleep))) p.set_free_inertia(s, sim.params.m_inertia_min);

    const double far = 2.0 * h0;                 // bases reach beyond the end walls [m]
    const double tall = 1e3 * h0;                // end walls are effectively unbounded [m]
    const double x_pro = -ws.pro_length, x_retro = ws.retro_length;
    Wall pro_base{{x_pro - far, 0.0}, {0.0, 0.0}, {}, 0.0, false, false, 0.0};
    pro_base.open_ends = true;
    sim.walls.push_back(pro_base);
    if (backstop) {
        sim.walls.push_back({{0.0, 0.0}, {0.0, tall}, {}, 0.0, false, false, 0.0});
    } else {
        // exp3's stationary Coulomb base: a rough wall under the eq. 5
        // traction law (as before the Coulomb base existed), a smooth wall
        // with a CoulombBase at rest under the default law.
        const bool coulomb_retro = experiment_of(c).retroside == Retroside::coulomb;
        const bool rough = coulomb_retro && w.base_law == BaseLaw::traction;
        Wall retro_base{{0.0, 0.0}, {x_retro + far, 0.0}, {}, 0.0, false, rough,
                        rough ? w.mu_br_over_mu_bp * w.mu_bp : 0.0};
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
    sp.buffer_left = w.sleep_buffer_pro * h0;  // the incoming plate
    sp.buffer_right = w.sleep_buffer * h0;     // the retroside
    if (push_wall) {
        // The sandbox: every disc lies right of the wall's start and its
        // rigid motion is rest; the far layer sleeps, the discs the wall
        // moves are awake, with sleep_buffer h0 beyond the outermost of them.
        sp.x_split = x_pro;
        sp.left = false;
        sp.right = true;
    }

    std::unique_ptr<BasalBoundary> base;
    const double v_base = push_wall ? 0.0 : w.v;  // the sandbox's base is at rest
    if (w.base_law == BaseLaw::traction)
        base = std::make_unique<ConveyorTraction>(kWallProBase, v_base, w.mu_bp, w.traction_gain, w.drag_gain);
    else
        base = std::make_unique<CoulombBase>(kWallProBase, v_base, w.mu_bp);
    ws.base = base.get();
    sim.boundaries.push_back(std::move(base));
    if (experiment_of(c).retroside == Retroside::coulomb && w.base_law == BaseLaw::coulomb) {
        auto retro = std::make_unique<CoulombBase>(kWallRetro, 0.0, w.mu_br_over_mu_bp * w.mu_bp);
        ws.retro_base = retro.get();
        sim.boundaries.push_back(std::move(retro));
    }
    if (experiment_of(c).retroside == Retroside::fixed) {
        auto fixed = std::make_unique<FixedRetroside>(kWallRetro);
        ws.fixed_retro = fixed.get();
        sim.boundaries.push_back(std::move(fixed));
    }

    ws.profile = wedge_profile_params(c);
    // Undeformed surface: the incoming layer away from both ends.
    ws.profile.y_mean = undeformed_surface(p, ws.profile, c);
    add_sediment_reserve(c, ws);  // nothing without sedimentation
    return ws;
}

ParkingGrid parking_grid(const Config& c, const WedgeSetup& w) {
    ParkingGrid g;
    g.pitch = 6.0 * c.packing.r_max + 2.0 * w.sim.params.skin;
    g.x0 = -w.pro_length + 0.5 * g.pitch;
    g.y0 = -2.0 * c.packing.h0;
    g.per_row = std::max<std::uint64_t>(
        1, static_cast<std::uint64_t>(std::floor((w.pro_length + w.retro_length) / g.pitch)) - 1);
    return g;
}

std::size_t add_sediment_reserve(const Config& c, WedgeSetup& w) {
    ParticleStore& p = w.sim.particles;
    const std::size_t n = p.size();
    w.reserve_begin = static_cast<std::uint32_t>(n);
    if (!c.surface.sedimenting() || n == 0 || !(c.surface.sediment_reserve > 0.0)) return 0;
    // The layer's particles in id order (a cluster at its smallest id), and
    // the layer area of a disc: L0 π R² / Σ π R² [h0²].
    std::int32_t max_cluster = -1;
    for (std::size_t s = 0; s < n; ++s) max_cluster = std::max(max_cluster, p.cluster[s]);
    std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(max_cluster + 1));
    double solid = 0.0;
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::size_t s = p.slot_of_id[id];
        solid += kPi * p.radius[s] * p.radius[s];
        if (p.cluster[s] >= 0) members[static_cast<std::size_t>(p.cluster[s])].push_back(id);
    }
    std::vector<std::vector<std::uint32_t>> templates;
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::int32_t cl = p.cluster[p.slot_of_id[id]];
        if (cl < 0) templates.push_back({id});
        else if (members[static_cast<std::size_t>(cl)].front() == id) templates.push_back(members[static_cast<std::size_t>(cl)]);
    }
    const double layer_length = c.packing.length / c.packing.h0;  // L0 [h0]
    const bool layered = p.has_materials();
    const std::uint8_t mat = layered ? material_id(c, c.surface.sediment_material) : 0;
    const double rho = layered ? c.materials[mat].m.density : c.material.density;  // [kg/m³]
    const ParkingGrid g = parking_grid(c, w);
    double area = 0.0;
    std::int32_t next_cluster = max_cluster + 1;
    std::size_t made = 0;
    for (; area < c.surface.sediment_reserve; ++made) {
        const std::vector<std::uint32_t>& t = templates[made % templates.size()];
        Vec2 centre{0.0, 0.0};
        for (const std::uint32_t id : t) centre = centre + p.x[p.slot_of_id[id]];
        centre = centre * (1.0 / static_cast<double>(t.size()));
        const Vec2 place = g.place(made);
        const std::int32_t cluster = p.cluster[p.slot_of_id[t.front()]] >= 0 ? next_cluster++ : -1;
        for (const std::uint32_t id : t) {
            const Vec2 at = place + (p.x[p.slot_of_id[id]] - centre);
            const double r = p.radius[p.slot_of_id[id]];
            const std::size_t s = p.add(at, r, rho, cluster);
            p.fix(s);
            p.flags[s] = static_cast<std::uint8_t>(p.flags[s] | kFlagRemoved | kFlagReserve);
            if (layered) p.material[s] = mat;
            area += layer_length * kPi * r * r / solid;
        }
    }
    return made;
}

}  // namespace orodem
