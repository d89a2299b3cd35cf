// The subcommands run, check, sweep and bench: thin glue from typed
// arguments to the library; the only code that prints progress.
#include <omp.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <csignal>
#include <sstream>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/series_reader.hpp"
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
#include "orodem/analysis/strain.hpp"
#include "orodem/engine/health.hpp"
#include "orodem/io/checkpoint.hpp"

#include "commands.hpp"

namespace fs = std::filesystem;
namespace orodem {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;   // the first SIGINT/SIGTERM, 0 while none came
volatile std::sig_atomic_t g_signal_count = 0;  // how many came

// The first signal asks for a stop with a checkpoint; a second one (an
// impatient Ctrl-C, or timeout's follow-up) is ignored so that the shutdown
// checkpoint is written; a third ends the process at once with the signal's
// default action (signal and raise are async-signal-safe).
extern "C" void on_stop_signal(int sig) {
    if (g_stop_signal == 0) g_stop_signal = sig;
    g_signal_count = g_signal_count + 1;  // (no ++ on a volatile: deprecated in C++20)
    if (g_signal_count >= 3) {
        ::signal(sig, SIG_DFL);
        ::raise(sig);
    }
}

}  // namespace

StopSignals::StopSignals() {
    g_stop_signal = 0;
    g_signal_count = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
}

StopSignals::~StopSignals() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
}

int StopSignals::pending() const { return static_cast<int>(g_stop_signal); }

Config load(const CommonArgs& a) {
    std::vector<Override> ov;
    for (const auto& s : a.sets) ov.push_back(parse_override(s));
    if (a.threads >= 0) ov.push_back({"run.threads", std::to_string(a.threads)});
    return load_config(a.config, ov);
}

bool ends_a_piece(const std::string& line) {
    for (const char* e : {"finished:", "interrupted by", "stopped at the wall-time limit", "stopped by an I/O error",
                          "STOPPED:", "UNSTABLE:"})
        if (line.rfind(e, 0) == 0) return true;
    return false;
}

bool starts_or_ends_a_piece(const std::string& line) {
    return ends_a_piece(line) || line.rfind("resumed by", 0) == 0;
}

namespace {

/// "integrate 6.1%, rebuild 0.4%, ..." with the seconds per phase of step().
std::string phase_breakdown(const PhaseTimes& t) {
    const double total = std::max(t.total(), 1e-300);
    std::string s;
    for (const auto& [name, secs] : {std::pair{"integrate", t.integrate}, {"rebuild", t.rebuild},
                                     {"pair forces", t.pair_forces}, {"gather+walls", t.gather},
                                     {"boundaries", t.boundaries}})
        s += fmt::format("{}{} {:.3f} s ({:.1f}%)", s.empty() ? "" : ", ", name, secs, 100.0 * secs / total);
    if (t.rebuilds > 0)
        s += fmt::format("; {} steps, {} rebuilds (one per {:.0f} steps)", t.steps, t.rebuilds,
                         static_cast<double>(t.steps) / static_cast<double>(t.rebuilds));
    return s;
}

}  // namespace

void set_threads(const Config& c) {
    if (c.run.threads > 0) omp_set_num_threads(c.run.threads);
}

std::string short_plate_warning(const Config& c) {
    const PlateEstimate pe = plate_estimate(c);
    if (c.wedge.pro_margin >= pe.pro_margin_min) return "";
    return fmt::format("wedge.pro_margin = {:g} h0 is shorter than the {:.1f} h0 the deformation front may need by "
                       "S = {:g} (critical taper {:.2f} deg for mu_bp = {:g}; docs/experiments.md \"Plate length\"); "
                       "raise wedge.pro_margin so that the trailing wall does not push the wedge",
                       c.wedge.pro_margin, pe.pro_margin_min, c.wedge.s_max, pe.alpha_deg, c.wedge.mu_bp);
}

void check_runnable(const Config& c) {
    check_model_size(c);
    timestep_for(c);
    if (is_wedge(c)) check_wedge_base(c);
}

