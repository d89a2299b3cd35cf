#include "orodem/render/plots.hpp"

#include "orodem/render/plot_util.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

const std::vector<std::string> kPlotColumns = {"S", "alpha_deg", "beta_deg", "H_over_h0", "peak_dx_over_h0",
                                               "dilation_pct"};

namespace {

using plot::Range;
using plot::Rgb;
using plot::append_bytes;
using plot::axis_range;
using plot::text_at;
using plot::tick_label;

Rgb run_color(std::size_t i) { return plot::palette(i); }

// Layout [px].
constexpr double kOuter = 16, kPanelLeft = 78, kPanelRight = 18, kPanelTop = 34, kPanelBottom = 52;
constexpr double kTitleHeight = 34, kLegendRow = 24, kFont = 14;

struct Curve {
    const std::vector<double>* x;
    const std::vector<double>* y;
    Rgb color;
    bool dashed;
    const std::vector<double>* lo = nullptr;  // band under the curve, drawn where x, lo and hi are finite
    const std::vector<double>* hi = nullptr;
};

constexpr double kBandAlpha = 0.2;  // opacity of a band's fill

struct Panel {
    std::string title, ylabel;
    std::vector<Curve> curves;
    bool taper_key = false;  // draw the "α solid, β dashed" key
};

void draw_panel(cairo_t* cr, const Panel& p, const Range& xr, double x0, double y0, double w, double h) {
    // Data range over every finite point.
    double lo = INFINITY, hi = -INFINITY;
    for (const Curve& c : p.curves)
        for (const std::vector<double>* y : {c.y, c.lo, c.hi})
            for (std::size_t k = 0; y && k < std::min(y->size(), c.x->size()); ++k)
                if (std::isfinite((*y)[k]) && std::isfinite((*c.x)[k])) {
                    lo = std::min(lo, (*y)[k]);
                    hi = std::max(hi, (*y)[k]);
                }
    if (lo < hi) {  // a little room so that lines do not run along the frame
        const double pad = 0.03 * (hi - lo);
        lo = lo >= 0.0 ? std::max(0.0, lo - pad) : lo - pad;  // non-negative data keep a 0 floor
        hi += pad;
    }
    const Range yr = axis_range(lo, hi, 6);
    auto px = [&](double x) { return x0 + (x - xr.lo) / (xr.hi - xr.lo) * w; };
    auto py = [&](double y) { return y0 + h - (y - yr.lo) / (yr.hi - yr.lo) * h; };

    // Grid, zero line, ticks and tick labels.
    cairo_set_font_size(cr, kFont - 1);
    plot::draw_grid(cr, xr, yr, x0, y0, w, h, true, true);

    // Curves, clipped to the plot area; NaN breaks a line.
    cairo_save(cr);
    cairo_rectangle(cr, x0, y0, w, h);
    cairo_clip(cr);
    // Bands first, under every line: lo forward and hi back along each run of
    // rows where both are finite.
    for (const Curve& c : p.curves) {
        if (!c.lo || !c.hi) continue;
        const std::size_t n = std::min({c.x->size(), c.lo->size(), c.hi->size()});
        auto ok = [&](std::size_t k) {
            return k < n && std::isfinite((*c.x)[k]) && std::isfinite((*c.lo)[k]) && std::isfinite((*c.hi)[k]);
        };
        cairo_set_source_rgba(cr, c.color.r, c.color.g, c.color.b, kBandAlpha);
        for (std::size_t k = 0; k < n;) {
            if (!ok(k)) {
                ++k;
                continue;
            }
            std::size_t e = k;
            while (ok(e)) ++e;
            cairo_move_to(cr, px((*c.x)[k]), py((*c.lo)[k]));
            for (std::size_t j = k + 1; j < e; ++j) cairo_line_to(cr, px((*c.x)[j]), py((*c.lo)[j]));
            for (std::size_t j = e; j-- > k;) cairo_line_to(cr, px((*c.x)[j]), py((*c.hi)[j]));
            cairo_close_path(cr);
            cairo_fill(cr);
            k = e;
        }
    }
    cairo_set_line_width(cr, 2.0);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const Curve& c : p.curves) {
        cairo_set_source_rgb(cr, c.color.r, c.color.g, c.color.b);
        const double dash[] = {8.0, 5.0};
        cairo_set_dash(cr, dash, c.dashed ? 2 : 0, 0.0);
        const std::size_t n = std::min(c.x->size(), c.y->size());
        auto ok = [&](std::size_t k) { return k < n && std::isfinite((*c.x)[k]) && std::isfinite((*c.y)[k]); };
        // Each run of finite points is a polyline; one too short to see (a
        // lone point, or points a pixel apart) is a marker instead: filled for
        // a solid curve, hollow for a dashed one.
        for (std::size_t k = 0; k < n;) {
            if (!ok(k)) {
                ++k;
                continue;
            }
            std::size_t e = k;
            double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
            for (; ok(e); ++e) {
                x_lo = std::min(x_lo, px((*c.x)[e])), x_hi = std::max(x_hi, px((*c.x)[e]));
                y_lo = std::min(y_lo, py((*c.y)[e])), y_hi = std::max(y_hi, py((*c.y)[e]));
            }
            if (x_hi - x_lo < 3.0 && y_hi - y_lo < 3.0) {
                cairo_new_sub_path(cr);
                cairo_arc(cr, 0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi), 3.5, 0, 2 * std::numbers::pi);
                if (c.dashed) {
                    cairo_set_dash(cr, nullptr, 0, 0.0);
                    cairo_set_line_width(cr, 1.5);
                    cairo_stroke(cr);
                    cairo_set_line_width(cr, 2.0);
                    cairo_set_dash(cr, dash, 2, 0.0);
                } else {
                    cairo_fill(cr);
                }
            } else {
                cairo_move_to(cr, px((*c.x)[k]), py((*c.y)[k]));
                for (std::size_t j = k + 1; j < e; ++j) cairo_line_to(cr, px((*c.x)[j]), py((*c.y)[j]));
                cairo_stroke(cr);
            }
            k = e;
        }
        cairo_new_path(cr);
    }
    cairo_set_dash(cr, nullptr, 0, 0.0);
    cairo_restore(cr);

    plot::draw_frame(cr, x0, y0, w, h, kPanelLeft, kFont, p.title, "S (shortening / h0)", p.ylabel);

    if (p.taper_key) {  // which line is which angle: in black, above the frame's right end
        const double kx = x0 + w - 120, ky = y0 - 17;
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_line_width(cr, 2.0);
        cairo_move_to(cr, kx, ky);
        cairo_line_to(cr, kx + 28, ky);
        cairo_stroke(cr);
        text_at(cr, "α", kx + 33, ky, 0.0, 0.35);
        const double dash[] = {8.0, 5.0};
        cairo_set_dash(cr, dash, 2, 0.0);
        cairo_move_to(cr, kx + 65, ky);
        cairo_line_to(cr, kx + 100, ky);
        cairo_stroke(cr);
        cairo_set_dash(cr, nullptr, 0, 0.0);
        text_at(cr, "β", kx + 105, ky, 0.0, 0.35);
    }
}

