// orodem calibrate CONFIG: the calibration experiments of setup/calibration.hpp
// (biaxial, basal-friction, repose), one test per packing kind and swept
// value, into a new run directory: config.toml, log.txt, one CSV per test, a
// summary CSV, PNG plots and report.md (tables, parameters, commands, plots).
// The run-directory contract is that of orodem run: a given --out must be
// absent or empty (else exit 2), and every file is written atomically.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/angles.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/render/calibration_plots.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/setup/calibration.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"

#include "commands.hpp"

namespace fs = std::filesystem;
namespace orodem {

namespace {

Config load_calibration(const CommonArgs& a) {
    Config c = load(a);
    if (!is_calibration(c))
        throw ConfigError(fmt::format("{}: run.experiment = \"{}\" is not a calibration experiment; orodem calibrate "
                                      "runs \"biaxial\", \"basal-friction\" or \"repose\" (orodem run runs the others)",
                                      c.path, c.run.experiment));
    timestep_for(c);  // refuses a numerics.dt above the stability limit
    check_calibration_size(c);
    return c;
}

std::string num(double v) { return fmt::format("{:.6g}", v); }

/// "discs-mu0.3": a file-name part for one test.
std::string tag(PackingKind kind, const char* what, double value) {
    return fmt::format("{}-{}{:g}", kind, what, value);
}

std::string command_line(const CommonArgs& a, const std::string& dir) {
    std::string s = "orodem calibrate " + a.config;
    for (const auto& set : a.sets) s += " --set " + set;
    if (a.threads >= 0) s += fmt::format(" --threads {}", a.threads);
    return s + " --out " + dir;
}

std::string material_lines(const Config& c) {
    const MaterialConfig& m = c.material;
    const PackingConfig& p = c.packing;
    const TimestepInfo t = timestep_for(c);
    std::string s;
    s += fmt::format("- material: ρ = {:g} kg/m³, k_n = {:g} N/m, k_s/k_n = {:.4g}, damping {} {:g} (normal), {:g} "
                     "(tangential), cohesion {:g} N\n",
                     m.density, m.k_n, m.k_s_over_k_n, m.damping_kind, m.damping_normal, m.damping_tangential,
                     m.cohesion);
    s += fmt::format("- discs: radii uniform in [{:g}, {:g}] m, packing seed {}; clusters are three touching "
                     "discs bonded rigidly\n",
                     p.r_min, p.r_max, p.seed);
    s += fmt::format("- preparation: settling/compaction damping ratio {:g}, at rest when E_kin < {:g} M g H, at "
                     "most {} steps\n",
                     p.settle_damping_ratio, p.settle_ke_ratio, p.settle_max_steps);
    s += fmt::format("- timestep dt = {:.6g} s (stability limit {:.6g} s, margin {:.2f}x)\n", t.dt, t.dt_crit,
                     t.margin());
    return s;
}

struct Timer {
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
};

// ------------------------------------------------------------------ biaxial

void report_biaxial(const Config& c, const std::vector<BiaxialResult>& res, const std::vector<double>& secs,
                    const std::string& dir, std::string& md) {
    const CalibrateConfig& k = c.calibrate;
    // One CSV per test, one summary.
    std::vector<std::string> files;
    for (const BiaxialResult& r : res) {
        std::string csv = "axial_strain,volumetric_strain,sigma1,sigma3,sigma1_top,sigma1_bottom,sigma3_left,"
                          "sigma3_right,stress_ratio,phi_deg,width,height,kinetic_energy,contacts\n";
        for (const BiaxialRow& w : r.rows)
            csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", num(w.axial_strain),
                               num(w.volumetric_strain), num(w.sigma1), num(w.sigma3), num(w.sigma1_top),
                               num(w.sigma1_bottom), num(w.sigma3_left), num(w.sigma3_right), num(w.stress_ratio),
                               num(w.phi_deg), num(w.width), num(w.height), num(w.kinetic_energy), w.contacts);
        const std::string name = "biaxial-" + tag(r.kind, "mu", r.mu) + ".csv";
        write_file_atomic(dir + "/" + name, csv);
        files.push_back(name);
    }
    std::string sum = "kind,mu,phi_peak_deg,axial_strain_at_peak,phi_cs_deg,phi_cs_sd_deg,phi_cs_rows,"
                      "volumetric_strain_end,solid_fraction0,width0,height0,discs,strain_rate,inertial_number,"
                      "sigma3_mean_error,sigma3_max_error,compaction_steps,shear_steps,wall_seconds\n";
    for (std::size_t i = 0; i < res.size(); ++i) {
        const BiaxialResult& r = res[i];
        sum += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.kind, num(r.mu),
                           num(r.phi_peak_deg), num(r.strain_at_peak), num(r.phi_cs.mean), num(r.phi_cs.sd),
                           r.phi_cs.n, num(r.volumetric_strain_end), num(r.solid_fraction0), num(r.width0),
                           num(r.height0), r.discs, num(r.strain_rate), num(r.inertial_number),
                           num(r.sigma3_mean_error), num(r.sigma3_max_error), r.compaction_steps, r.shear_steps,
                           fmt::format("{:.1f}", secs[i]));
    }
    write_file_atomic(dir + "/biaxial.csv", sum);

