#include "orodem/setup/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/coulomb_base.hpp"
#include "orodem/setup/layers.hpp"
#include "orodem/setup/wedge.hpp"
#include "orodem/boundary/servo_wall.hpp"
#include "orodem/core/error.hpp"
#include "orodem/core/angles.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"

namespace orodem {

namespace {


void say(const CalibrationLog& log, const std::string& line) {
    if (log) log(line);
}

/// An infinite smooth wall through a in direction dir.
Wall line_wall(Vec2 a, Vec2 dir) {
    Wall w;
    w.a = a;
    w.b = a + dir;
    w.infinite = true;
    return w;
}

LawParams material_law(const Config& c, double mu) {
    MaterialConfig m = c.material;
    m.mu = mu;
    return make_law(m);
}

double total_mass(const ParticleStore& p) {
    double m = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (!(p.flags[i] & kFlagFixed)) m += p.mass[i];
    return m;
}

double rms_speed(const Simulation& sim) {
    const double m = total_mass(sim.particles);
    return m > 0.0 ? std::sqrt(2.0 * sim.kinetic_energy() / m) : 0.0;
}

void require_finite(const Simulation& sim, const std::string& what) {
    const double ke = sim.kinetic_energy();
    if (!std::isfinite(ke))
        throw InstabilityError(fmt::format("{} went unstable at step {} (kinetic energy {}); reduce "
                                           "numerics.safety or material.k_n",
                                           what, sim.step_count, ke));
}

/// Sums the conveyor's total traction every step (after it was applied), for interval means.
class TractionMeter : public Boundary {
public:
    explicit TractionMeter(const BasalBoundary& c) : conveyor_(c) {}
    std::string_view name() const override { return "traction-meter"; }
    ForceHook force_hook() const override { return ForceHook::none; }
    void after_step(Simulation&) override {
        sum_ += conveyor_.total_traction();
        ++n_;
    }
    double take_mean() {
        const double m = n_ ? sum_ / static_cast<double>(n_) : 0.0;
        sum_ = 0.0;
        n_ = 0;
        return m;
    }

private:
    const BasalBoundary& conveyor_;
    double sum_ = 0.0;
    std::uint64_t n_ = 0;
};

std::uint64_t steps_for(double time, double dt) {
    return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(time / dt)));
}

}  // namespace

double mean_disc_diameter(const Config& c) { return c.packing.r_min + c.packing.r_max; }

// ------------------------------------------------------------------ biaxial

double BiaxialSample::width() const { return sim.walls[kBoxRight].a.x - sim.walls[kBoxLeft].a.x; }
double BiaxialSample::height() const { return sim.walls[kBoxTop].a.y - sim.walls[kBoxBottom].a.y; }
double BiaxialSample::solid_fraction() const {
    double a = 0.0;
    for (double r : sim.particles.radius) a += std::numbers::pi * r * r;
    return a / (width() * height());
}