std::string extension(const std::string& path) {
    const auto dot = path.rfind('.');
    const auto slash = path.rfind('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot + 1);
    for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return e;
}

}  // namespace

void plot_series(const std::vector<Series>& runs, const std::vector<std::string>& labels, const std::string& path,
                 const PlotOptions& o, const std::vector<SeriesBand>& bands) {
    for (const Series& s : runs)
        for (const std::string& col : kPlotColumns)
            if (!s.column(col))
                throw ConfigError(fmt::format("'{}' has no column '{}': not the series of a wedge run", s.path, col));

    // x axis shared by the panels: the S range of all runs.
    double s_lo = INFINITY, s_hi = -INFINITY;
    for (const Series& s : runs)
        for (double v : *s.column("S"))
            if (std::isfinite(v)) s_lo = std::min(s_lo, v), s_hi = std::max(s_hi, v);
    if (s_lo > 0 && s_lo <= s_hi) s_lo = 0;  // S axes start at 0
    const Range xr = axis_range(s_lo, s_hi, 8);

    Panel taper{"(a) Taper angles α (prowedge), β (retrowedge)", "angle (degrees)", {}, true};
    Panel height{"(b) Wedge height", "H / h0", {}, false};
    Panel peak{"(c) Peak deviation from the S point", "(x_peak − x_S) / h0", {}, false};
    Panel dil{"(d) Dilation", "D (%)", {}, false};
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const Series& s = runs[i];
        const Rgb c = run_color(i);
        const auto* S = s.column("S");
        const SeriesBand band = i < bands.size() ? bands[i] : SeriesBand{};
        auto curve = [&](const std::string& col, bool dashed) {
            Curve cv{S, s.column(col), c, dashed};
            if (band.lo && band.hi) cv.lo = band.lo->column(col), cv.hi = band.hi->column(col);
            return cv;
        };
        taper.curves.push_back(curve("alpha_deg", false));
        taper.curves.push_back(curve("beta_deg", true));
        height.curves.push_back(curve("H_over_h0", false));
        peak.curves.push_back(curve("peak_dx_over_h0", false));
        dil.curves.push_back(curve("dilation_pct", false));
    }

    // Layout: title, 2 x 2 panels, legend rows flowed under them.
    const double W = std::max(o.width_px, 400);
    const double cell_w = (W - 2 * kOuter) / 2;
    const double plot_w = cell_w - kPanelLeft - kPanelRight;
    const double plot_h = std::round(0.6 * plot_w);
    const double cell_h = kPanelTop + plot_h + kPanelBottom;
    const double top = kOuter + (o.title.empty() ? 0.0 : kTitleHeight);

    cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t* m = cairo_create(scratch);
    cairo_select_font_face(m, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(m, kFont);
    struct Entry {
        double x, y;
    };
    std::vector<Entry> entries;
    const double legend_x0 = kOuter + kPanelLeft, legend_x1 = W - kOuter;
    double ex = legend_x0, ey = 0;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        cairo_text_extents_t e;
        const std::string& label = i < labels.size() ? labels[i] : std::string();
        cairo_text_extents(m, label.c_str(), &e);
        const double wdt = 36 + 8 + e.x_advance + 28;
        if (ex > legend_x0 && ex + wdt > legend_x1) ex = legend_x0, ey += kLegendRow;
        entries.push_back({ex, ey});
        ex += wdt;
    }
    cairo_destroy(m);
    cairo_surface_destroy(scratch);
    const double legend_h = runs.empty() ? 0.0 : ey + kLegendRow + 8;
    const double H = std::ceil(top + 2 * cell_h + legend_h + kOuter);
    const int Wi = static_cast<int>(W), Hi = static_cast<int>(H);

    const std::string ext = extension(path);
    std::string bytes;
    cairo_surface_t* surface = nullptr;
    if (ext == "svg") surface = cairo_svg_surface_create_for_stream(append_bytes, &bytes, W, H);
    else if (ext == "pdf") surface = cairo_pdf_surface_create_for_stream(append_bytes, &bytes, W, H);
    else surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, Wi, Hi);
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
        const auto st = cairo_surface_status(surface);
        cairo_surface_destroy(surface);
        throw IoError(fmt::format("cannot create plot '{}': {}", path, cairo_status_to_string(st)));
    }
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_source_rgb(cr, 0, 0, 0);
    if (!o.title.empty()) {
        cairo_set_font_size(cr, kFont + 3);
        text_at(cr, o.title, W / 2, kOuter + 8, 0.5, 1.0);
    }
    const Panel* panels[] = {&taper, &height, &peak, &dil};
    for (int k = 0; k < 4; ++k) {
        const double cx = kOuter + (k % 2) * cell_w, cy = top + (k / 2) * cell_h;
        draw_panel(cr, *panels[k], xr, cx + kPanelLeft, cy + kPanelTop, plot_w, plot_h);
    }
    // Legend: one colour per run.
    cairo_set_font_size(cr, kFont);
    const double ly = top + 2 * cell_h;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Rgb c = run_color(i);
        const double x = entries[i].x, y = ly + entries[i].y + kLegendRow / 2;
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_set_line_width(cr, 3.0);
        cairo_move_to(cr, x, y);
        cairo_line_to(cr, x + 36, y);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        text_at(cr, i < labels.size() ? labels[i] : std::string(), x + 44, y, 0.0, 0.35);
    }
    cairo_destroy(cr);

    cairo_status_t st = CAIRO_STATUS_SUCCESS;
    if (ext != "svg" && ext != "pdf") st = cairo_surface_write_to_png_stream(surface, append_bytes, &bytes);
    cairo_surface_finish(surface);
    if (st == CAIRO_STATUS_SUCCESS) st = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (st != CAIRO_STATUS_SUCCESS)
        throw IoError(fmt::format("cannot draw plot '{}': {}", path, cairo_status_to_string(st)));
    write_file_atomic(path, bytes);
}

}  // namespace orodem
