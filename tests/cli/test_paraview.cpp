// A wedge run's ParaView output opened by VTK's own Python reader (python3-vtk9,
// or the same vtk module of python3-paraview where ParaView is installed):
// every snapshot listed in run.pvd is read by vtkXMLUnstructuredGridReader
// and carries the point data of SPEC §4; and scripts/paraview-view under
// pvbatch. Each skips with a message where its program is missing.
#include <gtest/gtest.h>

#include "cli/cli_util.hpp"
#include <stdlib.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace cli;

TEST(ParaView, RunPvdSnapshotsOpenInVtk) {
    if (run("/usr/bin/python3 -c 'import vtk'") != 0) GTEST_SKIP() << "python3-vtk9 not installed";
    char tmpl[] = "/tmp/orodem-paraview-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    const fs::path dir = tmpl;
    write_tiny_exp1(dir);
    std::string out;
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " run " + (dir / "tiny.toml").string() + " --out " +
                  (dir / "r").string() + " --threads 1", &out), 0) << out;
    const std::string py = R"PY(
import sys, os, xml.etree.ElementTree as ET, vtk
run = sys.argv[1]
sets = ET.parse(os.path.join(run, "run.pvd")).getroot().find("Collection").findall("DataSet")
assert len(sets) >= 3, len(sets)
for d in sets:
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(run, d.get("file")))
    r.Update()
    g = r.GetOutput()
    assert g.GetNumberOfPoints() > 20, g.GetNumberOfPoints()
    assert g.GetNumberOfCells() == g.GetNumberOfPoints()
    pd = g.GetPointData()
    for name in ("id", "radius", "velocity", "initial_depth", "side", "cluster_id", "rel_disp"):
        assert pd.GetArray(name) is not None, name
    assert pd.GetArray("velocity").GetNumberOfComponents() == 3
print("ok", len(sets), "snapshots,", g.GetNumberOfPoints(), "points, S =", [float(d.get("timestep")) for d in sets])
)PY";
    {
        std::ofstream f(dir / "check.py");
        f << py;
    }
    ASSERT_EQ(run("/usr/bin/python3 " + (dir / "check.py").string() + " " + (dir / "r").string(), &out), 0) << out;
    EXPECT_NE(out.find("ok 3 snapshots"), std::string::npos) << out;
    std::printf("%s", out.c_str());
    fs::remove_all(dir);
}

TEST(ParaView, ParaviewViewScriptDrawsARunWithPvbatch) {
    // scripts/paraview-view under pvbatch (ParaView's Python, no window): a PNG of the last snapshot, discs at
    // their true size. Skipped where ParaView is not installed.
    if (run("command -v pvbatch >/dev/null 2>&1") != 0) GTEST_SKIP() << "pvbatch (ParaView) not installed";
    // Debian's ParaView renders through X even with --screenshot: without a display it runs in xvfb-run's.
    std::string pvbatch = "pvbatch ";
    if (const char* display = std::getenv("DISPLAY"); display == nullptr || *display == '\0') {
        if (run("command -v xvfb-run >/dev/null 2>&1") != 0)
            GTEST_SKIP() << "no display for pvbatch and no xvfb-run (scripts/install-deps installs xvfb beside ParaView)";
        pvbatch = "xvfb-run -a pvbatch ";
    }
    char tmpl[] = "/tmp/orodem-pvview-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    const fs::path dir = tmpl;
    write_tiny_exp1(dir);
    std::string out;
    ASSERT_EQ(run(std::string(ORODEM_EXE) + " run " + (dir / "tiny.toml").string() + " --out " + (dir / "r").string() +
                      " --threads 1", &out), 0) << out;
    ASSERT_EQ(run(pvbatch + std::string(ORODEM_SOURCE_DIR) + "/scripts/paraview-view " + (dir / "r").string() +
                      " --color side --screenshot " + (dir / "view.png").string() + " 2>&1", &out), 0) << out;
    EXPECT_GT(fs::file_size(dir / "view.png"), 1000u) << out;
    fs::remove_all(dir);
}
