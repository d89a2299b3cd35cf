// Pictures of the particle state (SPEC §3; paper Figures 8, 9, 12, 13), on
// a render/canvas (PNG and PDF through Cairo, SVG with <text> elements).
// Each disc is a filled circle at its true radius; x in units of h0 with the
// S point at 0, y in units of h0 above the base.
//
// One frame per run: run_view derives the crop from the config alone (the
// model box: where the incoming plate's trailing wall ends up at s_max, the
// retroside's end, and a wedge height estimated from s_max), so every
// picture of a run (written by the run, by `orodem render`, by `orodem
// movie`) has the same crop, the same pixel size and the same fonts.
//
// One colour scale per run: "horizons" colours alternating bands of initial
// depth (h0/5 thick), retroside material (side = 1) darker; "displacement"
// colours the relative displacement of neighbours since the previous output,
// |Δx_i − Δx_j| (max over the disc's neighbours), divided by the convergence
// over that interval, ΔS h0: a value of 1 means a neighbour moved past the
// disc by as much as the belt moved. The bar runs from 0 (light grey, so
// undeformed material stays visible on white) to kDisplacementFull (dark
// red); larger values are drawn at the top colour. The same for every frame
// of every run: frames and runs can be compared by colour. (Measured on the
// demo exp1, S = 1, 2, 3: the 90th percentile is 0.09-0.13, the 99th
// 0.27-0.41, the largest 0.3-0.65, a few discs rolling down the slopes.)
// Snapshots written before rel_disp_abs existed hold only the per-snapshot
// normalised rel_disp; they are drawn with full colour at its 0.99 quantile
// and the legend says so ("per-frame scale").
//
// "strain" colours each disc by its incremental maximum shear strain γ over
// the output interval (the snapshot's shear_strain), "strain_total" by the
// finite γ from S = 0 (shear_strain_total), each on a fixed logarithmic bar
// (kStrainLo..kStrainHi, kStrainTotalLo..kStrainTotalHi; docs/figures.md
// gives the data they were chosen from), the active faults of the output
// drawn over them as lines from root to tip: pro-vergent solid blue,
// retro-vergent dashed green, both on a white halo. The faults come in as
// plain segments (FaultLine): render/ knows no fault table (run/ is above it).
//
// Every picture carries its legend (a colour bar with its values and unit,
// or the horizon swatches) and fonts of 1/60 of the width (27 px on a
// 1600 px picture: 2.7 mm when printed 16 cm wide).
#pragma once

#include "orodem/core/named.hpp"

#include <string>
#include <vector>

#include "orodem/analysis/faults.hpp"
#include "orodem/io/config.hpp"
#include "orodem/render/canvas.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

/// What a picture's discs are coloured by (orodem render and movie --color-by): the initial-depth horizons, the
/// relative displacement since the previous output, the shear strain of the output interval, or since S = 0,
/// a layered run's damage, a run with [surface]'s growth strata (deposition S) or largest burial depth.
enum class ColorBy { horizons, displacement, strain, strain_total, damage, deposition, burial };
inline constexpr Named<ColorBy> kColorBys[] = {{ColorBy::horizons, "horizons"},
                                               {ColorBy::displacement, "displacement"},
                                               {ColorBy::strain, "strain"},
                                               {ColorBy::strain_total, "strain_total"},
                                               {ColorBy::damage, "damage"},
                                               {ColorBy::deposition, "deposition"},
                                               {ColorBy::burial, "burial"}};
constexpr const char* name_of(ColorBy v) { return name_in(kColorBys, v); }

/// Top of the displacement colour bar: relative displacement / (ΔS h0) [-].
inline constexpr double kDisplacementFull = 0.3;
/// The incremental shear strain bar (log scale): γ over one output interval [-].
inline constexpr double kStrainLo = 1e-3, kStrainHi = 1.0;
/// The finite shear strain bar (log scale): γ since S = 0 [-].
inline constexpr double kStrainTotalLo = 1e-2, kStrainTotalHi = 10.0;
/// The damage bar of a layered run (log scale): sliding distance [mean disc diameters].
inline constexpr double kDamageLo = 1e-2, kDamageHi = 100.0;
/// The largest burial depth bar of a run with [surface]: max_burial_depth [h0].
inline constexpr double kBurialHi = 2.0;

/// A fault drawn on a strain map: a segment from root to tip [m] (the run's
/// coordinates: x from the S point, y from the base), and its vergence (+1
/// pro-vergent, −1 retro-vergent, as Fault::vergence).
struct FaultLine {
    Vec2 root, tip;
    int vergence = 0;
    std::int64_t id = -1;  // the fault's track id, drawn at its tip (the same fault has the same number in every frame)
    bool operator==(const FaultLine&) const = default;
};
/// The active faults of `faults` whose dip is within the detector's range
/// (kFaultDipMinDeg to kFaultDipMaxDeg, analysis/faults.hpp) as lines; unit converts their lengths to
/// metres (1 for the run's faults, h0 for faults.csv's rows, which are in h0).
std::vector<FaultLine> active_fault_lines(const std::vector<Fault>& faults, double unit);

struct ViewOptions {
    double x_min = 0, x_max = 1;   // visible range [m]
    double y_min = 0, y_max = 1;   // [m]
    double h0 = 1;                 // length unit of the axes [m]
    double x_s = 0;                // S point [m]
    int width_px = 1600;           // picture width; the height follows from the frame's aspect ratio
    double band = 1;               // horizon band thickness [m]
    ColorBy color_by = ColorBy::horizons;  // horizons | displacement | strain | strain_total | damage (layered runs)
    double output_ds = 0;          // the run's ΔS between outputs (named in the strain legend; 0: not named)
    std::string title;             // header text, e.g. "exp1"
    bool per_frame_scale = false;  // displacement values are normalised per frame (old snapshots)
    double displacement_quantile = 0.99;  // per_frame_scale only: of the positive values, the full-colour one
    std::size_t layers = 0;        // a layered run's layers from the base (the horizons legend's hues); 0: one material
    double s_max = 0;              // the run's last S (the deposition bar's top; 0: 1)
};

