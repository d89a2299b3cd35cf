// The fault table of a run directory (analysis/faults.hpp, io/fault_table.hpp)
// for `orodem faults`: its faults.csv, or, for a run made before the fault
// table existed, the same table computed again from its snapshots (the
// positions of consecutive snapshots by disc id give each interval's strain,
// then detection and tracking exactly as the run loop does them).
// run_fault_lines turns the table into the lines drawn on the strain maps of
// `orodem render` and `orodem movie` (render/ gets them as plain segments).
#pragma once

#include <string>
#include <vector>

#include "orodem/io/fault_table.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/render/run_figures.hpp"

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

/// The belt's decoupling point (analysis/basal_decoupling.hpp) over the
/// interval ending at the snapshot nearest S, from that snapshot and the one
/// before it, in h0 from the S point (NaN for the first snapshot).
double run_decoupling_at(const std::string& dir, double S);

/// Per snapshot of snaps, the active faults of the run's output at its S (in
/// metres: the table's h0 units times h0); an empty list for a snapshot that
/// is no output of the table (e.g. S = 0).
RunFaultLines run_fault_lines(const RunFaults& f, const std::vector<Snapshot>& snaps, double h0);

}  // namespace orodem