BiaxialSample make_biaxial_sample(const Config& c, PackingKind kind, double mu) {
    const CalibrateConfig& k = c.calibrate;
    // The compaction shrinks both sides at the same strain rate, so the loose
    // packing must already have the sample's aspect ratio: a trial packing
    // gives the loose lattice's solid fraction φ_l, then the packing is made
    // sqrt(φ_c/φ_l) times wider with the disc area of a k.width × k.height
    // sample at φ_c (generate_packing makes disc area 0.9 L (h0 + 3 r_max)).
    constexpr double phi_c = 0.82;  // solid fraction after compaction, about [-]
    PackingConfig pc = c.packing;
    pc.kind = kind;
    pc.length = k.width;
    pc.h0 = std::max(pc.r_max, phi_c * k.height / 0.9 - 3.0 * pc.r_max);
    const auto fraction = [](const ParticleStore& p, double length) {
        double area = 0.0, top = 0.0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            area += std::numbers::pi * p.radius[i] * p.radius[i];
            top = std::max(top, p.x[i].y + p.radius[i]);
        }
        return area / (length * top);
    };
    const double phi_l = fraction(generate_packing(pc, c.material.density), pc.length);
    pc.length = k.width * std::sqrt(phi_c / phi_l);
    pc.h0 = std::max(pc.r_max, phi_c * k.width * k.height / (0.9 * pc.length) - 3.0 * pc.r_max);
    BiaxialSample s;
    s.mu = mu;
    Simulation& sim = s.sim;
    sim.particles = generate_packing(pc, c.material.density);
    // Compaction friction: the tested μ, or calibrate.compaction_mu (0: the densest sample).
    const double mu_compact = c.calibrate.compaction_mu >= 0.0 ? c.calibrate.compaction_mu : mu;
    sim.params.law = with_damping_ratio(material_law(c, mu_compact), c.packing.settle_damping_ratio);
    if (!c.calibrate.material.empty()) {  // a named material: its own law, weakening and cohesion (setup/layers.hpp)
        sim.materials = with_damping_ratio(material_table(c), c.packing.settle_damping_ratio);
        if (c.calibrate.compaction_mu >= 0.0)
            for (PairLaw& pl : sim.materials.pairs) pl.law.mu = pl.mu_residual = c.calibrate.compaction_mu;
        assign_material(c, sim.particles, c.calibrate.material);
    }
    sim.params.dt = timestep_for(c).dt;
    sim.params.gravity = {0.0, 0.0};
    sim.params.skin = c.numerics.skin;
    double top = 0.0;
    for (std::size_t i = 0; i < sim.particles.size(); ++i)
        top = std::max(top, sim.particles.x[i].y + sim.particles.radius[i]);
    sim.walls.push_back(line_wall({0.0, 0.0}, {1.0, 0.0}));       // bottom
    sim.walls.push_back(line_wall({0.0, top}, {1.0, 0.0}));       // top
    sim.walls.push_back(line_wall({0.0, 0.0}, {0.0, 1.0}));       // left
    sim.walls.push_back(line_wall({pc.length, 0.0}, {0.0, 1.0})); // right
    std::vector<BoxSide> sides = {{kBoxBottom, {0.0, -1.0}, kBoxLeft, kBoxRight},
                                  {kBoxTop, {0.0, 1.0}, kBoxLeft, kBoxRight},
                                  {kBoxLeft, {-1.0, 0.0}, kBoxBottom, kBoxTop},
                                  {kBoxRight, {1.0, 0.0}, kBoxBottom, kBoxTop}};
    auto servo = std::make_unique<ServoWalls>(std::move(sides), k.servo_gain);
    s.servo = servo.get();
    sim.boundaries.push_back(std::move(servo));
    sim.initialize();
    return s;
}

CompactionResult compact_biaxial(BiaxialSample& s, const Config& c, const CalibrationLog& log) {
    const CalibrateConfig& k = c.calibrate;
    Simulation& sim = s.sim;
    const double sigma = k.confining_stress;
    // Free travel and compaction at strain rates up to 5 ε̇ on both sides
    // (the servo slows the walls as the stress approaches the target); at
    // rest means slower than the shear's fluctuations, ε̇ d.
    const double rate = 5.0 * k.strain_rate;
    const double v_rest = k.strain_rate * mean_disc_diameter(c);
    s.servo->set_servo(kBoxTop, sigma, rate * s.height());
    s.servo->set_servo(kBoxRight, sigma, rate * s.width());
    const std::uint64_t chunk = 500;
    const std::uint64_t first = sim.step_count;
    CompactionResult r;
    std::uint64_t next_log = 0;
    for (;;) {
        s.servo->reset_means();
        sim.advance(chunk);
        require_finite(sim, "compaction");
        r.steps = sim.step_count - first;
        r.sigma_top = s.servo->mean_stress(kBoxTop);
        r.sigma_right = s.servo->mean_stress(kBoxRight);
        s.servo->set_servo(kBoxTop, sigma, rate * s.height());  // the speed limits follow the sample
        s.servo->set_servo(kBoxRight, sigma, rate * s.width());
        r.v_rms = rms_speed(sim);
        const double e_top = std::fabs(r.sigma_top / sigma - 1.0), e_right = std::fabs(r.sigma_right / sigma - 1.0);
        if (r.steps >= next_log) {
            say(log, fmt::format("  compaction step {}: σ_top/σ_3 = {:.4f}, σ_right/σ_3 = {:.4f}, v_rms = {:.3g} m/s, "
                                 "box {:.4g} x {:.4g} m",
                                 r.steps, r.sigma_top / sigma, r.sigma_right / sigma, r.v_rms, s.width(),
                                 s.height()));
            next_log += 20 * chunk;
        }
        if (e_top < k.servo_tolerance && e_right < k.servo_tolerance && r.v_rms < v_rest) break;
        if (static_cast<std::int64_t>(r.steps) >= c.packing.settle_max_steps)
            throw InstabilityError(fmt::format(
                "the biaxial sample did not reach σ_3 = {:g} Pa at rest within packing.settle_max_steps = {} steps "
                "(σ_top/σ_3 = {:.4f}, σ_right/σ_3 = {:.4f}, v_rms = {:.3g} m/s, wanted < {:.3g}); raise "
                "packing.settle_max_steps or calibrate.servo_tolerance",
                sigma, c.packing.settle_max_steps, r.sigma_top / sigma, r.sigma_right / sigma, r.v_rms, v_rest));
    }
    for (std::size_t side = 0; side < 4; ++side) {
        s.servo->clear_servo(side);
        sim.walls[side].velocity = {};
    }
    return r;
}

