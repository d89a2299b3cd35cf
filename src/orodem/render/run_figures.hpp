// Pictures of a saved run (`orodem render`, `orodem movie`): its snapshots
// (run.pvd) read back as frames and drawn in the run's own frame
// (run_view of its config.toml), so they match the pictures the run wrote.
//
// The movie: every snapshot drawn as a PNG (the run's picture size) into a
// temporary folder beside the output, then encoded by ffmpeg (Debian's
// package, found on PATH; MissingToolError when absent) into a temporary
// file in that folder, renamed into place; the folder is removed whatever
// happens. ffmpeg runs as a child process (posix_spawnp) with its messages
// in a log file there; when it fails, the error quotes the log's last line.
//
// Strain maps (--color-by strain | strain_total) need the snapshots' strain
// arrays (shear_strain, shear_strain_total); a snapshot without them (an
// orodem before strain maps) stops the figure or the movie with a
// ConfigError naming it, before anything is written. Their fault lines come
// from the caller (run/run_faults.hpp reads the run's fault table; render/
// lies below run/ and knows no fault table).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "orodem/io/config.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/render/particle_view.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

/// A run directory's config basics and snapshot list.
struct SavedRun {
    std::string dir;
    ConfigBasics config;
    std::vector<Snapshot> snaps;
    std::vector<double> S_exact;  // the outputs' S as the run computed them (a checkpoint's list), when known:
                                  // read_frame's displacement then matches the run's to the bit; else empty
};
/// Reads RUN_DIR/config.toml (leniently) and RUN_DIR/run.pvd.
SavedRun open_saved_run(const std::string& dir);

/// One snapshot ready to draw.
struct Frame {
    ParticleStore p;
    std::vector<double> displacement;  // per slot, see Panel::displacement; empty: none (first snapshot)
    bool per_frame_scale = false;      // the snapshot has only the normalised rel_disp (older orodem)
    double S = 0;
    std::vector<double> strain;        // per slot, shear_strain (γ of the interval); empty: not in the snapshot
    std::vector<double> strain_total;  // per slot, shear_strain_total (γ since S = 0); empty: not in the snapshot
    std::vector<double> birth_S;       // per slot, with [surface]: S of deposition (0 for the layer); empty: none
    std::vector<double> burial;        // per slot, with [surface]: max_burial_depth [h0]; empty: none
    std::string file;                  // the snapshot's path (for messages)
};
/// Snapshot k of the run: rel_disp_abs / ((S_k − S_{k−1}) h0) as the displacement.
Frame read_frame(const SavedRun& run, std::size_t k);

/// Indices of the snapshots nearest each S of `at`, ascending, without repeats.
std::vector<std::size_t> nearest_snapshots(const std::vector<Snapshot>& snaps, const std::vector<double>& at);

/// Per snapshot of a run (as SavedRun::snaps), the fault lines drawn on its strain map.
using RunFaultLines = std::vector<std::vector<FaultLine>>;

/// The panel of frame f coloured by color_by, with its fault lines (may be
/// null); ConfigError naming the snapshot when a strain colouring finds no
/// strain array in it.
Panel frame_panel(const Frame& f, ColorBy color_by, const std::vector<FaultLine>* faults);

/// Whether snapshot k holds the arrays that color_by needs (always true but
/// for strain and strain_total).
bool has_colour_data(const SavedRun& run, std::size_t k, ColorBy color_by);
/// The same, as a ConfigError naming the snapshot when it does not.
void require_colour_data(const SavedRun& run, std::size_t k, ColorBy color_by);

/// What a caller changes in the run's frame (orodem render, orodem movie).
struct FrameChoice {
    double x_lo = std::nan(""), x_hi = std::nan("");  // x range [h0 from the S point]; NaN: the run's
    std::string title;                                 // the pictures' title; empty: the experiment's name
};
/// run_view of the run's config with `choice` applied; ConfigError unless x_lo < x_hi (when given).
ViewOptions saved_run_view(const SavedRun& run, int width_px, const FrameChoice& choice = {});

/// The stacked figure (render_panels) of the chosen snapshots into out;
/// faults (may be null) gives the strain maps' fault lines.
PictureInfo render_run_figure(const SavedRun& run, const std::vector<std::size_t>& chosen, ColorBy color_by,
                              int width_px, const std::string& out, const RunFaultLines* faults = nullptr,
                              const FrameChoice& frame = {});

struct MovieOptions {
    ColorBy color_by = ColorBy::horizons;  // horizons | displacement | strain | strain_total
    int width_px = 1600;                // frame width [px] (ffmpeg pads to even sizes)
    double fps = 25.0;                  // the file's frame rate [1/s]
    double seconds = 10.0;              // the movie's length [s]: each snapshot shown seconds / snapshots
    bool blend = false;                 // cross-fade from each snapshot to the next (else: each held, repeated frames)
    RunFaultLines faults;               // strain maps: per snapshot; empty: no lines
    FrameChoice frame;
};
/// The frames a movie of `snapshots` has at o.fps over o.seconds (round(fps · seconds));
/// ConfigError when they are fewer than the snapshots (some would never be shown).
std::size_t movie_frames(std::size_t snapshots, const MovieOptions& o);
/// An animation of every snapshot of the run into out (.mp4: H.264; .gif),
/// o.seconds long at o.fps: each snapshot drawn once and shown for
/// o.seconds / snapshots, as repeated frames or (blend) cross-faded into the
/// next by ffmpeg's framerate filter; returns movie_frames. MissingToolError
/// when ffmpeg is not on PATH (checked before anything is drawn), IoError
/// when it fails.
std::size_t render_run_movie(const SavedRun& run, const MovieOptions& o, const std::string& out);

/// The movie format of a path: "mp4" or "gif"; ConfigError otherwise.
std::string movie_format(const std::string& path);

}  // namespace orodem