/// A new run directory: `out` if given (must be absent or empty), else
/// runs/<config stem>, runs/<stem>-2, ... whichever is free first.
std::string choose_run_dir(const std::string& out, const std::string& config_path) {
    auto usable = [](const fs::path& p) { return !fs::exists(p) || (fs::is_directory(p) && fs::is_empty(p)); };
    if (!out.empty()) {
        std::error_code ec;
        if (fs::exists(out, ec) && !fs::is_directory(out, ec))
            throw ConfigError(fmt::format("--out {}: is a file, not a directory; choose a new directory", out));
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

int cmd_check(const CommonArgs& a) {
    const Config c = load(a);
    if (is_calibration(c)) return check_calibration(c);
    check_model_size(c);
    const TimestepInfo t = timestep_for(c);
    if (is_wedge(c)) check_wedge_base(c);
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
        if (c.wedge.base_law == "traction")
            fmt::print("belt speed v'          = {:g} m/s (eq. 6 traction base; limit {:.4g} m/s, margin {:.1f}x)\n",
                       c.wedge.v, belt_speed_limit(c), belt_speed_limit(c) / c.wedge.v);
        else
            fmt::print("belt speed v'          = {:g} m/s (Coulomb base, mu_bp = {:g})\n", c.wedge.v, c.wedge.mu_bp);
        fmt::print("inertial number I      = {:.3g} (v'/h0 (r_min + r_max) sqrt(rho / (rho g h0)); quasi-static "
                   "below 1e-3)\n",
                   inertial_number(c));
        const PlateEstimate pe = plate_estimate(c);
        fmt::print("plate beyond s_max     = {:g} h0 (wedge.pro_margin); the deformation front reaches about {:.1f} h0 "
                   "from the S point by S = {:g} (critical taper {:.2f} deg for phi = {:.1f} deg, phi_b = {:.1f} deg), "
                   "so at least {:.1f} h0 is needed\n",
                   c.wedge.pro_margin, pe.front_h0, c.wedge.s_max, pe.alpha_deg, pe.phi_deg, pe.phi_b_deg,
                   pe.pro_margin_min);
        if (const std::string w = short_plate_warning(c); !w.empty()) fmt::print(stderr, "orodem: warning: {}\n", w);
        // Rates of wedge runs on the 2-core development machine per awake
        // disc (docs/benchmarks.md); with sleeping zones about two thirds of
        // the discs are awake on average over S = 0-8 (the intermediate runs).
        constexpr double kRate1 = 2.8e7, kRate2 = 4.8e7;  // awake disc-steps/s, 1 and 2 threads
        const double awake = c.wedge.sleep ? 2.0 / 3.0 : 1.0;
        const double work = steps * static_cast<double>(n) * 0.8 * awake;  // 0.8: the cut to h0
        fmt::print("steps to S = {:g}       = {:.3g} ({:.3g} {}disc-steps)\n", c.wedge.s_max, steps, work,
                   c.wedge.sleep ? "awake " : "");
        fmt::print("estimated run time     = {} on 1 thread, {} on 2 (at {:.2g} and {:.2g} {}disc-steps/s measured on "
                   "2 cores{}; plus settling if not cached)\n",
                   duration_text(work / kRate1), duration_text(work / kRate2), kRate1, kRate2,
                   c.wedge.sleep ? "awake " : "", c.wedge.sleep ? ", two thirds of the discs awake" : "");
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

namespace {

/// Progress on a terminal only: one rewritten line.
class Progress {
public:
    Progress() : tty_(::isatty(STDOUT_FILENO) != 0), t0_(std::chrono::steady_clock::now()) {}
    double elapsed() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    }
    /// A status line, on a terminal only: the line is cleared and rewritten.
    template <class... T>
    void show(fmt::format_string<T...> f, T&&... args) {
        if (!tty_) return;
        fmt::print("\r\033[K{}", fmt::format(f, std::forward<T>(args)...));
        std::fflush(stdout);
    }
    /// A wedge run's progress: S, its percentage of s_max, steps/s since this
    /// piece began (at step `first`) and the time left, blank until a rate
    /// exists (one second of running). On a terminal the line is rewritten at
    /// most once a second, and at every output (at_output); elsewhere (a log
    /// file, nohup) a plain line is printed at every output only.
    void run_line(double S, double s_max, std::uint64_t first, std::uint64_t step, std::uint64_t total,
                  bool at_output) {
        const double now = elapsed();
        if (tty_ ? (!at_output && now - shown_at_ < 1.0) : !at_output) return;
        shown_at_ = now;
        const double rate = now >= 1.0 && step > first ? static_cast<double>(step - first) / now : 0.0;
        std::string text = fmt::format("S = {:.3f} of {:g} ({:.1f}%)", S, s_max, 100.0 * S / s_max);
        if (rate > 0.0)
            text += fmt::format(", {:.0f} steps/s, {} left", rate,
                                duration_text(static_cast<double>(total - std::min(total, step)) / rate));
        if (tty_) show("{}", text);
        else fmt::print("{}\n", text);
    }
    void done() {
        if (tty_) fmt::print("\n");
    }

private:
    bool tty_;
    std::chrono::steady_clock::time_point t0_;
    double shown_at_ = -1.0;  // elapsed() when the run line was last shown [s]
};

/// The settled layer of c: from the cache when present, else settled now
/// (series rows of the settling go to `series` when given) and cached.
ParticleStore prepare_layer(const Config& c, const std::string& dir, LineFile& log, LineFile* series) {
    const std::string cache = packing_cache_path(c);
    std::string why;
    if (auto cached = load_packing(cache, packing_key(c), c.material.density, &why)) {
        log.line(fmt::format("packing reused from {} ({} discs)", cache, cached->size()));
        fmt::print("packing reused from {}\n", cache);
        return std::move(*cached);
    }
    // Settling is not checkpointed (it ends in the packing cache, and takes
    // minutes at most): a signal ends it with exit 128 + signal and a rerun
    // (for a wedge: --resume) settles again. The handler is in place before
    // the log says "settling".
    StopSignals signals;
    log.line(fmt::format("settling a new packing ({})", why));
    Simulation sim = make_settle_simulation(c);
    sim.initialize();
    log.line(fmt::format("generated {} discs ({}); settling", sim.particles.size(), c.packing.kind));
    Progress progress;
    const SettleProgress done = settle(sim, c.packing, c.run.output_interval, [&](const SettleProgress& s) {
        if (const int sig = signals.pending()) {
            const std::string msg = fmt::format(
                "by {} while settling the packing (step {}, {:.0f} s); settling is not checkpointed, so it "
                "starts again when the run is started again{}",
                sig == SIGINT ? "SIGINT" : "SIGTERM", s.step, progress.elapsed(),
                is_wedge(c) ? fmt::format(": orodem run {}/config.toml --out {} --resume", dir, dir)
                            : std::string(" (with a new --out)"));
            log.line("interrupted " + msg);
            throw InterruptedError(msg, sig);
        }
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
           "discs_sliding_on_base,fixed_discs,mean_overlap_ratio,max_speed,base_normal_force,trailing_wall_push,"
           "beta_inner_deg,beta_outer_deg,retro_break_x_over_h0";
}

/// How many columns the series.csv of a run being resumed has: a run that an
/// older orodem started keeps the columns it started with.
std::size_t resumed_series_columns(const std::string& path) {
    const std::string text = read_file(path);
    return csv_leading_columns(text.substr(0, text.find('\n')), series_header(), path);
}

std::uint64_t file_bytes(const std::string& path) {
    std::error_code ec;
    const auto n = fs::file_size(path, ec);
    if (ec) throw IoError(fmt::format("cannot stat '{}': {}", path, ec.message()));
    return static_cast<std::uint64_t>(n);
}

/// Free bytes for an unprivileged user on the file system holding path.
std::uint64_t free_bytes(const std::string& path) {
    struct statvfs s {};
    if (::statvfs(path.c_str(), &s) != 0) throw_io_error("cannot query free space of", path);
    return static_cast<std::uint64_t>(s.f_bavail) * static_cast<std::uint64_t>(s.f_frsize);
}

/// Refuses (IoError, exit 4) when the disk holding dir cannot take what the
/// rest of the run writes: per remaining output one snapshot and its two
/// pictures (sized like the last ones written), two checkpoints plus the one
/// being written, and 2 MB for series, log and the final plots.
void check_free_space(const std::string& dir, const std::string& last_snapshot, std::uint64_t outputs_left,
                      std::uint64_t checkpoint_size) {
    const std::string name = fs::path(last_snapshot).stem().string();
    const std::uint64_t vtu = file_bytes(dir + "/" + last_snapshot);
    std::uint64_t pictures = 0;
    for (const char* kind : {"horizons", "displacement"}) {
        std::error_code ec;
        const auto n = fs::file_size(fmt::format("{}/figures/{}_{}.png", dir, kind, name), ec);
        if (!ec) pictures = std::max<std::uint64_t>(pictures, n);
    }
    const std::uint64_t need = outputs_left * (vtu + 2 * pictures) + 3 * checkpoint_size + (2u << 20);
    const std::uint64_t have = free_bytes(dir);
    if (have < need)
        throw IoError(fmt::format(
            "not enough free space for {}: the rest of the run needs about {:.1f} MB ({} outputs x ({:.2f} MB "
            "snapshot + 2 x {:.2f} MB pictures) + 3 x {:.2f} MB checkpoints + 2 MB), {:.1f} MB are free; free some "
            "space or choose --out on another disk, then resume with --resume",
            dir, static_cast<double>(need) / 1e6, outputs_left, static_cast<double>(vtu) / 1e6,
            static_cast<double>(pictures) / 1e6, static_cast<double>(checkpoint_size) / 1e6,
            static_cast<double>(have) / 1e6));
}

/// Runs (or, with `resumed`, continues) a wedge experiment; writes series rows,
/// snapshots, pictures, checkpoints and log lines. Returns the exit status:
/// 0, or 128 + signal when interrupted (after a checkpoint).
int run_wedge(const Config& c, WedgeSetup& w, const std::string& dir, LineFile& log, const RunLoopState* resumed) {
    Simulation& sim = w.sim;
    const double h0 = c.packing.h0;
    const std::uint64_t cfg_hash = config_hash(c);
    const std::string ckpt_dir = dir + "/checkpoint";
    RunLoopState st;
    bool initial_overlap_allowed = false;  // run.allow_initial_overlap used: no overlap limit at step 0
    if (resumed) {
        st = *resumed;
        w.profile.y_mean = st.surface_y_mean;
    } else {
        sim.initialize();
        st.surface_y_mean = w.profile.y_mean;
        log.line(fmt::format("{}: {} discs, incoming plate {:.4g} h0, retroside {:.4g} h0, undeformed surface "
                             "y_mean = {:.4g} m, v = {:g} m/s",
                             c.run.experiment, sim.particles.size(), w.pro_length / h0, w.retro_length / h0,
                             w.profile.y_mean, c.wedge.v));
        // RELIABILITY-CHECKLIST 4: the initial layer's overlaps, reported, and
        // refused above the stop level unless run.allow_initial_overlap.
        const OverlapSummary o = overlap_summary(sim, c.run.warn_overlap_ratio);
        const std::string where =
            o.touching == 0 ? std::string("no discs touch")
                            : fmt::format("worst overlap/R = {:.4f} between discs {} at ({:.6g}, {:.6g}) m and {} at "
                                          "({:.6g}, {:.6g}) m",
                                          o.worst, o.id_i, o.x_i.x, o.x_i.y, o.id_j, o.x_j.x, o.x_j.y);
        log.line(fmt::format("initial overlaps: {} touching pairs, {} above run.warn_overlap_ratio = {:g}; {}",
                             o.touching, o.above, c.run.warn_overlap_ratio, where));
        if (o.worst > c.run.max_overlap_ratio) {
            if (!c.run.allow_initial_overlap)
                throw ConfigError(fmt::format(
                    "the initial layer is not settled: {} (above run.max_overlap_ratio = {:g}; {} pairs above "
                    "run.warn_overlap_ratio = {:g}); delete the packing cache {} to settle it again, or set "
                    "run.allow_initial_overlap = true to start anyway",
                    where, c.run.max_overlap_ratio, o.above, c.run.warn_overlap_ratio, packing_cache_path(c)));
            initial_overlap_allowed = true;
            log.line("warning: starting anyway (run.allow_initial_overlap = true); the overlap limit applies from "
                     "the first health check after step 0");
        }
    }
    const std::string series_path = dir + "/series.csv";
    const std::size_t series_columns =
        resumed ? resumed_series_columns(series_path) : std::numeric_limits<std::size_t>::max();
    LineFile series(series_path);
    if (!resumed) series.line(series_header());
    const double dt = sim.params.dt;
    const auto steps_per_output =
        std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(c.wedge.output_ds * h0 / (c.wedge.v * dt))));
    // Whole output intervals only, so the last row sits on s_max (to one step).
    const auto n_outputs = static_cast<std::uint64_t>(std::max(1LL, std::llround(c.wedge.s_max / c.wedge.output_ds)));
    const std::uint64_t total_steps = n_outputs * steps_per_output;
    const std::uint64_t first_step = sim.step_count;  // this piece's first step (a resume starts later)
    Progress progress;
    // The rate logged with each output is over the interval since the previous
    // output (or since this piece began): `orodem status` takes the median of
    // the last few as the current speed, which a mean since the start overstates
    // once the wedge has woken more discs.
    std::uint64_t rate_from_step = first_step;  // [-]
    double rate_from_secs = 0.0;                // wall time of the previous output since this piece began [s]

    // Health limits (docs/reliability.md): the domain is the box between the
    // end walls (2 h0 beyond) from h0 below the base up to the height of all
    // the material stacked in one column h0 wide; the speed bound is twice the
    // free-fall speed from that height plus ten times the belt speed.
    HealthLimits lim;
    lim.max_overlap_ratio = c.run.max_overlap_ratio;
    const double ceiling = c.run.domain_height > 0.0 ? c.run.domain_height * h0
                                                     : w.pro_length + w.retro_length + 2.0 * h0;
    lim.y_min = -h0;
    lim.y_max = ceiling;
    lim.x_max = (w.retro_length > 0.0 ? w.retro_length : 0.0) + 2.0 * h0;
    lim.max_speed = 2.0 * std::sqrt(2.0 * c.numerics.gravity * ceiling) + 10.0 * c.wedge.v;
    auto update_limits = [&]() { lim.x_min = sim.walls[kWallProEnd].a.x - 2.0 * h0; };

    std::string last_good;           // checkpoint bytes of the last output that passed the checks
    std::uint64_t last_good_step = 0;
    std::string last_good_snapshot;  // its snapshot
    auto state_bytes = [&]() {
        st.series_bytes = file_bytes(series_path);
        st.log_bytes = file_bytes(dir + "/log.txt");
        return encode_checkpoint(sim, st, cfg_hash);
    };
    auto last_checkpoint_time = std::chrono::steady_clock::now();
    auto save_checkpoint = [&](const std::string& bytes) {
        const std::string path = write_checkpoint(ckpt_dir, sim.step_count, bytes);
        last_checkpoint_time = std::chrono::steady_clock::now();
        return path;
    };
    // Stops the run: snapshot of the bad state for inspection, checkpoint of
    // the last good one, InstabilityError (exit 3).
    // run.on_domain_exit = "stop": set by check(), carried out by the loop.
    std::optional<HealthProblem> stop_for;
    auto check = [&]() {
        update_limits();
        HealthLimits now = lim;
        if (initial_overlap_allowed && sim.step_count == first_step) now.max_overlap_ratio = 1e300;
        const auto problem = check_health(sim, now);
        if (!problem) return;
        if (problem->what == "left the domain" && c.run.on_domain_exit == "stop") {
            stop_for = problem;
            return;
        }
        const double S = c.wedge.v * sim.time / h0;
        std::string saved = "no earlier good state was kept";
        if (!last_good.empty()) {
            const std::string path = write_checkpoint(ckpt_dir, last_good_step, last_good, 0);
            saved = fmt::format("last good state: step {} (snapshot {}, checkpoint {})", last_good_step,
                                last_good_snapshot, path);
        }
        std::string bad_snapshot;
        try {
            bad_snapshot = fmt::format("{}/snapshots/unstable-step{}.vtu", dir, sim.step_count);
            write_vtu(bad_snapshot, sim.particles, std::vector<double>(sim.particles.size(), 0.0));
        } catch (const std::exception&) {
            bad_snapshot = "(could not be written)";
        }
        const std::string msg = fmt::format(
            "step {} (S = {:.4f}): disc {} at ({:.6g}, {:.6g}) m: {} ({}). Likely cause: {}. {}; the state at "
            "the failure is in {}",
            sim.step_count, S, problem->id, problem->x.x, problem->x.y, problem->what, problem->detail,
            problem->advice, saved, bad_snapshot);
        log.line("UNSTABLE: " + msg);
        throw InstabilityError(msg);
    };

    auto write_row = [&]() -> WedgeMeasures {
        const double S = c.wedge.v * sim.time / h0;
        const double ke = sim.kinetic_energy();
        if (!std::isfinite(ke))
            throw InstabilityError(fmt::format("non-finite kinetic energy at step {} (S = {:.3f}); reduce "
                                               "numerics.safety or wedge.v", sim.step_count, S));
        const WedgeMeasures m = measure_wedge(sim.particles, w.profile, c.wedge.v * sim.time);
        const std::size_t fixed = w.fixed_retro ? w.fixed_retro->fixed_count() : 0;
        series.line(csv_first_fields(fmt::format("{},{:.9g},{:.6f},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.9g},{},{:.6g},{:.6g},{:.6g},"
                                "{:.6g},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}",
                                sim.step_count, sim.time, S, m.H_over_h0, m.alpha_deg, m.beta_deg,
                                m.peak_dx_over_h0, m.dilation_pct, ke, sim.touching_contacts(),
                                sim.max_overlap_ratio(), m.toe_pro_x / h0, m.toe_retro_x / h0,
                                w.base->total_traction(), w.base->discs_on_base(), w.base->discs_sliding(), fixed,
                                sim.mean_overlap_ratio(), sim.max_speed(), sim.wall_force(kWallProBase).y,
                                -sim.wall_force(kWallProEnd).x, m.beta_inner_deg, m.beta_outer_deg,
                                m.retro_break_x / h0),
                                series_columns));
        const double secs = progress.elapsed();
        const double rate =
            static_cast<double>(sim.step_count - rate_from_step) / std::max(secs - rate_from_secs, 1e-9);
        rate_from_step = sim.step_count;
        rate_from_secs = secs;
        log.line(fmt::format("S = {:.3f}: H/h0 = {:.3f}, alpha = {:.2f}, beta = {:.2f}; health: max overlap/R = {:.4f}, "
                             "max speed = {:.3g} m/s, contacts/disc = {:.2f}; {} discs asleep; {:.0f} steps/s",
                             S, m.H_over_h0, m.alpha_deg, m.beta_deg, sim.max_overlap_ratio(), sim.max_speed(),
                             static_cast<double>(sim.touching_contacts()) / static_cast<double>(sim.particles.size()),
                             sim.sleeping_count(), rate));
        progress.run_line(S, c.wedge.s_max, first_step, sim.step_count, total_steps, true);
        return m;
    };
    make_dirs(dir + "/figures");
    make_dirs(dir + "/snapshots");
    if (!resumed) st.x_then = positions_by_id(sim.particles);
    ViewOptions view;
    view.x_min = w.profile.x_min;
    view.x_max = w.profile.x_max;
    view.y_min = 0.0;
    view.y_max = 4.0 * h0;
    view.h0 = h0;
    view.band = h0 / 5.0;
    auto draw = [&]() {
        const double S = c.wedge.v * sim.time / h0;
        const std::vector<double> rel = relative_displacement(sim, st.x_then);
        std::vector<Vec2> x_now = positions_by_id(sim.particles);
        // Strain over the interval since the previous output (none at S = 0):
        // neighbourhoods of two mean disc diameters (analysis/strain.hpp).
        const StrainField strain =
            local_strain(st.x_then, x_now, 2.0 * (c.packing.r_min + c.packing.r_max));
        st.x_then = std::move(x_now);
        const std::string name = fmt::format("S{:06.3f}", S);
        const VtuStamp stamp{S, sim.step_count, sim.time};
        write_vtu(fmt::format("{}/snapshots/{}.vtu", dir, name), sim.particles, rel, &stamp, &strain);
        st.pvd.emplace_back(S, fmt::format("snapshots/{}.vtu", name));
        write_pvd(dir + "/run.pvd", st.pvd);
        view.label = fmt::format("{}   S = {:.2f}   initial depth", c.run.experiment, S);
        view.color_by = "horizons";
        render_particles(sim.particles, nullptr, view, fmt::format("{}/figures/horizons_{}.png", dir, name));
        if (sim.step_count > 0) {
            view.label = fmt::format("{}   S = {:.2f}   relative displacement since the previous output", c.run.experiment, S);
            view.color_by = "displacement";
            render_particles(sim.particles, &rel, view, fmt::format("{}/figures/displacement_{}.png", dir, name));
        }
    };
    // One output: checks, row, snapshot and pictures, then the state kept as
    // the last good one and (every checkpoint_every_outputs) a checkpoint.
    // The free space is checked at every output against what the rest of the
    // run writes (after the checkpoint, so a stop for space can be resumed).
    bool overlap_warned = false;  // stderr once; log.txt at every output
    // The paper's plates are infinite slabs ([40]): once the raised surface
    // runs back to within h0 of the trailing wall, the wall pushes the
    // deformed plate and the toe, α and D measure the whole plate. Said once
    // per process, on stderr and in log.txt (never at S = 0: plate_at_trailing_wall).
    bool wall_warned = false;
    auto output = [&]() {
        check();
        const WedgeMeasures m = write_row();
        draw();
        if (const double wall_x = sim.walls[kWallProEnd].a.x;
            !wall_warned && plate_at_trailing_wall(m, wall_x, h0, c.wedge.v * sim.time)) {
            const std::string msg = fmt::format(
                "the prowedge reaches the trailing wall at S = {:.3f} (toe at {:.2f} h0, wall at {:.2f} h0 from the "
                "S point): from here the wall pushes the deformed plate, and the toe, alpha and D measure the whole "
                "plate; the incoming plate is too short for this run: raise wedge.pro_margin (now {:g} h0)",
                c.wedge.v * sim.time / h0, m.toe_pro_x / h0, wall_x / h0, c.wedge.pro_margin);
            log.line("warning: " + msg);
            fmt::print(stderr, "\norodem: warning: {}\n", msg);
            wall_warned = true;
        }
        ++st.outputs;
        if (const double worst = sim.max_overlap_ratio(); worst > c.run.warn_overlap_ratio) {
            const std::string msg = fmt::format(
                "largest overlap/R = {:.4f} at step {} (S = {:.3f}) is above run.warn_overlap_ratio = {:g} (the run "
                "stops at run.max_overlap_ratio = {:g}); consider a smaller wedge.v or numerics.safety, or a larger "
                "material.k_n",
                worst, sim.step_count, c.wedge.v * sim.time / h0, c.run.warn_overlap_ratio, c.run.max_overlap_ratio);
            log.line("warning: " + msg);
            if (!overlap_warned) fmt::print(stderr, "\norodem: warning: {} (further warnings in log.txt only)\n", msg);
            overlap_warned = true;
        }
        const bool stopping = stop_for.has_value();
        last_good = state_bytes();
        last_good_step = sim.step_count;
        last_good_snapshot = st.pvd.back().second;
        if (st.outputs % static_cast<std::uint64_t>(c.run.checkpoint_every_outputs) == 0 ||
            sim.step_count >= total_steps || stopping)
            save_checkpoint(last_good);
        if (stopping) {
            const HealthProblem& pr = *stop_for;
            const std::string msg = fmt::format(
                "step {} (S = {:.4f}): disc {} at ({:.6g}, {:.6g}) m left the domain ({}); run stopped as "
                "run.on_domain_exit = \"stop\" asks: the outputs and the checkpoint of this step are written. "
                "Likely cause: {}",
                sim.step_count, c.wedge.v * sim.time / h0, pr.id, pr.x.x, pr.x.y, pr.detail, pr.advice);
            log.line("STOPPED: " + msg);
            throw InstabilityError(msg);
        }
        check_free_space(dir, st.pvd.back().second, n_outputs + 1 - std::min(n_outputs + 1, st.outputs),
                         last_good.size());
    };

    StopSignals signals;
    if (resumed) {
        if (!st.pvd.empty()) {
            write_pvd(dir + "/run.pvd", st.pvd);
            last_good = encode_checkpoint(sim, st, cfg_hash);
            last_good_step = sim.step_count;
            last_good_snapshot = st.pvd.back().second;
            check_free_space(dir, st.pvd.back().second, n_outputs + 1 - std::min(n_outputs + 1, st.outputs),
                             last_good.size());
        }
    } else {
        output();
    }
    // Steps in chunks of at most 100 (chunking does not change the result):
    // between chunks, the signal flag and the wall-clock checkpoint timer are
    // looked at; every 1000 steps the state is checked.
    constexpr std::uint64_t kChunk = 100;
    constexpr std::uint64_t kCheckEvery = 1000;
    const double checkpoint_secs = 60.0 * c.run.checkpoint_minutes;
    while (sim.step_count < total_steps) {
        const std::uint64_t next_output = std::min(total_steps, (sim.step_count / steps_per_output + 1) * steps_per_output);
        const std::uint64_t next_stop = std::min(next_output, (sim.step_count / kChunk + 1) * kChunk);
        sim.advance(next_stop - sim.step_count);
        progress.run_line(c.wedge.v * sim.time / h0, c.wedge.s_max, first_step, sim.step_count, total_steps, false);
        if (sim.step_count == next_output) {
            output();
        } else if (sim.step_count % kCheckEvery == 0) {
            check();
            if (stop_for) output();  // writes this step's outputs and checkpoint, then stops (exit 3)
        }
        // Stopping between chunks (a signal, a batch job's time limit:
        // RELIABILITY-CHECKLIST 10): a checked state, a checkpoint, a log
        // line and on stderr the command that continues the run.
        auto stop_with_checkpoint = [&](const std::string& why, const char* continue_label) {
            if (sim.step_count != next_output) check();
            const std::string path = save_checkpoint(state_bytes());
            const std::string what = fmt::format("{} at step {} (S = {:.4f}) after {:.1f} s wall", why, sim.step_count,
                                                 c.wedge.v * sim.time / h0, progress.elapsed());
            log.line(fmt::format("{}; checkpoint {}", what, path));
            log.line("step phases (this process): " + phase_breakdown(sim.phase_times()));
            progress.done();
            fmt::print(stderr, "orodem: {}; checkpoint written to {}\n{}: orodem run {}/config.toml --out {} --resume\n",
                       what, path, continue_label, dir, dir);
        };
        if (const int sig = signals.pending()) {
            stop_with_checkpoint(fmt::format("interrupted by {}", sig == SIGINT ? "SIGINT" : "SIGTERM"), "resume with");
            return 128 + sig;
        }
        if (c.run.max_wall_minutes > 0.0 && progress.elapsed() >= 60.0 * c.run.max_wall_minutes &&
            sim.step_count < total_steps) {
            stop_with_checkpoint(
                fmt::format("stopped at the wall-time limit run.max_wall_minutes = {:g}", c.run.max_wall_minutes),
                "continue with");
            return static_cast<int>(ExitCode::time_limit);
        }
        if (checkpoint_secs > 0.0 && sim.step_count != next_output &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint_time).count() >=
                checkpoint_secs) {
            if (sim.step_count % kCheckEvery != 0) check();
            if (stop_for) output();
            save_checkpoint(state_bytes());
        }
    }
    progress.done();
    log.line(fmt::format("finished: S = {:.3f} after {} steps, {:.1f} s wall", c.wedge.v * sim.time / h0,
                         sim.step_count, progress.elapsed()));
    log.line("step phases (this process): " + phase_breakdown(sim.phase_times()));
    cmd_plot({dir}, dir + "/figures/plots.png");
    return 0;
}

/// run_wedge, and when an I/O error (a full disk, a failed write) stops it,
/// an end line in log.txt first (if the log can still be written), so that
/// orodem status says how the piece ended and adds up its wall time.
int run_wedge_logging_io_stops(const Config& c, WedgeSetup& w, const std::string& dir, LineFile& log,
                               const RunLoopState* resumed) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
        return run_wedge(c, w, dir, log, resumed);
    } catch (const IoError& e) {
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        try {
            log.line(fmt::format("stopped by an I/O error at step {} (S = {:.4f}) after {:.1f} s wall: {}",
                                 w.sim.step_count, c.wedge.v * w.sim.time / c.packing.h0, secs, e.what()));
        } catch (const IoError&) {
            // The log cannot be written either (the disk is full): orodem status
            // then says "no end line"; the exit status (4) and stderr say why.
        }
        throw;
    }
}

