#include "orodem/render/particle_view.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "orodem/io/files.hpp"
#include "orodem/render/plot_util.hpp"

namespace orodem {

namespace {

// Two horizon colours (proside) and their darker retroside shades.
constexpr Colour kBandA{0.93, 0.76, 0.38}, kBandB{0.55, 0.70, 0.85};
constexpr double kRetroShade = 0.55;
constexpr Colour kBlack{0, 0, 0}, kSPoint{0.8, 0.0, 0.0}, kWhite{1, 1, 1};
constexpr Colour kPathGrey{0.80, 0.80, 0.80};  // growth strata: the layer's discs
// Fault lines on strain maps: pro-vergent solid blue, retro-vergent dashed
// green (told apart by style too, in grey print and for colour-blind eyes).
constexpr Colour kProFault{0.05, 0.30, 0.95}, kRetroFault{0.0, 0.60, 0.25};
// The frame's wedge: slopes whose cotangents add up to this (run_view) [-].
constexpr double kCotangentSum = 6.0;

Colour shade(Colour c, double f) { return {c.r * f, c.g * f, c.b * f}; }

Colour horizon_colour(double depth, double band, bool retro) {
    const long k = static_cast<long>(std::floor(std::max(0.0, depth) / band));
    const Colour c = (k % 2 == 0) ? kBandA : kBandB;
    return retro ? shade(c, kRetroShade) : c;
}

/// A layered run's horizons: each layer (from the base, the same id on both
/// sides) in its own hue family, the bands of initial depth as a light and a
/// dark tone of it, so horizons stay visible within each layer.
constexpr Colour kLayerHues[][2] = {
    {{0.93, 0.80, 0.55}, {0.80, 0.62, 0.35}},  // sand
    {{0.62, 0.74, 0.90}, {0.40, 0.55, 0.78}},  // blue
    {{0.74, 0.88, 0.62}, {0.52, 0.70, 0.40}},  // green
    {{0.92, 0.66, 0.62}, {0.78, 0.44, 0.40}},  // brick
    {{0.80, 0.72, 0.90}, {0.60, 0.50, 0.75}},  // lilac
    {{0.70, 0.70, 0.70}, {0.48, 0.48, 0.48}},  // grey
};
Colour layer_colour(std::uint8_t layer, double depth, double band, bool retro) {
    const long k = static_cast<long>(std::floor(std::max(0.0, depth) / band));
    const Colour c = kLayerHues[layer % std::size(kLayerHues)][k % 2];
    return retro ? shade(c, kRetroShade) : c;
}

/// The displacement colour map at s in [0, 1] (clamped): light grey, yellow,
/// orange-red, dark red, linear between the stops.
Colour displacement_colour(double s) {
    constexpr Colour stops[] = {{0.82, 0.82, 0.82}, {1.0, 0.85, 0.30}, {0.90, 0.35, 0.10}, {0.45, 0.0, 0.05}};
    constexpr int n = static_cast<int>(std::size(stops)) - 1;
    s = std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0) * n;
    const int k = std::min(static_cast<int>(s), n - 1);
    const double f = s - k;
    const Colour a = stops[k], b = stops[k + 1];
    return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

/// Where v lies along g's bar, 0 at lo, 1 at hi (clamped; NaN, and v ≤ 0 on
/// a log bar, at 0).
double bar_position(const Legend& g, double v) {
    double s = 0.0;
    if (g.log_scale)
        s = v > 0.0 ? (std::log10(v) - std::log10(g.lo)) / (std::log10(g.hi) - std::log10(g.lo)) : 0.0;
    else
        s = (v - g.lo) / (g.hi - g.lo);
    return std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0);
}

/// Pixel layout of a picture, every length from the font size F = width / 60.
struct Layout {
    double F, left, right, head, gap, bottom;  // [px]
    double plot_w, plot_h, scale;              // plot area [px], [px per m]
    int width, height;
};

Layout layout(const ViewOptions& o, std::size_t panels) {
    Layout L;
    L.width = o.width_px;
    L.F = plot::font_size(o.width_px);
    L.left = 3.4 * L.F;
    L.right = 1.2 * L.F;
    L.head = 3.2 * L.F;
    L.gap = 0.9 * L.F;
    L.bottom = 3.0 * L.F;
    L.plot_w = L.width - L.left - L.right;
    L.scale = L.plot_w / (o.x_max - o.x_min);
    L.plot_h = std::round((o.y_max - o.y_min) * L.scale);
    const double n = static_cast<double>(std::max<std::size_t>(panels, 1));
    L.height = static_cast<int>(std::ceil(L.head + n * L.plot_h + (n - 1) * L.gap + L.bottom));
    return L;
}

/// The fault lines' width [px].
double fault_width(const Layout& L) { return std::max(2.0, L.F / 8.0); }

std::string tick_text(double t, double step) { return plot::tick_label(t, step); }

/// The legend in the header's right part, right-aligned at x_right.
void draw_legend(Canvas& c, const Legend& g, double x_right, const Layout& L) {
    const double size = 0.85 * L.F;
    if (g.swatches.empty()) {  // a colour bar
        const double bar_w = 9.0 * L.F, bar_h = 0.7 * L.F, bar_y = 0.55 * L.F;
        const double x0 = x_right - bar_w - 0.5 * L.F;
        constexpr int steps = 120;
        for (int k = 0; k < steps; ++k)
            c.fill_rect(x0 + bar_w * k / steps, bar_y, bar_w / steps + 0.5, bar_h, displacement_colour((k + 0.5) / steps));
        c.stroke_rect(x0, bar_y, bar_w, bar_h, kBlack, 1.0);
        const double step = g.ticks.size() > 1 ? g.ticks[1] - g.ticks[0] : 1.0;
        std::string first_label;
        for (std::size_t k = 0; k < g.ticks.size(); ++k) {
            const double X = x0 + bar_w * bar_position(g, g.ticks[k]);
            c.line(X, bar_y + bar_h, X, bar_y + bar_h + 0.25 * L.F, kBlack, 1.0);
            const bool first = k == 0, last = k + 1 == g.ticks.size();
            const std::string label = g.log_scale ? fmt::format("{}{:g}", first ? "≤ " : last ? "≥ " : "", g.ticks[k])
                                                  : (last ? "≥ " : "") + tick_text(g.ticks[k], step);
            c.text(label, X, bar_y + bar_h + 0.4 * L.F, size, HAlign::centre, VAlign::top);
            if (first) first_label = label;
        }
        c.text(g.title, x0 - 0.6 * L.F, bar_y + 0.5 * bar_h, size, HAlign::right, VAlign::middle);
        // The fault line styles under the title, clear of the first tick label.
        double x = x0 - 0.5 * text_width(first_label, size) - 1.0 * L.F;
        const double y = bar_y + bar_h + 0.9 * L.F, lw = fault_width(L);
        for (std::size_t k = g.line_keys.size(); k-- > 0;) {
            x -= text_width(g.line_keys[k], size);
            c.text(g.line_keys[k], x, y, size, HAlign::left, VAlign::middle);
            x -= 0.4 * L.F + 2.0 * L.F;
            c.line(x, y, x + 2.0 * L.F, y, k == 0 ? kProFault : kRetroFault, lw, k != 0);
            x -= 1.2 * L.F;
        }
        if (!g.line_keys.empty()) {  // the strain maps' faults (not the displacement or damage bars)
            const std::string what = fmt::format("active faults dipping {:g}-{:g}°, numbered by their id:",
                                                 kFaultDipMinDeg, kFaultDipMaxDeg);
            c.text(what, x - text_width(what, size), y, size, HAlign::left, VAlign::middle);
        }
        return;
    }
    // Swatches, laid out from the right: "label [ ][ ]" pairs.
    const double sw = 1.1 * L.F, y = 0.6 * L.F;
    double x = x_right;
    for (std::size_t k = g.swatches.size(); k-- > 0;) {
        const auto& [label, colour] = g.swatches[k];
        x -= sw;
        c.fill_rect(x, y, sw, sw, colour);
        if (!label.empty()) {
            x -= 0.4 * L.F;
            c.text(label, x, y + 0.5 * sw, size, HAlign::right, VAlign::middle);
            x -= text_width(label, size) + 1.0 * L.F;
        }
    }
    c.text(g.title, x_right, y + sw + 0.45 * L.F, size, HAlign::right, VAlign::top);
}

/// Draws one panel; the fault lines it drew are appended to drawn.
void draw_panel(Canvas& c, const Panel& panel, const ViewOptions& o, const Layout& L, double top, bool x_labels,
                const Legend& g, double full, std::vector<FaultLine>& drawn) {
    const double x0 = L.left;
    auto px = [&](double x) { return x0 + (x - o.x_min) * L.scale; };
    auto py = [&](double y) { return top + (o.y_max - y) * L.scale; };
    const bool by_disp = o.color_by == ColorBy::displacement, by_strain = is_strain(o.color_by);
    const bool by_damage = o.color_by == ColorBy::damage;
    const bool by_path = o.color_by == ColorBy::deposition || o.color_by == ColorBy::burial;
    const ParticleStore& p = *panel.p;
    const bool layered = p.has_materials();  // layer hues and damage (a layered run's snapshots)
    c.clip(x0, top, L.plot_w, L.plot_h);
    bool cut_above = false;  // material reaching over the frame's top edge
    // In id order (the order of a snapshot's discs), so that a picture drawn
    // again from a snapshot (orodem render, orodem resume --s-max) lays the
    // discs' antialiased edges over each other as the run did.
    const bool by_id = p.slot_of_id.size() == p.size();
    for (std::size_t k = 0; k < p.size(); ++k) {
        const std::size_t s = by_id ? p.slot_of_id[k] : k;
        const double x = p.x[s].x, y = p.x[s].y, r = p.radius[s];
        if (x + r < o.x_min || x - r > o.x_max || y + r < o.y_min) continue;
        cut_above = cut_above || y + r > o.y_max;
        if (y - r > o.y_max) continue;
        const double path = by_path && panel.path ? (*panel.path)[s] : std::nan("");
        // Growth strata: the layer's discs (birth S 0) grey, each deposit by its S.
        const bool grey = by_path && (!(path >= 0.0) || (o.color_by == ColorBy::deposition && !(path > 0.0)));
        const Colour col = grey ? kPathGrey
                           : by_path ? bar_colour(g, path)
                           : by_strain ? bar_colour(g, panel.strain ? (*panel.strain)[s] : 0.0)
                           : by_damage ? bar_colour(g, layered ? p.damage[s] : 0.0)
                           : !by_disp ? (layered ? layer_colour(p.layer[s], p.initial_depth[s], o.band, p.side[s] != 0)
                                                 : horizon_colour(p.initial_depth[s], o.band, p.side[s] != 0))
                           : panel.displacement && full > 0.0 ? bar_colour(g, (*panel.displacement)[s] * (g.hi / full))
                                                              : bar_colour(g, 0.0);
        c.disc(px(x), py(y), r * L.scale, col);
    }
    if (by_strain && panel.faults) {  // on a white halo, readable over any colour
        const double w = fault_width(L);
        for (const FaultLine& f : *panel.faults)
            c.line(px(f.root.x), py(f.root.y), px(f.tip.x), py(f.tip.y), kWhite, w + 0.5 * w);
        for (const FaultLine& f : *panel.faults) {
            c.line(px(f.root.x), py(f.root.y), px(f.tip.x), py(f.tip.y), f.vergence > 0 ? kProFault : kRetroFault, w,
                   f.vergence <= 0);
            if (f.id >= 0)  // its id just above its tip
                c.text(fmt::format("{}", f.id), px(f.tip.x), py(f.tip.y) - 0.3 * L.F, 0.85 * L.F, HAlign::centre,
                       VAlign::baseline, true, false, f.vergence > 0 ? kProFault : kRetroFault);
            drawn.push_back(f);
        }
    }
    c.unclip();
    const double lw = std::max(1.0, L.F / 18.0), size = 0.85 * L.F, bottom = top + L.plot_h;
    c.stroke_rect(x0, top, L.plot_w, L.plot_h, kBlack, lw);
    // y ticks [h0] on every panel.
    const double y_span = (o.y_max - o.y_min) / o.h0, y_step = y_span > 3.0 ? 1.0 : 0.5;
    for (double t = std::ceil(o.y_min / o.h0 / y_step - 1e-9) * y_step; t * o.h0 <= o.y_max + 1e-9 * o.h0; t += y_step) {
        const double Y = py(t * o.h0);
        c.line(x0 - 0.3 * L.F, Y, x0, Y, kBlack, lw);
        c.text(tick_text(t, y_step), x0 - 0.45 * L.F, Y, size, HAlign::right, VAlign::middle);
    }
    // x ticks [h0 from the S point] on every panel, labelled under the last.
    const double x_step = plot::nice_step((o.x_max - o.x_min) / o.h0, 12);
    for (double t = std::ceil((o.x_min - o.x_s) / o.h0 / x_step - 1e-9) * x_step; o.x_s + t * o.h0 <= o.x_max;
         t += x_step) {
        const double X = px(o.x_s + t * o.h0);
        c.line(X, bottom, X, bottom + 0.3 * L.F, kBlack, lw);
        if (x_labels) c.text(tick_text(t, x_step), X, bottom + 0.7 * L.F, size, HAlign::centre, VAlign::top);
    }
    // The S point: a red triangle pointing up at the base.
    const double Xs = px(o.x_s), a = 0.3 * L.F;
    c.polygon({Xs, bottom, Xs - a, bottom + 1.8 * a, Xs + a, bottom + 1.8 * a}, kSPoint);
    // The panel's S on a white patch (readable over material).
    const std::string label = fmt::format("S = {:.2f}", panel.S);
    const double label_size = 0.9 * L.F;
    c.fill_rect(x0 + lw, top + lw, text_width(label, label_size, true) + 0.6 * L.F, 1.3 * L.F, kWhite);
    c.text(label, x0 + 0.3 * L.F, top + 0.35 * L.F, label_size, HAlign::left, VAlign::top, true);
    if (cut_above)  // said, not hidden: the run's frame was too low for this wedge
        c.text("material above the frame is cut off", x0 + L.plot_w - 0.3 * L.F, top + 0.35 * L.F, size,
               HAlign::right, VAlign::top, false, false, kSPoint);
}

}  // namespace


