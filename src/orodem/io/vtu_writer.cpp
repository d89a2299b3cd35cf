#include "orodem/io/vtu_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

namespace {

struct Array {
    std::string name;
    std::string type;  // VTK type name
    int components;
    std::string bytes;
};

template <class T>
Array make_array(const std::string& name, const char* type, int comps, const std::vector<T>& v) {
    Array a{name, type, comps, {}};
    a.bytes.assign(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    return a;
}

}  // namespace

void write_vtu(const std::string& path, const ParticleStore& p, const std::vector<double>& rel_disp,
               const VtuStamp* stamp, const StrainField* strain, const std::vector<double>* rel_disp_abs,
               const std::vector<VtuByIdArray>* by_id) {
    const std::size_t n = p.size();
    // Discs in id order, so that files of one run line up point by point.
    std::vector<double> pts(3 * n), vel(3 * n), radius(n), depth(n), omega(n), rd(n, 0.0);
    std::vector<std::int64_t> id(n), conn(n), offs(n);
    std::vector<std::int32_t> side(n), cluster(n), fixed(n), asleep(n);
    std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::size_t s = p.slot_of_id[k];
        pts[3 * k] = p.x[s].x; pts[3 * k + 1] = p.x[s].y; pts[3 * k + 2] = 0.0;
        vel[3 * k] = p.v[s].x; vel[3 * k + 1] = p.v[s].y; vel[3 * k + 2] = 0.0;
        radius[k] = p.radius[s];
        depth[k] = p.initial_depth[s];
        omega[k] = p.omega[s];
        if (!rel_disp.empty()) rd[k] = rel_disp[s];
        id[k] = p.id[s];
        side[k] = p.side[s];
        cluster[k] = p.cluster[s];
        fixed[k] = (p.flags[s] & kFlagFixed) ? 1 : 0;
        asleep[k] = (p.flags[s] & kFlagAsleep) ? 1 : 0;
        conn[k] = k;
        offs[k] = k + 1;
    }
    const std::vector<Array> point_data = {
        make_array("id", "Int64", 1, id),
        make_array("radius", "Float64", 1, radius),
        make_array("velocity", "Float64", 3, vel),
        make_array("initial_depth", "Float64", 1, depth),
        make_array("side", "Int32", 1, side),
        make_array("cluster_id", "Int32", 1, cluster),
        make_array("rel_disp", "Float64", 1, rd),
        make_array("omega", "Float64", 1, omega),
        make_array("fixed", "Int32", 1, fixed),
        make_array("asleep", "Int32", 1, asleep)};
    std::vector<Array> all_point_data = point_data;
    if (strain && strain->shear.size() == n) {  // by id, as the points are written
        all_point_data.push_back(make_array("shear_strain", "Float64", 1, strain->shear));
        all_point_data.push_back(make_array("vol_strain", "Float64", 1, strain->volumetric));
        all_point_data.push_back(make_array("rotation", "Float64", 1, strain->rotation));
        all_point_data.push_back(make_array("d2min", "Float64", 1, strain->d2min));
        if (strain->shear_total.size() == n)
            all_point_data.push_back(make_array("shear_strain_total", "Float64", 1, strain->shear_total));
    }
    if (p.has_materials()) {  // layered runs only: material and layer ids, damage [mean diameters]
        std::vector<std::int32_t> material(n), layer(n);
        std::vector<double> damage(n);
        for (std::uint32_t k = 0; k < n; ++k) {
            const std::size_t s = p.slot_of_id[k];
            material[k] = p.material[s];
            layer[k] = p.layer[s];
            damage[k] = p.damage[s];
        }
        all_point_data.push_back(make_array("material", "Int32", 1, material));
        all_point_data.push_back(make_array("layer", "Int32", 1, layer));
        all_point_data.push_back(make_array("damage", "Float64", 1, damage));
    }
    if (rel_disp_abs && rel_disp_abs->size() == n) {  // per slot: into id order
        std::vector<double> abs(n);
        for (std::uint32_t k = 0; k < n; ++k) abs[k] = (*rel_disp_abs)[p.slot_of_id[k]];
        all_point_data.push_back(make_array("rel_disp_abs", "Float64", 1, abs));
    }
    if (by_id)
        for (const VtuByIdArray& a : *by_id)
            if (a.values && a.values->size() == n) all_point_data.push_back(make_array(a.name, "Float64", 1, *a.values));
    const Array points = make_array("Points", "Float64", 3, pts);
    const std::vector<Array> cells = {make_array("connectivity", "Int64", 1, conn),
                                      make_array("offsets", "Int64", 1, offs),
                                      make_array("types", "UInt8", 1, types)};
    std::string xml, data;
    auto declare = [&](const Array& a) {
        xml += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>\n",
                           a.type, a.name, a.components, data.size());
        const std::uint64_t len = a.bytes.size();
        data.append(reinterpret_cast<const char*>(&len), sizeof len);
        data += a.bytes;
    };
    xml += "<?xml version=\"1.0\"?>\n";
    xml += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
    xml += "  <UnstructuredGrid>\n";
    if (stamp) {
        // Field data (one tuple each), declared like the point data.
        std::vector<Array> fields;
        fields.push_back(make_array("S", "Float64", 1, std::vector<double>{stamp->S}));
        fields.push_back(make_array("step", "Int64", 1, std::vector<std::int64_t>{static_cast<std::int64_t>(stamp->step)}));
        fields.push_back(make_array("time", "Float64", 1, std::vector<double>{stamp->time}));
        xml += "    <FieldData>\n";
        for (const auto& a : fields) {
            xml += fmt::format("      <DataArray type=\"{}\" Name=\"{}\" NumberOfTuples=\"1\" format=\"appended\" "
                               "offset=\"{}\"/>\n",
                               a.type, a.name, data.size());
            const std::uint64_t len = a.bytes.size();
            data.append(reinterpret_cast<const char*>(&len), sizeof len);
            data += a.bytes;
        }
        xml += "    </FieldData>\n";
    }
    xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
    xml += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
    for (const auto& a : all_point_data) declare(a);
    xml += "      </PointData>\n      <Points>\n";
    declare(points);
    xml += "      </Points>\n      <Cells>\n";
    for (const auto& a : cells) declare(a);
    xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
    xml += "  <AppendedData encoding=\"raw\">\n_";
    xml += data;
    xml += "\n  </AppendedData>\n</VTKFile>\n";
    write_file_atomic(path, xml);
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& entries) {
    std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (const auto& [S, file] : entries)
        xml += fmt::format("    <DataSet timestep=\"{:.6f}\" group=\"\" part=\"0\" file=\"{}\"/>\n", S, file);
    xml += "  </Collection>\n</VTKFile>\n";
    write_file_atomic(path, xml);
}

