// The S plots of one or more runs (SPEC §3: taper, height, peak, dilation
// against S): what `orodem run` draws at its end into figures/plots.png, what
// `orodem sweep` draws over its members and what `orodem plot` draws on
// request. Runs overlaid are labelled by what differs between their resolved
// configs; with seeds, the runs that differ only in their seeds are drawn as
// one mean curve over a band from their lowest to their highest value.
#pragma once

#include <string>
#include <vector>

namespace orodem {

struct RunPlot {
    std::string path;                // the picture written
    std::vector<std::string> notes;  // one line per seed group: its label and runs
};

/// Draws the plots of run_dirs into out (default RUN_DIR/figures/plots.png
/// for one run, <common parent>/plots.png for several; .png, .svg or .pdf).
RunPlot plot_runs(const std::vector<std::string>& run_dirs, const std::string& out, bool seeds = false);

}  // namespace orodem