std::vector<FaultLine> active_fault_lines(const std::vector<Fault>& faults, double unit) {
    std::vector<FaultLine> out;
    for (const Fault& f : faults)
        if (f.active && f.dip_deg >= kFaultDipMinDeg && f.dip_deg <= kFaultDipMaxDeg)
            out.push_back({unit * f.root, unit * f.tip, f.vergence, f.id});
    return out;
}

Colour bar_colour(const Legend& g, double v) { return displacement_colour(bar_position(g, v)); }

ViewOptions run_view(const ConfigBasics& b, int width_px) {
    const double h0 = b.h0;
    const bool backstop = experiment_of(b.experiment).backstop;
    ViewOptions v;
    v.x_min = -(b.pro_margin + 0.5) * h0;
    v.x_max = (backstop ? 0.0 : b.retro_length * h0) + 0.5 * h0;
    v.y_min = -0.05 * h0;
    v.y_max = h0 * (1.0 + std::sqrt(2.0 * std::max(b.s_max, 0.0) / kCotangentSum)) + 0.15 * h0;
    v.h0 = h0;
    v.x_s = 0.0;
    v.band = h0 / 5.0;
    v.width_px = width_px;
    v.title = b.experiment;
    v.output_ds = b.output_ds;
    v.layers = b.layers;
    v.s_max = b.s_max;
    return v;
}

