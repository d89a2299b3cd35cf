// `orodem render RUN_DIR`: pictures from a run's saved snapshots (run.pvd),
// in the run's own frame and colour scales (render/particle_view.hpp):
// with --out FILE one figure stacking the snapshots nearest --at (as the
// paper's Figures 9 and 13); without it the horizon, displacement and strain
// picture of each snapshot into --dir (default RUN_DIR/figures/rendered/,
// never the run's own figures/). An existing file is never replaced
// without --force: every target is checked before anything is drawn.
// `orodem movie RUN_DIR --out FILE.mp4|.gif`: every snapshot, animated by ffmpeg.
// Strain maps carry the run's active faults, read from its fault table
// (run/run_faults.hpp) here and handed to render/ as lines.
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"
#include "orodem/render/run_figures.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/run_faults.hpp"

#include "commands.hpp"

namespace fs = std::filesystem;
namespace orodem {

namespace {

/// ConfigError when a target exists and --force was not given.
void refuse_existing(const std::vector<std::string>& targets, bool force, const char* command) {
    if (force) return;
    std::size_t existing = 0;
    std::string first;
    for (const auto& t : targets)
        if (fs::exists(t) && existing++ == 0) first = t;
    if (existing == 0) return;
    throw ConfigError(fmt::format("'{}'{} exists already; orodem {} does not replace files unless asked: choose "
                                  "another output or add --force",
                                  first, existing > 1 ? fmt::format(" (and {} more)", existing - 1) : "", command));
}

/// The paper's choice when --at is absent: four snapshots evenly spread up to the last.
std::vector<double> default_stack(const std::vector<Snapshot>& snaps) {
    const double last = snaps.back().S;
    return {0.25 * last, 0.5 * last, 0.75 * last, last};
}

/// --xlim and --title as a FrameChoice (ConfigError unless --xlim has two values).
FrameChoice frame_choice(const std::vector<double>& xlim, const std::string& title) {
    FrameChoice f;
    f.title = title;
    if (xlim.empty()) return f;
    if (xlim.size() != 2)
        throw ConfigError(fmt::format("--xlim: give two numbers A,B (x from A to B h0 from the S point), not {}",
                                      xlim.size()));
    f.x_lo = xlim[0];
    f.x_hi = xlim[1];
    return f;
}

/// The fault lines of every snapshot of the run (faults.csv, or computed
/// again from the snapshots for a run made before it).
RunFaultLines fault_lines_of(const SavedRun& run) {
    return run_fault_lines(run_faults(run.dir), run.snaps, run.config.h0);
}

}  // namespace

int cmd_render(const RenderArgs& a) {
    require_run_dir(a.run_dir);
    const SavedRun run = open_saved_run(a.run_dir);
    const FrameChoice frame = frame_choice(a.xlim, a.title);
    saved_run_view(run, a.width, frame);  // exit 2 for a bad --xlim before anything is drawn
    if (!a.out.empty()) {
        picture_format(a.out);  // exit 2 before anything else
        refuse_existing({a.out}, a.force, "render");
        const std::vector<std::size_t> chosen = nearest_snapshots(run.snaps, a.at.empty() ? default_stack(run.snaps) : a.at);
        RunFaultLines faults;
        if (needs_snapshot_array(a.color_by))
            for (std::size_t k : chosen) require_colour_data(run, k, a.color_by);  // exit 2, nothing written
        if (is_strain(a.color_by)) faults = fault_lines_of(run);
        const fs::path parent = fs::absolute(a.out).parent_path();
        make_dirs(parent.string());
        const PictureInfo info = render_run_figure(run, chosen, a.color_by, a.width, a.out, &faults, frame);
        std::string list;
        for (std::size_t k : chosen) list += fmt::format("{}{:.2f}", list.empty() ? "" : ", ", run.snaps[k].S);
        fmt::print("render: {} panels (S = {}), {} x {} px{}, in {}\n", chosen.size(), list, info.width_px,
                   info.height_px,
                   is_strain(a.color_by) ? fmt::format(", {} active faults drawn", info.faults_drawn.size()) : "",
                   a.out);
        return 0;
    }
    std::vector<std::size_t> chosen;
    if (a.at.empty())
        for (std::size_t k = 0; k < run.snaps.size(); ++k) chosen.push_back(k);
    else
        chosen = nearest_snapshots(run.snaps, a.at);
    const std::string dir = a.dir.empty() ? (fs::path(a.run_dir) / "figures" / "rendered").string() : a.dir;
    // Strain maps for the snapshots that hold strain (not the first: no interval).
    std::vector<bool> strain(run.snaps.size(), false);
    std::size_t strain_maps = 0;
    std::vector<std::string> targets;
    for (std::size_t k : chosen) {
        const std::string name = fs::path(run.snaps[k].file).stem().string();
        targets.push_back(fmt::format("{}/horizons_{}.{}", dir, name, a.format));
        if (k == 0) continue;
        targets.push_back(fmt::format("{}/displacement_{}.{}", dir, name, a.format));
        strain[k] = has_colour_data(run, k, ColorBy::strain);
        if (strain[k]) targets.push_back(fmt::format("{}/strain_{}.{}", dir, name, a.format));
        strain_maps += strain[k] ? 1 : 0;
    }
    refuse_existing(targets, a.force, "render");
    const RunFaultLines faults = strain_maps > 0 ? fault_lines_of(run) : RunFaultLines{};
    make_dirs(dir);
    std::size_t pictures = 0;
    for (std::size_t k : chosen) {
        const Frame f = read_frame(run, k);
        ViewOptions view = saved_run_view(run, a.width, frame);
        view.per_frame_scale = f.per_frame_scale;
        Panel panel = strain[k] ? frame_panel(f, ColorBy::strain, &faults[k]) : frame_panel(f, ColorBy::horizons, nullptr);
        pictures += render_output_pictures(panel, view, dir, fs::path(run.snaps[k].file).stem().string(), a.format).size();
    }
    const std::size_t later = chosen.size() - (chosen.front() == 0 ? 1 : 0);  // snapshots with an interval
    fmt::print("render: {} pictures of {} snapshots in {}{}\n", pictures, chosen.size(), dir,
               strain_maps < later ? fmt::format(" ({} without strain arrays: no strain map)", later - strain_maps)
                                   : "");
    return 0;
}

int cmd_movie(const MovieArgs& a) {
    require_run_dir(a.run_dir);
    movie_format(a.out);  // exit 2 before anything else
    refuse_existing({a.out}, a.force, "movie");
    const SavedRun run = open_saved_run(a.run_dir);
    MovieOptions o;
    o.color_by = a.color_by;
    o.width_px = a.width;
    o.fps = a.fps;
    o.seconds = a.seconds;
    o.blend = a.blend;
    o.frame = frame_choice(a.xlim, a.title);
    movie_frames(run.snaps.size(), o);          // exit 2 before anything is drawn
    saved_run_view(run, a.width, o.frame);
    if (needs_snapshot_array(a.color_by))
        require_colour_data(run, run.snaps.size() - 1, a.color_by);  // exit 2, nothing written
    if (is_strain(a.color_by)) o.faults = fault_lines_of(run);
    const std::size_t frames = render_run_movie(run, o, a.out);
    fmt::print("movie: {} snapshots, each shown {:.3g} s ({}), {:g} s at {:g} frames per second ({} frames) in {}\n",
               run.snaps.size(), a.seconds / static_cast<double>(run.snaps.size()),
               a.blend ? "cross-faded into the next" : "repeated frames", a.seconds, a.fps, frames, a.out);
    return 0;
}

}  // namespace orodem
