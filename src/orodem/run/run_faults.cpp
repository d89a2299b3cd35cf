#include "orodem/run/run_faults.hpp"

#include "orodem/core/nearest.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "orodem/analysis/basal_decoupling.hpp"
#include "orodem/analysis/strain.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/run/run_dir.hpp"

namespace fs = std::filesystem;

namespace orodem {

namespace {

/// The positions of a snapshot file by disc id (NaN for an id it lacks), and
/// (if radius is given) the radii likewise.
std::vector<Vec2> positions_by_id(const std::string& vtu, std::vector<double>* radius = nullptr) {
    return positions_by_id(read_vtu(vtu), vtu, radius);
}

}  // namespace

RunFaults run_faults(const std::string& dir, bool from_snapshots) {
    require_run_dir(dir);
    const fs::path d(dir);
    RunFaults out;
    const std::string csv = (d / "faults.csv").string();
    if (!from_snapshots && fs::exists(csv)) {
        out.rows = read_faults_csv(csv);
        for (const FaultRow& r : out.rows)
            if (out.outputs.empty() || out.outputs.back() != r.S) out.outputs.push_back(r.S);
        if (out.outputs.empty()) {  // no fault found yet: the outputs are those of run.pvd
            for (const Snapshot& s : read_pvd((d / "run.pvd").string())) out.outputs.push_back(s.S);
        }
        return out;
    }
    const Config c = load_config((d / "config.toml").string());
    if (!is_wedge(c))
        throw ConfigError(fmt::format("'{}' is a {} run, which has no wedge and no faults; faults takes a run of "
                                      "exp1, exp2, exp3 or critical-wedge",
                                      dir, c.run.experiment));
    out.from_snapshots = true;
    const double h0 = c.packing.h0, d_mean = c.packing.r_min + c.packing.r_max;
    const FaultParams p = fault_params(d_mean, h0);
    FaultTracker tracker;
    std::vector<Vec2> x_then;
    for (const Snapshot& s : read_pvd((d / "run.pvd").string())) {
        std::vector<Vec2> x_now = positions_by_id((d / s.file).string());
        std::vector<Fault> found;
        if (!x_then.empty() && s.S > 0.0) {
            const StrainField strain = local_strain(x_then, x_now, 2.0 * d_mean);
            found = detect_faults(x_now, strain.shear, p).faults;
        }
        for (const Fault& f : tracker.update(std::move(found), s.S, h0)) {
            FaultRow r;
            r.S = s.S;
            r.fault = f;
            r.fault.root = (1.0 / h0) * f.root;
            r.fault.tip = (1.0 / h0) * f.tip;
            r.fault.length = f.length / h0;
            r.fault.width = f.width / h0;
            r.fault.slip = f.slip / h0;
            out.rows.push_back(r);
        }
        out.outputs.push_back(s.S);
        x_then = std::move(x_now);
    }
    return out;
}

std::vector<Fault> faults_at(const RunFaults& f, double S, double* S_out) {
    if (f.outputs.empty()) throw IoError("the run has no output yet");
    const double best = f.outputs[nearest_output(f.outputs, S, "--at")];
    if (S_out) *S_out = best;
    std::vector<Fault> at;
    for (const FaultRow& r : f.rows)
        if (r.S == best) at.push_back(r.fault);
    return at;
}

double run_decoupling_at(const std::string& dir, double S) {
    const fs::path d(dir);
    const std::vector<Snapshot> snaps = read_pvd((d / "run.pvd").string());
    std::size_t k = 0;
    for (std::size_t i = 1; i < snaps.size(); ++i)
        if (std::fabs(snaps[i].S - S) < std::fabs(snaps[k].S - S)) k = i;
    if (k == 0) return std::nan("");
    const double h0 = load_config((d / "config.toml").string()).packing.h0;
    std::vector<double> radius;
    const std::vector<Vec2> x_then = positions_by_id((d / snaps[k - 1].file).string(), &radius);
    const std::vector<Vec2> x_now = positions_by_id((d / snaps[k].file).string());
    return basal_decoupling_x(x_then, x_now, radius, (snaps[k].S - snaps[k - 1].S) * h0, kDecouplingBinOverH0 * h0) /
           h0;
}

RunFaultLines run_fault_lines(const RunFaults& f, const std::vector<Snapshot>& snaps, double h0) {
    RunFaultLines out(snaps.size());
    for (std::size_t k = 0; k < snaps.size(); ++k) {
        std::vector<Fault> at;  // faults.csv writes S with 6 decimals
        for (const FaultRow& r : f.rows)
            if (std::fabs(r.S - snaps[k].S) < 1e-5) at.push_back(r.fault);
        out[k] = active_fault_lines(at, h0);
    }
    return out;
}

}  // namespace orodem
