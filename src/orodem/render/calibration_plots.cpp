#include "orodem/render/calibration_plots.hpp"

#include "orodem/render/plot_util.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

namespace {

using plot::Rgb;
using plot::append_bytes;
using plot::text_at;
using plot::tick_label;
using Axis = plot::Range;

Rgb color(int i) { return plot::palette(static_cast<std::size_t>(i < 0 ? 0 : i)); }

constexpr double kFont = 14, kOuter = 16, kLeft = 78, kRight = 18, kTop = 34, kBottom = 52, kLegendRow = 24;

Axis axis_for(double lo, double hi, int target) { return plot::axis_range(lo, hi, target); }

/// Frame, grid, ticks and labels of a plot area; returns nothing, draws axes.
void draw_axes(cairo_t* cr, const Axis& xa, const Axis& ya, double x0, double y0, double w, double h,
               const std::string& title, const std::string& xlabel, const std::string& ylabel, bool x_ticks) {
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, kFont - 1);
    plot::draw_grid(cr, xa, ya, x0, y0, w, h, x_ticks, false);
    plot::draw_frame(cr, x0, y0, w, h, kLeft, kFont, title, xlabel, ylabel);
}

void set_dash(cairo_t* cr, bool dashed) {
    const double dash[] = {8.0, 5.0};
    cairo_set_dash(cr, dash, dashed ? 2 : 0, 0.0);
}

void draw_panel(cairo_t* cr, const PlotPanel& p, double x0, double y0, double w, double h) {
    double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
    for (const PlotCurve& c : p.curves)
        for (std::size_t k = 0; k < std::min(c.x.size(), c.y.size()); ++k)
            if (std::isfinite(c.x[k]) && std::isfinite(c.y[k])) {
                xlo = std::min(xlo, c.x[k]), xhi = std::max(xhi, c.x[k]);
                ylo = std::min(ylo, c.y[k]), yhi = std::max(yhi, c.y[k]);
            }
    if (ylo < yhi) {
        const double pad = 0.04 * (yhi - ylo);
        ylo = ylo >= 0.0 ? std::max(0.0, ylo - pad) : ylo - pad;
        yhi += pad;
    }
    const Axis xa = axis_for(xlo, xhi, 8), ya = axis_for(ylo, yhi, 6);
    draw_axes(cr, xa, ya, x0, y0, w, h, p.title, p.xlabel, p.ylabel, true);
    auto px = [&](double x) { return x0 + (x - xa.lo) / (xa.hi - xa.lo) * w; };
    auto py = [&](double y) { return y0 + h - (y - ya.lo) / (ya.hi - ya.lo) * h; };
    cairo_save(cr);
    cairo_rectangle(cr, x0, y0, w, h);
    cairo_clip(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const PlotCurve& c : p.curves) {
        const Rgb col = color(c.color);
        cairo_set_source_rgb(cr, col.r, col.g, col.b);
        const std::size_t n = std::min(c.x.size(), c.y.size());
        auto ok = [&](std::size_t k) { return k < n && std::isfinite(c.x[k]) && std::isfinite(c.y[k]); };
        if (c.points) {
            for (std::size_t k = 0; k < n; ++k)
                if (ok(k)) {
                    cairo_new_sub_path(cr);
                    cairo_arc(cr, px(c.x[k]), py(c.y[k]), 2.5, 0, 2 * std::numbers::pi);
                }
            cairo_fill(cr);
            continue;
        }
        cairo_set_line_width(cr, 2.0);
        set_dash(cr, c.dashed);
        for (std::size_t k = 0; k < n;) {
            if (!ok(k)) {
                ++k;
                continue;
            }
            cairo_move_to(cr, px(c.x[k]), py(c.y[k]));
            std::size_t e = k + 1;
            for (; ok(e); ++e) cairo_line_to(cr, px(c.x[e]), py(c.y[e]));
            cairo_stroke(cr);
            k = e;
        }
        set_dash(cr, false);
    }
    cairo_restore(cr);
}


struct LegendEntry {
    std::string label;
    int color;
    bool dashed, points;
};

