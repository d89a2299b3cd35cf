// What the plots share (render/plots.cpp, the S plots; render/
// calibration_plots.cpp, the calibration reports), drawn on a Canvas
// (render/canvas.hpp) so that PNG, PDF and SVG (with <text>) come from one
// drawing: the line palette, "nice" axis ranges and ticks, and a figure of
// panels in a grid under a title and above a legend.
//
// Fonts and lengths follow the particle pictures (docs/figures.md): the
// label font F is 1/60 of the figure's width (at least 12 px), tick labels
// 0.85 F, the figure's title 1.15 F, and every margin and line width is a
// multiple of F, so a figure printed at any width reads the same. The
// figure keeps the pixel size the plots had when they were drawn with fixed
// 14 px fonts (legacy_height), so a request gives the picture size it gave
// before; the plot areas take what the larger labels leave.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "orodem/render/canvas.hpp"

namespace orodem::plot {

/// Ten well-separated line colours, cycled when there are more lines.
Colour palette(std::size_t i);

/// An axis from lo to hi with ticks every step.
struct Range {
    double lo = 0, hi = 1, step = 0.2;
};

/// A "nice" tick step (1, 2 or 5 × 10^k) giving about `target` intervals.
double nice_step(double span, int target);

/// Axis range covering [lo, hi] (finite, or none: lo > hi), on tick multiples.
Range axis_range(double lo, double hi, int target);

/// Tick label: "{:g}", with round-off around zero shown as 0.
std::string tick_label(double t, double step);

/// The label font of a picture `width_px` wide: width / 60, at least 12 [px].
double font_size(double width_px);

/// A plot area [px] and the axes it spans.
struct Area {
    double x0 = 0, y0 = 0, w = 1, h = 1;
    Range xr, yr;
    double px(double x) const { return x0 + (x - xr.lo) / (xr.hi - xr.lo) * w; }
    double py(double y) const { return y0 + h - (y - yr.lo) / (yr.hi - yr.lo) * h; }
};

/// One legend entry: a short line (dashed or not) or a marker, and a label;
/// with band > 0 the line lies on a swatch of its colour at that opacity.
/// `key`: an entry the old 14 px layout did not have (the S plots' α and β
/// line styles), left out of legacy_height's legend rows.
struct LegendEntry {
    std::string label;
    Colour colour;
    bool dashed = false, marker = false;
    double band = 0.0;
    bool key = false;
    bool note = false;  // a line of text alone on its row (no key): what a symbol or a shading means
};

/// Pixel layout of a figure: `rows` x `columns` panels under an optional
/// title, the legend's rows under them.
struct Figure {
    int width = 0, height = 0;
    double F = 12;                                      // label font [px]
    double outer = 0, left = 0, head = 0, bottom = 0;   // margins [px]
    double top = 0, cell_w = 0, cell_h = 0;             // first row's top, grid cell [px]
    double plot_w = 0, plot_h = 0;                      // each plot area [px]
    double legend_y = 0, row = 0;                       // legend top, row height [px]
    std::vector<std::pair<double, double>> legend_at;   // each entry's left end, row middle [px]
    int columns = 1;
    /// The plot area of panel k (row-major), axes unset.
    Area panel(std::size_t k) const;
    /// Line width: `w` in units of F / 14 (the old 14 px font) [px].
    double lw(double w) const { return w * F / 14.0; }
};

/// The figure's height when it was drawn with fixed 14 px fonts: the panels
/// of aspect h/w = `aspect`, the title line, `legend_rows` legend rows [px].
int legacy_height(int width, int columns, int rows, double aspect, bool title, int legend_rows);

/// The rows the legend's entries (but the keys) took in that old layout.
int legacy_legend_rows(int width, const std::vector<LegendEntry>& legend);

/// Lays a figure of the given width out (at least 400 px wide); its height
/// is legacy_height with the old legend rows, so the picture keeps its old
/// size, unless the plot areas would then be flatter than 0.3 (a legend
/// needing many more rows at the larger font): then the figure grows.
Figure figure_layout(int width_px, int columns, int rows, double aspect, bool title,
                     const std::vector<LegendEntry>& legend);

/// Light grid lines (a darker zero line), tick labels and, with `marks`,
/// tick marks for the area; vertical lines and x labels only with `x_ticks`.
/// Where the x labels would crowd, only every 2nd (5th, 10th) tick is labelled.
void draw_grid(Canvas& c, const Figure& f, const Area& a, bool x_ticks, bool marks);

/// The area's black frame, its title (bold) above its left end, the x label
/// under the tick labels and the y label upright in the left margin.
void draw_frame(Canvas& c, const Figure& f, const Area& a, const std::string& title, const std::string& xlabel,
                const std::string& ylabel);

/// The figure's title, centred at its top (nothing when empty).
void draw_title(Canvas& c, const Figure& f, const std::string& title);

/// The legend entries at f.legend_at.
void draw_legend(Canvas& c, const Figure& f, const std::vector<LegendEntry>& entries);
/// The notes of `legend` broken at spaces into as many notes (rows) as they
/// need to fit a figure width_px wide (figure_layout's legend width).
std::vector<LegendEntry> wrap_notes(const std::vector<LegendEntry>& legend, int width_px);

/// Index ranges [begin, end) of the consecutive rows where every column is
/// finite (the shortest column's length bounds them).
std::vector<std::pair<std::size_t, std::size_t>> finite_runs(const std::vector<const std::vector<double>*>& cols);

/// The canvas's bytes written to path atomically (io/files.hpp).
void write_picture(Canvas& c, const std::string& path);

}  // namespace orodem::plot