    // Plots: per kind, the stress ratio and the volumetric strain against ε_a, one colour per μ_i.
    std::vector<PlotPanel> panels;
    for (PackingKind kind : k.kinds) {
        PlotPanel ratio{fmt::format("Stress ratio, {}", kind), "axial strain ε_a",
                        "(σ1 − σ3)/(σ1 + σ3) = sin φ_mob", {}};
        PlotPanel vol{fmt::format("Volumetric strain, {}", kind), "axial strain ε_a",
                      "ε_v = ΔA/A0 (dilation > 0)", {}};
        for (const BiaxialResult& r : res) {
            if (r.kind != kind) continue;
            int col = 0;
            for (std::size_t m = 0; m < k.mu_values.size(); ++m)
                if (k.mu_values[m] == r.mu) col = static_cast<int>(m);
            PlotCurve a{{}, {}, fmt::format("μ_i = {:g}", r.mu), col, false, false};
            PlotCurve b = a;
            for (const BiaxialRow& w : r.rows) {
                a.x.push_back(w.axial_strain);
                a.y.push_back(w.stress_ratio);
                b.x.push_back(w.axial_strain);
                b.y.push_back(w.volumetric_strain);
            }
            ratio.curves.push_back(std::move(a));
            vol.curves.push_back(std::move(b));
        }
        panels.push_back(std::move(ratio));
        panels.push_back(std::move(vol));
    }
    plot_panels(panels, 2, "Biaxial tests: σ_3 held by servo walls, gravity-free", dir + "/biaxial.png");
    // Friction angles against μ_i.
    PlotPanel angles{"Friction angles against contact friction", "μ_i", "angle (°)", {}};
    int col = 0;
    for (PackingKind kind : k.kinds) {
        PlotCurve peak{{}, {}, fmt::format("{} peak", kind), col, false, false}, cs{{}, {}, fmt::format("{} critical state", kind), col, true,
                                                                       false};
        for (const BiaxialResult& r : res)
            if (r.kind == kind) {
                peak.x.push_back(r.mu), peak.y.push_back(r.phi_peak_deg);
                cs.x.push_back(r.mu), cs.y.push_back(r.phi_cs.mean);
            }
        angles.curves.push_back(std::move(peak));
        angles.curves.push_back(std::move(cs));
        ++col;
    }
    plot_panels({angles}, 1, "", dir + "/biaxial-angles.png", 900);

