#include "orodem/render/plot_util.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include <fmt/format.h>

namespace orodem::plot {

namespace {

constexpr Rgb kPalette[] = {{0.12, 0.47, 0.71}, {0.89, 0.10, 0.11}, {0.20, 0.63, 0.17}, {1.00, 0.50, 0.00},
                            {0.42, 0.24, 0.60}, {0.65, 0.34, 0.16}, {0.91, 0.16, 0.54}, {0.40, 0.40, 0.40},
                            {0.74, 0.74, 0.13}, {0.09, 0.75, 0.81}};

}  // namespace

Rgb palette(std::size_t i) { return kPalette[i % std::size(kPalette)]; }

double nice_step(double span, int target) {
    const double raw = span / target;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    const double f = raw / mag;
    return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * mag;
}

Range axis_range(double lo, double hi, int target) {
    if (!(lo <= hi)) lo = 0, hi = 1;
    if (hi - lo < 1e-12 * std::max(1.0, std::fabs(hi))) {
        const double pad = lo == 0.0 ? 1.0 : 0.1 * std::fabs(lo);
        lo -= pad;
        hi += pad;
    }
    Range r;
    r.step = nice_step(hi - lo, target);
    // Data within a thousandth of a step past a tick (S = 1.000001) stays on that tick.
    r.lo = std::floor(lo / r.step + 1e-3) * r.step;
    r.hi = std::ceil(hi / r.step - 1e-3) * r.step;
    return r;
}

void text_at(cairo_t* cr, const std::string& s, double x, double y, double ax, double ay) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    cairo_move_to(cr, x - ax * e.x_advance, y + ay * e.height);
    cairo_show_text(cr, s.c_str());
}

std::string tick_label(double t, double step) {
    if (std::fabs(t) < 1e-9 * step) t = 0.0;
    return fmt::format("{:g}", t);
}

void draw_grid(cairo_t* cr, const Range& xr, const Range& yr, double x0, double y0, double w, double h,
               bool x_ticks, bool marks) {
    auto px = [&](double x) { return x0 + (x - xr.lo) / (xr.hi - xr.lo) * w; };
    auto py = [&](double y) { return y0 + h - (y - yr.lo) / (yr.hi - yr.lo) * h; };
    auto line = [cr](double xa, double ya, double xb, double yb) {
        cairo_move_to(cr, xa, ya);
        cairo_line_to(cr, xb, yb);
        cairo_stroke(cr);
    };
    cairo_set_line_width(cr, 1.0);
    for (int k = 0; x_ticks; ++k) {
        const double t = xr.lo + k * xr.step;
        if (t > xr.hi + 1e-9 * xr.step) break;
        cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
        line(px(t), y0, px(t), y0 + h);
        cairo_set_source_rgb(cr, 0, 0, 0);
        if (marks) line(px(t), y0 + h, px(t), y0 + h + 5);
        text_at(cr, tick_label(t, xr.step), px(t), y0 + h + 9, 0.5, 1.0);
    }
    for (int k = 0;; ++k) {
        const double t = yr.lo + k * yr.step;
        if (t > yr.hi + 1e-9 * yr.step) break;
        const bool zero = std::fabs(t) < 1e-9 * yr.step && yr.lo < 0 && yr.hi > 0;
        const double g = zero ? 0.6 : 0.9;
        cairo_set_source_rgb(cr, g, g, g);
        line(x0, py(t), x0 + w, py(t));
        cairo_set_source_rgb(cr, 0, 0, 0);
        if (marks) line(x0 - 5, py(t), x0, py(t));
        text_at(cr, tick_label(t, yr.step), x0 - 8, py(t), 1.0, 0.5);
    }
}

void draw_frame(cairo_t* cr, double x0, double y0, double w, double h, double left, double font,
                const std::string& title, const std::string& xlabel, const std::string& ylabel) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.2);
    cairo_rectangle(cr, x0, y0, w, h);
    cairo_stroke(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, font + 1);
    text_at(cr, title, x0, y0 - 12, 0.0, 0.0);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, font);
    text_at(cr, xlabel, x0 + w / 2, y0 + h + 44, 0.5, 0.0);
    cairo_save(cr);
    cairo_translate(cr, x0 - left + 18, y0 + h / 2);
    cairo_rotate(cr, -std::numbers::pi / 2);
    text_at(cr, ylabel, 0, 0, 0.5, 0.0);
    cairo_restore(cr);
}

cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

}  // namespace orodem::plot