/// A wedge run from the beginning in dir (config.toml and log.txt exist).
int start_wedge(const Config& c, const std::string& dir, LineFile& log) {
    const ParticleStore layer = prepare_layer(c, dir, log, nullptr);
    WedgeSetup w = make_wedge(c, layer);
    const int rc = run_wedge_logging_io_stops(c, w, dir, log, nullptr);
    if (rc != 0) return rc;
    fmt::print("outputs in {}/ (config.toml, log.txt, series.csv)\n", dir);
    return 0;
}

/// The first line where the resolved configs differ, ignoring the keys that
/// do not change results (run.threads, run.checkpoint_minutes, run.max_wall_minutes); "" if none.
std::string first_config_difference(const Config& a, const Config& b) {
    auto lines = [](const Config& c) {
        std::vector<std::string> out;
        std::istringstream in(to_toml(c));
        std::string section, l;
        while (std::getline(in, l)) {
            if (!l.empty() && l[0] == '[') section = l;
            if (l.rfind("threads =", 0) == 0 || l.rfind("checkpoint_minutes =", 0) == 0 ||
                l.rfind("max_wall_minutes =", 0) == 0)
                continue;
            out.push_back(section + " " + l);
        }
        return out;
    };
    const auto la = lines(a), lb = lines(b);
    for (std::size_t k = 0; k < std::max(la.size(), lb.size()); ++k) {
        const std::string x = k < la.size() ? la[k] : "(nothing)", y = k < lb.size() ? lb[k] : "(nothing)";
        if (x != y) return fmt::format("the run has '{}', this config has '{}'", x, y);
    }
    return "";
}

