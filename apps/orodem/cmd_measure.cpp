// orodem measure RUN_DIR: the wedge measures of each saved snapshot of a wedge
// run taken again from the snapshot alone, as CSV on standard output: the
// columns of series.csv that a snapshot determines (run/series_columns.hpp),
// in the same formats, so they can be compared with the run's own rows. The
// belt's decoupling point comes from each snapshot and the one before it.
// Given a sweep's folder: every member's rows in one table, in the sweep's
// order, after a first column `run` naming the member's folder.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/analysis/basal_decoupling.hpp"
#include "orodem/analysis/wedge_profile.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/series_columns.hpp"
#include "orodem/run/sweep.hpp"
#include "orodem/setup/wedge.hpp"

#include "commands.hpp"

namespace fs = std::filesystem;
namespace orodem {

namespace {

/// The measures of the run in run_dir, one line each, after `prefix`; the header first when `header`.
void measure_run(const std::string& run_dir, const std::string& prefix, bool header) {
    require_run_dir(run_dir);
    const fs::path dir(run_dir);
    const Config c = load_config((dir / "config.toml").string());
    const std::string& e = c.run.experiment;
    if (!is_wedge(c))
        throw ConfigError(fmt::format("'{}' is a {} run, which has no wedge to measure; measure takes a run of "
                                      "exp1, exp2, exp3 or critical-wedge",
                                      run_dir, e));
    const std::vector<Snapshot> snaps = read_pvd((dir / "run.pvd").string());
    if (snaps.front().S != 0.0)
        throw IoError(fmt::format("'{}': the first snapshot is at S = {:g}; measure needs the one at S = 0, where "
                                  "the undeformed surface y_mean is taken as the run took it",
                                  (dir / "run.pvd").string(), snaps.front().S));
    ProfileParams pp = wedge_profile_params(c);
    const double h0 = c.packing.h0;
    if (header) fmt::print("{}{}\n", prefix.empty() ? "" : "run,", series_header(true));
    std::vector<Vec2> x_then;  // the previous snapshot's positions and radii by disc id
    std::vector<double> r_then;
    for (std::size_t k = 0; k < snaps.size(); ++k) {
        const std::string vtu = (dir / snaps[k].file).string();
        const VtuData d = read_vtu(vtu);
        const auto& radius = d.require("radius", vtu);
        ParticleStore p;
        for (std::size_t i = 0; i < d.x.size(); ++i) p.add(d.x[i], radius[i], 1.0);
        if (p.size() == 0) throw IoError(fmt::format("'{}': snapshot holds no discs", vtu));
        if (k == 0) pp.y_mean = undeformed_surface(p, pp, c);
        std::vector<double> r_now;
        std::vector<Vec2> x_now = positions_by_id(d, vtu, &r_now);
        SeriesRow r;
        r.S = snaps[k].S;
        r.h0 = h0;
        r.m = measure_wedge(p, pp, snaps[k].S * h0);
        r.decoupling_x = k == 0 ? std::nan("")
                                : basal_decoupling_x(x_then, x_now, r_then, (snaps[k].S - snaps[k - 1].S) * h0,
                                                     kDecouplingBinOverH0 * h0);
        x_then = std::move(x_now);
        r_then = std::move(r_now);
        fmt::print("{}{}\n", prefix, series_line(r, static_cast<std::size_t>(-1), true));
    }
}

}  // namespace

int cmd_measure(const std::string& run_dir) {
    bool manifest = false;
    const std::vector<std::string> members =
        fs::exists(fs::path(run_dir) / "config.toml") ? std::vector<std::string>{} : sweep_folders(run_dir, manifest);
    if (members.empty()) {
        measure_run(run_dir, "", true);
        return 0;
    }
    // A sweep's folder: the members that have snapshots; the others are named on stderr.
    bool header = true;
    for (const std::string& m : members) {
        if (!fs::exists(fs::path(m) / "run.pvd")) {
            fmt::print(stderr, "orodem: measure: {} has no snapshots yet (not started); left out\n", m);
            continue;
        }
        std::string name = fs::path(m).filename().string();
        if (name.find_first_of(",\"") != std::string::npos) {  // a CSV cell
            std::string q = "\"";
            for (char ch : name) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
            name = q + "\"";
        }
        measure_run(m, name + ",", header);
        header = false;
    }
    return 0;
}

}  // namespace orodem