Legend picture_legend(const ViewOptions& o) {
    Legend g;
    if (o.color_by == ColorBy::displacement) {
        if (o.per_frame_scale) {
            g.title = fmt::format("relative displacement / its {:g}th percentile in this frame (old snapshot)",
                                  100.0 * o.displacement_quantile);
            g.lo = 0.0;
            g.hi = 1.0;
            g.ticks = {0.0, 0.25, 0.5, 0.75, 1.0};
        } else {
            g.title = "relative displacement of neighbours |Δx_i − Δx_j| / (ΔS h0)";
            g.lo = 0.0;
            g.hi = kDisplacementFull;
            g.ticks = {0.0, 0.1, 0.2, 0.3};
        }
        return g;
    }
    if (is_strain(o.color_by)) {
        const bool total = o.color_by == ColorBy::strain_total;
        g.title = total ? std::string("finite max shear strain γ since S = 0 [-], log scale")
                  : o.output_ds > 0.0
                      ? fmt::format("max shear strain γ over the output interval ΔS = {:g} [-], log scale", o.output_ds)
                      : std::string("max shear strain γ over the output interval [-], log scale");
        g.lo = total ? kStrainTotalLo : kStrainLo;
        g.hi = total ? kStrainTotalHi : kStrainHi;
        g.log_scale = true;
        for (double t = g.lo; t <= g.hi * (1 + 1e-9); t *= 10.0) g.ticks.push_back(t);
        g.line_keys = {"pro-vergent fault", "retro-vergent fault"};
        return g;
    }
    if (o.color_by == ColorBy::damage) {
        g.title = "damage: contacts' sliding [mean diameters], log scale";
        g.lo = kDamageLo;
        g.hi = kDamageHi;
        g.log_scale = true;
        for (double t = g.lo; t <= g.hi * (1 + 1e-9); t *= 10.0) g.ticks.push_back(t);
        return g;
    }
    if (o.color_by == ColorBy::deposition) {
        g.title = "growth strata: S of deposition [-] (the layer grey)";
        g.lo = 0.0;
        g.hi = o.s_max > 0.0 ? o.s_max : 1.0;
        // Ticks at a round step (1, 2 or 5 times a power of ten), at most five intervals.
        const double p10 = std::pow(10.0, std::floor(std::log10(g.hi / 5.0)));
        double step = p10;
        for (const double m : {1.0, 2.0, 5.0, 10.0})
            if (g.hi / (m * p10) <= 5.0) { step = m * p10; break; }
        g.hi = step * std::ceil(g.hi / step - 1e-9);  // the bar ends at a tick
        for (double t = 0.0; t <= g.hi * (1 + 1e-9); t += step) g.ticks.push_back(t);
        return g;
    }
    if (o.color_by == ColorBy::burial) {
        g.title = "largest burial depth [h0]";
        g.lo = 0.0;
        g.hi = kBurialHi;
        for (int k = 0; k <= 4; ++k) g.ticks.push_back(g.hi * k / 4.0);
        return g;
    }
    if (o.layers > 0) {  // a layered run: one hue family per layer, bands of initial depth within it
        g.title = fmt::format("layers from the base (bands of initial depth, {:g} h0 thick, in each)", o.band / o.h0);
        for (std::size_t l = 0; l < o.layers; ++l)
            g.swatches.push_back({fmt::format("layer {}", l + 1), kLayerHues[l % std::size(kLayerHues)][0]});
        return g;
    }
    g.title = fmt::format("horizons: bands of initial depth, {:g} h0 thick", o.band / o.h0);
    g.swatches = {{"proside", kBandA}, {"", kBandB}, {"retroside", shade(kBandA, kRetroShade)},
                  {"", shade(kBandB, kRetroShade)}};
    return g;
}