/// Data rows of a series.csv (lines after the header); 0 when it is absent.
std::size_t series_rows(const std::string& path) {
    if (!fs::exists(path)) return 0;
    const std::string text = read_file(path);
    const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    return lines > 0 ? lines - 1 : 0;
}

/// Cuts a file back to its length at the checkpoint.
void truncate_to(const std::string& path, std::uint64_t bytes) {
    const std::uint64_t now = file_bytes(path);
    if (now < bytes)
        throw IoError(fmt::format("'{}' has {} bytes, fewer than the {} it had at the checkpoint; the run directory "
                                  "was changed after the checkpoint, so it cannot be resumed exactly",
                                  path, now, bytes));
    if (::truncate(path.c_str(), static_cast<off_t>(bytes)) != 0) throw_io_error("cannot truncate", path);
}

}  // namespace

int resume_run(const Config& c, const std::string& dir) {
    if (dir.empty())
        throw ConfigError("--resume needs --out DIR: the run directory to continue (it holds config.toml and checkpoint/)");
    if (!is_wedge(c))
        throw ConfigError(fmt::format("--resume: run.experiment = \"{}\" writes no checkpoints; only the wedge "
                                      "experiments can be resumed", c.run.experiment));
    if (!fs::exists(dir + "/config.toml"))
        throw ConfigError(fmt::format("--resume --out {}: no config.toml there; give the directory of the run to continue", dir));
    const Config saved = load_config(dir + "/config.toml");
    if (config_hash(saved) != config_hash(c))
        throw ConfigError(fmt::format("--resume --out {}: {} differs from the run's config ({}); resume with "
                                      "orodem run {}/config.toml --out {} --resume",
                                      dir, c.path, first_config_difference(saved, c), dir, dir));
    if (orodem::list_checkpoints(dir + "/checkpoint").empty()) {
        // Outputs but no checkpoint (checkpoint/ deleted or emptied): they
        // cannot be continued, and starting again would rewrite them.
        if (const std::size_t rows = series_rows(dir + "/series.csv"); rows > 0)
            throw ConfigError(fmt::format(
                "--resume {}: no checkpoint in {}/checkpoint/, but series.csv has {} output rows; a resume cannot "
                "continue them and would overwrite them, so nothing was changed. Keep the run as it is, or start "
                "it again in a new directory: orodem run {}/config.toml --out NEW_DIR",
                dir, dir, rows, dir));
        // Interrupted before its first checkpoint (while settling): nothing
        // to continue, so the run starts from the beginning in the same place.
        for (const char* partial : {"series.csv", "run.pvd", "snapshots", "figures", "checkpoint"})
            fs::remove_all(fs::path(dir) / partial);
        LineFile log(dir + "/log.txt");
        log.line(fmt::format("resumed by orodem {}: no checkpoint yet, so the run starts from the beginning",
                             ORODEM_VERSION));
        fmt::print("{} has no checkpoint yet: starting the run from the beginning\n", dir);
        return start_wedge(c, dir, log);
    }
    WedgeSetup w = make_wedge(c, ParticleStore{});
    RunLoopState st;
    std::vector<std::string> notes;
    std::string path;
    try {
        path = restore_newest_checkpoint(dir + "/checkpoint", config_hash(c), w.sim, st, &notes);
    } catch (const CheckpointError& e) {
        // Every checkpoint is damaged: nothing to continue from; nothing changed.
        throw ConfigError(fmt::format("--resume {}: {}; nothing was changed. Keep the run as it is, or start it "
                                      "again in a new directory: orodem run {}/config.toml --out NEW_DIR",
                                      dir, e.what(), dir));
    }
    for (const auto& n : notes) fmt::print(stderr, "orodem: warning: {}\n", n);
    // log.txt beyond the checkpoint: the rows and warnings that the resumed
    // run writes again, and the history of the pieces since: the previous
    // piece's end line (a signal, a time limit) with its phase times, and the
    // start line of a piece killed before its first checkpoint. Those are
    // kept, so that the log and orodem status show every piece and how it
    // ended and ran.
    std::vector<std::string> history;
    {
        const std::string log_text = read_file(dir + "/log.txt");
        std::istringstream tail(log_text.size() > st.log_bytes ? log_text.substr(st.log_bytes) : std::string());
        for (std::string line; std::getline(tail, line);)
            if (starts_or_ends_a_piece(line) || line.rfind("step phases (this process)", 0) == 0)
                history.push_back(line);
    }
    truncate_to(dir + "/series.csv", st.series_bytes);
    truncate_to(dir + "/log.txt", st.log_bytes);
    LineFile log(dir + "/log.txt");
    for (const auto& line : history) log.line(line);
    for (const auto& n : notes) log.line("warning: " + n);
    log.line(fmt::format("resumed by orodem {} from {} at step {} (S = {:.4f}) with {} threads", ORODEM_VERSION, path,
                         w.sim.step_count, c.wedge.v * w.sim.time / c.packing.h0, omp_get_max_threads()));
    fmt::print("resuming {} from step {} ({})\n", dir, w.sim.step_count, path);
    const int rc = run_wedge_logging_io_stops(c, w, dir, log, &st);
    if (rc == 0) fmt::print("outputs in {}/ (config.toml, log.txt, series.csv)\n", dir);
    return rc;
}


