#include "orodem/render/calibration_plots.hpp"

#include <algorithm>
#include <cmath>

#include "orodem/render/canvas.hpp"
#include "orodem/render/plot_util.hpp"

namespace orodem {

namespace {

using plot::Area;
using plot::LegendEntry;

Colour color(int i) { return plot::palette(static_cast<std::size_t>(i < 0 ? 0 : i)); }

constexpr double kPanelAspect = 0.62, kBarAspect = 0.55;  // plot areas' height / width in the old layout

void draw_panel(Canvas& cv, const plot::Figure& f, const PlotPanel& p, Area a) {
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
    a.xr = plot::axis_range(xlo, xhi, 8);
    a.yr = plot::axis_range(ylo, yhi, 6);
    plot::draw_grid(cv, f, a, true, false);
    cv.clip(a.x0, a.y0, a.w, a.h);
    for (const PlotCurve& c : p.curves) {
        const Colour col = color(c.color);
        for (const auto& [k, e] : plot::finite_runs({&c.x, &c.y})) {
            std::vector<double> xy;
            for (std::size_t j = k; j < e; ++j) {
                if (c.points) cv.disc(a.px(c.x[j]), a.py(c.y[j]), f.lw(2.5), col);
                else xy.insert(xy.end(), {a.px(c.x[j]), a.py(c.y[j])});
            }
            if (!c.points) cv.polyline(xy, col, f.lw(2.0), c.dashed);
        }
    }
    cv.unclip();
    plot::draw_frame(cv, f, a, p.title, p.xlabel, p.ylabel);
}

}  // namespace

void plot_panels(const std::vector<PlotPanel>& panels, int columns, const std::string& title,
                 const std::string& path, int width_px) {
    columns = std::max(1, columns);
    const int rows = std::max(1, (static_cast<int>(panels.size()) + columns - 1) / columns);
    std::vector<LegendEntry> entries;
    std::vector<const PlotCurve*> firsts;  // the curve each entry stands for
    for (const PlotPanel& p : panels)
        for (const PlotCurve& c : p.curves) {
            if (c.label.empty()) continue;
            bool seen = false;
            for (const PlotCurve* e : firsts)
                seen = seen || (e->label == c.label && e->color == c.color && e->dashed == c.dashed);
            if (seen) continue;
            firsts.push_back(&c);
            entries.push_back({c.label, color(c.color), c.dashed, c.points});
        }
    const plot::Figure f = plot::figure_layout(width_px, columns, rows, kPanelAspect, !title.empty(), entries);
    const auto canvas = make_canvas(picture_format(path), f.width, f.height);
    plot::draw_title(*canvas, f, title);
    for (std::size_t k = 0; k < panels.size(); ++k) draw_panel(*canvas, f, panels[k], f.panel(k));
    plot::draw_legend(*canvas, f, entries);
    plot::write_picture(*canvas, path);
}

void plot_bars(const std::vector<std::string>& categories, const std::vector<BarSeries>& series,
               const std::string& title, const std::string& xlabel, const std::string& ylabel,
               const std::string& path, int width_px) {
    std::vector<LegendEntry> entries;
    for (std::size_t s = 0; s < series.size(); ++s) entries.push_back({series[s].label, color(static_cast<int>(s))});
    const plot::Figure f = plot::figure_layout(width_px, 1, 1, kBarAspect, !title.empty(), entries);
    double yhi = 0.0, ylo = 0.0;
    for (const BarSeries& s : series)
        for (std::size_t k = 0; k < s.value.size(); ++k) {
            if (!std::isfinite(s.value[k])) continue;
            const double e = k < s.error.size() && std::isfinite(s.error[k]) ? std::fabs(s.error[k]) : 0.0;
            yhi = std::max(yhi, s.value[k] + e);
            ylo = std::min(ylo, s.value[k] - e);
        }
    Area a = f.panel(0);
    a.yr = plot::axis_range(ylo, yhi * 1.05, 6);
    a.xr = {0.0, static_cast<double>(std::max<std::size_t>(categories.size(), 1)), 1.0};
    const auto canvas = make_canvas(picture_format(path), f.width, f.height);
    Canvas& cv = *canvas;
    plot::draw_title(cv, f, title);
    plot::draw_grid(cv, f, a, false, false);
    const double group_w = a.w / a.xr.hi;
    const double bar_w = 0.8 * group_w / static_cast<double>(std::max<std::size_t>(series.size(), 1));
    const Colour black{};
    for (std::size_t k = 0; k < categories.size(); ++k) {
        const double gx = a.x0 + group_w * static_cast<double>(k) + 0.1 * group_w;
        cv.text(categories[k], a.x0 + group_w * (static_cast<double>(k) + 0.5), a.y0 + a.h + 0.45 * f.F, 0.85 * f.F,
                HAlign::centre, VAlign::top);
        for (std::size_t s = 0; s < series.size(); ++s) {
            if (k >= series[s].value.size() || !std::isfinite(series[s].value[k])) continue;
            const double v = series[s].value[k];
            const double bx = gx + bar_w * static_cast<double>(s);
            cv.fill_rect(bx + 1, std::min(a.py(v), a.py(0.0)), bar_w - 2, std::fabs(a.py(0.0) - a.py(v)),
                         color(static_cast<int>(s)));
            const double e = k < series[s].error.size() && std::isfinite(series[s].error[k])
                                 ? std::fabs(series[s].error[k])
                                 : 0.0;
            if (e > 0.0) {
                const double cx = bx + 0.5 * bar_w, w = 0.2 * bar_w, lw = f.lw(1.5);
                cv.line(cx, a.py(v - e), cx, a.py(v + e), black, lw);
                cv.line(cx - w, a.py(v - e), cx + w, a.py(v - e), black, lw);
                cv.line(cx - w, a.py(v + e), cx + w, a.py(v + e), black, lw);
            }
        }
    }
    plot::draw_frame(cv, f, a, "", xlabel, ylabel);
    plot::draw_legend(cv, f, entries);
    plot::write_picture(cv, path);
}

}  // namespace orodem