BiaxialResult shear_biaxial(BiaxialSample& s, const Config& c, const CalibrationLog& log) {
    const CalibrateConfig& k = c.calibrate;
    Simulation& sim = s.sim;
    ServoWalls& servo = *s.servo;
    BiaxialResult res;
    res.mu = s.mu;
    res.discs = sim.particles.size();
    res.strain_rate = k.strain_rate;
    res.inertial_number =
        k.strain_rate * mean_disc_diameter(c) * std::sqrt(c.material.density / k.confining_stress);
    res.width0 = s.width();
    res.height0 = s.height();
    res.solid_fraction0 = s.solid_fraction();
    const double W0 = res.width0, H0 = res.height0, A0 = W0 * H0;

    // The material's own damping from here on; initialize() refreshes the
    // walls' laws and keeps every contact's history.
    sim.params.law = material_law(c, res.mu);
    if (sim.has_materials()) {
        // The material's own damping, and a fresh material: the compaction's sliding is not damage.
        sim.materials = material_table(c);
        sim.reset_material_state();
    }
    sim.initialize();
    const double sigma3 = k.confining_stress;
    sim.walls[kBoxTop].velocity = {0.0, -k.strain_rate * H0};
    const double v_max = k.strain_rate * (H0 + W0);
    servo.set_servo(kBoxLeft, sigma3, v_max);
    servo.set_servo(kBoxRight, sigma3, v_max);

    const std::uint64_t per_row = steps_for(k.output_strain / k.strain_rate, sim.params.dt);
    const std::uint64_t first = sim.step_count;
    const double t_end = k.max_strain / k.strain_rate;  // simulated shearing time [s]
    double eps_a_prev = 0.0, eps_v_prev = 0.0;
    double next_log = 0.1;
    double err_sum = 0.0;
    servo.reset_means();
    while (static_cast<double>(sim.step_count - first) * sim.params.dt < t_end - 0.5 * sim.params.dt) {
        sim.advance(per_row);
        require_finite(sim, "the biaxial test");
        BiaxialRow row;
        row.width = s.width();
        row.height = s.height();
        const double eps_a = (H0 - row.height) / H0, eps_v = (row.width * row.height - A0) / A0;
        // Stresses are means over the interval; strains at its middle.
        row.axial_strain = 0.5 * (eps_a_prev + eps_a);
        row.volumetric_strain = 0.5 * (eps_v_prev + eps_v);
        eps_a_prev = eps_a;
        eps_v_prev = eps_v;
        row.sigma1_top = servo.mean_stress(kBoxTop);
        row.sigma1_bottom = servo.mean_stress(kBoxBottom);
        row.sigma3_left = servo.mean_stress(kBoxLeft);
        row.sigma3_right = servo.mean_stress(kBoxRight);
        servo.reset_means();
        row.sigma1 = 0.5 * (row.sigma1_top + row.sigma1_bottom);
        row.sigma3 = 0.5 * (row.sigma3_left + row.sigma3_right);
        row.stress_ratio = (row.sigma1 - row.sigma3) / (row.sigma1 + row.sigma3);
        row.phi_deg = mobilized_friction_deg(row.sigma1, row.sigma3);
        row.kinetic_energy = sim.kinetic_energy();
        row.contacts = sim.touching_contacts();
        const double err = std::fabs(row.sigma3 / sigma3 - 1.0);
        err_sum += err;
        res.sigma3_max_error = std::max(res.sigma3_max_error, err);
        res.rows.push_back(row);
        if (eps_a >= next_log - 1e-12) {
            say(log, fmt::format("  ε_a = {:.3f}: φ_mob = {:.2f}°, σ3/σ_3 = {:.4f}, ε_v = {:+.4f}", eps_a,
                                 row.phi_deg, row.sigma3 / sigma3, eps_v));
            next_log += 0.1;
        }
    }
    res.shear_steps = sim.step_count - first;
    res.sigma3_mean_error = res.rows.empty() ? 0.0 : err_sum / static_cast<double>(res.rows.size());
    std::vector<double> ea, phi;
    for (const BiaxialRow& r : res.rows) {
        ea.push_back(r.axial_strain);
        phi.push_back(r.phi_deg);
        if (r.phi_deg > res.phi_peak_deg) {
            res.phi_peak_deg = r.phi_deg;
            res.strain_at_peak = r.axial_strain;
        }
    }
    res.phi_cs = window_stats(ea, phi, k.critical_from, k.max_strain);
    res.volumetric_strain_end = eps_v_prev;
    return res;
}