    md += "## Results\n\n";
    md += "| packing | μ_i | φ_peak (°) | ε_a at peak | φ_cs (°) | spread ± (°) | tan φ_peak | tan φ_cs | ε_v at end "
          "| solid fraction | discs | σ_3 error mean / max | wall time (s) |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < res.size(); ++i) {
        const BiaxialResult& r = res[i];
        md += fmt::format("| {} | {:g} | {:.1f} | {:.3f} | {:.1f} | {:.1f} | {:.3f} | {:.3f} | {:+.3f} | {:.3f} | {} "
                          "| {:.1f}% / {:.1f}% | {:.0f} |\n",
                          r.kind, r.mu, r.phi_peak_deg, r.strain_at_peak, r.phi_cs.mean, r.phi_cs.sd,
                          std::tan(r.phi_peak_deg / kDeg), std::tan(r.phi_cs.mean / kDeg), r.volumetric_strain_end,
                          r.solid_fraction0, r.discs, 100.0 * r.sigma3_mean_error, 100.0 * r.sigma3_max_error,
                          secs[i]);
    }
    md += fmt::format("\nφ_peak: the largest mobilized friction angle sin φ = (σ1 − σ3)/(σ1 + σ3) over the rows; "
                      "φ_cs: the mean over axial strain {:g}–{:g}, ± its standard deviation over those rows. "
                      "Solid fraction after the compaction; σ_3 error: |σ3/σ_3 − 1| over the rows.\n\n",
                      k.critical_from, k.max_strain);
    md += "![Stress ratio and volumetric strain against axial strain](biaxial.png)\n\n";
    md += "![Peak and critical-state friction angles against μ_i](biaxial-angles.png)\n\n";
    md += "## Parameters\n\n";
    md += material_lines(c);
    const double d = mean_disc_diameter(c);
    md += fmt::format("- sample: about {:g} m wide and {:g} m high after compaction (each test's size in "
                      "biaxial.csv), gravity 0, four smooth walls\n",
                      k.width, k.height);
    md += fmt::format("- confining stress σ_3 = {:g} Pa (also the isotropic compaction stress); servo α = {:g}, "
                      "compaction ends within {:g}% of σ_3\n",
                      k.confining_stress, k.servo_gain, 100.0 * k.servo_tolerance);
    md += fmt::format("- axial strain rate ε̇ = {:.4g} 1/s to ε_a = {:g}; inertial number I = ε̇ d sqrt(ρ/σ_3) = "
                      "{:.3g} with d = r_min + r_max = {:g} m (limit {:g}; a cluster is about twice as large, "
                      "so its I is about twice this)\n",
                      k.strain_rate, k.max_strain, k.strain_rate * d * std::sqrt(c.material.density /
                                                                                   k.confining_stress),
                      d, k.max_inertial_number);
    md += fmt::format("- rows every Δε_a = {:g} (stresses are means over every step of the interval)\n\n",
                      k.output_strain);
    md += "## Method\n\n"
          "A loose packing is generated in a box of four smooth infinite walls with gravity 0. The top and right "
          "walls are servo-controlled (wall speed = α L (σ − σ_3)/(k_n N_c dt), clamped) until both stresses are "
          "within the tolerance of σ_3 and the r.m.s. disc speed is below ε̇ d. Then the material's damping is "
          "restored, the top wall moves down at ε̇ H0 with the bottom fixed, and both side walls are servo-"
          "controlled to σ_3. σ1 is the mean of the top and bottom wall stresses, σ3 that of the side walls, each "
          "the wall force over the current side length.\n\n";
    md += "## Files\n\n";
    md += "- [biaxial.csv](biaxial.csv): one row per test (the table above, with more columns)\n";
    for (const auto& f : files) md += fmt::format("- [{}]({}): the series of one test\n", f, f);
}

// ----------------------------------------------------------- basal friction

