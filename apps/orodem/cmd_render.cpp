// `orodem render RUN_DIR`: re-draws the horizon and displacement pictures
// (SPEC §3) from the saved snapshots listed in run.pvd into RUN_DIR/figures/.
// `orodem measure RUN_DIR`: the wedge measures of every saved snapshot, taken
// again with this orodem's analysis (a run that an older orodem made gains
// the measures added since), as CSV on standard output.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "orodem/core/error.hpp"
#include "orodem/analysis/wedge_profile.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/render/particle_view.hpp"
#include "orodem/setup/wedge.hpp"

#include "commands.hpp"

namespace fs = std::filesystem;
namespace orodem {

namespace {

struct Snapshot {
    double S;
    std::string file;  // relative to the run directory
};

/// The (S, file) entries of run.pvd, one per file (the last S of a repeated file).
std::vector<Snapshot> read_pvd(const std::string& path) {
    const std::string b = read_file(path);
    auto attr = [&](std::size_t tag, std::size_t end, const std::string& key) -> std::string {
        const auto k = b.find(" " + key + "=\"", tag);
        if (k == std::string::npos || k > end) throw IoError(fmt::format("'{}': DataSet without {}", path, key));
        const auto v = k + key.size() + 3;
        return b.substr(v, b.find('"', v) - v);
    };
    std::vector<Snapshot> out;
    for (auto pos = b.find("<DataSet"); pos != std::string::npos; pos = b.find("<DataSet", pos + 1)) {
        const auto end = b.find('>', pos);
        const std::string ts = attr(pos, end, "timestep");
        char* stop = nullptr;
        const double S = std::strtod(ts.c_str(), &stop);
        if (stop == ts.c_str()) throw IoError(fmt::format("'{}': timestep '{}' is not a number", path, ts));
        Snapshot s{S, attr(pos, end, "file")};
        if (!out.empty() && out.back().file == s.file) out.back() = s;
        else out.push_back(s);
    }
    if (out.empty()) throw IoError(fmt::format("'{}': lists no snapshots", path));
    return out;
}

const std::vector<double>& need(const VtuData& d, const std::string& name, const std::string& path) {
    const auto* a = d.find(name);
    if (!a) throw IoError(fmt::format("'{}': snapshot has no '{}' array", path, name));
    return *a;
}

}  // namespace

int cmd_render(const std::string& run_dir, const std::vector<double>& at, const std::string& format, int width) {
    require_run_dir(run_dir);
    const fs::path dir(run_dir);
    const std::string config_path = (dir / "config.toml").string();
    toml::table config;
    try {
        config = toml::parse(std::string_view(read_file(config_path)), std::string_view(config_path));
    } catch (const toml::parse_error& e) {
        throw IoError(fmt::format("'{}': not readable as TOML: {}", config_path, e.description()));
    }
    const double h0 = config["packing"]["h0"].value_or(std::numeric_limits<double>::quiet_NaN());
    if (!(h0 > 0)) throw ConfigError(fmt::format("'{}': no positive packing.h0", config_path));
    const std::string experiment = config["run"]["experiment"].value_or(std::string("run"));

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
        const auto& radius = need(d, "radius", vtu);
        const auto& depth = need(d, "initial_depth", vtu);
        const auto& side = need(d, "side", vtu);
        const auto& rel = need(d, "rel_disp", vtu);
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
        view.label = fmt::format("{}   S = {:.2f}   initial depth", experiment, snap.S);
        view.color_by = "horizons";
        render_particles(p, nullptr, view, (dir / "figures" / fmt::format("horizons_{}.{}", name, format)).string());
        ++pictures;
        if (k > 0) {  // the first snapshot has no previous output to move from
            view.label = fmt::format("{}   S = {:.2f}   relative displacement since the previous output",
                                     experiment, snap.S);
            view.color_by = "displacement";
            render_particles(p, &rel, view,
                             (dir / "figures" / fmt::format("displacement_{}.{}", name, format)).string());
            ++pictures;
        }
    }
    fmt::print("render: {} pictures of {} snapshots in {}\n", pictures, chosen.size(), (dir / "figures").string());
    return 0;
}

int cmd_measure(const std::string& run_dir) {
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
    fmt::print("S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,toe_pro_x_over_h0,toe_retro_x_over_h0,"
               "beta_inner_deg,beta_outer_deg,retro_break_x_over_h0\n");
    for (std::size_t k = 0; k < snaps.size(); ++k) {
        const std::string vtu = (dir / snaps[k].file).string();
        const VtuData d = read_vtu(vtu);
        const auto& radius = need(d, "radius", vtu);
        ParticleStore p;
        for (std::size_t i = 0; i < d.x.size(); ++i) p.add(d.x[i], radius[i], 1.0);
        if (p.size() == 0) throw IoError(fmt::format("'{}': snapshot holds no discs", vtu));
        if (k == 0) pp.y_mean = undeformed_surface(p, pp);
        const WedgeMeasures m = measure_wedge(p, pp, snaps[k].S * h0);
        fmt::print("{:.6f},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", snaps[k].S,
                   m.H_over_h0, m.alpha_deg, m.beta_deg, m.peak_dx_over_h0, m.dilation_pct, m.toe_pro_x / h0,
                   m.toe_retro_x / h0, m.beta_inner_deg, m.beta_outer_deg, m.retro_break_x / h0);
    }
    return 0;
}

}  // namespace orodem