/// Lays out legend entries in rows between x0 and x1; returns the positions and the height.
std::vector<std::pair<double, double>> legend_layout(const std::vector<LegendEntry>& entries, double x0, double x1,
                                                     double& height) {
    cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t* m = cairo_create(scratch);
    cairo_select_font_face(m, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(m, kFont);
    std::vector<std::pair<double, double>> at;
    double ex = x0, ey = 0;
    for (const LegendEntry& e : entries) {
        cairo_text_extents_t t;
        cairo_text_extents(m, e.label.c_str(), &t);
        const double wdt = 36 + 8 + t.x_advance + 28;
        if (ex > x0 && ex + wdt > x1) ex = x0, ey += kLegendRow;
        at.emplace_back(ex, ey);
        ex += wdt;
    }
    cairo_destroy(m);
    cairo_surface_destroy(scratch);
    height = entries.empty() ? 0.0 : ey + kLegendRow + 8;
    return at;
}

void draw_legend(cairo_t* cr, const std::vector<LegendEntry>& entries,
                 const std::vector<std::pair<double, double>>& at, double y0) {
    cairo_set_font_size(cr, kFont);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Rgb c = color(entries[i].color);
        const double x = at[i].first, y = y0 + at[i].second + kLegendRow / 2;
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        if (entries[i].points) {
            cairo_arc(cr, x + 18, y, 4.0, 0, 2 * std::numbers::pi);
            cairo_fill(cr);
        } else {
            cairo_set_line_width(cr, 3.0);
            set_dash(cr, entries[i].dashed);
            cairo_move_to(cr, x, y);
            cairo_line_to(cr, x + 36, y);
            cairo_stroke(cr);
            set_dash(cr, false);
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        text_at(cr, entries[i].label, x + 44, y, 0.0, 0.35);
    }
}

/// Writes the image surface as PNG atomically, then destroys it.
void finish_png(cairo_surface_t* surface, const std::string& path) {
    std::string bytes;
    cairo_status_t st = cairo_surface_write_to_png_stream(surface, append_bytes, &bytes);
    cairo_surface_finish(surface);
    if (st == CAIRO_STATUS_SUCCESS) st = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (st != CAIRO_STATUS_SUCCESS)
        throw IoError(fmt::format("cannot draw plot '{}': {}", path, cairo_status_to_string(st)));
    write_file_atomic(path, bytes);
}

cairo_surface_t* new_surface(int w, int h, const std::string& path) {
    cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        const auto st = cairo_surface_status(s);
        cairo_surface_destroy(s);
        throw IoError(fmt::format("cannot create plot '{}': {}", path, cairo_status_to_string(st)));
    }
    return s;
}

void draw_title(cairo_t* cr, const std::string& title, double W) {
    if (title.empty()) return;
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, kFont + 3);
    text_at(cr, title, W / 2, kOuter + 8, 0.5, 1.0);
}

}  // namespace

void plot_panels(const std::vector<PlotPanel>& panels, int columns, const std::string& title,
                 const std::string& path, int width_px) {
    columns = std::max(1, columns);
    const int rows = std::max(1, (static_cast<int>(panels.size()) + columns - 1) / columns);
    const double W = std::max(width_px, 400);
    const double cell_w = (W - 2 * kOuter) / columns;
    const double plot_w = cell_w - kLeft - kRight;
    const double plot_h = std::round(0.62 * plot_w);
    const double cell_h = kTop + plot_h + kBottom;
    const double top = kOuter + (title.empty() ? 0.0 : 34.0);
    std::vector<LegendEntry> entries;
    for (const PlotPanel& p : panels)
        for (const PlotCurve& c : p.curves) {
            if (c.label.empty()) continue;
            bool seen = false;
            for (const LegendEntry& e : entries)
                seen = seen || (e.label == c.label && e.color == c.color && e.dashed == c.dashed);
            if (!seen) entries.push_back({c.label, c.color, c.dashed, c.points});
        }
    double legend_h = 0;
    const auto at = legend_layout(entries, kOuter + kLeft, W - kOuter, legend_h);
    const double H = std::ceil(top + rows * cell_h + legend_h + kOuter);
    cairo_surface_t* surface = new_surface(static_cast<int>(W), static_cast<int>(H), path);
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_title(cr, title, W);
    for (std::size_t k = 0; k < panels.size(); ++k) {
        const double cx = kOuter + static_cast<double>(static_cast<int>(k) % columns) * cell_w;
        const double cy = top + static_cast<double>(static_cast<int>(k) / columns) * cell_h;
        draw_panel(cr, panels[k], cx + kLeft, cy + kTop, plot_w, plot_h);
    }
    draw_legend(cr, entries, at, top + rows * cell_h);
    cairo_destroy(cr);
    finish_png(surface, path);
}

