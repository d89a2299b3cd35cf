#include "orodem/run/runner.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <regex>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "orodem/engine/pair_kernel.hpp"

#include "orodem/core/error.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/physics/stability.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/run_log.hpp"
#include "orodem/run/run_faults.hpp"
#include "orodem/run/wedge_run.hpp"
#include "orodem/render/run_figures.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"

namespace fs = std::filesystem;

namespace orodem {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The settled layer of c: from the cache when present, else settled now
/// (series rows of the settling go to `series` when given) and cached.
ParticleStore prepare_layer(const Config& c, const std::string& dir, RunLog& log, LineFile* series,
                            RunObserver& obs) {
    const std::string cache = packing_cache_path(c);
    std::string why;
    if (auto cached = load_packing(cache, packing_key(c), c.material.density, &why)) {
        log.line(fmt::format("packing reused from {} ({} discs)", cache, cached->size()));
        obs.note(fmt::format("packing reused from {}", cache));
        return std::move(*cached);
    }
    // Settling is not checkpointed (it ends in the packing cache, and takes
    // minutes at most): a stop request ends it with exit 128 + signal and a
    // rerun (for a wedge: --resume) settles again. Stop requests are watched
    // before the log says "settling".
    StopWatch watch(obs);
    log.line(fmt::format("settling a new packing ({})", why));
    Simulation sim = make_settle_simulation(c);
    sim.initialize();
    log.line(fmt::format("generated {} discs ({}); settling", sim.particles.size(), name_of(c.packing.kind)));
    const auto t0 = std::chrono::steady_clock::now();
    // The thread count between reports, as WedgeRun chooses it between chunks (run/thread_governor.hpp).
    const int requested = omp_get_max_threads();
    const bool adapt = requested > 1 && ThreadGovernor::enabled_by_environment();
    ThreadGovernor threads(requested);
    auto last_report = t0;
    std::uint64_t last_step = 0;
    const SettleProgress done = settle(sim, c.packing, c.run.output_interval, [&](const SettleProgress& s) {
        if (adapt) {
            const auto now = std::chrono::steady_clock::now();
            threads.record(s.step - last_step, std::chrono::duration<double>(now - last_report).count());
            last_report = now;
            last_step = s.step;
            omp_set_num_threads(threads.threads());
            say_thread_changes(threads, log, obs);
        }
        if (const int sig = obs.stop_requested()) {
            const std::string msg = fmt::format(
                "by {} while settling the packing (step {}, {:.0f} s); settling is not checkpointed, so it "
                "starts again when the run is started again{}",
                stop_signal_name(sig), s.step, seconds_since(t0),
                is_wedge(c) ? fmt::format(": orodem run {}/config.toml --out {} --resume", dir, dir)
                            : std::string(" (with a new --out)"));
            EventRecord e;
            e.kind = RunEvent::interrupted;
            e.step = s.step;
            e.text = "interrupted " + msg;
            log.event(e);
            throw InterruptedError(msg, sig);
        }
        if (series)
            series->line(fmt::format("{},{:.9g},{:.9g},{:.6g},{},{:.6g}", s.step, s.time, s.kinetic_energy,
                                     s.ke_ratio, s.contacts, sim.max_overlap_ratio()));
        obs.settling(fmt::format("settling {} discs: t = {:.3f} s, step {}, E_kin/(M g h0) = {:.2e} (target {:.1e})",
                                 sim.particles.size(), s.time, s.step, s.ke_ratio, c.packing.settle_ke_ratio));
    });
    obs.progress_done();
    omp_set_num_threads(requested);
    const double secs = seconds_since(t0);
    log.line(fmt::format("settled after {} steps ({:.4g} s simulated, {:.1f} s wall, {:.3g} disc-steps/s); "
                         "E_kin/(M g h0) = {:.3g}, max overlap/R = {:.4f}",
                         done.step, done.time, secs,
                         static_cast<double>(done.step) * static_cast<double>(sim.particles.size()) / secs,
                         done.ke_ratio, sim.max_overlap_ratio()));
    cut_layer(sim.particles, c.packing.h0);
    const std::string bytes = encode_packing(sim.particles, packing_key(c));
    try {
        save_packing(cache, bytes);
        log.line(fmt::format("cut to h0 = {:g} m: {} discs; cached in {}", c.packing.h0, sim.particles.size(), cache));
    } catch (const IoError& e) {
        // A read-only or full cache folder (common on clusters) costs the next
        // run a settling, not this run.
        const std::string msg = fmt::format("the settled packing was not cached ({}); set packing.cache_dir to a "
                                            "writable folder to reuse it; this run continues with it in memory",
                                            e.what());
        log.line(fmt::format("cut to h0 = {:g} m: {} discs; {}", c.packing.h0, sim.particles.size(), msg));
        obs.warning(msg, false);
    }
    // The layer as the cache gives it back (what it keeps of each disc and
    // nothing else: the settling's rotation angles are not kept), so that a
    // run from a fresh layer and one from the cache are the same run, their
    // checkpoints included.
    if (auto layer = decode_packing(bytes, packing_key(c), c.material.density, &why)) return std::move(*layer);
    throw IoError(fmt::format("the settled packing cannot be read back: {}", why));
}

/// A WedgeRun, and when an I/O error (a full disk, a failed write) stops it,
/// an end line in log.txt first (if the log can still be written), so that
/// orodem status says how the piece ended and adds up its wall time.
int run_wedge(const Config& c, WedgeSetup& w, const std::string& dir, RunLog& log, RunObserver& obs,
              const RunLoopState* resumed) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
        WedgeRun run(c, w, dir, log, obs, resumed);
        return run.run();
    } catch (const IoError& e) {
        try {
            EventRecord ev;
            ev.kind = RunEvent::io_error;
            ev.step = w.sim.step_count;
            ev.S = c.wedge.v * w.sim.time / c.packing.h0;
            ev.wall_s = seconds_since(t0);
            ev.text = fmt::format("stopped by an I/O error at step {} (S = {:.4f}) after {:.1f} s wall: {}",
                                  ev.step, ev.S, ev.wall_s, e.what());
            log.event(ev);
        } catch (const IoError&) {
            // The log cannot be written either (the disk is full): orodem status
            // then says "no end line"; the exit status (4) and stderr say why.
        }
        throw;
    }
}