void report_basal(const Config& c, const std::vector<BasalResult>& res, const std::vector<double>& secs,
                  const std::string& dir, std::string& md) {
    const CalibrateConfig& k = c.calibrate;
    std::vector<std::string> files;
    for (const BasalResult& r : res) {
        std::string csv = "time,base_normal,traction,holding_force,back_force,mu_eff,mu_walls,discs_on_base,"
                          "discs_sliding\n";
        for (const BasalRow& w : r.rows)
            csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", num(w.time), num(w.base_normal), num(w.traction),
                               num(w.holding_force), num(w.back_force), num(w.mu_eff), num(w.mu_walls), w.on_base,
                               w.sliding);
        const std::string name = "basal-friction-" + tag(r.kind, "mu_bp", r.mu_bp) + ".csv";
        write_file_atomic(dir + "/" + name, csv);
        files.push_back(name);
    }
    std::string sum = "kind,mu,mu_bp,mu_eff,mu_eff_sd,mu_walls,mu_walls_sd,phi_eff_deg,phi_bp_deg,rows,"
                      "sliding_fraction,traction_limit_ratio,discs,block_length,block_height,weight,wall_seconds\n";
    for (std::size_t i = 0; i < res.size(); ++i) {
        const BasalResult& r = res[i];
        sum += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.1f}\n", r.kind, num(r.mu),
                           num(r.mu_bp), num(r.mu_eff.mean), num(r.mu_eff.sd), num(r.mu_walls.mean),
                           num(r.mu_walls.sd), num(r.phi_eff_deg),
                           num(std::atan(r.mu_bp) * kDeg), r.mu_eff.n, num(r.sliding_fraction),
                           num(r.traction_limit_ratio), r.discs, num(r.block_length), num(r.block_height),
                           num(r.weight), secs[i]);
    }
    write_file_atomic(dir + "/basal-friction.csv", sum);

    std::vector<std::string> cats;
    for (double v : k.mu_bp_values) cats.push_back(fmt::format("μ_bp = {:g}", v));
    std::vector<BarSeries> series;
    series.push_back({"input μ_bp", k.mu_bp_values, {}});
    for (PackingKind kind : k.kinds) {
        BarSeries s{fmt::format("measured, {}", kind), {}, {}};
        for (double v : k.mu_bp_values) {
            double m = std::nan(""), e = 0.0;
            for (const BasalResult& r : res)
                if (r.kind == kind && r.mu_bp == v) m = r.mu_eff.mean, e = r.mu_eff.sd;
            s.value.push_back(m);
            s.error.push_back(e);
        }
        series.push_back(std::move(s));
    }
    plot_bars(cats, series, "Effective basal friction of a block held on the conveyor base",
              "proside basal friction μ_bp", "horizontal / normal force on the base", dir + "/basal-friction.png");
    // The series: how long the block takes to reach its steady state.
    std::vector<PlotPanel> panels;
    for (PackingKind kind : k.kinds) {
        PlotPanel p{fmt::format("Effective basal friction against time, {}", kind), "time since the belt started (s)",
                    "traction / normal force", {}};
        for (const BasalResult& r : res) {
            if (r.kind != kind) continue;
            int col = 0;
            for (std::size_t m = 0; m < k.mu_bp_values.size(); ++m)
                if (k.mu_bp_values[m] == r.mu_bp) col = static_cast<int>(m);
            PlotCurve cv{{}, {}, fmt::format("μ_bp = {:g}", r.mu_bp), col, false, false};
            for (const BasalRow& w : r.rows) {
                cv.x.push_back(w.time);
                cv.y.push_back(w.mu_eff);
            }
            p.curves.push_back(std::move(cv));
        }
        panels.push_back(std::move(p));
    }
    plot_panels(panels, 2, fmt::format("Measured over t ≥ {:g} s", k.measure_from * k.duration),
                dir + "/basal-friction-series.png", 1600);

    md += "## Results\n\n";
    md += "| packing | μ_bp | atan μ_bp (°) | measured μ_eff | ± sd | φ_b = atan μ_eff (°) | walls' measure | "
          "sliding fraction | min γ_b v'/(μ_bp N) | discs | wall time (s) |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < res.size(); ++i) {
        const BasalResult& r = res[i];
        md += fmt::format("| {} | {:g} | {:.1f} | {:.4f} | {:.4f} | {:.2f} | {:.4f} ± {:.4f} | {:.3f} | {:.3g} | {} | "
                          "{:.0f} |\n",
                          r.kind, r.mu_bp, std::atan(r.mu_bp) * kDeg, r.mu_eff.mean, r.mu_eff.sd, r.phi_eff_deg,
                          r.mu_walls.mean, r.mu_walls.sd, r.sliding_fraction, r.traction_limit_ratio, r.discs,
                          secs[i]);
    }
    md += "\nμ_eff: the base's horizontal force (total traction) over its normal force, interval means averaged "
          "over the measurement window, ± the standard deviation of the rows. Walls' measure: the end walls' net "
          "horizontal force over the same normal force (the same number once the block's momentum is steady). "
          "Sliding fraction: base discs at the Coulomb cap μ_bp N (the others ride with the belt: the slip is in "
          "the material above them). min γ_b v'/(μ_bp N): the traction a base disc at rest gets over its cap, for "
          "the most loaded disc at the end; below 1 that disc cannot transmit μ_bp N (traction law only; the Coulomb "
          "base has no such limit: nan).\n\n";
    md += "![Effective basal friction against μ_bp](basal-friction.png)\n\n";
    md += "![Effective basal friction against time](basal-friction-series.png)\n\n";
    md += "## Parameters\n\n";
    md += material_lines(c);
    md += fmt::format("- μ_i = {:g}; block {:g} m long, {:g} m thick, settled under gravity g = {:g} m/s² and cut\n",
                      c.material.mu, k.block_length, k.block_height, c.numerics.gravity);
    const bool traction = k.base_law == BaseLaw::traction;
    md += fmt::format("- base law {}; belt speed v' = {:g} m/s{}; {:g} s of belt motion, measured over "
                      "t ≥ {:g} s, rows every {:g} s; dt = {:.4g} s\n\n",
                      k.base_law, k.belt_speed,
                      traction ? fmt::format(", traction gain g_b = {:g}", k.traction_gain) : std::string(),
                      k.duration, k.measure_from * k.duration, c.run.output_interval, timestep_for(c).dt);
    md += "## Method\n\n";
    md += traction ? "The settled block rests on the smooth proside base (y = 0) whose ConveyorTraction (eq. 5: F = "
                     "γ_b (v' − v_i) capped at μ_bp N, γ_b = g_b m_i / dt) drags every disc touching it"
                   : "The settled block rests on the proside base (y = 0), a Coulomb base (CoulombBase: each disc "
                     "touching it has a spring-slider against the belt, stiffness k_s, limited by μ_bp N) that "
                     "carries every disc touching it";
    md += " toward a fixed smooth wall at the block's right end, as the belt drags the wedge against the backstop; "
          "a fixed smooth wall at its left end keeps the block's free face from slumping. In steady state the "
          "walls' net horizontal force is the total basal traction, and the base's normal force is the block's "
          "weight.\n\n";
    md += "## Files\n\n- [basal-friction.csv](basal-friction.csv): one row per test\n";
    for (const auto& f : files) md += fmt::format("- [{}]({}): the series of one test\n", f, f);
}

