// Plots of the wedge measurements against the shortening S, several runs
// overlaid (SPEC §3; paper Figures 10, 11, 14, 15), drawn on a Canvas
// (render/canvas.hpp, laid out by render/plot_util.hpp: fonts 1/60 of the
// width). Four panels: taper angles α (solid) and β (dashed), H/h0, peak
// deviation (x_peak − x_S)/h0 and dilation D (%), each against S (runs
// with [surface], whose series carry the ledger: two more, the eroded and
// deposited area, and the stored area against the influx); one
// colour per run and a legend under the panels naming the two line styles
// and the runs, then notes defining every symbol. NaN values (no wedge yet)
// leave gaps; α and β are masked while H < kTaperMinHeight h0 and drawn over
// a band of ± 1 standard error of their line fits (series columns
// alpha_se_deg, beta_se_deg) when the run has no band of its own. A run may carry a band
// (e.g. the lowest and highest values over packing seeds, `orodem plot
// --seeds`), shaded in its colour behind its curves and in its legend entry.
// Format from the extension (.svg with <text> labels, .pdf, otherwise PNG);
// the file is written atomically.
#pragma once

#include <string>
#include <vector>

#include "orodem/io/series_reader.hpp"

namespace orodem {

struct PlotOptions {
    int width_px = 1400;   // figure width; the height follows from it and the legend
    std::string title;     // optional line above the panels
};

/// α and β are drawn only where H/h0 is at least this (a wedge a few discs
/// high has no meaningful slope); said in the figure.
extern const double kTaperMinHeight;

/// The columns the plots need (series.csv of a wedge run, SPEC §4).
extern const std::vector<std::string> kPlotColumns;

/// The band of one run: series with the run's rows, holding the lowest and
/// the highest value of each column (seed_ensemble's lo and hi).
struct SeriesBand {
    const Series* lo = nullptr;
    const Series* hi = nullptr;
};

/// runs[i] is drawn with labels[i], over bands[i] when bands has an entry
/// for it with both series set. Throws ConfigError when a series lacks one
/// of kPlotColumns, IoError when the file cannot be written.
void plot_series(const std::vector<Series>& runs, const std::vector<std::string>& labels,
                 const std::string& path, const PlotOptions& options = {},
                 const std::vector<SeriesBand>& bands = {});

}  // namespace orodem
