// The subcommands run, check, sweep and bench: thin glue from typed
// arguments to the library; the only code that prints progress.
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/io/pile_file.hpp"
#include "orodem/setup/bench_pile.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"
#include "orodem/analysis/wedge_profile.hpp"
#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/render/particle_view.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/analysis/rel_disp.hpp"

#include "commands.hpp"

namespace fs = std::filesystem;
namespace orodem {

namespace {



Config load(const CommonArgs& a) {
    std::vector<Override> ov;
    for (const auto& s : a.sets) ov.push_back(parse_override(s));
    if (a.threads >= 0) ov.push_back({"run.threads", std::to_string(a.threads)});
    return load_config(a.config, ov);
}

/// "integrate 6.1%, rebuild 0.4%, ..." with the seconds per phase of step().
std::string phase_breakdown(const PhaseTimes& t) {
    const double total = std::max(t.total(), 1e-300);
    std::string s;
    for (const auto& [name, secs] : {std::pair{"integrate", t.integrate}, {"rebuild", t.rebuild},
                                     {"pair forces", t.pair_forces}, {"gather+walls", t.gather},
                                     {"boundaries", t.boundaries}})
        s += fmt::format("{}{} {:.3f} s ({:.1f}%)", s.empty() ? "" : ", ", name, secs, 100.0 * secs / total);
    return s;
}

void set_threads(const Config& c) {
    if (c.run.threads > 0) omp_set_num_threads(c.run.threads);
}

/// A new run directory: `out` if given (must be absent or empty), else
/// runs/<config stem>, runs/<stem>-2, ... whichever is free first.
std::string choose_run_dir(const std::string& out, const std::string& config_path) {
    auto usable = [](const fs::path& p) { return !fs::exists(p) || (fs::is_directory(p) && fs::is_empty(p)); };
    if (!out.empty()) {
        if (!usable(out))
            throw ConfigError(fmt::format("--out {}: directory exists and is not empty; choose a new directory "
                                          "(runs are never overwritten)", out));
        return out;
    }
    const std::string stem = fs::path(config_path).stem().string();
    for (int k = 1;; ++k) {
        const fs::path p = fs::path("runs") / (k == 1 ? stem : fmt::format("{}-{}", stem, k));
        if (usable(p)) return p.string();
    }
}

}  // namespace

int cmd_check(const CommonArgs& a) {
    const Config c = load(a);
    const TimestepInfo t = timestep_for(c);
    if (is_wedge(c)) check_belt_speed(c);
    const std::size_t n = generated_particle_count(c);
    std::cout << to_toml(c);
    fmt::print("# derived\n");
    fmt::print("particles generated    = {} discs ({}), before the cut to h0\n", n, c.packing.kind);
    fmt::print("layer                  = {:g} m long, h0 = {:g} m\n", c.packing.length, c.packing.h0);
    fmt::print("dt                     = {:.6g} s ({})\n", t.dt, c.numerics.dt > 0 ? "requested" : "automatic");
    fmt::print("stability limit        = {:.6g} s (margin {:.2f}x)\n", t.dt_crit, t.margin());
    fmt::print("collision time t_c     = {:.6g} s ({:.1f} steps)\n", t.t_collision, t.t_collision / t.dt);
    if (is_wedge(c)) {
        const double steps = c.wedge.s_max * c.packing.h0 / (c.wedge.v * t.dt);
        fmt::print("belt speed v'          = {:g} m/s (eq. 6 limit {:.4g} m/s, margin {:.1f}x)\n", c.wedge.v,
                   belt_speed_limit(c), belt_speed_limit(c) / c.wedge.v);
        fmt::print("steps to S = {:g}       = {:.3g} ({:.3g} disc-steps)\n", c.wedge.s_max, steps,
                   steps * static_cast<double>(n) * 0.8);
        fmt::print("estimated run time     = {:.0f} s at 1.5e7 disc-steps/s (plus settling if not cached)\n",
                   steps * static_cast<double>(n) * 0.8 / 1.5e7);
    }
    fmt::print("packing cache          = {}\n", packing_cache_path(c));
    return 0;
}

namespace {

/// Progress on a terminal only: one rewritten line.
class Progress {
public:
    Progress() : tty_(::isatty(STDOUT_FILENO) != 0), t0_(std::chrono::steady_clock::now()) {}
    double elapsed() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    }
    template <class... T>
    void show(fmt::format_string<T...> f, T&&... args) {
        if (!tty_) return;
        fmt::print("\r{}   ", fmt::format(f, std::forward<T>(args)...));
        std::fflush(stdout);
    }
    void done() {
        if (tty_) fmt::print("\n");
    }

private:
    bool tty_;
    std::chrono::steady_clock::time_point t0_;
};

/// The settled layer of c: from the cache when present, else settled now
/// (series rows of the settling go to `series` when given) and cached.
ParticleStore prepare_layer(const Config& c, LineFile& log, LineFile* series) {
    const std::string cache = packing_cache_path(c);
    std::string why;
    if (auto cached = load_packing(cache, packing_key(c), c.material.density, &why)) {
        log.line(fmt::format("packing reused from {} ({} discs)", cache, cached->size()));
        fmt::print("packing reused from {}\n", cache);
        return std::move(*cached);
    }
    log.line(fmt::format("settling a new packing ({})", why));
    Simulation sim = make_settle_simulation(c);
    sim.initialize();
    log.line(fmt::format("generated {} discs ({}); settling", sim.particles.size(), c.packing.kind));
    Progress progress;
    const SettleProgress done = settle(sim, c.packing, c.run.output_interval, [&](const SettleProgress& s) {
        if (series)
            series->line(fmt::format("{},{:.9g},{:.9g},{:.6g},{},{:.6g}", s.step, s.time, s.kinetic_energy,
                                     s.ke_ratio, s.contacts, sim.max_overlap_ratio()));
        progress.show("settling {} discs: t = {:.3f} s, step {}, E_kin/(M g h0) = {:.2e} (target {:.1e})",
                      sim.particles.size(), s.time, s.step, s.ke_ratio, c.packing.settle_ke_ratio);
    });
    progress.done();
    const double secs = progress.elapsed();
    log.line(fmt::format("settled after {} steps ({:.4g} s simulated, {:.1f} s wall, {:.3g} disc-steps/s); "
                         "E_kin/(M g h0) = {:.3g}, max overlap/R = {:.4f}",
                         done.step, done.time, secs,
                         static_cast<double>(done.step) * static_cast<double>(sim.particles.size()) / secs,
                         done.ke_ratio, sim.max_overlap_ratio()));
    cut_layer(sim.particles, c.packing.h0);
    save_packing(cache, sim.particles, packing_key(c));
    log.line(fmt::format("cut to h0 = {:g} m: {} discs; cached in {}", c.packing.h0, sim.particles.size(), cache));
    return std::move(sim.particles);
}

std::string series_header() {
    return "step,time,S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,kinetic_energy,contacts,"
           "max_overlap_ratio,toe_pro_x_over_h0,toe_retro_x_over_h0,base_traction,discs_on_base,"
           "discs_sliding_on_base,fixed_discs,mean_overlap_ratio,max_speed,base_normal_force";
}

/// Runs a wedge experiment from the layer; writes series rows and log lines.
void run_wedge(const Config& c, const ParticleStore& layer, const std::string& dir, LineFile& log) {
    WedgeSetup w = make_wedge(c, layer);
    Simulation& sim = w.sim;
    sim.initialize();
    const double h0 = c.packing.h0;
    log.line(fmt::format("{}: {} discs, incoming plate {:.4g} h0, retroside {:.4g} h0, undeformed surface "
                         "y_mean = {:.4g} m, v = {:g} m/s",
                         c.run.experiment, sim.particles.size(), w.pro_length / h0, w.retro_length / h0,
                         w.profile.y_mean, c.wedge.v));
    LineFile series(dir + "/series.csv");
    series.line(series_header());
    const double dt = sim.params.dt;
    const auto steps_per_output =
        std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(c.wedge.output_ds * h0 / (c.wedge.v * dt))));
    // Whole output intervals only, so the last row sits on s_max (to one step).
    const auto n_outputs = static_cast<std::uint64_t>(std::max(1LL, std::llround(c.wedge.s_max / c.wedge.output_ds)));
    const std::uint64_t total_steps = n_outputs * steps_per_output;
    Progress progress;
    auto write_row = [&]() {
        const double S = c.wedge.v * sim.time / h0;
        const double ke = sim.kinetic_energy();
        if (!std::isfinite(ke))
            throw InstabilityError(fmt::format("non-finite kinetic energy at step {} (S = {:.3f}); reduce "
                                               "numerics.safety or wedge.v", sim.step_count, S));
        const WedgeMeasures m = measure_wedge(sim.particles, w.profile, c.wedge.v * sim.time);
        const std::size_t fixed = w.fixed_retro ? w.fixed_retro->fixed_count() : 0;
        series.line(fmt::format("{},{:.9g},{:.6f},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.9g},{},{:.6g},{:.6g},{:.6g},"
                                "{:.6g},{},{},{},{:.6g},{:.6g},{:.6g}",
                                sim.step_count, sim.time, S, m.H_over_h0, m.alpha_deg, m.beta_deg,
                                m.peak_dx_over_h0, m.dilation_pct, ke, sim.touching_contacts(),
                                sim.max_overlap_ratio(), m.toe_pro_x / h0, m.toe_retro_x / h0,
                                w.base->total_traction(), w.base->discs_on_base(), w.base->discs_sliding(), fixed,
                                sim.mean_overlap_ratio(), sim.max_speed(), sim.wall_force(kWallProBase).y));
        const double secs = progress.elapsed();
        const double rate = static_cast<double>(sim.step_count) / std::max(secs, 1e-9);
        log.line(fmt::format("S = {:.3f}: H/h0 = {:.3f}, alpha = {:.2f}, beta = {:.2f}; health: max overlap/R = {:.4f}, "
                             "max speed = {:.3g} m/s, contacts/disc = {:.2f}; {:.0f} steps/s",
                             S, m.H_over_h0, m.alpha_deg, m.beta_deg, sim.max_overlap_ratio(), sim.max_speed(),
                             static_cast<double>(sim.touching_contacts()) / static_cast<double>(sim.particles.size()),
                             rate));
        progress.show("S = {:.3f} / {:g}, {:.0f} steps/s, {:.0f} s left", S, c.wedge.s_max, rate,
                      static_cast<double>(total_steps - std::min(total_steps, sim.step_count)) / std::max(rate, 1e-9));
    };
    make_dirs(dir + "/figures");
    make_dirs(dir + "/snapshots");
    std::vector<std::pair<double, std::string>> pvd;
    std::vector<Vec2> x_then = positions_by_id(sim.particles);
    ViewOptions view;
    view.x_min = w.profile.x_min;
    view.x_max = w.profile.x_max;
    view.y_min = 0.0;
    view.y_max = (1.5 + 0.6 * std::sqrt(c.wedge.s_max)) * h0;  // room for H ≈ h0 sqrt(S/3) [m]
    view.h0 = h0;
    view.band = h0 / 5.0;
    auto draw = [&]() {
        const double S = c.wedge.v * sim.time / h0;
        const std::vector<double> rel = relative_displacement(sim, x_then);
        x_then = positions_by_id(sim.particles);
        const std::string name = fmt::format("S{:06.3f}", S);
        write_vtu(fmt::format("{}/snapshots/{}.vtu", dir, name), sim.particles, rel);
        pvd.emplace_back(S, fmt::format("snapshots/{}.vtu", name));
        write_pvd(dir + "/run.pvd", pvd);
        view.label = fmt::format("{}   S = {:.2f}   initial depth", c.run.experiment, S);
        view.color_by = "horizons";
        render_particles(sim.particles, nullptr, view, fmt::format("{}/figures/horizons_{}.png", dir, name));
        if (sim.step_count > 0) {
            view.label = fmt::format("{}   S = {:.2f}   relative displacement since the previous output", c.run.experiment, S);
            view.color_by = "displacement";
            render_particles(sim.particles, &rel, view, fmt::format("{}/figures/displacement_{}.png", dir, name));
        }
    };
    write_row();
    draw();
    while (sim.step_count < total_steps) {
        sim.advance(std::min(steps_per_output, total_steps - sim.step_count));
        write_row();
        draw();
    }
    progress.done();
    log.line(fmt::format("finished: S = {:.3f} after {} steps, {:.1f} s wall", c.wedge.v * sim.time / h0,
                         sim.step_count, progress.elapsed()));
    log.line("step phases: " + phase_breakdown(sim.phase_times()));
    cmd_plot({dir}, dir + "/figures/plots.png");
}

}  // namespace