// ------------------------------------------------------------------- repose

void report_repose(const Config& c, const std::vector<ReposeResult>& res, const std::vector<double>& secs,
                   const std::string& dir, std::string& md) {
    const CalibrateConfig& k = c.calibrate;
    std::vector<std::string> files;
    for (const ReposeResult& r : res) {
        std::string csv = "x,surface_top,height_above_floor\n";
        for (std::size_t j = 0; j < r.profile.x.size(); ++j)
            csv += fmt::format("{},{},{}\n", num(r.profile.x[j]), num(r.profile.top[j]),
                               num(r.profile.top[j] - r.profile.base_y));
        const std::string name = "repose-" + tag(r.kind, "mu", r.mu) + ".csv";
        write_file_atomic(dir + "/" + name, csv);
        files.push_back(name);
    }
    std::string sum = "kind,mu,angle_deg,angle_left_deg,angle_right_deg,slope_se_left,slope_se_right,points_left,"
                      "points_right,heap_height,x_peak,discs,time,steps,wall_seconds\n";
    for (std::size_t i = 0; i < res.size(); ++i) {
        const ReposeResult& r = res[i];
        sum += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.1f}\n", r.kind, num(r.mu),
                           num(r.fit.angle_deg), num(r.fit.angle_left_deg), num(r.fit.angle_right_deg),
                           num(r.fit.left.slope_se), num(r.fit.right.slope_se), r.fit.left.n, r.fit.right.n,
                           num(r.profile.height), num(r.profile.x_peak), r.discs, num(r.time), r.steps, secs[i]);
    }
    write_file_atomic(dir + "/repose.csv", sum);

    std::vector<PlotPanel> panels;
    for (PackingKind kind : k.kinds) {
        PlotPanel p{fmt::format("Heap surfaces, {}", kind), "x (m)", "height above the floor (m)", {}};
        for (const ReposeResult& r : res) {
            if (r.kind != kind) continue;
            int col = 0;
            for (std::size_t m = 0; m < k.mu_values.size(); ++m)
                if (k.mu_values[m] == r.mu) col = static_cast<int>(m);
            PlotCurve s{{}, {}, fmt::format("μ_i = {:g}", r.mu), col, false, true};
            for (std::size_t j = 0; j < r.profile.x.size(); ++j) {
                s.x.push_back(r.profile.x[j]);
                s.y.push_back(r.profile.top[j] - r.profile.base_y);
            }
            p.curves.push_back(std::move(s));
            // The fitted flanks over their windows.
            const double lo = k.fit_from * r.profile.height, hi = k.fit_to * r.profile.height;
            for (const LineFit* f : {&r.fit.left, &r.fit.right}) {
                if (!std::isfinite(f->slope) || f->slope == 0.0) continue;
                PlotCurve line{{}, {}, "fitted flanks", col, true, false};
                for (double h : {lo, hi}) {
                    line.x.push_back((h + r.profile.base_y - f->intercept) / f->slope);
                    line.y.push_back(h);
                }
                p.curves.push_back(std::move(line));
            }
        }
        panels.push_back(std::move(p));
    }
    plot_panels(panels, 2, "Angle of repose: heaps at rest and their fitted flanks", dir + "/repose.png", 1600);

    md += "## Results\n\n";
    md += "| packing | μ_i | repose angle (°) | left flank (°) | right flank (°) | heap height (m) | surface points "
          "left + right | discs | time to rest (s) | wall time (s) |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < res.size(); ++i) {
        const ReposeResult& r = res[i];
        md += fmt::format("| {} | {:g} | {:.1f} | {:.1f} ± {:.1f} | {:.1f} ± {:.1f} | {:.3g} | {} + {} | {} | {:.3g} "
                          "| {:.0f} |\n",
                          r.kind, r.mu, r.fit.angle_deg, r.fit.angle_left_deg,
                          std::atan(r.fit.left.slope_se) * kDeg, r.fit.angle_right_deg,
                          std::atan(r.fit.right.slope_se) * kDeg, r.profile.height, r.fit.left.n, r.fit.right.n,
                          r.discs, r.time, secs[i]);
    }
    md += fmt::format("\nThe repose angle is the mean of the two flanks; each flank's ± is the standard error of "
                      "its fitted slope (as an angle). Surface points: the highest disc top in each column of width "
                      "2 r_max, fitted between {:g} and {:g} of the heap height.\n\n",
                      k.fit_from, k.fit_to);
    md += "![Heap surfaces and fitted flanks](repose.png)\n\n";
    md += "## Parameters\n\n";
    md += material_lines(c);
    md += fmt::format("- column {:g} m wide, {:g} m high, settled in a box and cut; side walls rise at {:g} m/s; "
                      "g = {:g} m/s²\n",
                      k.column_width, k.column_height, k.lift_speed, c.numerics.gravity);
    md += fmt::format("- floor: touching fixed discs of radius r_max = {:g} m (a rough floor); at rest when "
                      "E_kin < {:g} M g H\n\n",
                      c.packing.r_max, c.packing.settle_ke_ratio);
    md += "## Method\n\n"
          "The settled column stands on a floor of fixed discs between two walls, which rise at the lift speed and "
          "let the material flow out from below (the lifted-cylinder method). When the heap is at rest its surface "
          "is taken column by column, and each flank is fitted by least squares between the given fractions of "
          "the heap height, which leaves out the toe (scattered discs) and the rounded top.\n\n";
    md += "## Files\n\n- [repose.csv](repose.csv): one row per test\n";
    for (const auto& f : files) md += fmt::format("- [{}]({}): the heap surface of one test\n", f, f);
}

}  // namespace

