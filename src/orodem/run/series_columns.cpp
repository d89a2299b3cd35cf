#include "orodem/run/series_columns.hpp"

#include <fmt/format.h>

namespace orodem {

namespace {

using F = ColumnFormat;

const std::vector<SeriesColumn> kColumns = {
    {"step", "steps taken [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.step); }, false},
    {"time", "simulated time [s]", F::g9, [](const SeriesRow& r) { return r.time; }, false},
    {"S", "normalised convergence S = v' t / h0 [-]", F::f6, [](const SeriesRow& r) { return r.S; }, true},
    {"H_over_h0", "wedge height above the undeformed surface / h0 [-]", F::g6, [](const SeriesRow& r) { return r.m.H_over_h0; }, true},
    {"alpha_deg", "prowedge surface slope α, least-squares line from the pro toe to the peak [deg]", F::g6, [](const SeriesRow& r) { return r.m.alpha_deg; }, true},
    {"beta_deg", "retrowedge surface slope β, from the peak to the retro toe [deg]", F::g6, [](const SeriesRow& r) { return r.m.beta_deg; }, true},
    {"peak_dx_over_h0", "x of the highest surface column from the S point / h0 (positive: retroside) [-]", F::g6, [](const SeriesRow& r) { return r.m.peak_dx_over_h0; }, true},
    {"dilation_pct", "dilation D: area of the deformed wedge against the accreted layer's [%]", F::g6, [](const SeriesRow& r) { return r.m.dilation_pct; }, true},
    {"kinetic_energy", "kinetic energy ½ Σ m v² [J]", F::g9, [](const SeriesRow& r) { return r.kinetic_energy; }, false},
    {"contacts", "touching disc pairs and wall contacts [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.contacts); }, false},
    {"max_overlap_ratio", "largest overlap / smaller radius over unbonded pairs [-]", F::g6, [](const SeriesRow& r) { return r.max_overlap_ratio; }, false},
    {"toe_pro_x_over_h0", "prowedge toe x / h0, where the surface first rises toe_threshold above the undeformed surface [-]", F::g6, [](const SeriesRow& r) { return r.m.toe_pro_x / r.h0; }, true},
    {"toe_retro_x_over_h0", "retrowedge toe x / h0 [-]", F::g6, [](const SeriesRow& r) { return r.m.toe_retro_x / r.h0; }, true},
    {"base_traction", "total tangential force of the proside base on the discs [N]", F::g6, [](const SeriesRow& r) { return r.base_traction; }, false},
    {"discs_on_base", "discs touching the proside base [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.discs_on_base); }, false},
    {"discs_sliding_on_base", "of those, discs sliding on the base (Coulomb limit reached) [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.discs_sliding); },
     false},
    {"fixed_discs", "exp1, exp2: retroside discs held fixed [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.fixed_discs); }, false},
    {"mean_overlap_ratio", "mean overlap / smaller radius over touching unbonded pairs [-]", F::g6, [](const SeriesRow& r) { return r.mean_overlap_ratio; }, false},
    {"max_speed", "largest disc speed [m/s]", F::g6, [](const SeriesRow& r) { return r.max_speed; }, false},
    {"base_normal_force", "total normal force of the proside base [N]", F::g6, [](const SeriesRow& r) { return r.base_normal_force; }, false},
    {"trailing_wall_push", "x force of the discs on the trailing (proside end) wall [N]", F::g6, [](const SeriesRow& r) { return r.trailing_wall_push; }, false},
    {"beta_inner_deg", "retroside inner slope, two segments fitted from the peak to the retro toe (NaN: retroside under 2 h0) [deg]", F::g6, [](const SeriesRow& r) { return r.m.beta_inner_deg; }, true},
    {"beta_outer_deg", "retroside outer slope of the same fit [deg]", F::g6, [](const SeriesRow& r) { return r.m.beta_outer_deg; }, true},
    {"retro_break_x_over_h0", "x / h0 of the break between the two retroside segments [-]", F::g6, [](const SeriesRow& r) { return r.m.retro_break_x / r.h0; }, true},
    {"active_pro_faults", "active pro-vergent faults over the output interval (docs/physics.md \"Faults\") [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.pro_faults); }, false},
    {"active_retro_faults", "active retro-vergent faults [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.retro_faults); }, false},
    {"front_thrust_x_over_h0", "root x / h0 of the most proside active pro-vergent fault (NaN: none) [-]", F::g6, [](const SeriesRow& r) { return r.front_thrust_x / r.h0; }, false},
    {"stage", "the paper's stage reached ([45]-[52]): 0 no active fault, 1 block uplift at the S point, 2 pro-vergent thrusting in the incoming plate, 3 retrowedge accretion; kept once two outputs show it [-]", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.stage); }, false},
    {"alpha_se_deg", "standard error of α's line fit [deg]", F::g6, [](const SeriesRow& r) { return r.m.alpha_se_deg; }, true},
    {"beta_se_deg", "standard error of β's line fit [deg]", F::g6, [](const SeriesRow& r) { return r.m.beta_se_deg; }, true},
    {"section_push", "x force through the section 1 h0 ahead of the prowedge toe (NaN: no toe) [N]", F::g6, [](const SeriesRow& r) { return r.section_push; }, false},
    {"decoupling_x_over_h0", "x / h0 where the base layer stops riding the belt over the interval (NaN: none, first output) [-]", F::g6, [](const SeriesRow& r) { return r.decoupling_x / r.h0; }, true},
};

void append(std::string& out, ColumnFormat f, double v) {
    switch (f) {
        case F::integer: fmt::format_to(std::back_inserter(out), "{}", static_cast<std::uint64_t>(v)); break;
        case F::g9: fmt::format_to(std::back_inserter(out), "{:.9g}", v); break;
        case F::g6: fmt::format_to(std::back_inserter(out), "{:.6g}", v); break;
        case F::f6: fmt::format_to(std::back_inserter(out), "{:.6f}", v); break;
    }
}

}  // namespace

const std::vector<SeriesColumn>& series_columns() { return kColumns; }

std::string series_header(bool snapshot_only) {
    std::string out;
    for (const SeriesColumn& col : kColumns) {
        if (snapshot_only && !col.from_snapshot) continue;
        if (!out.empty()) out += ',';
        out += col.name;
    }
    return out;
}

std::string series_line(const SeriesRow& r, std::size_t n, bool snapshot_only) {
    std::string out;
    std::size_t written = 0;
    for (const SeriesColumn& col : kColumns) {
        if (written == n) break;
        if (snapshot_only && !col.from_snapshot) continue;
        if (written++ > 0) out += ',';
        append(out, col.format, col.value(r));
    }
    return out;
}

}  // namespace orodem