void plot_bars(const std::vector<std::string>& categories, const std::vector<BarSeries>& series,
               const std::string& title, const std::string& xlabel, const std::string& ylabel,
               const std::string& path, int width_px) {
    const double W = std::max(width_px, 400);
    const double plot_w = W - 2 * kOuter - kLeft - kRight;
    const double plot_h = std::round(0.55 * plot_w);
    const double top = kOuter + (title.empty() ? 0.0 : 34.0);
    std::vector<LegendEntry> entries;
    for (std::size_t s = 0; s < series.size(); ++s)
        entries.push_back({series[s].label, static_cast<int>(s), false, false});
    double legend_h = 0;
    const auto at = legend_layout(entries, kOuter + kLeft, W - kOuter, legend_h);
    const double H = std::ceil(top + kTop + plot_h + kBottom + legend_h + kOuter);
    double yhi = 0.0, ylo = 0.0;
    for (const BarSeries& s : series)
        for (std::size_t k = 0; k < s.value.size(); ++k) {
            if (!std::isfinite(s.value[k])) continue;
            const double e = k < s.error.size() && std::isfinite(s.error[k]) ? std::fabs(s.error[k]) : 0.0;
            yhi = std::max(yhi, s.value[k] + e);
            ylo = std::min(ylo, s.value[k] - e);
        }
    const Axis ya = axis_for(ylo, yhi * 1.05, 6);
    const Axis xa{0.0, static_cast<double>(std::max<std::size_t>(categories.size(), 1)), 1.0};
    cairo_surface_t* surface = new_surface(static_cast<int>(W), static_cast<int>(H), path);
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_title(cr, title, W);
    const double x0 = kOuter + kLeft, y0 = top + kTop;
    draw_axes(cr, xa, ya, x0, y0, plot_w, plot_h, "", xlabel, ylabel, false);
    auto py = [&](double y) { return y0 + plot_h - (y - ya.lo) / (ya.hi - ya.lo) * plot_h; };
    const double group_w = plot_w / xa.hi;
    const double bar_w = 0.8 * group_w / static_cast<double>(std::max<std::size_t>(series.size(), 1));
    cairo_set_font_size(cr, kFont - 1);
    for (std::size_t k = 0; k < categories.size(); ++k) {
        const double gx = x0 + group_w * static_cast<double>(k) + 0.1 * group_w;
        cairo_set_source_rgb(cr, 0, 0, 0);
        text_at(cr, categories[k], x0 + group_w * (static_cast<double>(k) + 0.5), y0 + plot_h + 9, 0.5, 1.0);
        for (std::size_t s = 0; s < series.size(); ++s) {
            if (k >= series[s].value.size() || !std::isfinite(series[s].value[k])) continue;
            const double v = series[s].value[k];
            const double bx = gx + bar_w * static_cast<double>(s);
            const Rgb c = color(static_cast<int>(s));
            cairo_set_source_rgb(cr, c.r, c.g, c.b);
            cairo_rectangle(cr, bx + 1, std::min(py(v), py(0.0)), bar_w - 2, std::fabs(py(0.0) - py(v)));
            cairo_fill(cr);
            const double e = k < series[s].error.size() && std::isfinite(series[s].error[k])
                                 ? std::fabs(series[s].error[k])
                                 : 0.0;
            if (e > 0.0) {
                cairo_set_source_rgb(cr, 0, 0, 0);
                cairo_set_line_width(cr, 1.5);
                const double cx = bx + 0.5 * bar_w;
                cairo_move_to(cr, cx, py(v - e));
                cairo_line_to(cr, cx, py(v + e));
                cairo_move_to(cr, cx - 0.2 * bar_w, py(v - e));
                cairo_line_to(cr, cx + 0.2 * bar_w, py(v - e));
                cairo_move_to(cr, cx - 0.2 * bar_w, py(v + e));
                cairo_line_to(cr, cx + 0.2 * bar_w, py(v + e));
                cairo_stroke(cr);
            }
        }
    }
    draw_legend(cr, entries, at, y0 + plot_h + kBottom);
    cairo_destroy(cr);
    finish_png(surface, path);
}

}  // namespace orodem
