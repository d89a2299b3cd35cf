// Small pieces shared by the Cairo plots (render/plots.cpp, the series
// plots; render/calibration_plots.cpp, the calibration reports): the line
// palette, "nice" axis ranges and ticks, anchored text, and a PNG-to-memory
// sink.
#pragma once

#include <cairo.h>

#include <cstddef>
#include <string>

namespace orodem::plot {

struct Rgb {
    double r, g, b;
};

/// Ten well-separated line colours, cycled when there are more lines.
Rgb palette(std::size_t i);

/// An axis from lo to hi with ticks every step.
struct Range {
    double lo = 0, hi = 1, step = 0.2;
};

/// A "nice" tick step (1, 2 or 5 × 10^k) giving about `target` intervals.
double nice_step(double span, int target);

/// Axis range covering [lo, hi] (finite, or none: lo > hi), on tick multiples.
Range axis_range(double lo, double hi, int target);

/// Draws s with its anchor (ax, ay) ∈ [0, 1]² of its extent at (x, y).
void text_at(cairo_t* cr, const std::string& s, double x, double y, double ax, double ay);

/// Tick label: "{:g}", with round-off around zero shown as 0.
std::string tick_label(double t, double step);

/// Grid lines (a darker zero line), tick labels in the current font and, with
/// `marks`, 5-pixel tick marks, for the plot area (x0, y0, w, h) spanning
/// xr × yr; vertical lines and x labels only with `x_ticks`.
void draw_grid(cairo_t* cr, const Range& xr, const Range& yr, double x0, double y0, double w, double h,
               bool x_ticks, bool marks);

/// The black frame of the plot area (x0, y0, w, h), its title (bold, font
/// + 1) above its left end, the x label below it and the y label turned
/// upright 18 px inside the left margin `left` [px], labels at `font` [pt].
void draw_frame(cairo_t* cr, double x0, double y0, double w, double h, double left, double font,
                const std::string& title, const std::string& xlabel, const std::string& ylabel);

/// cairo write function appending to the std::string* closure.
cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length);

}  // namespace orodem::plot
