#include "orodem/render/plot_util.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "orodem/io/files.hpp"

namespace orodem::plot {

namespace {

constexpr Colour kPalette[] = {{0.12, 0.47, 0.71}, {0.89, 0.10, 0.11}, {0.20, 0.63, 0.17}, {1.00, 0.50, 0.00},
                               {0.42, 0.24, 0.60}, {0.65, 0.34, 0.16}, {0.91, 0.16, 0.54}, {0.40, 0.40, 0.40},
                               {0.74, 0.74, 0.13}, {0.09, 0.75, 0.81}};
constexpr Colour kBlack{0, 0, 0}, kGrid{0.9, 0.9, 0.9}, kZero{0.6, 0.6, 0.6};

// Lengths in units of the label font F.
constexpr double kOuter = 0.7, kLeft = 5.0, kRight = 1.0, kHead = 2.0, kBottom = 3.4, kTitle = 2.0;
constexpr double kTick = 0.85, kTitleFont = 1.15, kRow = 1.6;
constexpr double kKeyLine = 2.2, kKeyGap = 0.4, kKeySpace = 1.4;  // a legend entry: line, gap, label, space

/// The size at which s (bold or not) fits in max_w [px], at most `size`.
double fit(const std::string& s, double size, double max_w, bool bold = false) {
    const double w = text_width(s, size, bold);
    return w > max_w && w > 0.0 ? size * max_w / w : size;
}

}  // namespace

Colour palette(std::size_t i) { return kPalette[i % std::size(kPalette)]; }

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

std::string tick_label(double t, double step) {
    if (std::fabs(t) < 1e-9 * step) t = 0.0;
    return fmt::format("{:g}", t);
}

double font_size(double width_px) { return std::max(12.0, width_px / 60.0); }

Area Figure::panel(std::size_t k) const {
    const auto col = static_cast<double>(k % static_cast<std::size_t>(columns));
    const auto row_k = static_cast<double>(k / static_cast<std::size_t>(columns));
    Area a;
    a.x0 = outer + col * cell_w + left;
    a.y0 = top + row_k * cell_h + head;
    a.w = plot_w;
    a.h = plot_h;
    return a;
}

int legacy_height(int width, int columns, int rows, double aspect, bool title, int legend_rows) {
    // The old layout [px]: 16 outer, 78 + 18 beside and 34 + 52 around each
    // plot area, 34 for the title, legend rows of 24 and 8 under them.
    const double plot_w = (std::max(width, 400) - 32.0) / columns - 96.0;
    const double legend = legend_rows > 0 ? 24.0 * legend_rows + 8.0 : 0.0;
    return static_cast<int>(std::ceil(16.0 + (title ? 34.0 : 0.0) + rows * (86.0 + std::round(aspect * plot_w)) +
                                      legend + 16.0));
}

int legacy_legend_rows(int width, const std::vector<LegendEntry>& legend) {
    // Entries of 36 + 8 + label + 28 px in 14 px type, from 94 px to the width less 16.
    const double x0 = 94.0, x1 = std::max(width, 400) - 16.0;
    double ex = x0;
    int rows = 0;
    for (const LegendEntry& e : legend) {
        if (e.key) continue;
        if (e.note) {  // a row of its own
            if (rows == 0) rows = 1;
            else if (ex > x0) ++rows;
            ex = x1 + 1.0;  // the next entry starts a row
            continue;
        }
        const double w = 72.0 + text_width(e.label, 14.0);
        if (rows == 0) rows = 1;
        else if (ex > x0 && ex + w > x1) ex = x0, ++rows;
        ex += w;
    }
    return rows;
}

Figure figure_layout(int width_px, int columns, int rows, double aspect, bool title,
                     const std::vector<LegendEntry>& legend) {
    Figure f;
    f.columns = std::max(1, columns);
    rows = std::max(1, rows);
    f.width = std::max(width_px, 400);
    f.F = font_size(f.width);
    const double F = f.F;
    f.outer = kOuter * F;
    f.left = kLeft * F;
    f.head = kHead * F;
    f.bottom = kBottom * F;
    f.row = kRow * F;
    f.top = f.outer + (title ? kTitle * F : 0.0);
    f.cell_w = (f.width - 2 * f.outer) / f.columns;
    f.plot_w = f.cell_w - f.left - kRight * F;
    // Legend entries flowed in rows under the panels, from the first plot area's left edge.
    const double x0 = f.outer + f.left, x1 = f.width - f.outer;
    double ex = x0;
    int legend_rows = legend.empty() ? 0 : 1;
    for (const LegendEntry& e : legend) {
        if (e.note) {  // a row of its own
            if (ex > x0) ++legend_rows;
            f.legend_at.emplace_back(x0, (legend_rows - 0.5) * f.row);
            ex = x1 + 1.0;  // the next entry starts a row
            continue;
        }
        const double w = (kKeyLine + kKeyGap + kKeySpace) * F + text_width(e.label, F);
        if (ex > x0 && ex + w > x1) ex = x0, ++legend_rows;
        f.legend_at.emplace_back(ex, (legend_rows - 0.5) * f.row);
        ex += w;
    }
    const double legend_h = legend_rows > 0 ? legend_rows * f.row + 0.4 * F : 0.0;
    f.height = legacy_height(f.width, f.columns, rows, aspect, title, legacy_legend_rows(f.width, legend));
    f.plot_h = std::floor((f.height - f.top - legend_h - f.outer) / rows - f.head - f.bottom);
    if (f.plot_h < 0.3 * f.plot_w) {  // narrow figures, long legends: the figure grows instead
        f.plot_h = std::round(0.3 * f.plot_w);
        f.height = static_cast<int>(std::ceil(f.top + rows * (f.head + f.plot_h + f.bottom) + legend_h + f.outer));
    }
    f.cell_h = f.head + f.plot_h + f.bottom;
    f.legend_y = f.top + rows * f.cell_h;
    for (auto& at : f.legend_at) at.second += f.legend_y;
    return f;
}

void draw_grid(Canvas& c, const Figure& f, const Area& a, bool x_ticks, bool marks) {
    const double size = kTick * f.F, mark = 0.25 * f.F, lw = f.lw(1.0);
    // Every x tick gets its line; labels at every `every`-th tick so that
    // they stay half a font apart (1, 2 or 5: a multiple of the step).
    std::vector<double> xt;
    for (int k = 0; x_ticks; ++k) {
        const double t = a.xr.lo + k * a.xr.step;
        if (t > a.xr.hi + 1e-9 * a.xr.step) break;
        xt.push_back(t);
    }
    double widest = 0.0;
    for (double t : xt) widest = std::max(widest, text_width(tick_label(t, a.xr.step), size));
    const double spacing = a.w * a.xr.step / (a.xr.hi - a.xr.lo);
    int every = 1;
    for (int e : {1, 2, 5, 10})
        if ((every = e) * spacing >= widest + 0.5 * f.F) break;
    for (std::size_t k = 0; k < xt.size(); ++k) {
        const double x = a.px(xt[k]);
        c.line(x, a.y0, x, a.y0 + a.h, kGrid, lw);
        if (marks) c.line(x, a.y0 + a.h, x, a.y0 + a.h + mark, kBlack, lw);
        // Labels on multiples of every steps (from 0 where the axis holds it).
        const long n = std::lround(xt[k] / a.xr.step);
        if (n % every == 0)
            c.text(tick_label(xt[k], a.xr.step), x, a.y0 + a.h + 0.45 * f.F, size, HAlign::centre, VAlign::top);
    }
    for (int k = 0;; ++k) {
        const double t = a.yr.lo + k * a.yr.step;
        if (t > a.yr.hi + 1e-9 * a.yr.step) break;
        const bool zero = std::fabs(t) < 1e-9 * a.yr.step && a.yr.lo < 0 && a.yr.hi > 0;
        const double y = a.py(t);
        c.line(a.x0, y, a.x0 + a.w, y, zero ? kZero : kGrid, lw);
        if (marks) c.line(a.x0 - mark, y, a.x0, y, kBlack, lw);
        c.text(tick_label(t, a.yr.step), a.x0 - 0.4 * f.F, y, size, HAlign::right, VAlign::middle);
    }
}

void draw_frame(Canvas& c, const Figure& f, const Area& a, const std::string& title, const std::string& xlabel,
                const std::string& ylabel) {
    const double F = f.F;
    c.stroke_rect(a.x0, a.y0, a.w, a.h, kBlack, f.lw(1.2));
    if (!title.empty())
        c.text(title, a.x0, a.y0 - 0.6 * F, fit(title, F, a.w + kRight * F, true), HAlign::left, VAlign::baseline,
               true);
    if (!xlabel.empty())
        c.text(xlabel, a.x0 + a.w / 2, a.y0 + a.h + 1.8 * F, fit(xlabel, F, a.w), HAlign::centre, VAlign::top);
    if (!ylabel.empty())
        c.text(ylabel, a.x0 - f.left + 1.0 * F, a.y0 + a.h / 2, fit(ylabel, F, a.h), HAlign::centre,
               VAlign::baseline, false, true);
}

void draw_title(Canvas& c, const Figure& f, const std::string& title) {
    if (title.empty()) return;
    const double size = fit(title, kTitleFont * f.F, f.width - 2 * f.outer);
    c.text(title, f.width / 2.0, f.outer + 0.3 * f.F, size, HAlign::centre, VAlign::top);
}

void draw_legend(Canvas& c, const Figure& f, const std::vector<LegendEntry>& entries) {
    const double F = f.F;
    for (std::size_t i = 0; i < entries.size() && i < f.legend_at.size(); ++i) {
        const LegendEntry& e = entries[i];
        const auto [x, y] = f.legend_at[i];
        if (e.note) {
            c.text(e.label, x, y, 0.85 * F, HAlign::left, VAlign::middle);
            continue;
        }
        if (e.band > 0.0) {
            const double x1 = x + kKeyLine * F, h = 0.45 * F;
            c.polygon({x, y - h, x1, y - h, x1, y + h, x, y + h}, e.colour, e.band);
        }
        if (e.marker)
            c.disc(x + 0.5 * kKeyLine * F, y, f.lw(4.0), e.colour);
        else
            c.line(x, y, x + kKeyLine * F, y, e.colour, f.lw(3.0), e.dashed);
        c.text(e.label, x + (kKeyLine + kKeyGap) * F, y, F, HAlign::left, VAlign::middle);
    }
}

std::vector<LegendEntry> wrap_notes(const std::vector<LegendEntry>& legend, int width_px) {
    const double W = std::max(width_px, 400), F = font_size(W), room = W - (2.0 * kOuter + kLeft) * F;
    std::vector<LegendEntry> out;
    for (const LegendEntry& e : legend) {
        if (!e.note) {
            out.push_back(e);
            continue;
        }
        std::string line;
        std::size_t pos = 0;
        while (pos < e.label.size()) {
            const std::size_t sp = e.label.find(' ', pos);
            const std::string word = e.label.substr(pos, sp == std::string::npos ? std::string::npos : sp - pos);
            pos = sp == std::string::npos ? e.label.size() : sp + 1;
            const std::string longer = line.empty() ? word : line + " " + word;
            if (!line.empty() && text_width(longer, 0.85 * F) > room) {
                out.push_back(e);
                out.back().label = line;
                line = word;
            } else {
                line = longer;
            }
        }
        out.push_back(e);
        out.back().label = line;
    }
    return out;
}

std::vector<std::pair<std::size_t, std::size_t>> finite_runs(const std::vector<const std::vector<double>*>& cols) {
    std::size_t n = cols.empty() ? 0 : cols.front()->size();
    for (const auto* col : cols) n = std::min(n, col->size());
    auto ok = [&](std::size_t k) {
        return k < n && std::all_of(cols.begin(), cols.end(), [k](const auto* col) { return std::isfinite((*col)[k]); });
    };
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (std::size_t k = 0; k < n;) {
        if (!ok(k)) {
            ++k;
            continue;
        }
        std::size_t e = k;
        while (ok(e)) ++e;
        runs.emplace_back(k, e);
        k = e;
    }
    return runs;
}

void write_picture(Canvas& c, const std::string& path) { write_file_atomic(path, c.finish()); }

}  // namespace orodem::plot
