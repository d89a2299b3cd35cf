#include "orodem/io/fault_table.hpp"

#include <cstdlib>
#include <sstream>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

std::string faults_header() {
    return "S,id,vergence,dip_deg,root_x_over_h0,root_y_over_h0,tip_x_over_h0,tip_y_over_h0,length_over_h0,"
           "width_over_h0,slip_over_h0,discs,active,first_S";
}

std::string faults_line(double S, const Fault& f, double h0) {
    return fmt::format("{:.6f},{},{},{:.4g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{},{},{:.6f}", S, f.id,
                       f.vergence > 0 ? "pro" : "retro", f.dip_deg, f.root.x / h0, f.root.y / h0, f.tip.x / h0,
                       f.tip.y / h0, f.length / h0, f.width / h0, f.slip / h0, f.discs, f.active ? 1 : 0, f.first_S);
}

std::vector<FaultRow> read_faults_csv(const std::string& path) {
    const std::string text = read_file(path);
    std::istringstream in(text);
    std::string line;
    std::vector<FaultRow> rows;
    std::size_t line_no = 0;
    while (std::getline(in, line)) {
        ++line_no;
        if (line_no == 1) {
            if (line != faults_header())
                throw IoError(fmt::format("'{}' line 1: not the header of a fault table ({})", path, faults_header()));
            continue;
        }
        if (line.empty()) continue;
        std::vector<std::string> cells;
        std::istringstream ls(line);
        for (std::string cell; std::getline(ls, cell, ',');) cells.push_back(cell);
        auto num = [&](std::size_t k) {
            char* end = nullptr;
            const double v = std::strtod(cells[k].c_str(), &end);
            if (cells[k].empty() || *end != '\0')
                throw IoError(fmt::format("'{}' line {}: column {} is '{}', not a number", path, line_no, k + 1, cells[k]));
            return v;
        };
        if (cells.size() != 14 || (cells[2] != "pro" && cells[2] != "retro"))
            throw IoError(fmt::format("'{}' line {}: not a row of 14 columns with vergence pro or retro", path, line_no));
        FaultRow r;
        r.S = num(0);
        r.fault.id = static_cast<std::int64_t>(num(1));
        r.fault.vergence = cells[2] == "pro" ? +1 : -1;
        r.fault.dip_deg = num(3);
        r.fault.root = {num(4), num(5)};
        r.fault.tip = {num(6), num(7)};
        r.fault.length = num(8);
        r.fault.width = num(9);
        r.fault.slip = num(10);
        r.fault.discs = static_cast<std::uint32_t>(num(11));
        r.fault.active = num(12) != 0.0;
        r.fault.first_S = num(13);
        rows.push_back(r);
    }
    return rows;
}

}  // namespace orodem