BiaxialResult run_biaxial(const Config& c, PackingKind kind, double mu, const CalibrationLog& log) {
    BiaxialSample s = make_biaxial_sample(c, kind, mu);
    say(log, fmt::format("biaxial {} μ_i = {:g}: {} discs, loose box {:.4g} x {:.4g} m", name_of(kind), mu,
                         s.sim.particles.size(), s.width(), s.height()));
    const CompactionResult comp = compact_biaxial(s, c, log);
    say(log, fmt::format("  compacted in {} steps to {:.4g} x {:.4g} m, solid fraction {:.4f}", comp.steps,
                         s.width(), s.height(), s.solid_fraction()));
    BiaxialResult r = shear_biaxial(s, c, log);
    r.kind = kind;
    r.compaction_steps = comp.steps;
    say(log, fmt::format("  φ_peak = {:.2f}° at ε_a = {:.3f}, φ_cs = {:.2f} ± {:.2f}°, σ3 error mean {:.2f}% max "
                         "{:.2f}%",
                         r.phi_peak_deg, r.strain_at_peak, r.phi_cs.mean, r.phi_cs.sd, 100.0 * r.sigma3_mean_error,
                         100.0 * r.sigma3_max_error));
    return r;
}

// ----------------------------------------------------------- basal friction

ParticleStore settled_block(const Config& c, PackingKind kind, double mu, double length, double height,
                            const CalibrationLog& log) {
    Config cc = c;
    cc.packing.kind = kind;
    cc.material.mu = mu;
    cc.packing.length = length;
    cc.packing.h0 = height;
    Simulation sim = make_settle_simulation(cc);
    sim.initialize();
    const SettleProgress done = settle(sim, cc.packing, cc.run.output_interval, {});
    const std::size_t before = sim.particles.size();
    cut_layer(sim.particles, height);
    say(log, fmt::format("  settled {} discs ({}, {:.4g} x {:.4g} m) in {} steps; {} kept after the cut", before,
                         name_of(kind), length, height, done.step, sim.particles.size()));
    return std::move(sim.particles);
}