/// The frame of every picture of a run (see the note above): x from half an
/// h0 left of where the trailing wall stands at s_max (−pro_margin h0) to
/// half an h0 beyond the retroside's end (retro_length h0; the backstop at 0
/// for critical-wedge); y from −0.05 h0 to h0 (1 + sqrt(2 s_max / 6)) +
/// 0.15 h0: the layer and a triangular wedge above it holding the material
/// accreted by s_max (area s_max h0²), of slopes whose cotangents add up to
/// 6 (e.g. 12° and 30°; the wedges measured so far add up to about 9, e.g.
/// H/h0 = 1.34 at S = 8 in docs/studies/rate-study.md, so they fit with room).
/// Material above the frame is cut off at its top edge, and the panel says
/// so in red ("material above the frame is cut off").
ViewOptions run_view(const ConfigBasics& b, int width_px = 1600);

/// What a picture's legend shows, as numbers (tests compare them between frames).
struct Legend {
    std::string title;     // e.g. "relative displacement |Δx_i − Δx_j| / (ΔS h0)"
    double lo = 0, hi = 0; // colour bar ends (displacement, strain); 0, 0 for horizons
    bool log_scale = false;     // the bar is logarithmic (strain)
    std::vector<double> ticks;  // labelled values along the bar
    std::vector<std::pair<std::string, Colour>> swatches;  // horizons: label and colour of each swatch
    std::vector<std::string> line_keys;  // strain: the fault line styles (pro-vergent, retro-vergent)
};
/// The legend of pictures drawn with o (frame-independent but for per_frame_scale).
Legend picture_legend(const ViewOptions& o);

/// Whether color_by is one of the strain maps (strain, strain_total).
constexpr bool is_strain(ColorBy c) { return c == ColorBy::strain || c == ColorBy::strain_total; }
/// Whether color_by draws an array that only some runs' snapshots hold (strain maps: runs made since they
/// exist; damage: layered runs; deposition, burial: runs with [surface]).
constexpr bool needs_snapshot_array(ColorBy c) { return c != ColorBy::horizons && c != ColorBy::displacement; }

/// The colour of value v on g's colour bar: linear or logarithmic between
/// lo and hi; v below lo (on a log bar also v ≤ 0) or NaN takes the bottom
/// colour, v above hi the top one.
Colour bar_colour(const Legend& g, double v);

/// One panel of a picture: a state and its displacement values.
struct Panel {
    const ParticleStore* p = nullptr;
    /// Per slot, color_by = displacement: relative displacement / (ΔS h0), or
    /// normalised per frame with per_frame_scale; null: no previous output
    /// (the first snapshot), every disc drawn at 0.
    const std::vector<double>* displacement = nullptr;
    double S = 0;  // written in the panel's corner
    /// Per slot, color_by = strain or strain_total: γ [-] (NaN: undefined,
    /// drawn at the bottom colour); null: every disc at the bottom colour.
    const std::vector<double>* strain = nullptr;
    /// strain, strain_total: the lines drawn over the discs (null: none).
    const std::vector<FaultLine>* faults = nullptr;
    /// Per slot, color_by = deposition: birth S (0 or NaN: the layer's, drawn
    /// grey); burial: the largest burial depth [h0]. Null: every disc grey.
    const std::vector<double>* path = nullptr;
};

/// Pixel size and legend of a written picture.
struct PictureInfo {
    int width_px = 0, height_px = 0;
    Legend legend;
    std::vector<FaultLine> faults_drawn;  // every fault line drawn, panel by panel
};

/// The pixel size of a picture of n panels drawn with o.
PictureInfo picture_size(const ViewOptions& o, std::size_t panels);

/// Where panel k of n lies in the picture: its plot area's left and top
/// edges, width and height [px], and the scale [px per m] (the same in x and
/// y): a point (x, y) [m] is drawn at (left + (x − x_min) scale, top +
/// (y_max − y) scale).
struct PlotArea {
    double left = 0, top = 0, width = 0, height = 0, scale = 0;
};
PlotArea plot_area(const ViewOptions& o, std::size_t panels, std::size_t k);

/// Draws the panels stacked top to bottom (as the paper's Figures 9 and 13),
/// sharing the x axis (labelled under the last one), each with its S and the
/// S point marked, under one header with o.title and the legend, into path
/// (format from its extension: .png, .svg, .pdf), written atomically.
PictureInfo render_panels(const std::vector<Panel>& panels, const ViewOptions& o, const std::string& path);

/// Nearest-rank quantile q in (0, 1] of the positive entries of v (the value
/// at rank ceil(q n) of the n positive entries in ascending order); 0 when
/// no entry is positive. Independent of the order of v.
double positive_quantile(const std::vector<double>& v, double q);

/// The pictures of one output, as `orodem run` writes them and `orodem
/// render` writes them again: dir/horizons_<name>.<ext>; when
/// panel.displacement is given (not for the first output, which has no
/// previous one to move from) dir/displacement_<name>.<ext>; when
/// panel.strain is given (incremental γ; not for the first output either)
/// dir/strain_<name>.<ext> with panel.faults drawn on it. view gives the
/// frame; its colouring is set here. Returns the pictures written, in that
/// order.
std::vector<PictureInfo> render_output_pictures(const Panel& panel, ViewOptions view, const std::string& dir,
                                                const std::string& name, const std::string& ext = "png");

}  // namespace orodem