const std::vector<double>* VtuData::find(const std::string& name) const {
    for (const auto& [n, v] : arrays)
        if (n == name) return &v;
    return nullptr;
}

VtuData read_vtu(const std::string& path) {
    const std::string b = read_file(path);
    auto bad = [&](const std::string& why) { return IoError(fmt::format("'{}': not a readable orodem VTU: {}", path, why)); };
    const auto app = b.find("<AppendedData encoding=\"raw\">");
    if (app == std::string::npos) throw bad("no raw appended data");
    const auto base = b.find('_', app) + 1;
    VtuData out;
    std::size_t n = 0;
    if (auto pos = b.find("NumberOfPoints=\""); pos != std::string::npos) n = std::stoull(b.substr(pos + 16));
    auto attr = [&](std::size_t tag, const std::string& key) {
        const auto k = b.find(key + "=\"", tag);
        const auto e = b.find('"', k + key.size() + 2);
        return b.substr(k + key.size() + 2, e - k - key.size() - 2);
    };
    const auto field_begin = b.find("<FieldData>"), field_end = b.find("</FieldData>");
    for (std::size_t pos = b.find("<DataArray"); pos != std::string::npos && pos < app; pos = b.find("<DataArray", pos + 1)) {
        if (field_begin != std::string::npos && pos > field_begin && pos < field_end) continue;  // S, step, time
        const std::string name = attr(pos, "Name"), type = attr(pos, "type");
        const int comps = std::stoi(attr(pos, "NumberOfComponents"));
        const std::size_t off = base + std::stoull(attr(pos, "offset"));
        std::uint64_t len = 0;
        if (off + 8 > b.size()) throw bad("truncated");
        std::memcpy(&len, b.data() + off, 8);
        if (off + 8 + len > b.size()) throw bad("truncated");
        const char* d = b.data() + off + 8;
        std::vector<double> v;
        const std::size_t count = n * static_cast<std::size_t>(comps);
        auto get = [&](auto tag) {
            using T = decltype(tag);
            if (len != count * sizeof(T)) throw bad("array " + name + " has the wrong length");
            for (std::size_t k = 0; k < count; k += static_cast<std::size_t>(comps)) {
                T t;
                std::memcpy(&t, d + k * sizeof(T), sizeof(T));
                v.push_back(static_cast<double>(t));
                if (name == "Points") {
                    T y;
                    std::memcpy(&y, d + (k + 1) * sizeof(T), sizeof(T));
                    out.x.push_back({static_cast<double>(t), static_cast<double>(y)});
                }
            }
        };
        if (name == "connectivity" || name == "offsets" || name == "types") continue;
        if (type == "Float64") get(double{});
        else if (type == "Int64") get(std::int64_t{});
        else if (type == "Int32") get(std::int32_t{});
        else throw bad("unexpected type " + type);
        if (name != "Points") out.arrays.emplace_back(name, std::move(v));
    }
    if (out.x.size() != n) throw bad("points missing");
    return out;
}

