#include "orodem/render/plots.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <tuple>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/render/canvas.hpp"
#include "orodem/render/plot_util.hpp"

namespace orodem {

const double kTaperMinHeight = 0.5;

const std::vector<std::string> kPlotColumns = {"S", "alpha_deg", "beta_deg", "H_over_h0", "peak_dx_over_h0",
                                               "dilation_pct"};

namespace {

using plot::Area;
using plot::Range;
using plot::axis_range;

Colour run_color(std::size_t i) { return plot::palette(i); }

constexpr double kAspect = 0.6;     // the plot areas' height / width in the old layout (plot_util.hpp)
constexpr double kBandAlpha = 0.2;  // opacity of a band's fill

struct Curve {
    const std::vector<double>* x;
    const std::vector<double>* y;
    Colour color;
    bool dashed;
    const std::vector<double>* lo = nullptr;  // band under the curve, drawn where x, lo and hi are finite
    const std::vector<double>* hi = nullptr;
};

struct SeriesPanel {
    std::string title, ylabel;
    std::vector<Curve> curves;
};

void draw_panel(Canvas& cv, const plot::Figure& f, const SeriesPanel& p, Area a) {
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
    a.yr = axis_range(lo, hi, 6);
    plot::draw_grid(cv, f, a, true, true);

    // Curves, clipped to the plot area; NaN breaks a line.
    cv.clip(a.x0, a.y0, a.w, a.h);
    // Bands first, under every line: lo forward and hi back along each run of
    // rows where both are finite.
    for (const Curve& c : p.curves) {
        if (!c.lo || !c.hi) continue;
        for (const auto& [k, e] : plot::finite_runs({c.x, c.lo, c.hi})) {
            std::vector<double> xy;
            for (std::size_t j = k; j < e; ++j) xy.insert(xy.end(), {a.px((*c.x)[j]), a.py((*c.lo)[j])});
            for (std::size_t j = e; j-- > k;) xy.insert(xy.end(), {a.px((*c.x)[j]), a.py((*c.hi)[j])});
            cv.polygon(xy, c.color, kBandAlpha);
        }
    }
    const double width = f.lw(2.0), tiny = f.lw(3.0);
    for (const Curve& c : p.curves) {
        // Each run of finite points is a polyline; one too short to see (a
        // lone point, or points a pixel apart) is a marker instead: filled for
        // a solid curve, hollow for a dashed one.
        for (const auto& [k, e] : plot::finite_runs({c.x, c.y})) {
            std::vector<double> xy;
            double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
            for (std::size_t j = k; j < e; ++j) {
                const double X = a.px((*c.x)[j]), Y = a.py((*c.y)[j]);
                xy.insert(xy.end(), {X, Y});
                x_lo = std::min(x_lo, X), x_hi = std::max(x_hi, X), y_lo = std::min(y_lo, Y), y_hi = std::max(y_hi, Y);
            }
            if (x_hi - x_lo < tiny && y_hi - y_lo < tiny) {
                const double r = f.lw(3.5), X = 0.5 * (x_lo + x_hi), Y = 0.5 * (y_lo + y_hi);
                c.dashed ? cv.ring(X, Y, r, c.color, f.lw(1.5)) : cv.disc(X, Y, r, c.color);
            } else {
                cv.polyline(xy, c.color, width, c.dashed);
            }
        }
    }
    cv.unclip();
    plot::draw_frame(cv, f, a, p.title, "S (shortening / h0)", p.ylabel);
}

/// "svg" or "pdf" from the path's extension (any case), otherwise "png".
std::string format_of(const std::string& path) {
    const auto dot = path.rfind('.');
    const auto slash = path.rfind('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "png";
    std::string e = path.substr(dot + 1);
    for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return e == "svg" || e == "pdf" ? e : "png";
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

    SeriesPanel taper{fmt::format("(a) Taper angles α, β (where H ≥ {:g} h0)", kTaperMinHeight), "angle (degrees)", {}};
    SeriesPanel height{"(b) Wedge height", "H / h0", {}};
    SeriesPanel peak{"(c) Peak deviation from the S point", "(x_peak − x_S) / h0", {}};
    SeriesPanel dil{"(d) Dilation", "D (%)", {}};
    // Runs with [surface] (every run has the ledger's columns): its areas in two more panels.
    const bool ledger = !runs.empty() && std::all_of(runs.begin(), runs.end(), [](const Series& s) {
        return s.column("eroded_area") && s.column("deposited_area") && s.column("stored_area") &&
               s.column("influx_area") && s.column("ledger_error");
    });
    SeriesPanel moved{"(e) Eroded (solid) and deposited (dashed) area", "area / h0²", {}};
    SeriesPanel stored{"(f) Stored area (solid) against the influx (dashed)", "area / h0²", {}};
    double worst_error = 0.0, influx_at_worst = 0.0;  // the ledger's largest |closure error| [h0²]
    // Legend: which line is which angle (in black), then one colour per run,
    // over a swatch of its band when it has one.
    std::vector<plot::LegendEntry> legend = {{"α (prowedge)", {}, false, false, 0.0, true},
                                             {"β (retrowedge)", {}, true, false, 0.0, true}};
    // α and β masked while the wedge is lower than kTaperMinHeight h0 (a
    // slope fitted to a few discs' relief means nothing), over a band of ± one
    // standard error of their line fits (alpha_se_deg, beta_se_deg) unless the
    // run has a band of its own (the seeds' lowest to highest).
    std::deque<std::vector<double>> kept;  // the masked columns (stable addresses)
    bool se_drawn = false;
    auto masked = [&](const std::vector<double>* v, const std::vector<double>* H, const std::vector<double>* se,
                      double sign) -> const std::vector<double>* {
        if (!v || !H) return v;
        std::vector<double> out(v->size(), std::nan(""));
        for (std::size_t k = 0; k < v->size() && k < H->size(); ++k)
            if ((*H)[k] >= kTaperMinHeight) out[k] = (*v)[k] + (se && k < se->size() ? sign * (*se)[k] : 0.0);
        kept.push_back(std::move(out));
        return &kept.back();
    };
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const Series& s = runs[i];
        const Colour c = run_color(i);
        const auto* S = s.column("S");
        const SeriesBand band = i < bands.size() ? bands[i] : SeriesBand{};
        auto curve = [&](const std::string& col, bool dashed) {
            Curve cv{S, s.column(col), c, dashed};
            if (band.lo && band.hi) cv.lo = band.lo->column(col), cv.hi = band.hi->column(col);
            return cv;
        };
        const auto* H = s.column("H_over_h0");
        for (const auto& [col, se_col, dashed] : {std::tuple{"alpha_deg", "alpha_se_deg", false},
                                                  std::tuple{"beta_deg", "beta_se_deg", true}}) {
            Curve cv = curve(col, dashed);
            const std::vector<double>* se = s.column(se_col);
            if (!cv.lo && se) {
                cv.lo = masked(cv.y, H, se, -1.0);
                cv.hi = masked(cv.y, H, se, +1.0);
                se_drawn = true;
            } else {
                cv.lo = masked(cv.lo, H, nullptr, 0.0);
                cv.hi = masked(cv.hi, H, nullptr, 0.0);
            }
            cv.y = masked(cv.y, H, nullptr, 0.0);
            taper.curves.push_back(cv);
        }
        height.curves.push_back(curve("H_over_h0", false));
        peak.curves.push_back(curve("peak_dx_over_h0", false));
        dil.curves.push_back(curve("dilation_pct", false));
        if (ledger) {
            moved.curves.push_back(curve("eroded_area", false));
            moved.curves.push_back(curve("deposited_area", true));
            stored.curves.push_back(curve("stored_area", false));
            stored.curves.push_back(curve("influx_area", true));
            const auto* err = s.column("ledger_error");
            const auto* in = s.column("influx_area");
            for (std::size_t k = 0; k < err->size() && k < in->size(); ++k)
                if (std::fabs((*err)[k]) > worst_error) worst_error = std::fabs((*err)[k]), influx_at_worst = (*in)[k];
        }
        legend.push_back({i < labels.size() ? labels[i] : std::string(), c});
        legend.back().band = band.lo && band.hi ? kBandAlpha : 0.0;
    }
    if (runs.empty()) legend.clear();
    // Every symbol of the panels, said in the figure (a note a row, wrapped to the width).
    if (!runs.empty()) {
        std::vector<std::string> notes = {
            fmt::format("α, β: slopes of the pro- and retrowedge surface (line fits), drawn where the wedge height "
                        "H ≥ {:g} h0",
                        kTaperMinHeight)};
        if (se_drawn) notes.push_back("shaded around α, β: ± 1 standard error of the line fits");
        notes.insert(notes.end(),
                     {"S: shortening / h0; h0: the incoming layer's thickness; H: wedge height above the undeformed surface",
                      "x_peak − x_S: where the highest surface column stands, from the S point",
                      "D (%): dilation, the deformed wedge's area against the area of the layer it accreted"});
        if (ledger)
            notes.push_back(fmt::format("areas: layer area (π R² / φ0 a disc); stored = influx − eroded + deposited, "
                                        "the ledger closing to {:.2g} h0² at worst (influx {:.3g} h0² then)",
                                        worst_error, influx_at_worst));
        for (const std::string& n : notes) legend.push_back({n, {}, false, false, 0.0, false, true});
    }
    legend = plot::wrap_notes(legend, o.width_px);
    const plot::Figure f = plot::figure_layout(o.width_px, 2, ledger ? 3 : 2, kAspect, !o.title.empty(), legend);
    const auto canvas = make_canvas(format_of(path), f.width, f.height);
    plot::draw_title(*canvas, f, o.title);
    const SeriesPanel* panels[] = {&taper, &height, &peak, &dil, &moved, &stored};
    for (std::size_t k = 0; k < (ledger ? 6u : 4u); ++k) {
        Area a = f.panel(k);
        a.xr = xr;
        draw_panel(*canvas, f, *panels[k], a);
    }
    plot::draw_legend(*canvas, f, legend);
    plot::write_picture(*canvas, path);
}

}  // namespace orodem