/// A wedge run from the beginning in dir (config.toml and log.txt exist).
int start_wedge(const Config& c, const RunNumbers& n, const std::string& dir, RunLog& log, RunObserver& obs) {
    const ParticleStore layer = prepare_layer(c, dir, log, nullptr, obs);
    WedgeSetup w = make_wedge(c, layer, n);
    const int rc = run_wedge(c, w, dir, log, obs, nullptr);
    if (rc != 0) return rc;
    obs.note(fmt::format("outputs in {}/ (config.toml, log.txt, series.csv)", dir));
    return 0;
}

}  // namespace

RunNumbers check_runnable(const Config& c) {
    check_model_size(c);
    return derive_run_numbers(c);
}

RunTimeEstimate estimate_run_time(const Config& c, double discs, double dt) {
    // Rates of wedge runs per awake disc (counted as below) on the 2-core
    // development host of 7 Dec 2026 (AMD EPYC Zen 5 VM; docs/benchmarks.md
    // "Wall times"): 2 threads from the paper-size exp1 (636.3 s to S = 8,
    // 8.7e7) and the intermediate one (172.1 s, 9.7e7), 1 thread from the
    // intermediate one (291.3 s, 5.7e7). The Intel host of 6 Dec ran wedges
    // about 2.2 times slower: other machines differ as much.
    constexpr double kRate1 = 5.7e7, kRate2 = 9.0e7;  // awake disc-steps/s, 1 and 2 threads
    RunTimeEstimate e;
    e.steps = c.wedge.s_max * c.packing.h0 / (c.wedge.v * dt);
    const double awake = c.wedge.sleep ? 0.45 : 1.0;
    e.work = e.steps * discs * 0.8 * awake;  // 0.8: the cut to h0
    e.seconds_1 = e.work / kRate1;
    e.seconds_2 = e.work / kRate2;
    return e;
}

