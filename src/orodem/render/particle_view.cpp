#include "orodem/render/particle_view.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"
#include "orodem/render/plot_util.hpp"

namespace orodem {

namespace {

struct Rgb {
    double r, g, b;
};

// Two horizon colours (proside) and their darker retroside shades.
constexpr Rgb kBandA{0.93, 0.76, 0.38}, kBandB{0.55, 0.70, 0.85};
constexpr double kRetroShade = 0.55;

Rgb horizon_color(double depth, double band, bool retro) {
    const long k = static_cast<long>(std::floor(std::max(0.0, depth) / band));
    Rgb c = (k % 2 == 0) ? kBandA : kBandB;
    if (retro) c = {c.r * kRetroShade, c.g * kRetroShade, c.b * kRetroShade};
    return c;
}

Rgb displacement_color(double s) {
    s = std::clamp(s, 0.0, 1.0);
    // white -> orange -> dark red
    if (s < 0.5) return {1.0, 1.0 - 0.5 * s, 1.0 - 1.8 * s};
    return {1.0 - 0.7 * (s - 0.5), 0.75 - 1.3 * (s - 0.5), 0.1};
}

std::string extension(const std::string& path) {
    const auto dot = path.rfind('.');
    return dot == std::string::npos ? "" : path.substr(dot + 1);
}

}  // namespace

double positive_quantile(const std::vector<double>& v, double q) {
    std::vector<double> pos;
    pos.reserve(v.size());
    for (double x : v)
        if (x > 0.0) pos.push_back(x);
    if (pos.empty()) return 0.0;
    const auto n = static_cast<double>(pos.size());
    const std::size_t rank = static_cast<std::size_t>(std::clamp(std::ceil(q * n), 1.0, n));  // 1-based
    std::nth_element(pos.begin(), pos.begin() + static_cast<std::ptrdiff_t>(rank - 1), pos.end());
    return pos[rank - 1];
}

void render_particles(const ParticleStore& p, const std::vector<double>* scalar, const ViewOptions& o,
                      const std::string& path) {
    const double margin_l = 70, margin_r = 20, margin_t = 40, margin_b = 50;  // [px]
    const double scale = (o.width_px - margin_l - margin_r) / (o.x_max - o.x_min);  // px per m
    const int height_px = static_cast<int>(std::ceil((o.y_max - o.y_min) * scale + margin_t + margin_b));
    const std::string ext = extension(path);
    std::string bytes;  // the picture, written in one atomic write at the end (io/files.hpp)
    cairo_surface_t* surface = nullptr;
    if (ext == "svg") surface = cairo_svg_surface_create_for_stream(plot::append_bytes, &bytes, o.width_px, height_px);
    else if (ext == "pdf") surface = cairo_pdf_surface_create_for_stream(plot::append_bytes, &bytes, o.width_px, height_px);
    else surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, o.width_px, height_px);
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS)
        throw IoError(fmt::format("cannot create picture '{}': {}", path,
                                  cairo_status_to_string(cairo_surface_status(surface))));
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);

    auto px = [&](double x) { return margin_l + (x - o.x_min) * scale; };
    auto py = [&](double y) { return margin_t + (o.y_max - y) * scale; };

    const bool by_displacement = o.color_by == "displacement" && scalar;
    const double full_red = by_displacement ? positive_quantile(*scalar, o.displacement_quantile) : 0.0;

    // Discs.
    cairo_save(cr);
    cairo_rectangle(cr, margin_l, margin_t, (o.x_max - o.x_min) * scale, (o.y_max - o.y_min) * scale);
    cairo_clip(cr);
    for (std::size_t s = 0; s < p.size(); ++s) {
        const double x = p.x[s].x, y = p.x[s].y, r = p.radius[s];
        if (x + r < o.x_min || x - r > o.x_max || y + r < o.y_min || y - r > o.y_max) continue;
        const Rgb c = by_displacement
                          ? displacement_color(full_red > 0.0 ? (*scalar)[s] / full_red : 0.0)
                          : horizon_color(p.initial_depth[s], o.band, p.side[s] != 0);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_new_sub_path(cr);
        cairo_arc(cr, px(x), py(y), r * scale, 0, 2 * std::numbers::pi);
        cairo_fill(cr);
    }
    cairo_restore(cr);

    // Axes: x in h0 with the S point at 0, y in h0.
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, margin_l, margin_t, (o.x_max - o.x_min) * scale, (o.y_max - o.y_min) * scale);
    cairo_stroke(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 13);
    const double span = (o.x_max - o.x_min) / o.h0;
    const double step = span > 40 ? 5 : span > 16 ? 2 : 1;  // tick spacing [h0]
    for (double t = std::ceil((o.x_min - o.x_s) / o.h0 / step) * step; t * o.h0 + o.x_s <= o.x_max; t += step) {
        const double X = px(o.x_s + t * o.h0);
        cairo_move_to(cr, X, py(o.y_min));
        cairo_line_to(cr, X, py(o.y_min) + 5);
        cairo_stroke(cr);
        const std::string label = fmt::format("{:g}", t);
        cairo_text_extents_t e;
        cairo_text_extents(cr, label.c_str(), &e);
        cairo_move_to(cr, X - e.width / 2, py(o.y_min) + 20);
        cairo_show_text(cr, label.c_str());
    }
    for (double t = std::ceil(o.y_min / o.h0); t * o.h0 <= o.y_max; t += 1) {
        const double Y = py(t * o.h0);
        cairo_move_to(cr, margin_l - 5, Y);
        cairo_line_to(cr, margin_l, Y);
        cairo_stroke(cr);
        const std::string label = fmt::format("{:g}", t);
        cairo_text_extents_t e;
        cairo_text_extents(cr, label.c_str(), &e);
        cairo_move_to(cr, margin_l - 10 - e.width, Y + e.height / 2);
        cairo_show_text(cr, label.c_str());
    }
    cairo_move_to(cr, margin_l + 0.5 * (o.x_max - o.x_min) * scale - 60, height_px - 10);
    cairo_show_text(cr, "x / h0 (S point at 0)");
    cairo_save(cr);
    cairo_move_to(cr, 20, margin_t + 0.5 * (o.y_max - o.y_min) * scale + 20);
    cairo_rotate(cr, -std::numbers::pi / 2);
    cairo_show_text(cr, "y / h0");
    cairo_restore(cr);
    // S point marker and legend.
    cairo_set_source_rgb(cr, 0.8, 0, 0);
    cairo_move_to(cr, px(o.x_s), py(o.y_min));
    cairo_line_to(cr, px(o.x_s) - 6, py(o.y_min) + 10);
    cairo_line_to(cr, px(o.x_s) + 6, py(o.y_min) + 10);
    cairo_close_path(cr);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, 16);
    cairo_move_to(cr, margin_l, margin_t - 12);
    cairo_show_text(cr, o.label.c_str());

    cairo_destroy(cr);
    cairo_status_t st = CAIRO_STATUS_SUCCESS;
    if (ext != "svg" && ext != "pdf") st = cairo_surface_write_to_png_stream(surface, plot::append_bytes, &bytes);
    cairo_surface_finish(surface);
    if (st == CAIRO_STATUS_SUCCESS) st = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (st != CAIRO_STATUS_SUCCESS)
        throw IoError(fmt::format("cannot draw picture '{}': {}", path, cairo_status_to_string(st)));
    write_file_atomic(path, bytes);
}

int render_picture_pair(const ParticleStore& p, const std::vector<double>* rel, ViewOptions view,
                        const std::string& experiment, double S, const std::string& figures_dir,
                        const std::string& name, const std::string& ext) {
    view.label = fmt::format("{}   S = {:.2f}   initial depth", experiment, S);
    view.color_by = "horizons";
    render_particles(p, nullptr, view, fmt::format("{}/horizons_{}.{}", figures_dir, name, ext));
    if (!rel) return 1;
    view.label = fmt::format("{}   S = {:.2f}   relative displacement since the previous output", experiment, S);
    view.color_by = "displacement";
    render_particles(p, rel, view, fmt::format("{}/displacement_{}.{}", figures_dir, name, ext));
    return 2;
}

}  // namespace orodem
