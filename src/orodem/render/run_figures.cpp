#include "orodem/render/run_figures.hpp"

#include "orodem/core/nearest.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/process.hpp"

namespace fs = std::filesystem;
namespace orodem {

SavedRun open_saved_run(const std::string& dir) {
    SavedRun r;
    r.dir = dir;
    r.config = read_config_basics((fs::path(dir) / "config.toml").string());
    r.snaps = read_pvd((fs::path(dir) / "run.pvd").string());
    return r;
}

Frame read_frame(const SavedRun& run, std::size_t k) {
    const std::string vtu = (fs::path(run.dir) / run.snaps[k].file).string();
    const VtuData d = read_vtu(vtu);
    const auto& radius = d.require("radius", vtu);
    const auto& depth = d.require("initial_depth", vtu);
    const auto& side = d.require("side", vtu);
    Frame f;
    f.S = run.snaps[k].S;
    f.file = vtu;
    if (const auto* g = d.find("shear_strain")) f.strain = *g;
    if (const auto* g = d.find("shear_strain_total")) f.strain_total = *g;
    if (const auto* g = d.find("birth_S")) f.birth_S = *g;  // a run with [surface]: the particles' paths
    if (const auto* g = d.find("max_burial_depth")) f.burial = *g;
    for (std::size_t i = 0; i < d.x.size(); ++i) {
        const std::size_t s = f.p.add(d.x[i], radius[i], 1.0);
        f.p.initial_depth[s] = depth[i];
        f.p.side[s] = side[i] != 0 ? 1 : 0;
    }
    // A layered run's snapshots: layer and damage (the layer hues, --color-by damage).
    const auto* layer = d.find("layer");
    const auto* damage = d.find("damage");
    if (layer && damage && layer->size() == f.p.size() && damage->size() == f.p.size()) {
        f.p.material.assign(f.p.size(), 0);
        f.p.layer.resize(f.p.size());
        f.p.damage = *damage;
        for (std::size_t s = 0; s < f.p.size(); ++s) f.p.layer[s] = static_cast<std::uint8_t>((*layer)[s]);
    }
    if (f.p.size() == 0) throw IoError(fmt::format("'{}': snapshot holds no discs", vtu));
    if (k == 0) return f;  // no previous output to move from
    // Slots follow file order (p.add), so the arrays apply as they are.
    if (const auto* abs = d.find("rel_disp_abs")) {
        const bool exact = run.S_exact.size() == run.snaps.size();  // else run.pvd's S, to 6 decimals
        const double interval = exact ? (run.S_exact[k] - run.S_exact[k - 1]) * run.config.h0
                                      : (run.snaps[k].S - run.snaps[k - 1].S) * run.config.h0;  // [m]
        f.displacement.assign(abs->size(), 0.0);
        if (interval > 0.0)
            for (std::size_t i = 0; i < abs->size(); ++i) f.displacement[i] = (*abs)[i] / interval;
    } else {
        f.displacement = d.require("rel_disp", vtu);
        f.per_frame_scale = true;
    }
    return f;
}

std::vector<std::size_t> nearest_snapshots(const std::vector<Snapshot>& snaps, const std::vector<double>& at) {
    std::vector<double> S_values;
    for (const Snapshot& s : snaps) S_values.push_back(s.S);
    std::vector<std::size_t> chosen;
    for (double S : at) chosen.push_back(nearest_output(S_values, S, "--at"));
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    return chosen;
}

namespace {

[[noreturn]] void no_strain_error(const std::string& file, ColorBy color_by) {
    if (color_by == ColorBy::deposition || color_by == ColorBy::burial)
        throw ConfigError(fmt::format("'{}' holds no {} array: only a run with [surface] in its config has one; draw "
                                      "this run with --color-by horizons, displacement or strain",
                                      file, color_by == ColorBy::deposition ? "birth_S" : "max_burial_depth"));
    if (color_by == ColorBy::damage)
        throw ConfigError(fmt::format("'{}' holds no damage array: only a layered run (materials and [[layers]] in its "
                                      "config) has one; draw this run with --color-by horizons, displacement or strain",
                                      file));
    throw ConfigError(fmt::format("'{}' holds no {} array (written by an orodem before strain maps): draw this run "
                                  "with --color-by horizons or displacement",
                                  file, color_by == ColorBy::strain_total ? "shear_strain_total" : "shear_strain"));
}

}  // namespace

Panel frame_panel(const Frame& f, ColorBy color_by, const std::vector<FaultLine>* faults) {
    Panel panel{&f.p, f.displacement.empty() ? nullptr : &f.displacement, f.S};
    if (color_by == ColorBy::deposition || color_by == ColorBy::burial) {
        const std::vector<double>& v = color_by == ColorBy::deposition ? f.birth_S : f.burial;
        if (v.size() != f.p.size()) no_strain_error(f.file, color_by);
        panel.path = &v;
        return panel;
    }
    if (!is_strain(color_by)) return panel;
    const bool total = color_by == ColorBy::strain_total;
    const std::vector<double>& g = total ? f.strain_total : f.strain;
    if (g.size() != f.p.size()) no_strain_error(f.file, color_by);
    panel.strain = &g;
    panel.faults = faults;
    return panel;
}

bool has_colour_data(const SavedRun& run, std::size_t k, ColorBy color_by) {
    if (color_by == ColorBy::damage) return read_frame(run, k).p.has_materials();
    if (color_by == ColorBy::deposition || color_by == ColorBy::burial) {
        const Frame f = read_frame(run, k);
        return (color_by == ColorBy::deposition ? f.birth_S : f.burial).size() == f.p.size();
    }
    if (!is_strain(color_by)) return true;
    const Frame f = read_frame(run, k);
    return (color_by == ColorBy::strain_total ? f.strain_total : f.strain).size() == f.p.size();
}

void require_colour_data(const SavedRun& run, std::size_t k, ColorBy color_by) {
    if (!has_colour_data(run, k, color_by)) no_strain_error((fs::path(run.dir) / run.snaps[k].file).string(), color_by);
}

ViewOptions saved_run_view(const SavedRun& run, int width_px, const FrameChoice& choice) {
    ViewOptions view = run_view(run.config, width_px);
    const bool lo = std::isfinite(choice.x_lo), hi = std::isfinite(choice.x_hi);
    if ((lo || hi) && !(lo && hi && choice.x_lo < choice.x_hi))
        throw ConfigError(fmt::format("--xlim {:g},{:g}: give two numbers A,B with A < B (in h0 from the S point)",
                                      choice.x_lo, choice.x_hi));
    if (lo) {
        view.x_min = view.x_s + choice.x_lo * view.h0;
        view.x_max = view.x_s + choice.x_hi * view.h0;
    }
    if (!choice.title.empty()) view.title = choice.title;
    return view;
}

PictureInfo render_run_figure(const SavedRun& run, const std::vector<std::size_t>& chosen, ColorBy color_by,
                              int width_px, const std::string& out, const RunFaultLines* faults,
                              const FrameChoice& frame) {
    std::vector<Frame> frames;
    for (std::size_t k : chosen) frames.push_back(read_frame(run, k));
    ViewOptions view = saved_run_view(run, width_px, frame);
    view.color_by = color_by;
    std::vector<Panel> panels;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Frame& f = frames[i];
        view.per_frame_scale = view.per_frame_scale || f.per_frame_scale;
        const std::size_t k = chosen[i];
        panels.push_back(frame_panel(f, color_by, faults && k < faults->size() ? &(*faults)[k] : nullptr));
    }
    return render_panels(panels, view, out);
}