void check_run_time(const Config& c, const RunNumbers& n, bool force, const std::string& what) {
    if (!is_wedge(c)) return;
    const RunTimeEstimate e = estimate_run_time(c, estimated_disc_count(c.packing), n.timestep.dt);
    auto hours = [](double s) { return fmt::format("{:.3g} h", s / 3600.0); };
    if (e.seconds_2 > 3600.0 * kLongRunHours && !force)
        throw ConfigError(fmt::format(
            "{} would take about {} on 2 threads ({:.3g} steps to S = {:g} at wedge.v = {:g} m/s, dt = {:.3g} s), "
            "more than {:g} h: check wedge.v, wedge.s_max and packing.h0, or add --force to start it anyway",
            what, hours(e.seconds_2), e.steps, c.wedge.s_max, c.wedge.v, n.timestep.dt, kLongRunHours));
    if (e.seconds_1 >= 3600.0)
        fmt::print("estimated run time: about {} on 1 thread, {} on 2 (orodem check explains)\n", hours(e.seconds_1),
                   hours(e.seconds_2));
}

std::string short_plate_warning(const Config& c, const PlateEstimate& pe) {
    if (experiment_of(c).push_wall || c.wedge.pro_margin >= pe.pro_margin_min) return "";
    return fmt::format("wedge.pro_margin = {:g} h0 is shorter than the {:.1f} h0 the deformation front may need by "
                       "S = {:g} (critical taper {:.2f} deg for mu_bp = {:g}; docs/experiments.md \"Plate length\"); "
                       "raise wedge.pro_margin so that the trailing wall does not push the wedge",
                       c.wedge.pro_margin, pe.pro_margin_min, c.wedge.s_max, pe.alpha_deg, c.wedge.mu_bp);
}

int start_run_in(const Config& c, const RunNumbers& n, const std::string& dir, RunObserver& obs) {
    const DirLock lock = lock_dir(dir, "the run directory");  // one writer (io/files.hpp); held to the end
    const TimestepInfo& t = n.timestep;
    write_file_atomic(dir + "/config.toml", to_toml(c));
    RunLog log(dir);
    EventRecord start;
    start.kind = RunEvent::start;
    start.dt = t.dt;
    start.text = fmt::format("orodem {} run of {} ({}) with {} threads, {} step kernels", ORODEM_VERSION, c.path,
                             c.run.experiment, omp_get_max_threads(), isa_name(kernel_isa()));
    log.event(start);
    log.line(fmt::format("dt = {:.6g} s, stability limit {:.6g} s (margin {:.2f}x), t_c = {:.1f} steps",
                         t.dt, t.dt_crit, t.margin(), t.t_collision / t.dt));
    // RELIABILITY-CHECKLIST 3: stable but coarse steps are allowed with a warning.
    std::vector<std::string> coarse;
    if (t.t_collision / t.dt < 20.0)
        coarse.push_back(fmt::format("a collision (t_c = {:.4g} s) spans only {:.1f} steps of dt = {:.4g} s, fewer than "
                                     "20; lower numerics.safety or numerics.dt for accurate contacts",
                                     t.t_collision, t.t_collision / t.dt, t.dt));
    if (const std::string w = is_wedge(c) ? short_plate_warning(c, n.plate) : std::string(); !w.empty()) coarse.push_back(w);
    if (is_wedge(c) && c.wedge.v * t.dt > 0.1 * c.packing.r_min)
        coarse.push_back(fmt::format("the belt moves {:.4g} m per step, more than 0.1 r_min = {:.4g} m; lower "
                                     "wedge.v or numerics.dt",
                                     c.wedge.v * t.dt, 0.1 * c.packing.r_min));
    for (const auto& w : coarse) {
        log.line("warning: " + w);
        obs.warning(w, false);
    }
    if (!is_wedge(c)) {
        LineFile series(dir + "/series.csv");
        // Header always; rows only when the layer is settled now (not cached).
        series.line("step,time,kinetic_energy,ke_ratio,contacts,max_overlap_ratio");
        const ParticleStore layer = prepare_layer(c, dir, log, &series, obs);
        save_packing(dir + "/packing.bin", layer, packing_key(c));
        const double surface = mean_surface_height(layer, 0.0, c.packing.length, 2.0 * c.packing.r_max);
        log.line(fmt::format("layer: {} discs, mean surface height {:.4g} m (h0 = {:g} m)", layer.size(), surface,
                             c.packing.h0));
        obs.note(fmt::format("layer of {} discs ready, mean surface {:.3g} m", layer.size(), surface));
        obs.note(fmt::format("outputs in {}/ (config.toml, log.txt, series.csv, packing.bin)", dir));
        return 0;
    }
    return start_wedge(c, n, dir, log, obs);
}