int cmd_run(const CommonArgs& a, const std::string& out_arg) {
    const Config c = load(a);
    const TimestepInfo t = timestep_for(c);
    if (is_wedge(c)) check_belt_speed(c);
    set_threads(c);
    const std::string dir = choose_run_dir(out_arg, c.path);
    make_dirs(dir);
    write_file_atomic(dir + "/config.toml", to_toml(c));
    LineFile log(dir + "/log.txt");
    log.line(fmt::format("orodem {} run of {} ({}) with {} threads", ORODEM_VERSION, c.path, c.run.experiment,
                         omp_get_max_threads()));
    log.line(fmt::format("dt = {:.6g} s, stability limit {:.6g} s (margin {:.2f}x), t_c = {:.1f} steps",
                         t.dt, t.dt_crit, t.margin(), t.t_collision / t.dt));
    if (!is_wedge(c)) {
        LineFile series(dir + "/series.csv");
        // Header always; rows only when the layer is settled now (not cached).
        series.line("step,time,kinetic_energy,ke_ratio,contacts,max_overlap_ratio");
        const ParticleStore layer = prepare_layer(c, log, &series);
        save_packing(dir + "/packing.bin", layer, packing_key(c));
        const double surface = mean_surface_height(layer, 0.0, c.packing.length, 2.0 * c.packing.r_max);
        log.line(fmt::format("layer: {} discs, mean surface height {:.4g} m (h0 = {:g} m)", layer.size(), surface,
                             c.packing.h0));
        fmt::print("layer of {} discs ready, mean surface {:.3g} m\n", layer.size(), surface);
        fmt::print("outputs in {}/ (config.toml, log.txt, series.csv, packing.bin)\n", dir);
        return 0;
    }
    const ParticleStore layer = prepare_layer(c, log, nullptr);
    run_wedge(c, layer, dir, log);
    fmt::print("outputs in {}/ (config.toml, log.txt, series.csv)\n", dir);
    return 0;
}

