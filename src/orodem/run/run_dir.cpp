#include "orodem/run/run_dir.hpp"

#include <sys/statvfs.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/io/fault_table.hpp"
#include "orodem/io/files.hpp"
#include "orodem/run/surface_erosion.hpp"

namespace fs = std::filesystem;

namespace orodem {

std::vector<RunDirFile> run_dir_files() {
    return {
        {"`config.toml`", "the fully resolved config: every key with its value, defaults written out; it is itself a "
                          "valid config that reproduces the run"},
        {"`log.txt`", "what happened: dt and stability margin, packing settled or reused from the cache, timings"},
        {"`events.csv`", fmt::format("the same events as numbers, for programs (`orodem status`, sweeps): `{}` with one "
                                     "row per start, resume, output and end of a piece (finished, interrupted, "
                                     "time_limit, io_error, unstable, stopped); append-only",
                                     kEventsHeader)},
        {"`checkpoint/`", "the newest two checkpoints (`ckpt-<step>.bin`) from which `orodem resume` continues the run "
                          "exactly"},
        {"`series.csv`", "one row per output (every `wedge.output_ds` of S), header row first; its columns are listed "
                         "below (\"series.csv columns\"); for `settle`: "
                         "`step,time,kinetic_energy,ke_ratio,contacts,max_overlap_ratio` (header only when the layer "
                         "came from the cache)"},
        {"`faults.csv`", fmt::format("the fault table: one row per known fault per output, `{}` (x from the S point, y "
                                     "from the base; `active = 0`: not found at this output, its last geometry); "
                                     "`orodem faults RUN_DIR` prints it",
                                     faults_header())},
        {"`run.pvd`, `snapshots/S*.vtu`",
         "ParaView time series (time value = S): per disc `id`, `radius`, `velocity`, `initial_depth`, `side` (0 pro, "
         "1 retro), `cluster_id`, `rel_disp` (normalised per snapshot), `omega`, `fixed`, `asleep`, `shear_strain`, "
         "`vol_strain`, `rotation`, `d2min`, `shear_strain_total` (finite, from S = 0), `rel_disp_abs` (m), in layered "
         "runs `material`, `layer`, `damage` (mean disc diameters), with `[surface]` `birth_S`, `max_burial_depth` "
         "(h0), `erosion_S`; field data `S`, `step`, `time`. Units and normalisation of each: [python.md](python.md)"},
        {"`eroded.csv`", fmt::format("with `[surface]` only: one row per disc removed by erosion, `{}` (x from the S "
                                     "point, depths in h0; birth S 0 for the layer, the deposition S for a deposit)",
                                     eroded_header())},
        {"`figures/`",
         "`horizons_S*.png` (initial-depth bands, retroside darker), `displacement_S*.png` (relative displacement of "
         "neighbours since the previous output per unit convergence, on one fixed colour bar), `strain_S*.png` (each "
         "disc's incremental maximum shear strain γ over the output interval on one fixed log colour bar, 0.001 to 1, "
         "with the output's active faults drawn from root to tip: pro-vergent solid blue, retro-vergent dashed "
         "green), all of one size with their legends ([figures.md](figures.md)); `plots.png` (α, β, H, peak, D vs S); "
         "`rendered/` what `orodem render` draws without `--out`"},
        {"`packing.bin`", "`settle` only: the settled layer (binary, checksummed)"},
    };
}

std::string choose_run_dir(const std::string& out, const std::string& config_path) {
    refuse_control_characters("--out", out);
    refuse_control_characters("the config's name", fs::path(config_path).filename().string());
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

void require_run_dir(const std::string& dir) {
    std::error_code ec;
    if (!fs::exists(dir, ec))
        throw ConfigError(fmt::format("'{}': no such run directory", dir));
    if (!fs::is_directory(dir, ec))
        throw ConfigError(fmt::format("'{}': not a run directory (not a directory)", dir));
    if (!fs::exists(fs::path(dir) / "config.toml", ec))
        throw ConfigError(fmt::format("'{}': not a run directory (no config.toml)", dir));
}

namespace {

/// The step of series.csv's last row (its leading number); NaN when there is none.
double last_series_step(const std::string& path) {
    if (!fs::exists(path)) return std::nan("");
    const std::string series = read_file(path);
    const std::size_t end = series.find_last_not_of('\n');
    const std::size_t begin = end == std::string::npos ? std::string::npos : series.rfind('\n', end);
    if (begin == std::string::npos) return std::nan("");
    const char* row = series.c_str() + begin + 1;
    char* after = nullptr;
    const double v = std::strtod(row, &after);
    return after == row ? std::nan("") : v;
}

}  // namespace

RunStatus run_state(const std::string& dir) {
    require_run_dir(dir);
    RunStatus r;
    r.config = load_config(dir + "/config.toml");
    const Config& c = r.config;
    if (!is_wedge(c)) {
        // A settled layer is not checkpointed: done when its packing is written, else settled again.
        r.state = fs::exists(dir + "/packing.bin") ? RunState::finished : RunState::not_started;
        return r;
    }
    if (!fs::exists(dir + "/log.txt")) return r;  // a sweep writes every member's config.toml first
    // events.csv (or, for a run started before it existed, log.txt read the
    // same way): the timestep, the last output (S and rate), the last event
    // that starts or ends a piece, and the wall time of the pieces that say it.
    const std::vector<EventRecord> events = read_events(dir);
    std::vector<double> rates;  // steps/s of each output, in order
    for (const EventRecord& e : events) {
        if (e.kind == RunEvent::start && std::isfinite(e.dt)) r.dt = e.dt;
        if (e.kind == RunEvent::output) {
            r.S = e.S;
            rates.push_back(e.steps_per_s);
        }
        if (e.kind == RunEvent::start || e.kind == RunEvent::resume) ++r.pieces;
        if (ends_a_piece(e.kind) && std::isfinite(e.wall_s)) {
            r.wall_s += e.wall_s;
            ++r.pieces_timed;
        }
    }
    if (const EventRecord* last = last_piece_event(events)) r.last = *last;
    if (!r.last || !ends_a_piece(r.last->kind)) r.state = RunState::no_end_line;
    else if (r.last->kind == RunEvent::finished) r.state = RunState::finished;
    else if (r.last->kind == RunEvent::unstable || r.last->kind == RunEvent::stopped) r.state = RunState::failed;
    else r.state = RunState::interrupted;
    r.last_step = last_series_step(dir + "/series.csv");
    const std::size_t n = std::min<std::size_t>(rates.size(), 3);
    std::vector<double> last_rates(rates.end() - static_cast<std::ptrdiff_t>(n), rates.end());
    std::sort(last_rates.begin(), last_rates.end());
    r.rate = last_rates.empty() ? std::nan("") : last_rates[n / 2];
    r.rate_outputs = static_cast<int>(n);
    if (std::isfinite(r.dt)) r.total_steps = c.wedge.s_max * c.packing.h0 / (c.wedge.v * r.dt);
    const auto checkpoints = list_checkpoints(dir + "/checkpoint");  // newest first
    if (!checkpoints.empty()) r.newest_checkpoint = checkpoints.front();
    std::error_code ec;
    const auto written = fs::last_write_time(dir + "/log.txt", ec);
    if (!ec) r.log_age_s = std::chrono::duration<double>(fs::file_time_type::clock::now() - written).count();
    return r;
}

std::size_t series_rows(const std::string& path) {
    if (!fs::exists(path)) return 0;
    const std::string text = read_file(path);
    const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    return lines > 0 ? lines - 1 : 0;
}

std::uint64_t free_bytes(const std::string& path) {
    struct statvfs s {};
    if (::statvfs(path.c_str(), &s) != 0) throw_io_error("cannot query free space of", path);
    return static_cast<std::uint64_t>(s.f_bavail) * static_cast<std::uint64_t>(s.f_frsize);
}

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

}  // namespace orodem