namespace {

/// Removes the temporary files (<name>.tmp-<pid>-<n>, temporary_name) that a writer killed while writing left
/// in dir and its sub-folders: with the directory locked, no live process is writing them.
void remove_leftover_temporaries(const std::string& dir) {
    static const std::regex temporary(R"(.+\.tmp-[0-9]+-[0-9]+)");
    std::vector<fs::path> leftovers;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
        if (it->is_regular_file(ec) && std::regex_match(it->path().filename().string(), temporary))
            leftovers.push_back(it->path());
    for (const fs::path& p : leftovers) remove_path(p.string());
}

/// resume_run once the run directory is locked; `how` (when not empty) starts the resume line of log.txt.
int resume_locked(const Config& c, const RunNumbers& n, const std::string& dir, RunObserver& obs,
                  const std::string& how = "") {
    const Config saved = load_config(dir + "/config.toml");
    if (config_hash(saved) != config_hash(c))
        throw ConfigError(fmt::format("--resume --out {}: {} differs from the run's config ({}); resume with "
                                      "orodem run {}/config.toml --out {} --resume",
                                      dir, c.path, first_config_difference(saved, c), dir, dir));
    if (list_checkpoints(dir + "/checkpoint").empty()) {
        // Outputs but no checkpoint (checkpoint/ deleted or emptied): they
        // cannot be continued, and starting again would rewrite them. The
        // S = 0 row alone is what a start writes again byte for byte (a stop
        // between it and the first checkpoint): the run starts again.
        if (const std::size_t rows = series_rows(dir + "/series.csv"); rows > 1)
            throw ConfigError(fmt::format(
                "--resume {}: no checkpoint in {}/checkpoint/, but series.csv has {} output rows; a resume cannot "
                "continue them and would overwrite them, so nothing was changed. Keep the run as it is, or start "
                "it again in a new directory: orodem run {}/config.toml --out NEW_DIR",
                dir, dir, rows, dir));
        // Interrupted before its first checkpoint (while settling, or right
        // after the S = 0 row): nothing to continue, so the run starts from
        // the beginning in the same place.
        for (const char* partial : {"series.csv", "faults.csv", "run.pvd", "snapshots", "figures", "checkpoint"})
            remove_path((fs::path(dir) / partial).string());
        RunLog log(dir);
        EventRecord e;
        e.kind = RunEvent::resume;
        e.text = fmt::format("resumed by orodem {}: no checkpoint yet, so the run starts from the beginning",
                             ORODEM_VERSION);
        log.event(e);
        obs.note(fmt::format("{} has no checkpoint yet: starting the run from the beginning", dir));
        return start_wedge(c, n, dir, log, obs);
    }
    WedgeSetup w = make_wedge(c, ParticleStore{}, n);
    RunLoopState st;
    std::vector<std::string> notes;
    std::string path;
    // A checkpoint fits the files on disk when each appended file is at least as long as it recorded and its
    // snapshots exist. After a power loss the newest checkpoint can be on disk while the rows written just before
    // it are not (the files are fsync'ed before each checkpoint, but a disk may reorder): the resume then falls
    // back to the newest checkpoint that fits, and cuts the files back to it.
    auto fits = [&dir](const RunLoopState& s) -> std::string {
        const struct {
            const char* name;
            std::uint64_t bytes;
            bool kept;
        } appended[] = {{"series.csv", s.series_bytes, true},
                        {"log.txt", s.log_bytes, true},
                        {"faults.csv", s.faults_bytes, s.faults_bytes > 0},
                        {"eroded.csv", s.surface.eroded_bytes, s.surface.on},
                        {"flexure.csv", s.flexure.profile_bytes, s.flexure.on}};
        for (const auto& f : appended) {
            if (!f.kept) continue;
            std::error_code ec;
            const std::uintmax_t size = fs::file_size(fs::path(dir) / f.name, ec);
            const std::uint64_t have = ec ? 0 : static_cast<std::uint64_t>(size);
            if (have < f.bytes)
                return fmt::format("{} is {} bytes, shorter than the {} it had when this checkpoint was written (lost "
                                   "after it, as in a power failure); an older checkpoint is used",
                                   f.name, have, f.bytes);
        }
        for (const auto& entry : s.pvd) {
            std::error_code ec;
            if (!fs::is_regular_file(fs::path(dir) / entry.second, ec))
                return fmt::format("its snapshot {} is missing; an older checkpoint is used", entry.second);
        }
        return "";
    };
    try {
        path = restore_newest_checkpoint(dir + "/checkpoint", accepted_config_hashes(c), w.sim, st, &notes, fits);
    } catch (const CheckpointError& e) {
        // Every checkpoint is damaged: nothing to continue from; nothing changed.
        throw ConfigError(fmt::format("--resume {}: {}; nothing was changed. Keep the run as it is, or start it "
                                      "again in a new directory: orodem run {}/config.toml --out NEW_DIR",
                                      dir, e.what(), dir));
    }
    // A finished run whose last output row is on disk has nothing to continue (an extension, `how`, has):
    // said, and nothing is written (its plots and log stay as they are). One that lost rows (a power loss)
    // resumes to finish them.
    if (const RunStatus done = run_state(dir); how.empty() && notes.empty() && done.state == RunState::finished &&
                                               done.last && static_cast<double>(done.last->step) == done.last_step) {
        obs.note(fmt::format("{} finished already at S = {:.3f}: nothing to continue; orodem resume {} --s-max S "
                             "extends it to a larger S",
                             dir, done.S, dir));
        return 0;
    }
    for (const auto& note : notes) obs.warning(note, false);
    // log.txt beyond the checkpoint: the rows and warnings that the resumed
    // run writes again, and the history of the pieces since: the previous
    // piece's end line (a signal, a time limit) with its phase times, and the
    // start line of a piece killed before its first checkpoint. Those are
    // kept, so that the log and orodem status show every piece and how it
    // ended and ran (events.csv keeps them as it is).
    std::vector<std::string> history;
    {
        const std::string log_text = read_file(dir + "/log.txt");
        std::istringstream tail(log_text.size() > st.log_bytes ? log_text.substr(st.log_bytes) : std::string());
        for (std::string line; std::getline(tail, line);)
            if (starts_or_ends_a_piece(line) || line.rfind("step phases (this process)", 0) == 0)
                history.push_back(line);
    }
    // events.csv is made from the whole log.txt (a run started before it
    // existed) before the log is cut back.
    RunLog log(dir);
    truncate_file(dir + "/series.csv", st.series_bytes);
    if (st.faults_bytes > 0 || std::filesystem::exists(dir + "/faults.csv")) truncate_file(dir + "/faults.csv", st.faults_bytes);
    truncate_file(dir + "/log.txt", st.log_bytes);
    if (st.surface.on) truncate_file(dir + "/eroded.csv", st.surface.eroded_bytes);
    if (st.flexure.on) truncate_file(dir + "/flexure.csv", st.flexure.profile_bytes);
    for (const auto& line : history) log.line(line);
    for (const auto& note : notes) log.line("warning: " + note);
    EventRecord e;
    e.kind = RunEvent::resume;
    e.step = w.sim.step_count;
    e.S = c.wedge.v * w.sim.time / c.packing.h0;
    e.text = fmt::format("{}resumed by orodem {} from {} at step {} (S = {:.4f}) with {} threads, {} step kernels",
                         how.empty() ? "" : how + "; ", ORODEM_VERSION, path, w.sim.step_count, e.S, omp_get_max_threads(), isa_name(kernel_isa()));
    log.event(e);
    obs.note(fmt::format("resuming {} from step {} ({})", dir, w.sim.step_count, path));
    const int rc = run_wedge(c, w, dir, log, obs, &st);
    if (rc == 0) obs.note(fmt::format("outputs in {}/ (config.toml, log.txt, series.csv)", dir));
    return rc;
}

}  // namespace

