#include "orodem/run/series_columns.hpp"

#include <fmt/format.h>

namespace orodem {

namespace {

using F = ColumnFormat;

const std::vector<SeriesColumn> kColumns = {
    {"step", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.step); }, false},
    {"time", F::g9, [](const SeriesRow& r) { return r.time; }, false},
    {"S", F::f6, [](const SeriesRow& r) { return r.S; }, true},
    {"H_over_h0", F::g6, [](const SeriesRow& r) { return r.m.H_over_h0; }, true},
    {"alpha_deg", F::g6, [](const SeriesRow& r) { return r.m.alpha_deg; }, true},
    {"beta_deg", F::g6, [](const SeriesRow& r) { return r.m.beta_deg; }, true},
    {"peak_dx_over_h0", F::g6, [](const SeriesRow& r) { return r.m.peak_dx_over_h0; }, true},
    {"dilation_pct", F::g6, [](const SeriesRow& r) { return r.m.dilation_pct; }, true},
    {"kinetic_energy", F::g9, [](const SeriesRow& r) { return r.kinetic_energy; }, false},
    {"contacts", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.contacts); }, false},
    {"max_overlap_ratio", F::g6, [](const SeriesRow& r) { return r.max_overlap_ratio; }, false},
    {"toe_pro_x_over_h0", F::g6, [](const SeriesRow& r) { return r.m.toe_pro_x / r.h0; }, true},
    {"toe_retro_x_over_h0", F::g6, [](const SeriesRow& r) { return r.m.toe_retro_x / r.h0; }, true},
    {"base_traction", F::g6, [](const SeriesRow& r) { return r.base_traction; }, false},
    {"discs_on_base", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.discs_on_base); }, false},
    {"discs_sliding_on_base", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.discs_sliding); },
     false},
    {"fixed_discs", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.fixed_discs); }, false},
    {"mean_overlap_ratio", F::g6, [](const SeriesRow& r) { return r.mean_overlap_ratio; }, false},
    {"max_speed", F::g6, [](const SeriesRow& r) { return r.max_speed; }, false},
    {"base_normal_force", F::g6, [](const SeriesRow& r) { return r.base_normal_force; }, false},
    {"trailing_wall_push", F::g6, [](const SeriesRow& r) { return r.trailing_wall_push; }, false},
    {"beta_inner_deg", F::g6, [](const SeriesRow& r) { return r.m.beta_inner_deg; }, true},
    {"beta_outer_deg", F::g6, [](const SeriesRow& r) { return r.m.beta_outer_deg; }, true},
    {"retro_break_x_over_h0", F::g6, [](const SeriesRow& r) { return r.m.retro_break_x / r.h0; }, true},
    {"active_pro_faults", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.pro_faults); }, false},
    {"active_retro_faults", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.retro_faults); }, false},
    {"front_thrust_x_over_h0", F::g6, [](const SeriesRow& r) { return r.front_thrust_x / r.h0; }, false},
    {"stage", F::integer, [](const SeriesRow& r) { return static_cast<double>(r.stage); }, false},
    {"alpha_se_deg", F::g6, [](const SeriesRow& r) { return r.m.alpha_se_deg; }, true},
    {"beta_se_deg", F::g6, [](const SeriesRow& r) { return r.m.beta_se_deg; }, true},
    {"section_push", F::g6, [](const SeriesRow& r) { return r.section_push; }, false},
    {"decoupling_x_over_h0", F::g6, [](const SeriesRow& r) { return r.decoupling_x / r.h0; }, true},
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
