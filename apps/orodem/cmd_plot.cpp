// `orodem plot RUN_DIR...`: the S plots of one or more runs (run/run_plots.hpp).
#include <fmt/format.h>

#include "orodem/run/run_plots.hpp"

#include "commands.hpp"

namespace orodem {

int cmd_plot(const std::vector<std::string>& run_dirs, const std::string& out, bool seeds) {
    const RunPlot p = plot_runs(run_dirs, out, seeds);
    for (const std::string& n : p.notes) fmt::print("plot: {}\n", n);
    fmt::print("plot: {}\n", p.path);
    return 0;
}

}  // namespace orodem