int resume_run(const Config& c, const RunNumbers& n, const std::string& dir, RunObserver& obs) {
    if (dir.empty())
        throw ConfigError("--resume needs --out DIR: the run directory to continue (it holds config.toml and checkpoint/)");
    if (!is_wedge(c))
        throw ConfigError(fmt::format("--resume: run.experiment = \"{}\" writes no checkpoints; only the wedge "
                                      "experiments can be resumed", c.run.experiment));
    if (!fs::exists(dir + "/config.toml"))
        throw ConfigError(fmt::format("--resume --out {}: no config.toml there; give the directory of the run to continue", dir));
    const DirLock lock = lock_dir(dir, "the run directory");  // one writer (io/files.hpp); held to the end
    remove_leftover_temporaries(dir);
    return resume_locked(c, n, dir, obs);
}

namespace {

/// The plate left ahead of the trailing wall at S when the incoming plate is
/// `plate` h0 beyond the S point at the start (s_max + pro_margin), and the
/// least that plate_estimate asks for at S [h0].
struct PlateAtS {
    double left = 0.0, needed = 0.0;
    bool enough() const { return left >= needed; }
};
PlateAtS plate_at(const Config& saved, double plate, double S) {
    Config at = saved;
    at.wedge.s_max = S;
    return {plate - S, plate_estimate(at).pro_margin_min};
}

}  // namespace