std::string movie_format(const std::string& path) {
    const auto dot = path.rfind('.');
    const std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    if (ext != "mp4" && ext != "gif")
        throw ConfigError(fmt::format("'{}': the movie format follows the extension, which must be .mp4 or .gif", path));
    return ext;
}

namespace {

/// Removes its folder (and what is in it) when it goes out of scope.
struct TempDir {
    std::string path;
    ~TempDir() {
        std::error_code ec;
        if (!path.empty()) fs::remove_all(path, ec);
    }
};

/// The last non-empty line of a text file ("" when none or unreadable).
std::string last_line(const std::string& path) {
    std::string text;
    try {
        text = read_file(path);
    } catch (const IoError&) {
        return "";
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const auto nl = text.rfind('\n');
    return nl == std::string::npos ? text : text.substr(nl + 1);
}

}  // namespace

std::size_t movie_frames(std::size_t snapshots, const MovieOptions& o) {
    const double frames = std::round(o.fps * o.seconds);
    if (!(frames >= static_cast<double>(snapshots)))
        throw ConfigError(fmt::format("--seconds {:g} at --fps {:g} is {:g} frames for {} snapshots: some would never "
                                      "be shown; give a longer --seconds or a higher --fps",
                                      o.seconds, o.fps, frames, snapshots));
    return static_cast<std::size_t>(frames);
}

std::size_t render_run_movie(const SavedRun& run, const MovieOptions& o, const std::string& out) {
    const std::string format = movie_format(out);
    const std::size_t frames = movie_frames(run.snaps.size(), o);
    const ViewOptions base = saved_run_view(run, o.width_px, o.frame);  // exit 2 before ffmpeg is looked for
    const std::string ffmpeg = find_on_path("ffmpeg");
    if (ffmpeg.empty())
        throw MissingToolError("orodem movie needs ffmpeg, which is not on PATH; install it "
                               "(Debian: apt-get install ffmpeg; scripts/install-deps does)");
    const fs::path target = fs::absolute(out);
    make_dirs(target.parent_path().string());
    TempDir tmp;
    std::string templ = (target.parent_path() / ".orodem-movie-XXXXXX").string();
    if (!::mkdtemp(templ.data())) throw_io_error("cannot make a temporary folder", templ);
    tmp.path = templ;

    ViewOptions view = base;
    view.color_by = o.color_by;
    for (std::size_t k = 0; k < run.snaps.size(); ++k) {
        const Frame f = read_frame(run, k);
        ViewOptions v = view;
        v.per_frame_scale = f.per_frame_scale;
        render_panels({frame_panel(f, o.color_by, k < o.faults.size() ? &o.faults[k] : nullptr)}, v,
                      fmt::format("{}/frame{:05d}.png", tmp.path, k));
    }
    const std::string encoded = tmp.path + "/movie." + format, log = tmp.path + "/ffmpeg.log";
    // The snapshots come in at snapshots / seconds per second; ffmpeg makes
    // the file's rate from them: fps (each snapshot's frame repeated) or
    // framerate (a cross-fade between consecutive snapshots).
    const double rate_in = static_cast<double>(run.snaps.size()) / o.seconds;
    const std::string timing = o.blend ? fmt::format("framerate=fps={:g}", o.fps) : fmt::format("fps={:g}", o.fps);
    // ffmpeg reads '%' in an image-sequence name as a pattern: one in the folder's name is written '%%'.
    std::string pattern;
    for (const char ch : tmp.path) pattern += ch == '%' ? std::string("%%") : std::string(1, ch);
    pattern += "/frame%05d.png";
    std::vector<std::string> args = {ffmpeg, "-nostdin", "-hide_banner", "-loglevel", "error", "-y",
                                     "-framerate", fmt::format("{:.17g}", rate_in), "-i", pattern};
    if (format == "gif") {
        args.insert(args.end(), {"-vf", timing + ",split[a][b];[a]palettegen[p];[b][p]paletteuse", "-f", "gif"});
    } else {  // H.264 wants even sizes and 4:2:0 chroma for common players
        args.insert(args.end(), {"-vf", timing + ",pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white", "-pix_fmt", "yuv420p",
                                 "-movflags", "+faststart", "-f", "mp4"});
    }
    args.insert(args.end(), {"-frames:v", std::to_string(frames)});
    args.push_back(encoded);
    ChildIo io;
    io.log = log;
    pid_t pid = -1;
    if (const int err = spawn_child(args, io, pid); err != 0)
        throw IoError(fmt::format("cannot start '{}': {}", args[0], std::strerror(err)));
    const int rc = wait_child(pid);
    if (rc != 0 || !fs::exists(encoded))
        throw IoError(fmt::format("ffmpeg could not make '{}' (exit status {}): {}", out, rc, last_line(log)));
    std::error_code ec;
    fs::rename(encoded, target, ec);
    if (ec) throw IoError(fmt::format("cannot move the movie into place as '{}': {}", out, ec.message()));
    return frames;
}

}  // namespace orodem
