// A small drawing surface for the particle pictures (render/particle_view)
// and the plots (render/plots, render/calibration_plots through
// render/plot_util): discs, rings, polygons, lines, polylines, rectangles
// and text, in pixels
// with y down, into PNG or PDF through Cairo, or into SVG through a writer
// of our own.
//
// Why our own SVG: Cairo's SVG surface writes every glyph as an outline
// (<symbol> paths), so the text of a figure cannot be edited or searched in
// Inkscape or Illustrator. SvgCanvas writes each text as a <text> element in
// a generic font family (sans-serif), discs as <circle>, and clips panels
// with <clipPath>. Cairo's PDF surface embeds the font as a subset with its
// character map, so PDF text is selectable and searchable (a PDF editor can
// change it with the embedded font's glyphs). Text layout uses Cairo's
// measured advance widths in both back ends and one fixed cap height
// (kCapHeight x font size) for vertical anchoring, so a figure is laid out
// the same in all three formats.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace orodem {

struct Colour {
    double r = 0, g = 0, b = 0;  // each in [0, 1]
};

enum class HAlign { left, centre, right };
enum class VAlign { top, middle, baseline };

/// Height of a capital letter as a fraction of the font size [-].
inline constexpr double kCapHeight = 0.72;

class Canvas {
public:
    virtual ~Canvas() = default;
    /// A filled disc, centre (x, y), radius r [px].
    virtual void disc(double x, double y, double r, Colour c) = 0;
    /// A circle's outline, centre (x, y), radius r, line width [px].
    virtual void ring(double x, double y, double r, Colour c, double width) = 0;
    /// A filled polygon through the points (x0, y0, x1, y1, ...) [px], at
    /// the given opacity (1: opaque).
    virtual void polygon(const std::vector<double>& xy, Colour c, double opacity = 1.0) = 0;
    /// A straight line of the given width [px]; dashed: 3 widths on, 3 off.
    virtual void line(double x0, double y0, double x1, double y1, Colour c, double width, bool dashed = false) = 0;
    /// An open line through the points (x0, y0, x1, y1, ...) [px] with round
    /// joins; dashed as line().
    virtual void polyline(const std::vector<double>& xy, Colour c, double width, bool dashed = false) = 0;
    /// A filled rectangle (x, y, w, h) [px].
    virtual void fill_rect(double x, double y, double w, double h, Colour c) = 0;
    /// A rectangle's outline of the given width [px].
    virtual void stroke_rect(double x, double y, double w, double h, Colour c, double width) = 0;
    /// Text of font size `size` [px] anchored at (x, y); upright: turned 90°
    /// counter-clockwise (reading upward), anchored about its own axes.
    virtual void text(const std::string& s, double x, double y, double size, HAlign h, VAlign v,
                      bool bold = false, bool upright = false, Colour c = {}) = 0;
    /// Everything drawn until unclip() is cut to the rectangle (x, y, w, h) [px].
    virtual void clip(double x, double y, double w, double h) = 0;
    virtual void unclip() = 0;
    /// The finished file's bytes; the canvas takes no more drawing.
    virtual std::string finish() = 0;
};

/// The picture format of a path from its extension: "png", "svg" or "pdf";
/// ConfigError naming the path and the three when it is none of them.
std::string picture_format(const std::string& path);

/// A white canvas of width x height pixels for format "png", "svg" or "pdf"
/// (PDF: one pixel is one point).
std::unique_ptr<Canvas> make_canvas(const std::string& format, int width, int height);

/// Advance width of s at font size `size` [px] (Cairo's sans-serif).
double text_width(const std::string& s, double size, bool bold = false);

}  // namespace orodem
