// `orodem render RUN_DIR`: re-draws the horizon and displacement pictures
// (SPEC §3) from the saved snapshots listed in run.pvd into RUN_DIR/figures/.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/analysis/wedge_profile.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/render/particle_view.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/setup/wedge.hpp"

#include "commands.hpp"

namespace fs = std::filesystem;
namespace orodem {

int cmd_render(const std::string& run_dir, const std::vector<double>& at, const std::string& format, int width) {
    require_run_dir(run_dir);
    const fs::path dir(run_dir);
    const ConfigBasics config = read_config_basics((dir / "config.toml").string());
    const double h0 = config.h0;
    const std::string& experiment = config.experiment;

    const std::vector<Snapshot> snaps = read_pvd((dir / "run.pvd").string());
    std::vector<std::size_t> chosen;
    if (at.empty()) {
        for (std::size_t k = 0; k < snaps.size(); ++k) chosen.push_back(k);
    } else {
        for (double S : at) {
            std::size_t best = 0;
            for (std::size_t k = 1; k < snaps.size(); ++k)
                if (std::fabs(snaps[k].S - S) < std::fabs(snaps[best].S - S)) best = k;
            chosen.push_back(best);
        }
        std::sort(chosen.begin(), chosen.end());
        chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    }

    make_dirs((dir / "figures").string());
    int pictures = 0;
    for (std::size_t k : chosen) {
        const Snapshot& snap = snaps[k];
        const std::string vtu = (dir / snap.file).string();
        const VtuData d = read_vtu(vtu);
        const auto& radius = d.require("radius", vtu);
        const auto& depth = d.require("initial_depth", vtu);
        const auto& side = d.require("side", vtu);
        const auto& rel = d.require("rel_disp", vtu);
        ParticleStore p;
        double x_lo = INFINITY, x_hi = -INFINITY, top = 0.0;
        for (std::size_t i = 0; i < d.x.size(); ++i) {
            const std::size_t s = p.add(d.x[i], radius[i], 1.0);
            p.initial_depth[s] = depth[i];
            p.side[s] = side[i] != 0 ? 1 : 0;
            x_lo = std::min(x_lo, d.x[i].x - radius[i]);
            x_hi = std::max(x_hi, d.x[i].x + radius[i]);
            top = std::max(top, d.x[i].y + radius[i]);
        }
        if (p.size() == 0) throw IoError(fmt::format("'{}': snapshot holds no discs", vtu));
        ViewOptions view;
        view.x_min = x_lo;
        view.x_max = x_hi;
        view.y_min = 0.0;
        view.y_max = top + 0.3 * h0;
        view.h0 = h0;
        view.band = h0 / 5.0;
        view.width_px = width;
        const std::string name = fs::path(snap.file).stem().string();
        // The first snapshot has no previous output to move from.
        pictures += render_picture_pair(p, k > 0 ? &rel : nullptr, view, experiment, snap.S,
                                        (dir / "figures").string(), name, format);
    }
    fmt::print("render: {} pictures of {} snapshots in {}\n", pictures, chosen.size(), (dir / "figures").string());
    return 0;
}

}  // namespace orodem