BasalResult run_basal_block(const Config& c, ParticleStore block, double mu, double mu_bp,
                            const CalibrationLog& log) {
    const CalibrateConfig& k = c.calibrate;
    const TimestepInfo t = timestep_for(c);
    const bool traction_law = k.base_law == BaseLaw::traction;
    const double v_limit = lightest_mass(c) * c.numerics.gravity / (c.material.k_n * t.dt);  // eq. 6
    if (traction_law && !(k.belt_speed < v_limit))
        throw ConfigError(fmt::format("{}: key 'calibrate.belt_speed' = {:g}: must satisfy eq. 6, v' < m g / (k_n dt) "
                                      "= {:g} m/s; lower it or material.k_n",
                                      c.path, k.belt_speed, v_limit));
    check_base_dashpot(c);
    BasalResult res;
    res.mu = mu;
    res.mu_bp = mu_bp;
    Simulation sim;
    sim.particles = std::move(block);
    if (c.layered()) {  // a layered block: [[layers]] in fractions of the block's height (setup/layers.hpp)
        assign_layers(c, sim.particles, k.block_height);
        sim.materials = material_table(c);
    }
    const ParticleStore& p = sim.particles;
    res.discs = p.size();
    sim.params.law = material_law(c, mu);
    sim.params.dt = t.dt;
    sim.params.gravity = {0.0, -c.numerics.gravity};
    sim.params.skin = c.numerics.skin;
    double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_hi = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        x_lo = std::min(x_lo, p.x[i].x - p.radius[i]);
        x_hi = std::max(x_hi, p.x[i].x + p.radius[i]);
        y_hi = std::max(y_hi, p.x[i].y + p.radius[i]);
    }
    res.block_length = x_hi - x_lo;
    res.block_height = y_hi;
    res.weight = total_mass(p) * c.numerics.gravity;
    // walls[0]: the base, its direction +x (the belt moves toward the
    // holding wall); walls[1]: the holding wall at the block's right end;
    // walls[2]: the back wall at its left end.
    sim.walls.push_back(line_wall({x_lo - 10.0, 0.0}, {1.0, 0.0}));
    sim.walls.push_back(line_wall({x_hi, 0.0}, {0.0, 1.0}));
    sim.walls.push_back(line_wall({x_lo, 0.0}, {0.0, 1.0}));
    std::unique_ptr<BasalBoundary> base;
    if (traction_law)
        base = std::make_unique<ConveyorTraction>(0, k.belt_speed, mu_bp, k.traction_gain);
    else
        base = std::make_unique<CoulombBase>(0, k.belt_speed, mu_bp);
    BasalBoundary& conveyor = *base;
    sim.boundaries.push_back(std::move(base));
    auto meter_box = std::make_unique<ServoWalls>(  // measured only, no servo
        std::vector<BoxSide>{{1, {1.0, 0.0}}, {0, {0.0, -1.0}}, {2, {-1.0, 0.0}}}, 0.5);
    ServoWalls& meter = *meter_box;
    sim.boundaries.push_back(std::move(meter_box));
    auto traction_box = std::make_unique<TractionMeter>(conveyor);
    TractionMeter& traction = *traction_box;
    sim.boundaries.push_back(std::move(traction_box));
    sim.initialize();

    const std::uint64_t per_row = steps_for(c.run.output_interval, t.dt);
    const std::uint64_t total = steps_for(k.duration, t.dt);
    std::vector<double> times, mus, walls, slide;
    while (sim.step_count < total) {
        meter.reset_means();
        traction.take_mean();
        sim.advance(std::min(per_row, total - sim.step_count));
        require_finite(sim, "the basal friction test");
        BasalRow row;
        row.time = sim.time;
        row.holding_force = meter.mean_stress(0);
        row.base_normal = meter.mean_stress(1);
        row.back_force = meter.mean_stress(2);
        row.traction = traction.take_mean();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        row.mu_eff = row.base_normal > 0.0 ? row.traction / row.base_normal : nan;
        row.mu_walls = row.base_normal > 0.0 ? (row.holding_force - row.back_force) / row.base_normal : nan;
        row.on_base = conveyor.discs_on_base();
        row.sliding = conveyor.discs_sliding();
        res.rows.push_back(row);
        times.push_back(row.time);
        mus.push_back(row.mu_eff);
        walls.push_back(row.mu_walls);
        slide.push_back(row.on_base ? static_cast<double>(row.sliding) / static_cast<double>(row.on_base) : 0.0);
    }
    const double from = k.measure_from * k.duration;
    res.mu_eff = window_stats(times, mus, from, k.duration + 1.0);
    res.mu_walls = window_stats(times, walls, from, k.duration + 1.0);
    res.phi_eff_deg = std::atan(res.mu_eff.mean) * kDeg;
    res.sliding_fraction = window_stats(times, slide, from, k.duration + 1.0).mean;
    // Traction law: can every base disc reach the cap at rest? γ_b v' / (μ_bp N)
    // per disc, the smallest (NaN for the Coulomb base, which has no such limit).
    double worst = traction_law ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
    const WallContactStore& ws = sim.wall_contacts;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::uint32_t q = ws.begin[i]; q < ws.begin[i + 1]; ++q)
            if (traction_law && ws.wall[q] == 0 && ws.f[q].y > 0.0 && mu_bp > 0.0)
                worst = std::min(worst, k.traction_gain * p.mass[i] / t.dt * k.belt_speed / (mu_bp * ws.f[q].y));
    res.traction_limit_ratio = worst;
    say(log, fmt::format("  μ_bp = {:g}: μ_eff = {:.4f} ± {:.4f} (φ_b = {:.2f}°; walls {:.4f} ± {:.4f}), sliding "
                         "fraction {:.3f}, min γ_b v'/(μ_bp N) = {:.3g}",
                         mu_bp, res.mu_eff.mean, res.mu_eff.sd, res.phi_eff_deg, res.mu_walls.mean, res.mu_walls.sd,
                         res.sliding_fraction, worst));
    return res;
}

