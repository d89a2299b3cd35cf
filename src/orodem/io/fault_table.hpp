// faults.csv, the fault table of a run (analysis/faults.hpp): one row per
// known fault per output, written by the run loop at every output and read
// back by `orodem faults`. Lengths in h0, x from the S point (positive
// toward the retroside), y from the base.
//
//   S, id, vergence ("pro" | "retro"), dip_deg, root_x_over_h0,
//   root_y_over_h0, tip_x_over_h0, tip_y_over_h0, length_over_h0,
//   width_over_h0, slip_over_h0 (over the output interval; 0 when inactive),
//   discs, active (1 found at this output, 0 not: its last geometry),
//   first_S (the output it was first found at)
#pragma once

#include <string>
#include <vector>

#include "orodem/analysis/faults.hpp"

namespace orodem {

std::string faults_header();
std::string faults_line(double S, const Fault& f, double h0);

struct FaultRow {
    double S = 0.0;
    Fault fault;  // lengths in h0 (as written)
};

/// The rows of a faults.csv; IoError naming the file and line when one is not a row.
std::vector<FaultRow> read_faults_csv(const std::string& path);

}  // namespace orodem