int cmd_run(const CommonArgs& a, const std::string& out_arg, bool resume) {
    const Config c = load(a);
    if (is_calibration(c))
        throw ConfigError(fmt::format("{}: run.experiment = \"{}\" is a calibration experiment: run it with orodem "
                                      "calibrate {}", c.path, c.run.experiment, c.path));
    check_runnable(c);
    set_threads(c);
    if (resume) return resume_run(c, out_arg);
    const std::string dir = choose_run_dir(out_arg, c.path);
    make_dirs(dir);
    return start_run_in(c, dir);
}

int start_run_in(const Config& c, const std::string& dir) {
    const TimestepInfo t = timestep_for(c);
    write_file_atomic(dir + "/config.toml", to_toml(c));
    LineFile log(dir + "/log.txt");
    log.line(fmt::format("orodem {} run of {} ({}) with {} threads", ORODEM_VERSION, c.path, c.run.experiment,
                         omp_get_max_threads()));
    log.line(fmt::format("dt = {:.6g} s, stability limit {:.6g} s (margin {:.2f}x), t_c = {:.1f} steps",
                         t.dt, t.dt_crit, t.margin(), t.t_collision / t.dt));
    // RELIABILITY-CHECKLIST 3: stable but coarse steps are allowed with a warning.
    std::vector<std::string> coarse;
    if (t.t_collision / t.dt < 20.0)
        coarse.push_back(fmt::format("a collision (t_c = {:.4g} s) spans only {:.1f} steps of dt = {:.4g} s, fewer than "
                                     "20; lower numerics.safety or numerics.dt for accurate contacts",
                                     t.t_collision, t.t_collision / t.dt, t.dt));
    if (const std::string w = is_wedge(c) ? short_plate_warning(c) : std::string(); !w.empty()) coarse.push_back(w);
    if (is_wedge(c) && c.wedge.v * t.dt > 0.1 * c.packing.r_min)
        coarse.push_back(fmt::format("the belt moves {:.4g} m per step, more than 0.1 r_min = {:.4g} m; lower "
                                     "wedge.v or numerics.dt",
                                     c.wedge.v * t.dt, 0.1 * c.packing.r_min));
    for (const auto& w : coarse) {
        log.line("warning: " + w);
        fmt::print(stderr, "orodem: warning: {}\n", w);
    }
    if (!is_wedge(c)) {
        LineFile series(dir + "/series.csv");
        // Header always; rows only when the layer is settled now (not cached).
        series.line("step,time,kinetic_energy,ke_ratio,contacts,max_overlap_ratio");
        const ParticleStore layer = prepare_layer(c, dir, log, &series);
        save_packing(dir + "/packing.bin", layer, packing_key(c));
        const double surface = mean_surface_height(layer, 0.0, c.packing.length, 2.0 * c.packing.r_max);
        log.line(fmt::format("layer: {} discs, mean surface height {:.4g} m (h0 = {:g} m)", layer.size(), surface,
                             c.packing.h0));
        fmt::print("layer of {} discs ready, mean surface {:.3g} m\n", layer.size(), surface);
        fmt::print("outputs in {}/ (config.toml, log.txt, series.csv, packing.bin)\n", dir);
        return 0;
    }
    return start_wedge(c, dir, log);
}

void ensure_packing_cached(const Config& c, const std::string& log_path) {
    LineFile log(log_path);
    prepare_layer(c, fs::path(log_path).parent_path().string(), log, nullptr);
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
