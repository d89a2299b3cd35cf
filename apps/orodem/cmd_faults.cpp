// orodem faults RUN_DIR [--at S] [--csv] [--recompute]: the fault table of a
// wedge run (src/orodem/run/run_faults.hpp) at one output (the last, or the
// one nearest --at): the paper's stage, the active pro- and retro-vergent
// faults, the frontal thrust, and one line per known fault. --csv prints the
// whole table (every output) in the format of faults.csv. A run made before
// the fault table existed is computed from its snapshots. Writes nothing.
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "orodem/analysis/faults.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/fault_table.hpp"
#include "orodem/run/run_faults.hpp"

#include "commands.hpp"

namespace orodem {

int cmd_faults(const std::string& run_dir, double at, bool csv, bool recompute) {
    const RunFaults f = run_faults(run_dir, recompute);
    if (csv) {
        fmt::print("{}\n", faults_header());
        for (const FaultRow& r : f.rows) fmt::print("{}\n", faults_line(r.S, r.fault, 1.0));
        return 0;
    }
    double S = 0.0;
    const std::vector<Fault> faults = faults_at(f, std::isnan(at) ? f.outputs.back() : at, &S);
    const FaultCounts n = count_faults(faults);
    static const char* const kStage[] = {"0 (no active fault)", "1 (block uplift between the shears rooted at the S point)",
                                         "2 (thrusting has propagated into the proside plate)",
                                         "3 (retrowedge accretion)"};
    fmt::print("faults of {} at S = {:.3f}{}\n", run_dir, S, f.from_snapshots ? " (computed from the snapshots)" : "");
    fmt::print("this output's faults show stage {} (series.csv: the stage reached)\n",
               kStage[classify_stage(faults, 1.0)]);
    fmt::print("active: {} pro-vergent, {} retro-vergent; {}\n", n.pro, n.retro,
               std::isnan(n.front_x) ? std::string("no frontal thrust")
                                     : fmt::format("frontal thrust root at {:.2f} h0 from the S point", n.front_x));
    double x_d = std::nan("");  // needs the snapshots, which a user may have deleted
    try {
        x_d = run_decoupling_at(run_dir, S);
    } catch (const IoError&) {
    }
    fmt::print("belt decoupling point (the base layer's speed falls to half the belt's): {}\n",
               std::isnan(x_d) ? std::string("none found") : fmt::format("{:.2f} h0 from the S point", x_d));
    fmt::print("{:>4}  {:<6} {:>6} {:>8} {:>10} {:>10} {:>9} {:>9} {:>10} {:>9} {:>8} {:>8}\n", "id", "verg.",
               "active", "dip(deg)", "root x/h0", "root y/h0", "tip x/h0", "tip y/h0", "length/h0", "width/h0",
               "slip/h0", "since S");
    for (const Fault& x : faults)
        fmt::print("{:>4}  {:<6} {:>6} {:>8.1f} {:>10.2f} {:>10.2f} {:>9.2f} {:>9.2f} {:>10.2f} {:>9.2f} {:>8.3f} {:>8.2f}\n",
                   x.id, x.vergence > 0 ? "pro" : "retro", x.active ? "yes" : "no", x.dip_deg, x.root.x, x.root.y,
                   x.tip.x, x.tip.y, x.length, x.width, x.slip, x.first_S);
    return 0;
}

}  // namespace orodem