std::vector<Override> extension_overrides(const Config& saved, double S, const std::string& dir) {
    const WedgeConfig& w = saved.wedge;
    const std::string cmd = fmt::format("orodem resume {} --s-max {:g}", dir, S);
    if (!is_wedge(saved))
        throw ConfigError(fmt::format("{}: run.experiment = \"{}\" is no wedge run; only those can be extended", cmd,
                                      saved.run.experiment));
    const auto outputs = [&](double s) { return std::max(1LL, std::llround(s / w.output_ds)); };
    if (!std::isfinite(S) || outputs(S) <= outputs(w.s_max))
        throw ConfigError(fmt::format("{}: the run goes to S = {:g} already; --s-max must reach at least one output "
                                      "interval (wedge.output_ds = {:g}) beyond it; nothing was changed",
                                      cmd, w.s_max, w.output_ds));
    // The sandbox: the layer is sandbox.length whatever S (the loader refuses an S the box cannot take).
    if (experiment_of(saved).push_wall) return {{"wedge.s_max", fmt::format("{}", S)}};
    const double plate = w.s_max + w.pro_margin;  // [h0] beyond the S point at the start
    // pro_margin such that s_max + pro_margin is the same double: the same
    // packing.length, the same discs, the same walls.
    double pro_margin = plate - S;
    for (int i = 0; i < 4 && S + pro_margin != plate; ++i)
        pro_margin = std::nextafter(pro_margin, S + pro_margin < plate ? 1e300 : -1e300);
    const PlateAtS at = plate_at(saved, plate, S);
    if (S + pro_margin != plate || !at.enough() || pro_margin <= 2.0) {
        // The largest S this plate allows, to 0.01 (bisection between the run's s_max and the plate).
        double lo = w.s_max, hi = plate;
        if (plate_at(saved, plate, lo).enough())
            for (int i = 0; i < 60; ++i) {
                const double mid = 0.5 * (lo + hi);
                (plate_at(saved, plate, mid).enough() && plate - mid > 2.0 ? lo : hi) = mid;
            }
        const double most = std::floor(lo * 100.0) / 100.0;
        throw ConfigError(fmt::format(
            "{}: the run's incoming plate is {:g} h0 long (wedge.s_max + wedge.pro_margin = {:g} + {:g}; packing.length "
            "= {:g} m with the retroside); at S = {:g} it would leave {:.2f} h0 ahead of the trailing wall, less than "
            "the {:.2f} h0 the deformation front may need (docs/experiments.md \"Plate length\"){}; start a new run "
            "with wedge.s_max = {:g} from your config file instead; nothing was changed",
            cmd, plate, w.s_max, w.pro_margin, saved.packing.length, S, at.left, std::max(at.needed, 2.0),
            most > w.s_max ? fmt::format("; this plate can be extended to S = {:g} at most", most)
                           : std::string("; this plate cannot be extended"),
            S));
    }
    return {{"wedge.s_max", fmt::format("{}", S)}, {"wedge.pro_margin", fmt::format("{}", pro_margin)}};
}

