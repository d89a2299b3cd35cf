// The columns of a wedge run's series.csv as one table: each column's name,
// how its number is written and where it comes from. The header, every row
// and `orodem measure` (the columns taken from a snapshot alone) are built
// from this table, so a new column is one line here (docs/ARCHITECTURE.md,
// "How to add a series column"). The formats are part of the run-directory
// contract: outputs stay byte-identical as long as a column's format does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "orodem/analysis/wedge_profile.hpp"

namespace orodem {

/// Everything one series row is made of, taken at one output.
struct SeriesRow {
    std::uint64_t step = 0;            // [-]
    double time = 0.0;                 // [s]
    double S = 0.0;                    // shortening / h0 [-]
    WedgeMeasures m;                   // the wedge measures (analysis/wedge_profile.hpp)
    double h0 = 1.0;                   // layer thickness [m]
    double kinetic_energy = 0.0;       // [J]
    std::uint64_t contacts = 0;        // touching pairs and wall contacts [-]
    double max_overlap_ratio = 0.0;    // [-]
    double base_traction = 0.0;        // total tangential force of the proside base [N]
    std::uint64_t discs_on_base = 0;   // [-]
    std::uint64_t discs_sliding = 0;   // [-]
    std::uint64_t fixed_discs = 0;     // exp1/exp2 retroside discs held fixed [-]
    double mean_overlap_ratio = 0.0;   // [-]
    double max_speed = 0.0;            // [m/s]
    double base_normal_force = 0.0;    // [N]
    double trailing_wall_push = 0.0;   // [N]
    int pro_faults = 0;                // active pro-vergent faults (analysis/faults.hpp) [-]
    int retro_faults = 0;              // active retro-vergent faults [-]
    double front_thrust_x = 0.0;       // root x of the most proside active pro-vergent fault (NaN: none) [m]
    int stage = 0;                     // the paper's stage reached, stage_reached [-]
    double section_push = 0.0;         // x force through the section 1 h0 ahead of the prowedge toe,
                                       // analysis/section_force.hpp (NaN: no toe) [N]
    double decoupling_x = 0.0;         // the belt's decoupling point over the interval ending here,
                                       // analysis/basal_decoupling.hpp (NaN: none, first output) [m]
};

enum class ColumnFormat {
    integer,  // "{}"
    g9,       // "{:.9g}"
    g6,       // "{:.6g}"
    f6,       // "{:.6f}"
};

struct SeriesColumn {
    const char* name;
    const char* meaning;                // with its unit in brackets (docs/reference.md's table is made from it)
    ColumnFormat format;
    double (*value)(const SeriesRow&);  // integers are exact below 2^53
    bool from_snapshot;                 // measurable again from a saved snapshot (orodem measure)
};

/// The columns in file order.
const std::vector<SeriesColumn>& series_columns();
/// "step,time,S,...": all columns, or (snapshot_only) those of orodem measure.
std::string series_header(bool snapshot_only = false);
/// One row: the first n columns (a run started by an older orodem keeps the
/// columns it started with), or the snapshot columns only.
std::string series_line(const SeriesRow& r, std::size_t n = static_cast<std::size_t>(-1), bool snapshot_only = false);

}  // namespace orodem
