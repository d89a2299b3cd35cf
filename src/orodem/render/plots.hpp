// Plots of the wedge measurements against the shortening S, several runs
// overlaid (SPEC §3; paper Figures 10, 11, 14, 15), drawn with Cairo. Four
// panels: taper angles α (solid) and β (dashed), H/h0, peak deviation
// (x_peak − x_S)/h0 and dilation D (%), each against S; one colour per run
// and a legend with the runs' labels. NaN values (no wedge yet) leave gaps.
// Format from the extension (.svg, .pdf, otherwise PNG); the file is written
// atomically.
#pragma once

#include <string>
#include <vector>

#include "orodem/io/series_reader.hpp"

namespace orodem {

struct PlotOptions {
    int width_px = 1400;   // figure width; the height follows from it and the legend
    std::string title;     // optional line above the panels
};

/// The columns the plots need (series.csv of a wedge run, SPEC §4).
extern const std::vector<std::string> kPlotColumns;

/// runs[i] is drawn with labels[i]. Throws ConfigError when a series lacks
/// one of kPlotColumns, IoError when the file cannot be written.
void plot_series(const std::vector<Series>& runs, const std::vector<std::string>& labels,
                 const std::string& path, const PlotOptions& options = {});

}  // namespace orodem