int extend_run(const Config& saved, const Config& c, const RunNumbers& n, const std::string& dir, RunObserver& obs) {
    const DirLock lock = lock_dir(dir, "the run directory");  // one writer (io/files.hpp); held to the end
    if (list_checkpoints(dir + "/checkpoint").empty())
        throw ConfigError(fmt::format("orodem resume {} --s-max {:g}: no checkpoint in {}/checkpoint/ to continue "
                                      "from; nothing was changed",
                                      dir, c.wedge.s_max, dir));
    // The newest checkpoint, made with the run's config (or with c's, when an
    // extension stopped between its first two writes), written again with
    // c's hash so that a plain resume of the extended run takes it.
    RunLoopState st;
    {
        WedgeSetup w = make_wedge(c, ParticleStore{}, n);
        try {
            restore_newest_checkpoint(dir + "/checkpoint", AcceptedHashes{config_hash(c), config_hash(saved)}, w.sim,
                                      st);
        } catch (const CheckpointError& e) {
            throw ConfigError(fmt::format("orodem resume {} --s-max {:g}: {}; nothing was changed", dir,
                                          c.wedge.s_max, e.what()));
        }
        write_checkpoint(dir + "/checkpoint", w.sim.step_count, encode_checkpoint(w.sim, st, config_hash(c)));
    }
    write_file_atomic(dir + "/config.toml", to_toml(c));
    // The pictures written so far, in the frame of the extended run (taller,
    // its trailing wall further on), from their snapshots as orodem render
    // draws them.
    SavedRun run = open_saved_run(dir);
    if (st.pvd.size() == run.snaps.size())
        for (const auto& [S, file] : st.pvd) run.S_exact.push_back(S);
    const ViewOptions view = run_view(config_basics(c));
    bool strain = false;
    for (std::size_t k = 1; k < run.snaps.size() && !strain; ++k) strain = has_colour_data(run, k, ColorBy::strain);
    const RunFaultLines faults = strain ? run_fault_lines(run_faults(dir), run.snaps, c.packing.h0) : RunFaultLines{};
    for (std::size_t k = 0; k < run.snaps.size(); ++k) {
        const Frame f = read_frame(run, k);
        ViewOptions v = view;
        v.per_frame_scale = f.per_frame_scale;
        const bool has_strain = k > 0 && f.strain.size() == f.p.size() && k < faults.size();
        const Panel panel = has_strain ? frame_panel(f, ColorBy::strain, &faults[k]) : frame_panel(f, ColorBy::horizons, nullptr);
        render_output_pictures(panel, v, dir + "/figures", fs::path(run.snaps[k].file).stem().string());
    }
    const std::string how = fmt::format(
        "extended from wedge.s_max = {:g} to {:g} on the same plate (wedge.pro_margin {:g} -> {:g}), the {} pictures "
        "so far drawn again in the extended run's frame",
        saved.wedge.s_max, c.wedge.s_max, saved.wedge.pro_margin, c.wedge.pro_margin, run.snaps.size());
    obs.note(fmt::format("extending {} from S = {:g} to S = {:g} (wedge.pro_margin {:g} -> {:g}, the plate unchanged)",
                         dir, saved.wedge.s_max, c.wedge.s_max, saved.wedge.pro_margin, c.wedge.pro_margin));
    return resume_locked(c, n, dir, obs, how);
}

void ensure_packing_cached(const Config& c, const std::string& dir, RunObserver& obs) {
    RunLog log(dir);
    prepare_layer(c, dir, log, nullptr, obs);
}

}  // namespace orodem