BasalResult run_basal_friction(const Config& c, PackingKind kind, double mu_bp, const CalibrationLog& log) {
    const CalibrateConfig& k = c.calibrate;
    say(log, fmt::format("basal friction {} μ_i = {:g}, μ_bp = {:g}: block {:g} x {:g} m, belt {:g} m/s", name_of(kind),
                         c.material.mu, mu_bp, k.block_length, k.block_height, k.belt_speed));
    ParticleStore block = settled_block(c, kind, c.material.mu, k.block_length, k.block_height, log);
    BasalResult r = run_basal_block(c, std::move(block), c.material.mu, mu_bp, log);
    r.kind = kind;
    return r;
}

// ------------------------------------------------------------------- repose

ReposeResult run_repose(const Config& c, PackingKind kind, double mu, const CalibrationLog& log) {
    const CalibrateConfig& k = c.calibrate;
    const double w = k.column_width, H = k.column_height, rf = c.packing.r_max;
    say(log, fmt::format("repose {} μ_i = {:g}: column {:g} x {:g} m, walls rise at {:g} m/s", name_of(kind), mu, w, H,
                         k.lift_speed));
    ParticleStore p = settled_block(c, kind, mu, w, H, log);
    ReposeResult res;
    res.kind = kind;
    res.mu = mu;
    res.discs = p.size();
    for (std::size_t i = 0; i < p.size(); ++i) {
        p.x[i].x -= 0.5 * w;
        p.x[i].y += 2.0 * rf;  // on top of the floor discs
    }
    // The floor: touching fixed discs of radius r_max, long enough for a heap
    // as flat as 5° from the column's area, and end walls beyond it.
    const double runout = std::sqrt(w * H / std::tan(5.0 / kDeg));
    const int half = static_cast<int>(std::ceil((0.5 * w + runout) / (2.0 * rf)));
    for (int j = -half; j < half; ++j) {
        const std::size_t s = p.add({(2.0 * j + 1.0) * rf, rf}, rf, c.material.density);
        p.fix(s);
    }
    const double x_end = 2.0 * half * rf;
    Simulation sim;
    sim.particles = std::move(p);
    sim.params.law = material_law(c, mu);
    const TimestepInfo t = timestep_for(c);
    sim.params.dt = t.dt;
    sim.params.gravity = {0.0, -c.numerics.gravity};
    sim.params.skin = c.numerics.skin;
    double top = 0.0;
    for (std::size_t i = 0; i < sim.particles.size(); ++i)
        top = std::max(top, sim.particles.x[i].y + sim.particles.radius[i]);
    // walls 0, 1: the column's sides, rising from the floor discs' tops (a
    // floor disc's centre may lie on the side's line); 2, 3: the ends of the floor.
    for (double x : {-0.5 * w, 0.5 * w}) {
        Wall side;
        side.a = {x, 2.0 * rf};
        side.b = {x, top + 2.0 * H};
        side.velocity = {0.0, k.lift_speed};
        sim.walls.push_back(side);
    }
    sim.walls.push_back(line_wall({-x_end, 0.0}, {0.0, 1.0}));
    sim.walls.push_back(line_wall({x_end, 0.0}, {0.0, 1.0}));
    sim.initialize();

    const double m_total = total_mass(sim.particles);
    const double e_ref = m_total * c.numerics.gravity * H;
    const std::uint64_t chunk = steps_for(c.run.output_interval, t.dt);
    bool lifted = false;
    for (;;) {
        sim.advance(chunk);
        require_finite(sim, "the repose test");
        const ParticleStore& q = sim.particles;
        if (!lifted) {
            double heap_top = 0.0;
            for (std::size_t i = 0; i < q.size(); ++i) heap_top = std::max(heap_top, q.x[i].y + q.radius[i]);
            if (sim.walls[0].a.y > heap_top + rf) {  // clear of every disc: stop them
                lifted = true;
                sim.walls[0].velocity = sim.walls[1].velocity = {};
                say(log, fmt::format("  walls clear of the heap at t = {:.3g} s", sim.time));
            }
        }
        const double ke = sim.kinetic_energy();
        if (lifted && ke < c.packing.settle_ke_ratio * e_ref) break;
        if (static_cast<std::int64_t>(sim.step_count) >= c.packing.settle_max_steps)
            throw InstabilityError(fmt::format(
                "the heap did not come to rest within packing.settle_max_steps = {} steps (E_kin/(M g H) = {:.3g}, "
                "wanted < {:.3g}); raise packing.settle_max_steps or packing.settle_ke_ratio",
                c.packing.settle_max_steps, ke / e_ref, c.packing.settle_ke_ratio));
    }
    res.time = sim.time;
    res.steps = sim.step_count;
    res.profile = heap_profile(sim.particles, 2.0 * rf, -x_end, x_end, 2.0 * c.packing.r_max);
    res.fit = fit_repose(res.profile, k.fit_from, k.fit_to);
    say(log, fmt::format("  at rest at t = {:.3g} s: heap {:.4g} m high; repose angle {:.2f}° (left {:.2f}°, right "
                         "{:.2f}°; {} + {} surface points)",
                         res.time, res.profile.height, res.fit.angle_deg, res.fit.angle_left_deg,
                         res.fit.angle_right_deg, res.fit.left.n, res.fit.right.n));
    return res;
}

void check_calibration_size(const Config& c) {
    const CalibrateConfig& k = c.calibrate;
    const std::string& e = c.run.experiment;
    const double length = e == "biaxial" ? k.width : e == "basal-friction" ? k.block_length : k.column_width;
    const double height = e == "biaxial" ? k.height : e == "basal-friction" ? k.block_height : k.column_height;
    for (PackingKind kind : k.kinds) calibration_sample(c, kind, length, height);
}

PackingConfig calibration_sample(const Config& c, PackingKind kind, double length, double height) {
    PackingConfig pc = c.packing;
    pc.kind = kind;
    pc.length = length;
    pc.h0 = height;
    check_disc_budget(c, pc, "the calibration sample",
                      "the [calibrate] sizes (width/height, block_length/block_height, column_width/column_height)");
    return pc;
}

}  // namespace orodem