namespace {

/// Splits "key=v1,v2,..." into the key and its values.
std::pair<std::string, std::vector<std::string>> parse_vary(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw ConfigError(fmt::format("--vary '{}': expected key=v1,v2,..., e.g. --vary wedge.mu_bp=0.1,0.2,0.3", text));
    std::vector<std::string> values;
    std::string rest = text.substr(eq + 1);
    for (std::size_t pos = 0;;) {
        const auto comma = rest.find(',', pos);
        values.push_back(rest.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    for (const auto& v : values)
        if (v.empty()) throw ConfigError(fmt::format("--vary '{}': empty value in the list", text));
    return {text.substr(0, eq), values};
}

}  // namespace

int cmd_sweep(const CommonArgs& a, const std::string& vary, const std::string& out_arg) {
    const auto [key, values] = parse_vary(vary);
    // Validate every member of the sweep before running any.
    bool all_wedges = true;  // then the overlay plots at the end
    for (const auto& v : values) {
        CommonArgs one = a;
        one.sets.push_back(key + "=" + v);
        const Config c = load(one);
        timestep_for(c);
        if (is_wedge(c)) check_belt_speed(c);
        all_wedges = all_wedges && is_wedge(c);
    }
    const std::string stem = fs::path(a.config).stem().string();
    const std::string root = out_arg.empty() ? choose_run_dir("", stem + "-sweep") : out_arg;
    if (!out_arg.empty() && fs::exists(root) && !fs::is_empty(root))
        throw ConfigError(fmt::format("--out {}: directory exists and is not empty; choose a new directory", root));
    make_dirs(root);
    std::vector<std::string> dirs;
    for (const auto& v : values) {
        CommonArgs one = a;
        one.sets.push_back(key + "=" + v);
        const std::string dir = fmt::format("{}/{}={}", root, key, v);
        fmt::print("sweep: {} = {} -> {}\n", key, v, dir);
        const int rc = cmd_run(one, dir);
        if (rc != 0) return rc;
        dirs.push_back(dir);
    }
    if (all_wedges) cmd_plot(dirs, root + "/plots.png");
    fmt::print("sweep outputs in {}/\n", root);
    return 0;
}

/// The canonical benchmark: run `steps` steps of the settled pile, check the
/// kinetic energy against the LAMMPS reference, print the speed.
int cmd_bench_pile(const std::string& pile, std::uint64_t steps, int threads) {
    if (threads > 0) omp_set_num_threads(threads);
    const ParticleStore discs = read_pile_file(pile, BenchPile{}.density);
    Simulation sim = make_bench_pile(discs);
    sim.initialize();
    // Times the step loop only, as LAMMPS's "Loop time" (set-up excluded).
    const auto t0 = std::chrono::steady_clock::now();
    double worst = 0.0;
    std::uint64_t done = 0;
    for (const BenchReference& ref : kBenchReference) {
        if (ref.step > steps) break;
        sim.advance(ref.step - done);
        done = ref.step;
        const double ke = sim.kinetic_energy();
        const double rel = std::fabs(ke - ref.kinetic_energy) / ref.kinetic_energy;
        worst = std::max(worst, rel);
        fmt::print("step {:6d}: kinetic energy {:.9g} (LAMMPS {:.9g}, rel. diff {:.2e})\n", ref.step, ke,
                   ref.kinetic_energy, rel);
    }
    sim.advance(steps - done);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double n = static_cast<double>(sim.particles.size());
    fmt::print("discs {} steps {} threads {} loop time {:.3f} s\n", sim.particles.size(), steps,
               omp_get_max_threads(), secs);
    fmt::print("timesteps/s {:.1f}  particle-steps/s {:.3e}  rebuilds {}\n", double(steps) / secs,
               n * double(steps) / secs, sim.rebuild_count());
    fmt::print("pairs {} ({:.2f} per disc)\n", sim.contacts.size(), double(sim.contacts.size()) / n);
    fmt::print("phases: {}\n", phase_breakdown(sim.phase_times()));
    fmt::print("state hash {:016x} (identical at any thread count)\n", sim.state_hash());
    fmt::print("reference check: worst relative kinetic-energy difference {:.2e} ({})\n", worst,
               worst < 1e-6 ? "matches" : "DIFFERS");
    return worst < 1e-6 ? 0 : static_cast<int>(ExitCode::unstable);
}

}  // namespace orodem