const std::vector<double>& VtuData::require(const std::string& name, const std::string& path) const {
    const auto* a = find(name);
    if (!a) throw IoError(fmt::format("'{}': snapshot has no '{}' array", path, name));
    return *a;
}

std::vector<Vec2> positions_by_id(const VtuData& d, const std::string& path, std::vector<double>* radius) {
    const std::vector<double>& id = d.require("id", path);
    std::size_t n = 0;
    for (double v : id) n = std::max(n, static_cast<std::size_t>(v) + 1);
    std::vector<Vec2> x(n, Vec2{std::nan(""), std::nan("")});
    for (std::size_t k = 0; k < d.x.size(); ++k) x[static_cast<std::size_t>(id[k])] = d.x[k];
    if (radius) {
        const std::vector<double>& r = d.require("radius", path);
        radius->assign(n, std::nan(""));
        for (std::size_t k = 0; k < d.x.size(); ++k) (*radius)[static_cast<std::size_t>(id[k])] = r[k];
    }
    return x;
}

std::vector<Snapshot> read_pvd(const std::string& path) {
    // 64 MiB is 300,000 entries, far beyond wedge.output_ds's 1e5-output limit.
    constexpr std::uint64_t kMaxPvdBytes = 64u << 20;
    const std::string b = read_file(path, kMaxPvdBytes);
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
        // Entries name files inside the run directory: an absolute path or a '..' would make measure and
        // render read outside it.
        const std::filesystem::path entry(s.file);
        const bool escapes = s.file.empty() || entry.is_absolute() ||
                             std::any_of(entry.begin(), entry.end(), [](const auto& part) { return part == ".."; });
        if (escapes)
            throw IoError(fmt::format("'{}': entry '{}' is not a file inside the run directory (absolute or with '..')",
                                      path, s.file));
        if (!out.empty() && out.back().file == s.file) out.back() = s;
        else out.push_back(s);
    }
    if (out.empty()) throw IoError(fmt::format("'{}': lists no snapshots", path));
    return out;
}

}  // namespace orodem
