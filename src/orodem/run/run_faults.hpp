// The fault table of a run directory (analysis/faults.hpp, io/fault_table.hpp)
// for `orodem faults`: its faults.csv, or, for a run made before the fault
// table existed, the same table computed again from its snapshots (the
// positions of consecutive snapshots by disc id give each interval's strain,
// then detection and tracking exactly as the run loop does them).
#pragma once

#include <string>
#include <vector>

#include "orodem/io/fault_table.hpp"

namespace orodem {

struct RunFaults {
    std::vector<FaultRow> rows;   // lengths in h0, as faults.csv
    std::vector<double> outputs;  // S of every output, ascending
    bool from_snapshots = false;  // computed again (no faults.csv)
};

/// dir: a wedge run directory. from_snapshots: compute from the snapshots
/// even when faults.csv exists.
RunFaults run_faults(const std::string& dir, bool from_snapshots = false);

/// The rows of `f` at the output nearest S (an output S is listed once).
std::vector<Fault> faults_at(const RunFaults& f, double S, double* S_out);

}  // namespace orodem
