#include "orodem/run/wedge_run.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "orodem/analysis/basal_decoupling.hpp"
#include "orodem/analysis/rel_disp.hpp"
#include "orodem/analysis/section_force.hpp"
#include "orodem/analysis/strain.hpp"
#include "orodem/boundary/basal_boundary.hpp"
#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/fault_table.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/io/series_reader.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/run_plots.hpp"
#include "orodem/run/series_columns.hpp"

namespace orodem {

namespace {

constexpr std::uint64_t kStepsPerChunk = 100;        // steps between looks at signals and timers
constexpr std::uint64_t kCheckEvery = 1000;  // steps between health checks

}  // namespace

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

int WedgeRun::run() {
    StopWatch watch(obs_);
    if (resumed_) continue_from_checkpoint();
    else output();
    while (sim_.step_count < total_steps_) {
        const std::uint64_t next_output = next_output_step();
        std::uint64_t to = std::min(next_output, (sim_.step_count / kStepsPerChunk + 1) * kStepsPerChunk);
        if (surface_.active()) to = std::min(to, surface_.next_step(sim_.step_count));
        if (flexure_.on()) to = std::min(to, flexure_.next_step(sim_.step_count));
        advance_to(to);
        if (surface_.due(sim_.step_count)) surface_.apply(sim_, st_.surface, S(), st_.x_then, eroded_file_);
        if (flexure_.due(sim_.step_count) && sim_.step_count != next_output) flexure_.solve(sim_, st_.flexure);
        if (sim_.step_count == next_output) {
            output();
        } else if (sim_.step_count % kCheckEvery == 0) {
            check();
            if (stop_for_) output();  // writes this step's outputs and checkpoint, then stops (exit 3)
        }
        // Stopping between chunks (a signal, a batch job's time limit:
        // RELIABILITY-CHECKLIST 10): a checked state, a checkpoint, a log
        // line and the command that continues the run.
        if (const int sig = obs_.stop_requested()) {
            if (sim_.step_count != next_output) check();
            stop_with_checkpoint(RunEvent::interrupted, fmt::format("interrupted by {}", stop_signal_name(sig)),
                                 "resume with");
            return 128 + sig;
        }
        if (wall_time_limit_reached()) {
            if (sim_.step_count != next_output) check();
            stop_with_checkpoint(
                RunEvent::time_limit, fmt::format("stopped at the wall-time limit run.max_wall_minutes = {:g}", c_.run.max_wall_minutes),
                "continue with");
            return static_cast<int>(ExitCode::time_limit);
        }
        if (checkpoint_timer_due(next_output)) {
            if (sim_.step_count % kCheckEvery != 0) check();
            if (stop_for_) output();
            save_checkpoint(state_bytes());
        }
    }
    finish();
    return 0;
}

WedgeRun::WedgeRun(const Config& c, WedgeSetup& w, const std::string& dir, RunLog& log, RunObserver& observer,
                   const RunLoopState* resumed)
    : c_(c), w_(w), sim_(w.sim), dir_(dir), log_(log), obs_(observer), resumed_(resumed != nullptr),
      h0_(c.packing.h0), cfg_hash_(config_hash(c)),
      adapt_threads_(omp_get_max_threads() > 1 && ThreadGovernor::enabled_by_environment()),
      threads_(omp_get_max_threads()), surface_(c, w), flexure_(c, w) {
    if (resumed) {
        st_ = *resumed;
        w_.profile.y_mean = st_.surface_y_mean;
    } else {
        start_from_layer();
    }
    const std::string series_path = dir_ + "/series.csv";
    // A run that an older orodem started keeps the columns it started with.
    series_columns_ = std::numeric_limits<std::size_t>::max();
    if (resumed_ && !surface_.on() && !flexure_.on()) {
        const std::string text = read_file(series_path);
        series_columns_ = csv_leading_columns(text.substr(0, text.find('\n')), series_header(), series_path);
    }
    // With [surface] the ledger's columns follow (run/surface_erosion.hpp),
    // with [flexure] the plate's (run/wedge_flexure.hpp).
    if (surface_.on()) {
        if (resumed_ && !st_.surface.on)
            throw ConfigError("the checkpoint has no erosion state ([surface]); resume with the run's own config.toml");
        if (!resumed_) surface_.start(sim_.particles, st_.surface);
        else surface_.resume(sim_.particles, st_.surface);
        eroded_file_ = LineFile(dir_ + "/eroded.csv");
        if (!resumed_) eroded_file_.line(eroded_header());
    }
    if (flexure_.on()) {
        if (resumed_ && !st_.flexure.on)
            throw ConfigError("the checkpoint has no plate state ([flexure]); resume with the run's own config.toml");
        if (!resumed_) flexure_.start(sim_, st_.flexure);  // two-way: the layer onto the bent base
        else flexure_.resume(sim_, st_.flexure);          // two-way: the bases' shape again
        flexure_file_ = LineFile(dir_ + "/flexure.csv");
        if (!resumed_) flexure_file_.line(flexure_profile_header());
    }
    if (surface_.on() || flexure_.on()) {
        const std::string full = series_header() + extra_series_header();
        if (resumed_) {
            const std::string text = read_file(series_path);
            if (text.substr(0, text.find('\n')) != full)
                throw ConfigError(fmt::format("'{}' does not have the columns of a run with{}{}", series_path,
                                              surface_.on() ? " [surface]" : "", flexure_.on() ? " [flexure]" : ""));
        }
        series_columns_ = std::numeric_limits<std::size_t>::max();
    }
    series_ = LineFile(series_path);
    if (!resumed_) series_.line(series_header() + extra_series_header());
    // faults.csv: a run resumed from a checkpoint older than the fault table
    // (faults_bytes = 0) starts it at the resume.
    const std::string faults_path = dir_ + "/faults.csv";
    const bool faults_new = !resumed_ || st_.faults_bytes == 0;
    faults_file_ = LineFile(faults_path);
    if (faults_new) faults_file_.line(faults_header());
    const double d_mean = c_.packing.r_min + c_.packing.r_max;
    fault_params_ = fault_params(d_mean, h0_);
    const double dt = sim_.params.dt;
    steps_per_output_ = std::max<std::uint64_t>(
        1, static_cast<std::uint64_t>(std::llround(c_.wedge.output_ds * h0_ / (c_.wedge.v * dt))));
    // Whole output intervals only, so the last row sits on s_max (to one step).
    n_outputs_ = static_cast<std::uint64_t>(std::max(1LL, std::llround(c_.wedge.s_max / c_.wedge.output_ds)));
    total_steps_ = n_outputs_ * steps_per_output_;
    first_step_ = sim_.step_count;
    rate_from_step_ = first_step_;
    t0_ = std::chrono::steady_clock::now();
    last_checkpoint_time_ = t0_;

    // Health limits (docs/reliability.md): the domain is the box between the
    // end walls (2 h0 beyond) from h0 below the base up to the height of all
    // the material stacked in one column h0 wide; the speed bound is twice the
    // free-fall speed from that height plus ten times the belt speed.
    lim_.max_overlap_ratio = c_.run.max_overlap_ratio;
    const double ceiling = c_.run.domain_height > 0.0 ? c_.run.domain_height * h0_
                                                      : w_.pro_length + w_.retro_length + 2.0 * h0_;
    lim_.y_min = -h0_;
    lim_.y_max = ceiling;
    lim_.x_max = (w_.retro_length > 0.0 ? w_.retro_length : 0.0) + 2.0 * h0_;
    lim_.max_speed = 2.0 * std::sqrt(2.0 * c_.numerics.gravity * ceiling) + 10.0 * c_.wedge.v;

    make_dirs(dir_ + "/figures");
    make_dirs(dir_ + "/snapshots");
    if (!resumed_) st_.x_then = positions_by_id(sim_.particles);
    view_ = run_view(config_basics(c_));  // the frame of every picture of the run
}

void WedgeRun::start_from_layer() {
    sim_.initialize();
    st_.surface_y_mean = w_.profile.y_mean;
    log_.line(fmt::format("{}: {} discs, incoming plate {:.4g} h0, retroside {:.4g} h0, undeformed surface "
                          "y_mean = {:.4g} m, v = {:g} m/s",
                          c_.run.experiment, sim_.particles.size(), w_.pro_length / h0_, w_.retro_length / h0_,
                          w_.profile.y_mean, c_.wedge.v));
    // RELIABILITY-CHECKLIST 4: the initial layer's overlaps, reported, and
    // refused above the stop level unless run.allow_initial_overlap.
    const OverlapSummary o = overlap_summary(sim_, c_.run.warn_overlap_ratio);
    const std::string where =
        o.touching == 0 ? std::string("no discs touch")
                        : fmt::format("worst overlap/R = {:.4f} between discs {} at ({:.6g}, {:.6g}) m and {} at "
                                      "({:.6g}, {:.6g}) m",
                                      o.worst, o.id_i, o.x_i.x, o.x_i.y, o.id_j, o.x_j.x, o.x_j.y);
    log_.line(fmt::format("initial overlaps: {} touching pairs, {} above run.warn_overlap_ratio = {:g}; {}",
                          o.touching, o.above, c_.run.warn_overlap_ratio, where));
    if (o.worst <= c_.run.max_overlap_ratio) return;
    if (!c_.run.allow_initial_overlap)
        throw ConfigError(fmt::format(
            "the initial layer is not settled: {} (above run.max_overlap_ratio = {:g}; {} pairs above "
            "run.warn_overlap_ratio = {:g}); delete the packing cache {} to settle it again, or set "
            "run.allow_initial_overlap = true to start anyway",
            where, c_.run.max_overlap_ratio, o.above, c_.run.warn_overlap_ratio, packing_cache_path(c_)));
    initial_overlap_allowed_ = true;
    log_.line("warning: starting anyway (run.allow_initial_overlap = true); the overlap limit applies from "
              "the first health check after step 0");
}

void WedgeRun::continue_from_checkpoint() {
    if (st_.pvd.empty()) return;
    write_pvd(dir_ + "/run.pvd", st_.pvd);
    last_good_ = encode_checkpoint(sim_, st_, cfg_hash_);
    last_good_step_ = sim_.step_count;
    last_good_snapshot_ = st_.pvd.back().second;
    check_space_left();
}

std::uint64_t WedgeRun::next_output_step() const {
    return std::min(total_steps_, (sim_.step_count / steps_per_output_ + 1) * steps_per_output_);
}

void WedgeRun::advance_to(std::uint64_t step) {
    const std::uint64_t n = step - sim_.step_count;
    if (!adapt_threads_) {
        sim_.advance(n);
    } else {
        omp_set_num_threads(threads_.threads());
        const auto t0 = std::chrono::steady_clock::now();
        sim_.advance(n);
        threads_.record(n, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        say_thread_changes(threads_, log_, obs_);
    }
    obs_.progress({S(), c_.wedge.s_max, first_step_, sim_.step_count, total_steps_, elapsed(), false});
}

void WedgeRun::output() {
    check();
    measure_structures();
    const WedgeMeasures m = write_row();
    draw();
    warn_if_plate_too_short(m);
    ++st_.outputs;
    warn_if_overlapping();
    keep_as_last_good();
    stop_if_left_domain();
    check_space_left();
}

// Stops the run on a health problem: a snapshot of the bad state for
// inspection, the checkpoint of the last good one, InstabilityError (exit 3).
// A disc leaving the domain under run.on_domain_exit = "stop" is kept in
// stop_for_ instead, and output() stops after writing this step.
void WedgeRun::check() {
    lim_.x_min = sim_.walls[kWallProEnd].a.x - 2.0 * h0_;
    HealthLimits now = lim_;
    if (initial_overlap_allowed_ && sim_.step_count == first_step_) now.max_overlap_ratio = 1e300;
    const auto problem = check_health(sim_, now);
    if (!problem) return;
    if (problem->what == "left the domain" && c_.run.on_domain_exit == "stop") {
        stop_for_ = problem;
        return;
    }
    std::string saved = "no earlier good state was kept";
    if (!last_good_.empty()) {
        const std::string path = write_checkpoint(dir_ + "/checkpoint", last_good_step_, last_good_, 0);
        saved = fmt::format("last good state: step {} (snapshot {}, checkpoint {})", last_good_step_,
                            last_good_snapshot_, path);
    }
    std::string bad_snapshot;
    try {
        bad_snapshot = fmt::format("{}/snapshots/unstable-step{}.vtu", dir_, sim_.step_count);
        write_vtu(bad_snapshot, sim_.particles, std::vector<double>(sim_.particles.size(), 0.0));
    } catch (const std::exception&) {
        bad_snapshot = "(could not be written)";
    }
    const std::string msg = fmt::format(
        "step {} (S = {:.4f}): disc {} at ({:.6g}, {:.6g}) m: {} ({}). Likely cause: {}. {}; the state at "
        "the failure is in {}",
        sim_.step_count, S(), problem->id, problem->x.x, problem->x.y, problem->what, problem->detail,
        problem->advice, saved, bad_snapshot);
    event(RunEvent::unstable, "UNSTABLE: " + msg);
    throw InstabilityError(msg);
}

WedgeMeasures WedgeRun::write_row() {
    const double ke = sim_.kinetic_energy();
    if (!std::isfinite(ke))
        throw InstabilityError(fmt::format("non-finite kinetic energy at step {} (S = {:.3f}); reduce "
                                           "numerics.safety or wedge.v", sim_.step_count, S()));
    SeriesRow r;
    r.step = sim_.step_count;
    r.time = sim_.time;
    r.S = S();
    r.m = measure_wedge(sim_.particles, w_.profile, c_.wedge.v * sim_.time);
    r.h0 = h0_;
    r.kinetic_energy = ke;
    r.contacts = sim_.touching_contacts();
    r.max_overlap_ratio = sim_.max_overlap_ratio();
    r.base_traction = w_.base->total_traction();
    r.discs_on_base = w_.base->discs_on_base();
    r.discs_sliding = w_.base->discs_sliding();
    r.fixed_discs = w_.fixed_retro ? w_.fixed_retro->fixed_count() : 0;
    r.mean_overlap_ratio = sim_.mean_overlap_ratio();
    r.max_speed = sim_.max_speed();
    r.base_normal_force = sim_.wall_force(kWallProBase).y;
    r.trailing_wall_push = -sim_.wall_force(kWallProEnd).x;
    r.section_push = std::isfinite(r.m.toe_pro_x)
                         ? section_force(sim_.particles, sim_.contacts, r.m.toe_pro_x - h0_, sim_.params.period_x).x
                         : std::nan("");
    r.pro_faults = fault_counts_.pro;
    r.retro_faults = fault_counts_.retro;
    r.front_thrust_x = fault_counts_.front_x;
    r.stage = st_.stage;
    r.decoupling_x = decoupling_x_;
    std::string line = series_line(r, series_columns_);
    if (surface_.on())
        line += "," + surface_series_line(surface_.ledger(sim_.particles, st_.surface, r.S, r.m.wedge_area));
    if (flexure_.on()) {
        // The plate under this output's load, written whole to flexure.csv.
        flexure_.solve(sim_, st_.flexure);
        flexure_.write_profile(st_.flexure, r.S, flexure_file_);
        line += "," + flexure_series_line(flexure_.measures(st_.flexure));
    }
    series_.line(line);
    const double secs = elapsed();
    const double rate = static_cast<double>(sim_.step_count - rate_from_step_) / std::max(secs - rate_from_secs_, 1e-9);
    rate_from_step_ = sim_.step_count;
    rate_from_secs_ = secs;
    event(RunEvent::output, fmt::format("S = {:.3f}: H/h0 = {:.3f}, alpha = {:.2f}, beta = {:.2f}; health: max overlap/R = {:.4f}, "
                         "max speed = {:.3g} m/s, contacts/disc = {:.2f}; {} discs asleep; {:.0f} steps/s",
                         r.S, r.m.H_over_h0, r.m.alpha_deg, r.m.beta_deg, r.max_overlap_ratio, r.max_speed,
                         static_cast<double>(r.contacts) / static_cast<double>(sim_.particles.size()),
                         sim_.sleeping_count(), rate),
          std::nan(""), rate);
    obs_.progress({r.S, c_.wedge.s_max, first_step_, sim_.step_count, total_steps_, secs, true});
    return r.m;
}

// The strain over the interval since the previous output (neighbourhoods of
// two mean disc diameters, analysis/strain.hpp), the finite strain from S = 0,
// and the faults of the interval with their track ids (analysis/faults.hpp),
// appended to faults.csv. The first output of a run has no interval: no
// faults, stage 0.
void WedgeRun::measure_structures() {
    const std::vector<Vec2> x_now = positions_by_id(sim_.particles);
    strain_ = local_strain(st_.x_then, x_now, 2.0 * (c_.packing.r_min + c_.packing.r_max));
    std::vector<Fault> found;
    decoupling_x_ = std::nan("");
    if (sim_.step_count > 0 && st_.outputs > 0) {
        std::vector<double> radius(x_now.size());
        for (std::size_t s = 0; s < sim_.particles.size(); ++s) radius[sim_.particles.id[s]] = sim_.particles.radius[s];
        if (st_.surface.removed > 0 || surface_.sedimenting()) {  // parked discs (eroded, the reserve) are not on the base
            std::vector<Vec2> x_then = st_.x_then;
            for (std::size_t s = 0; s < sim_.particles.size(); ++s)
                if (sim_.particles.flags[s] & kFlagRemoved) x_then[sim_.particles.id[s]] = {std::nan(""), std::nan("")};
            decoupling_x_ = basal_decoupling_x(x_then, x_now, radius, interval_m(), kDecouplingBinOverH0 * h0_);
        } else {
            decoupling_x_ = basal_decoupling_x(st_.x_then, x_now, radius, interval_m(), kDecouplingBinOverH0 * h0_);
        }
        accumulate_gradient(st_.F_total, strain_.F);
        found = detect_faults(x_now, strain_.shear, fault_params_).faults;
    } else if (st_.F_total.size() < x_now.size()) {
        st_.F_total.resize(x_now.size());
    }
    strain_.shear_total.resize(st_.F_total.size());
    for (std::size_t i = 0; i < st_.F_total.size(); ++i) strain_.shear_total[i] = strain_measures(st_.F_total[i]).shear;
    FaultTracker tracker{std::move(st_.faults), st_.next_fault_id};
    const std::vector<Fault> all = tracker.update(std::move(found), S(), h0_);
    st_.faults = std::move(tracker.known);
    st_.next_fault_id = tracker.next_id;
    fault_counts_ = count_faults(all);
    fault_lines_ = active_fault_lines(all, 1.0);
    const int now = classify_stage(all, h0_);
    st_.stage = stage_reached(st_.stage, st_.stage_last_output, now);
    st_.stage_last_output = now;
    for (const Fault& f : all) faults_file_.line(faults_line(S(), f, h0_));
}

// The snapshot (with the strain arrays of measure_structures) and its
// pictures: horizons, displacement and the strain map with the active faults
// (not at the first output, which has no interval).
void WedgeRun::draw() {
    const std::vector<double> rel_m = relative_displacement_m(sim_, st_.x_then);
    const std::vector<double> rel = normalised(rel_m);
    // The pictures' displacement: per unit convergence over the interval,
    // one colour scale for every frame (render/particle_view.hpp).
    const double interval = interval_m();
    std::vector<double> disp(rel_m.size(), 0.0);
    if (interval > 0.0)
        for (std::size_t s = 0; s < disp.size(); ++s) disp[s] = rel_m[s] / interval;
    st_.x_then = positions_by_id(sim_.particles);
    const std::string name = fmt::format("S{:06.3f}", S());
    const VtuStamp stamp{S(), sim_.step_count, sim_.time};
    // With [surface], the particles' paths (by id).
    const std::vector<VtuByIdArray> paths = {{"birth_S", &st_.surface.birth_S},
                                             {"max_burial_depth", &st_.surface.max_burial},
                                             {"erosion_S", &st_.surface.erosion_S}};
    write_vtu(fmt::format("{}/snapshots/{}.vtu", dir_, name), sim_.particles, rel, &stamp, &strain_, &rel_m,
              surface_.on() ? &paths : nullptr);
    st_.pvd.emplace_back(S(), fmt::format("snapshots/{}.vtu", name));
    write_pvd(dir_ + "/run.pvd", st_.pvd);
    const ParticleStore& p = sim_.particles;
    const bool interval_done = sim_.step_count > 0;
    std::vector<double> gamma;  // per slot (strain_ is by id)
    if (interval_done && strain_.shear.size() == p.size()) {
        gamma.resize(p.size());
        for (std::size_t s = 0; s < p.size(); ++s) gamma[s] = strain_.shear[p.id[s]];
    }
    render_output_pictures({&p, interval_done ? &disp : nullptr, S(), gamma.empty() ? nullptr : &gamma, &fault_lines_},
                           view_, dir_ + "/figures", name);
}

// The paper's plates are infinite slabs ([40]): once the raised surface runs
// back to within h0 of the trailing wall, the wall pushes the deformed plate
// and the toe, α and D measure the whole plate. Said once per process (never
// at S = 0: plate_at_trailing_wall).
void WedgeRun::warn_if_plate_too_short(const WedgeMeasures& m) {
    if (experiment_of(c_).push_wall) return;  // the sandbox's wedge grows against its wall by design
    const double wall_x = sim_.walls[kWallProEnd].a.x;
    if (wall_warned_ || !plate_at_trailing_wall(m, wall_x, h0_, c_.wedge.v * sim_.time)) return;
    const std::string msg = fmt::format(
        "the prowedge reaches the trailing wall at S = {:.3f} (toe at {:.2f} h0, wall at {:.2f} h0 from the "
        "S point): from here the wall pushes the deformed plate, and the toe, alpha and D measure the whole "
        "plate; the incoming plate is too short for this run: raise wedge.pro_margin (now {:g} h0)",
        S(), m.toe_pro_x / h0_, wall_x / h0_, c_.wedge.pro_margin);
    log_.line("warning: " + msg);
    obs_.warning(msg, true);
    wall_warned_ = true;
}

void WedgeRun::warn_if_overlapping() {
    // Where, and how many pairs: a lone impact (one pair, a disc rolling
    // down a slope) reads differently from a squeezed layer (many pairs).
    const OverlapSummary o = overlap_summary(sim_, c_.run.warn_overlap_ratio);
    if (o.worst <= c_.run.warn_overlap_ratio) return;
    const std::string msg = fmt::format(
        "largest overlap/R = {:.4f} at step {} (S = {:.3f}) between discs {} at ({:.6g}, {:.6g}) m and {} at "
        "({:.6g}, {:.6g}) m is above run.warn_overlap_ratio = {:g} ({} pair{} above it; the run stops at "
        "run.max_overlap_ratio = {:g}); consider a smaller wedge.v or numerics.safety, or a larger material.k_n",
        o.worst, sim_.step_count, S(), o.id_i, o.x_i.x, o.x_i.y, o.id_j, o.x_j.x, o.x_j.y, c_.run.warn_overlap_ratio,
        o.above, o.above == 1 ? "" : "s", c_.run.max_overlap_ratio);
    log_.line("warning: " + msg);
    if (!overlap_warned_) obs_.warning(msg + " (further warnings in log.txt only)", true);
    overlap_warned_ = true;
}

void WedgeRun::keep_as_last_good() {
    last_good_ = state_bytes();
    last_good_step_ = sim_.step_count;
    last_good_snapshot_ = st_.pvd.back().second;
    if (st_.outputs % static_cast<std::uint64_t>(c_.run.checkpoint_every_outputs) == 0 ||
        sim_.step_count >= total_steps_ || stop_for_)
        save_checkpoint(last_good_);
}

void WedgeRun::stop_if_left_domain() {
    if (!stop_for_) return;
    const HealthProblem& pr = *stop_for_;
    const std::string msg = fmt::format(
        "step {} (S = {:.4f}): disc {} at ({:.6g}, {:.6g}) m left the domain ({}); run stopped as "
        "run.on_domain_exit = \"stop\" asks: the outputs and the checkpoint of this step are written. "
        "Likely cause: {}",
        sim_.step_count, S(), pr.id, pr.x.x, pr.x.y, pr.detail, pr.advice);
    event(RunEvent::stopped, "STOPPED: " + msg);
    throw InstabilityError(msg);
}

// The free space is checked at every output against what the rest of the run
// writes (after the checkpoint, so a stop for space can be resumed).
void WedgeRun::check_space_left() {
    check_free_space(dir_, st_.pvd.back().second, n_outputs_ + 1 - std::min(n_outputs_ + 1, st_.outputs),
                     last_good_.size());
}

std::string WedgeRun::state_bytes() {
    st_.series_bytes = file_bytes(dir_ + "/series.csv");
    st_.faults_bytes = file_bytes(dir_ + "/faults.csv");
    st_.log_bytes = file_bytes(dir_ + "/log.txt");
    if (surface_.on()) st_.surface.eroded_bytes = file_bytes(dir_ + "/eroded.csv");
    if (flexure_.on()) st_.flexure.profile_bytes = file_bytes(dir_ + "/flexure.csv");
    return encode_checkpoint(sim_, st_, cfg_hash_);
}

std::string WedgeRun::save_checkpoint(const std::string& bytes) {
    // The appended files first: after a power loss the newest checkpoint
    // never expects rows that did not reach the disk.
    series_.sync();
    faults_file_.sync();
    if (eroded_file_.is_open()) eroded_file_.sync();
    if (flexure_file_.is_open()) flexure_file_.sync();
    log_.sync();
    const std::string path = write_checkpoint(dir_ + "/checkpoint", sim_.step_count, bytes);
    last_checkpoint_time_ = std::chrono::steady_clock::now();
    return path;
}

bool WedgeRun::checkpoint_timer_due(std::uint64_t next_output) const {
    const double every = 60.0 * c_.run.checkpoint_minutes;  // [s]
    return every > 0.0 && sim_.step_count != next_output &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint_time_).count() >= every;
}

bool WedgeRun::wall_time_limit_reached() const {
    return c_.run.max_wall_minutes > 0.0 && elapsed() >= 60.0 * c_.run.max_wall_minutes &&
           sim_.step_count < total_steps_;
}

void WedgeRun::stop_with_checkpoint(RunEvent kind, const std::string& why, const char* continue_label) {
    const std::string path = save_checkpoint(state_bytes());
    const double wall = elapsed();
    const std::string what =
        fmt::format("{} at step {} (S = {:.4f}) after {:.1f} s wall", why, sim_.step_count, S(), wall);
    event(kind, fmt::format("{}; checkpoint {}", what, path), wall);
    log_.line("step phases (this process): " + phase_breakdown(sim_.phase_times()));
    obs_.progress_done();
    obs_.stopped(what, path, continue_label, fmt::format("orodem run {}/config.toml --out {} --resume", dir_, dir_));
}

void WedgeRun::finish() {
    obs_.progress_done();
    const double wall = elapsed();
    event(RunEvent::finished, fmt::format("finished: S = {:.3f} after {} steps, {:.1f} s wall", S(), sim_.step_count,
                                          wall), wall);
    log_.line("step phases (this process): " + phase_breakdown(sim_.phase_times()));
    const RunPlot p = plot_runs({dir_}, dir_ + "/figures/plots.png");
    obs_.note("plot: " + p.path);
}

void WedgeRun::event(RunEvent kind, std::string text, double wall_s, double steps_per_s) {
    EventRecord e;
    e.kind = kind;
    e.step = sim_.step_count;
    e.S = S();
    e.wall_s = wall_s;
    e.steps_per_s = steps_per_s;
    e.text = std::move(text);
    log_.event(e);
}

std::string WedgeRun::extra_series_header() const {
    std::string h;
    if (surface_.on()) h += "," + surface_series_header();
    if (flexure_.on()) h += "," + flexure_series_header();
    return h;
}

double WedgeRun::S() const { return c_.wedge.v * sim_.time / h0_; }

double WedgeRun::interval_m() const { return st_.pvd.empty() ? 0.0 : (S() - st_.pvd.back().first) * h0_; }

double WedgeRun::elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

}  // namespace orodem
