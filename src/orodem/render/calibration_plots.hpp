// Plots of the calibration report (orodem calibrate; setup/calibration.hpp),
// drawn on a Canvas (render/canvas.hpp, laid out by render/plot_util.hpp:
// fonts 1/60 of the width) into files written atomically, PNG, SVG or PDF
// by the path's extension: panels of x-y curves with one shared legend, and
// grouped bar charts with error bars.
#pragma once

#include <string>
#include <vector>

namespace orodem {

struct PlotCurve {
    std::vector<double> x, y;  // NaN breaks the line
    std::string label;         // legend entry (curves with the same label and colour share one)
    int color = 0;             // palette index
    bool dashed = false;
    bool points = false;       // markers instead of a line
};

struct PlotPanel {
    std::string title, xlabel, ylabel;
    std::vector<PlotCurve> curves;
};

/// Panels in a grid of `columns` columns, a title line (may be empty) and a
/// legend of the labelled curves. Throws ConfigError when the path's
/// extension is not .png, .svg or .pdf, IoError when it cannot be written.
void plot_panels(const std::vector<PlotPanel>& panels, int columns, const std::string& title,
                 const std::string& path, int width_px = 1400);

struct BarSeries {
    std::string label;
    std::vector<double> value;  // one per category; NaN: no bar
    std::vector<double> error;  // half-length of the error bar (empty or 0: none)
};

/// Grouped bars: one group per category, one bar per series in it.
void plot_bars(const std::vector<std::string>& categories, const std::vector<BarSeries>& series,
               const std::string& title, const std::string& xlabel, const std::string& ylabel,
               const std::string& path, int width_px = 1000);

}  // namespace orodem
