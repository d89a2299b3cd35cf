// ParaView output (SPEC §4; io/vtu_writer): write_vtu then read_vtu returns
// the same per-particle data bit for bit, in id order, whatever the slot
// order; write_pvd lists every file with its S; and, where the system Python
// has VTK (Debian: python3-vtk9), VTK's own XML reader opens the file and
// reads the same numbers.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "orodem/core/error.hpp"
#include "orodem/io/vtu_writer.hpp"

using namespace orodem;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("orodem-vtu-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string slurp(const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// Bit pattern equality (== would also accept -0.0 for 0.0).
::testing::AssertionResult same_bits(double a, double b) {
    if (std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << a << " != " << b << " (bit patterns differ)";
}

constexpr std::size_t kN = 9;

/// Per id k: values with no short binary expansion (so truncation shows) and
/// a negative zero, a fixed disc, lone discs and a cluster.
double dbl(std::size_t k) { return static_cast<double>(k); }
Vec2 pos_of(std::size_t k) { return {std::sqrt(2.0 + dbl(k)) - 7.0, std::cbrt(3.0 + dbl(k)) / 3.0}; }
Vec2 vel_of(std::size_t k) { return {k == 4 ? -0.0 : 1e-3 / (dbl(k) + 1.0), -std::exp(-dbl(k))}; }
double radius_of(std::size_t k) { return 0.01 + 1e-3 * std::sin(dbl(k) + 0.5); }
double depth_of(std::size_t k) { return 0.1 * dbl(k) + 1.0 / 3.0; }
std::uint8_t side_of(std::size_t k) { return k % 3 == 2 ? 1 : 0; }
std::int32_t cluster_of(std::size_t k) { return k < 3 ? 0 : k < 6 ? -1 : 7; }
double rel_of(std::size_t k) { return k == 5 ? 1.0 : std::fmod(0.37 * dbl(k), 1.0); }

/// A store whose slot order is a permutation of id order (as after a
/// neighbour rebuild) and the rel_disp column per slot.
ParticleStore make_store(std::vector<double>& rel_per_slot) {
    ParticleStore p;
    for (std::size_t k = 0; k < kN; ++k) {
        const std::size_t s = p.add(pos_of(k), radius_of(k), 2500.0, cluster_of(k));
        p.v[s] = vel_of(k);
        p.omega[s] = 0.5 - dbl(k);
        p.initial_depth[s] = depth_of(k);
        p.side[s] = side_of(k);
    }
    p.fix(3);  // fixed: zero velocity
    p.flags[6] |= kFlagAsleep;  // in a sleeping zone (slot 6 holds id 6 before the permutation)
    // Permute slots: slot s holds id perm[s].
    const std::vector<std::size_t> perm = {4, 8, 0, 6, 2, 1, 7, 3, 5};
    p.for_each_column([&](auto& col) {
        auto old = col;
        for (std::size_t s = 0; s < kN; ++s) col[s] = old[perm[s]];
    });
    p.rebuild_slot_map();
    rel_per_slot.resize(kN);
    for (std::size_t s = 0; s < kN; ++s) rel_per_slot[s] = rel_of(p.id[s]);
    return p;
}

}  // namespace

TEST(Vtu, RoundTripIsBitExactInIdOrder) {
    const fs::path dir = scratch_dir("roundtrip");
    std::vector<double> rel;
    const ParticleStore p = make_store(rel);
    ASSERT_NE(p.id[0], 0u);  // the slots really are out of id order
    const std::string file = (dir / "s_0001.vtu").string();
    write_vtu(file, p, rel);
    const VtuData d = read_vtu(file);

    ASSERT_EQ(d.x.size(), kN);
    for (const char* name : {"id", "radius", "velocity", "initial_depth", "side", "cluster_id", "rel_disp"})
        ASSERT_NE(d.find(name), nullptr) << "array " << name << " missing (SPEC §4)";
    const auto& id = *d.find("id");
    const auto& radius = *d.find("radius");
    const auto& vel = *d.find("velocity");  // read_vtu keeps the first component
    const auto& depth = *d.find("initial_depth");
    const auto& side = *d.find("side");
    const auto& cluster = *d.find("cluster_id");
    const auto& rd = *d.find("rel_disp");
    for (std::size_t k = 0; k < kN; ++k) {
        SCOPED_TRACE("point " + std::to_string(k));
        EXPECT_EQ(id[k], double(k));  // id order
        const Vec2 v = k == 3 ? Vec2{} : vel_of(k);
        EXPECT_TRUE(same_bits(d.x[k].x, pos_of(k).x));
        EXPECT_TRUE(same_bits(d.x[k].y, pos_of(k).y));
        EXPECT_TRUE(same_bits(radius[k], radius_of(k)));
        EXPECT_TRUE(same_bits(vel[k], v.x));
        EXPECT_TRUE(same_bits(depth[k], depth_of(k)));
        EXPECT_EQ(side[k], double(side_of(k)));
        EXPECT_EQ(cluster[k], double(cluster_of(k)));
        EXPECT_TRUE(same_bits(rd[k], rel_of(k)));
    }
    if (const auto* fixed = d.find("fixed")) {
        for (std::size_t k = 0; k < kN; ++k) EXPECT_EQ((*fixed)[k], k == 3 ? 1.0 : 0.0);
    }
    const auto* asleep = d.find("asleep");
    ASSERT_NE(asleep, nullptr);
    for (std::size_t k = 0; k < kN; ++k) EXPECT_EQ((*asleep)[k], k == 6 ? 1.0 : 0.0);

    // An empty rel_disp column is written as zeros.
    write_vtu(file, p, {});
    const VtuData z = read_vtu(file);
    for (double v : *z.find("rel_disp")) EXPECT_TRUE(same_bits(v, 0.0));
    for (const auto& e : fs::directory_iterator(fs::path(file).parent_path()))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    fs::remove_all(dir);
}

TEST(Vtu, PvdListsEveryFileWithItsS) {
    const fs::path dir = scratch_dir("pvd");
    const std::vector<std::pair<double, std::string>> entries = {
        {0.0, "snapshots/s_00000.vtu"}, {0.25, "snapshots/s_00001.vtu"}, {1.0 / 3.0, "snapshots/s_00002.vtu"},
        {8.5, "snapshots/s_00003.vtu"}};
    const fs::path pvd = dir / "run.pvd";
    write_pvd(pvd.string(), entries);
    const std::string text = slurp(pvd);
    EXPECT_NE(text.find("type=\"Collection\""), std::string::npos);
    // Parse every <DataSet timestep="..." ... file="..."/> in order.
    std::vector<std::pair<double, std::string>> got;
    for (std::size_t pos = text.find("<DataSet"); pos != std::string::npos; pos = text.find("<DataSet", pos + 1)) {
        const std::size_t t = text.find("timestep=\"", pos) + 10;
        const std::size_t f = text.find("file=\"", pos) + 6;
        got.emplace_back(std::strtod(text.c_str() + t, nullptr), text.substr(f, text.find('"', f) - f));
    }
    ASSERT_EQ(got.size(), entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k) {
        EXPECT_EQ(got[k].second, entries[k].second);
        // S is written with 6 decimals: error ≤ 0.5e-6 (plus the parse's ulp).
        EXPECT_NEAR(got[k].first, entries[k].first, 0.5e-6 + 1e-15);
    }
    fs::remove_all(dir);
}

// run.pvd names files inside the run directory: an absolute entry or one
// with '..' (measure and render would read outside the run), a device
// (reading /dev/zero never ends) or a FIFO (opening it blocks) is refused
// with a one-line IoError at once.
TEST(Vtu, PvdEntriesOutsideTheRunAndFilesThatAreNotRegularAreRefused) {
    const fs::path dir = scratch_dir("pvd-bad");
    const fs::path pvd = dir / "run.pvd";
    for (const char* entry : {"/etc/passwd", "../other/run.vtu", "snapshots/../../x.vtu", ""}) {
        write_pvd(pvd.string(), {{0.0, "snapshots/s_00000.vtu"}, {0.5, entry}});
        try {
            (void)read_pvd(pvd.string());
            ADD_FAILURE() << "accepted the entry '" << entry << "'";
        } catch (const orodem::IoError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("not a file inside the run directory"), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
    write_pvd(pvd.string(), {{0.0, "snapshots/s_00000.vtu"}, {0.5, "./snapshots/s_00001.vtu"}});
    EXPECT_EQ(read_pvd(pvd.string()).size(), 2u);  // a harmless './' stays allowed
    const fs::path fifo = dir / "fifo.vtu";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string path : {std::string("/dev/zero"), fifo.string()}) {
        EXPECT_THROW((void)read_vtu(path), orodem::IoError) << path;
        EXPECT_THROW((void)read_pvd(path), orodem::IoError) << path;
    }
    fs::remove_all(dir);
}

TEST(Vtu, VtkReaderOpensTheFile) {
    if (std::system("/usr/bin/python3 -c 'import vtk' >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "/usr/bin/python3 has no vtk module (Debian: apt-get install python3-vtk9)";
    const fs::path dir = scratch_dir("vtk");
    std::vector<double> rel;
    const ParticleStore p = make_store(rel);
    const fs::path file = dir / "s.vtu";
    write_vtu(file.string(), p, rel);
    const fs::path script = dir / "read.py";
    {
        // Prints the point count, then per point: x y vx vy radius rel_disp,
        // as repr() (shortest round-trip form: parsing it back is exact).
        std::ofstream py(script);
        py << "import sys, vtk\n"
              "r = vtk.vtkXMLUnstructuredGridReader()\n"
              "r.SetFileName(sys.argv[1])\n"
              "r.Update()\n"
              "g = r.GetOutput()\n"
              "n = g.GetNumberOfPoints()\n"
              "print(n, g.GetNumberOfCells())\n"
              "pd = g.GetPointData()\n"
              "v, rad, rd = pd.GetArray('velocity'), pd.GetArray('radius'), pd.GetArray('rel_disp')\n"
              "for k in range(n):\n"
              "    x = g.GetPoint(k)\n"
              "    print(repr(x[0]), repr(x[1]), repr(v.GetComponent(k, 0)), repr(v.GetComponent(k, 1)),\n"
              "          repr(rad.GetValue(k)), repr(rd.GetValue(k)))\n";
    }
    const std::string cmd = "/usr/bin/python3 " + script.string() + " " + file.string() + " 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string out;
    char buf[4096];
    while (std::size_t got = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, got);
    ASSERT_EQ(::pclose(pipe), 0) << out;
    std::istringstream in(out);
    std::size_t npoints = 0, ncells = 0;
    in >> npoints >> ncells;
    ASSERT_EQ(npoints, kN) << out;
    EXPECT_EQ(ncells, kN);
    for (std::size_t k = 0; k < kN; ++k) {
        SCOPED_TRACE("point " + std::to_string(k));
        std::string f[6];
        for (auto& s : f) in >> s;
        ASSERT_TRUE(in) << out;
        auto num = [](const std::string& s) { return std::strtod(s.c_str(), nullptr); };
        const Vec2 v = k == 3 ? Vec2{} : vel_of(k);
        EXPECT_TRUE(same_bits(num(f[0]), pos_of(k).x));
        EXPECT_TRUE(same_bits(num(f[1]), pos_of(k).y));
        EXPECT_TRUE(same_bits(num(f[2]), v.x));
        EXPECT_TRUE(same_bits(num(f[3]), v.y));
        EXPECT_TRUE(same_bits(num(f[4]), radius_of(k)));
        EXPECT_TRUE(same_bits(num(f[5]), rel_of(k)));
    }
    fs::remove_all(dir);
}