int cmd_calibrate(const CommonArgs& a, const std::string& out_arg) {
    const Config c = load_calibration(a);
    if (c.run.threads > 0) omp_set_num_threads(c.run.threads);
    const std::string dir = choose_run_dir(out_arg, c.path);
    make_dirs(dir);
    write_file_atomic(dir + "/config.toml", to_toml(c));
    LineFile log(dir + "/log.txt");
    const std::string& e = c.run.experiment;
    log.line(fmt::format("orodem {} calibrate of {} ({}) with {} threads", ORODEM_VERSION, c.path, e,
                         omp_get_max_threads()));
    const CalibrationLog say = [&](const std::string& line) {
        log.line(line);
        fmt::print("{}\n", line);
        std::fflush(stdout);
    };
    const Timer total;
    const CalibrateConfig& k = c.calibrate;
    std::string md = fmt::format("# orodem calibration: {}\n\n", e);
    md += fmt::format("Command: `{}` (orodem {}, {} threads). Resolved config: [config.toml](config.toml); "
                      "progress: [log.txt](log.txt).\n\n",
                      command_line(a, dir), ORODEM_VERSION, omp_get_max_threads());
    std::vector<double> secs;
    if (e == "biaxial") {
        std::vector<BiaxialResult> res;
        for (PackingKind kind : k.kinds)
            for (double mu : k.mu_values) {
                const Timer t;
                res.push_back(run_biaxial(c, kind, mu, say));
                secs.push_back(t.seconds());
            }
        report_biaxial(c, res, secs, dir, md);
    } else if (e == "basal-friction") {
        std::vector<BasalResult> res;
        for (PackingKind kind : k.kinds)
            for (double mu_bp : k.mu_bp_values) {
                const Timer t;
                res.push_back(run_basal_friction(c, kind, mu_bp, say));
                secs.push_back(t.seconds());
            }
        report_basal(c, res, secs, dir, md);
    } else {
        std::vector<ReposeResult> res;
        for (PackingKind kind : k.kinds)
            for (double mu : k.mu_values) {
                const Timer t;
                res.push_back(run_repose(c, kind, mu, say));
                secs.push_back(t.seconds());
            }
        report_repose(c, res, secs, dir, md);
    }
    md += fmt::format("\nTotal wall time {:.0f} s.\n", total.seconds());
    write_file_atomic(dir + "/report.md", md);
    log.line(fmt::format("done in {:.1f} s: report.md", total.seconds()));
    fmt::print("report in {}/report.md\n", dir);
    return 0;
}

}  // namespace orodem