PictureInfo picture_size(const ViewOptions& o, std::size_t panels) {
    const Layout L = layout(o, panels);
    return {L.width, L.height, picture_legend(o), {}};
}

PlotArea plot_area(const ViewOptions& o, std::size_t panels, std::size_t k) {
    const Layout L = layout(o, panels);
    return {L.left, L.head + static_cast<double>(k) * (L.plot_h + L.gap), L.plot_w, L.plot_h, L.scale};
}

PictureInfo render_panels(const std::vector<Panel>& panels, const ViewOptions& o, const std::string& path) {
    const std::string format = picture_format(path);
    const Layout L = layout(o, panels.size());
    const Legend legend = picture_legend(o);
    std::unique_ptr<Canvas> c = make_canvas(format, L.width, L.height);
    std::vector<FaultLine> drawn;
    c->text(o.title, L.left, 0.55 * L.F, L.F, HAlign::left, VAlign::top, true);
    draw_legend(*c, legend, L.width - L.right, L);
    for (std::size_t k = 0; k < panels.size(); ++k) {
        double full = 1.0;  // displacement: the value drawn at the top of the bar
        if (o.color_by == ColorBy::displacement && panels[k].displacement)
            full = o.per_frame_scale ? positive_quantile(*panels[k].displacement, o.displacement_quantile)
                                     : kDisplacementFull;
        draw_panel(*c, panels[k], o, L, L.head + static_cast<double>(k) * (L.plot_h + L.gap), k + 1 == panels.size(),
                   legend, full, drawn);
    }
    const double stack_bottom = L.height - L.bottom;
    c->text("x / h0 (S point at 0)", L.left + 0.5 * L.plot_w, stack_bottom + 1.75 * L.F, L.F, HAlign::centre,
            VAlign::top);
    c->text("y / h0", 0.35 * L.F, 0.5 * (L.head + stack_bottom), L.F, HAlign::centre, VAlign::top, false, true);
    write_file_atomic(path, c->finish());
    return {L.width, L.height, legend, std::move(drawn)};
}

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

std::vector<PictureInfo> render_output_pictures(const Panel& panel, ViewOptions view, const std::string& dir,
                                                const std::string& name, const std::string& ext) {
    std::vector<PictureInfo> out;
    view.color_by = ColorBy::horizons;
    out.push_back(render_panels({{panel.p, nullptr, panel.S}}, view, fmt::format("{}/horizons_{}.{}", dir, name, ext)));
    if (panel.displacement) {
        view.color_by = ColorBy::displacement;
        out.push_back(render_panels({{panel.p, panel.displacement, panel.S}}, view,
                                    fmt::format("{}/displacement_{}.{}", dir, name, ext)));
    }
    if (panel.strain) {
        view.color_by = ColorBy::strain;
        view.per_frame_scale = false;
        out.push_back(render_panels({{panel.p, nullptr, panel.S, panel.strain, panel.faults}}, view,
                                    fmt::format("{}/strain_{}.{}", dir, name, ext)));
    }
    return out;
}

}  // namespace orodem
