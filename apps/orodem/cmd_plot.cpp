// `orodem plot RUN_DIR...`: the S plots of one or more runs (run/run_plots.hpp).
// A sweep's folder (with sweep.toml) stands for its members that have
// outputs, in the sweep's order, drawn into DIR/plots.png as the sweep draws
// them (a sweep over the seeds as their mean over a band): the plots of a
// sweep whose members ran elsewhere (a Slurm job array).
#include <filesystem>

#include <fmt/format.h>

#include "orodem/io/series_reader.hpp"
#include "orodem/io/sweep_manifest.hpp"
#include "orodem/run/run_plots.hpp"

#include "commands.hpp"
#include "orodem/core/error.hpp"

namespace orodem {

int cmd_plot(const std::vector<std::string>& run_dirs, const std::string& out, bool seeds) {
    namespace fs = std::filesystem;
    if (run_dirs.size() == 1 && fs::exists(sweep_manifest_path(run_dirs[0]))) {
        const SweepManifest m = read_sweep_manifest(run_dirs[0]);
        std::vector<std::string> members;
        for (const SweepMember& member : sweep_members(m)) {
            const std::string d = sweep_member_dir(run_dirs[0], member);
            if (fs::exists(d + "/series.csv")) members.push_back(d);
            else fmt::print("plot: {} has no outputs yet; left out\n", d);
        }
        if (members.empty())
            throw ConfigError(fmt::format("{}: no member of the sweep has outputs yet (orodem status {})",
                                          run_dirs[0], run_dirs[0]));
        const RunPlot p = plot_runs(members, out.empty() ? run_dirs[0] + "/plots.png" : out, seeds || varies_seed(m));
        for (const std::string& n : p.notes) fmt::print("plot: {}\n", n);
        fmt::print("plot: {}\n", p.path);
        return 0;
    }
    const RunPlot p = plot_runs(run_dirs, out, seeds);
    for (const std::string& n : p.notes) fmt::print("plot: {}\n", n);
    fmt::print("plot: {}\n", p.path);
    return 0;
}

}  // namespace orodem
